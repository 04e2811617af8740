#include "rover/dl/stereo/correlator.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "rover/dl/stereo/image_prep.hpp"
#include "test_images.hpp"

namespace rover::dl::stereo {
namespace {

constexpr int kInf = std::numeric_limits<int>::max();

// Brute-force reference of everything correlator.hpp specifies (costs, winner, tests, peak).
DisparityImage Reference(const cv::Mat& l, const cv::Mat& r, const CorrelatorOptions& o) {
  const int w = l.cols, h = l.rows, half = o.window / 2, nd = o.num_disparities;
  DisparityImage out;
  out.Reset(l.size(), PixelStatus::kBorder);
  const auto cost = [&](int x, int y, int k) {
    const int d = o.min_disparity + k;
    if (k < 0 || k >= nd || x - d - half < 0 || x - d + half > w - 1) return kInf;
    int s = 0;
    for (int j = -half; j <= half; ++j) {
      for (int i = -half; i <= half; ++i) {
        s += std::abs(l.at<std::uint8_t>(y + j, x + i) - r.at<std::uint8_t>(y + j, x + i - d));
      }
    }
    return s;
  };
  for (int y = half; y < h - half; ++y) {
    std::vector<std::vector<int>> c(static_cast<std::size_t>(w), std::vector<int>(nd + 2, kInf));
    for (int x = half; x < w - half; ++x) {
      for (int k = -1; k <= nd; ++k) c[x][k + 1] = cost(x, y, k);
    }
    const auto at = [&](int x, int k) { return c[static_cast<std::size_t>(x)][k + 1]; };
    std::vector<int> right_best(static_cast<std::size_t>(w), -1);
    for (int xr = 0; xr < w; ++xr) {
      int best = kInf;
      for (int k = 0; k < nd; ++k) {
        const int x = xr + o.min_disparity + k;
        if (x < half || x >= w - half) continue;
        if (at(x, k) < best) {
          best = at(x, k);
          right_best[xr] = k;
        }
      }
    }
    for (int x = half; x < w - half; ++x) {
      int best = kInf, bk = 0;
      for (int k = 0; k < nd; ++k) {
        if (at(x, k) < best) {
          best = at(x, k);
          bk = k;
        }
      }
      PixelStatus st = PixelStatus::kValid;
      const int cm = at(x, bk - 1), cp = at(x, bk + 1);
      const bool edge = cm == kInf || cp == kInf;
      int second = kInf;
      for (int k = 0; k < nd; ++k) {
        if (std::abs(k - bk) > 1) second = std::min(second, at(x, k));
      }
      const int d = o.min_disparity + bk;
      if (best == kInf) {
        st = PixelStatus::kNoMatch;
      } else if (edge && o.reject_range_edge) {
        st = PixelStatus::kRangeEdge;
      } else if (!edge && cm + cp - 2 * best < std::ceil(o.min_curvature * o.window * o.window)) {
        st = PixelStatus::kFlat;
      } else if (o.uniqueness_ratio > 0 && second != kInf &&
                 second * 1024.0 <= best * std::round(1024.0 * (1.0 + o.uniqueness_ratio))) {
        st = PixelStatus::kNotUnique;
      } else if (o.lr_max_diff >= 0 && std::abs(right_best[x - d] - bk) > o.lr_max_diff) {
        st = PixelStatus::kLeftRight;
      }
      out.status.at<std::uint8_t>(y, x) = static_cast<std::uint8_t>(st);
      if (st == PixelStatus::kValid) {
        const double den = o.subpixel == SubpixelMethod::kParabola ? cm + cp - 2.0 * best
                                                                   : std::max(cm, cp) - 1.0 * best;
        const bool fit = o.subpixel != SubpixelMethod::kNone && !edge && den > 0;
        out.disparity.at<float>(y, x) = static_cast<float>(d + (fit ? 0.5 * (cm - cp) / den : 0.0));
      }
    }
  }
  return out;
}

std::vector<SimdLevel> SupportedLevels() {
  std::vector<SimdLevel> levels = {SimdLevel::kScalar};
  if (DetectSimdLevel() != SimdLevel::kScalar) levels.push_back(SimdLevel::kSse2);
  if (DetectSimdLevel() == SimdLevel::kAvx2) levels.push_back(SimdLevel::kAvx2);
  return levels;
}

void NoisyPair(double d, cv::Size size, cv::Mat* l, cv::Mat* r, std::uint64_t seed) {
  testing::ConstantDisparityPair(testing::Texture(seed), size, d, l, r);
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, 6.0);
  for (cv::Mat* m : {l, r}) {
    for (auto it = m->begin<std::uint8_t>(); it != m->end<std::uint8_t>(); ++it) {
      *it = testing::Texture::Quantise(*it + noise(rng));
    }
  }
}

TEST(CorrelatorTest, MatchesBruteForceReferenceForEverySimdLevelAndThreadCount) {
  cv::Mat l, r;
  NoisyPair(7.3, cv::Size(61, 29), &l, &r, 1);
  for (const int window : {5, 7}) {
    CorrelatorOptions o;
    o.window = window;
    o.subpixel = window == 5 ? SubpixelMethod::kParabola : SubpixelMethod::kEquiangular;
    o.min_disparity = -3;
    o.num_disparities = 20;
    o.uniqueness_ratio = 0.05;
    o.min_curvature = 0.3;
    const DisparityImage ref = Reference(l, r, o);
    EXPECT_GT(ref.CountValid(), 200);
    for (const SimdLevel simd : SupportedLevels()) {
      for (const int threads : {1, 3}) {
        o.simd = simd;
        o.num_threads = threads;
        auto c = Correlator::Create(o);
        ASSERT_TRUE(c.ok()) << c.status().ToString();
        DisparityImage out;
        ASSERT_TRUE(c->Compute(l, r, &out).ok());
        SCOPED_TRACE(std::string(SimdLevelName(simd)) + " threads " + std::to_string(threads) +
                     " window " + std::to_string(window));
        EXPECT_EQ(cv::norm(out.status, ref.status, cv::NORM_INF), 0.0);
        int mismatches = 0;
        for (int v = 0; v < l.rows; ++v) {
          for (int u = 0; u < l.cols; ++u) {
            const float a = out.disparity.at<float>(v, u), b = ref.disparity.at<float>(v, u);
            if (std::isnan(a) != std::isnan(b) || (!std::isnan(a) && std::abs(a - b) > 1e-4)) {
              ++mismatches;
            }
          }
        }
        EXPECT_EQ(mismatches, 0);
      }
    }
  }
}

// Mean absolute error of the sub-pixel disparity on a texture shifted by d (exact sampling).
double SubpixelError(double d, SubpixelMethod method, int* count) {
  cv::Mat l, r, pl, pr;
  testing::ConstantDisparityPair(testing::Texture(7), cv::Size(120, 60), d, &l, &r);
  EXPECT_TRUE(Prefilter(l, PrefilterOptions(), &pl).ok());
  EXPECT_TRUE(Prefilter(r, PrefilterOptions(), &pr).ok());
  CorrelatorOptions o;
  o.num_disparities = 32;
  o.subpixel = method;
  auto c = Correlator::Create(o);
  EXPECT_TRUE(c.ok());
  DisparityImage out;
  EXPECT_TRUE(c->Compute(pl, pr, &out).ok());
  double sum = 0.0;
  int n = 0;
  for (int v = 0; v < l.rows; ++v) {
    for (int u = 0; u < l.cols; ++u) {
      const float e = out.disparity.at<float>(v, u);
      if (std::isnan(e)) continue;
      sum += std::abs(e - d);
      ++n;
    }
  }
  *count = n;
  return n > 0 ? sum / n : 1e9;
}

// The default (equiangular) fit: < 0.1 px mean error at integer, quarter, half and other
// shifts. The parabola, biased towards integers on the V-shaped SAD valley, stays within 0.15.
TEST(CorrelatorTest, SubpixelAccuracyOnShiftedTexture) {
  const int interior = (120 - 6 - 16) * (60 - 6);
  for (const double d : {10.0, 10.25, 10.5, 10.75, 3.3, 7.6}) {
    int n = 0;
    const double equiangular = SubpixelError(d, SubpixelMethod::kEquiangular, &n);
    EXPECT_GT(n, 0.9 * interior) << "d " << d;
    EXPECT_LT(equiangular, 0.1) << "d " << d;
    const double parabola = SubpixelError(d, SubpixelMethod::kParabola, &n);
    EXPECT_LT(parabola, 0.15) << "d " << d;
    std::printf("shift %.2f px: mean abs error %.3f px (equiangular), %.3f px (parabola)\n", d,
                equiangular, parabola);
  }
}

TEST(CorrelatorTest, PeriodicTextureIsRejectedAsNotUnique) {
  cv::Mat l(40, 100, CV_8UC1), r(40, 100, CV_8UC1);
  const auto f = [](int u, int v) {
    return testing::Texture::Quantise(128 + 60 * std::sin(2 * std::numbers::pi * u / 8.0) +
                                      30 * std::sin(2 * std::numbers::pi * v / 13.0));
  };
  for (int v = 0; v < l.rows; ++v) {
    for (int u = 0; u < l.cols; ++u) {
      l.at<std::uint8_t>(v, u) = f(u, v);
      r.at<std::uint8_t>(v, u) = f(u + 5, v);
    }
  }
  CorrelatorOptions o;
  o.num_disparities = 32;
  auto c = Correlator::Create(o);
  ASSERT_TRUE(c.ok());
  DisparityImage out;
  ASSERT_TRUE(c->Compute(l, r, &out).ok());
  int full_range = 0, valid = 0, not_unique = 0;
  for (int v = 3; v < l.rows - 3; ++v) {
    for (int u = 31 + 3; u < l.cols - 3; ++u) {  // pixels with the complete search range
      ++full_range;
      const auto s = static_cast<PixelStatus>(out.status.at<std::uint8_t>(v, u));
      valid += s == PixelStatus::kValid;
      not_unique += s == PixelStatus::kNotUnique;
    }
  }
  EXPECT_EQ(valid, 0);
  EXPECT_GT(not_unique, 0.9 * full_range);
}

TEST(CorrelatorTest, LeftRightCheckRejectsOccludedRegion) {
  cv::Mat l, r, truth, occluded;
  const cv::Rect fg(60, 10, 30, 40);
  testing::ForegroundPair(cv::Size(130, 60), fg, 4, 14, &l, &r, &truth, &occluded);
  cv::Mat pl, pr;
  ASSERT_TRUE(Prefilter(l, PrefilterOptions(), &pl).ok());
  ASSERT_TRUE(Prefilter(r, PrefilterOptions(), &pr).ok());
  const auto run = [&](int lr_max_diff) {
    CorrelatorOptions o;
    o.num_disparities = 24;
    o.uniqueness_ratio = 0.0;  // isolate the left-right check
    o.min_curvature = 0.0;
    o.lr_max_diff = lr_max_diff;
    auto c = Correlator::Create(o);
    DisparityImage out;
    EXPECT_TRUE(c.ok() && c->Compute(pl, pr, &out).ok());
    return out;
  };
  const DisparityImage with_lr = run(1), without_lr = run(-1);
  int occ = 0, occ_valid_with = 0, occ_valid_without = 0, occ_lr = 0;
  int vis = 0, vis_good = 0;
  for (int v = fg.y + 4; v < fg.y + fg.height - 4; ++v) {
    for (int u = 30; u < l.cols - 4; ++u) {
      const bool valid = with_lr.status.at<std::uint8_t>(v, u) == 0;
      if (occluded.at<std::uint8_t>(v, u) != 0) {
        ++occ;
        occ_valid_with += valid;
        occ_valid_without += without_lr.status.at<std::uint8_t>(v, u) == 0;
        occ_lr +=
            with_lr.status.at<std::uint8_t>(v, u) == static_cast<int>(PixelStatus::kLeftRight);
      } else if (std::abs(u - fg.x) > 4 && std::abs(u - fg.x - fg.width) > 4 &&
                 std::abs(u - (fg.x - 10)) > 4) {
        ++vis;
        vis_good +=
            valid && std::abs(with_lr.disparity.at<float>(v, u) - truth.at<float>(v, u)) < 1.0f;
      }
    }
  }
  ASSERT_GT(occ, 200);
  EXPECT_LT(occ_valid_with, 0.2 * occ);
  EXPECT_GT(occ_valid_without, 0.8 * occ);  // without the check the occluded band gets matched
  EXPECT_GT(occ_lr, 0.6 * occ);
  EXPECT_GT(vis_good, 0.95 * vis);
}

TEST(CorrelatorTest, BorderNoMatchRangeEdgeAndFullSearch) {
  cv::Mat l, r;
  // Smooth texture (periods 30-80 px): the cost falls steadily towards the true disparity 12,
  // which lies beyond the search range [0, 10), so the minima sit at the range's edge.
  testing::ConstantDisparityPair(testing::Texture(9, 30.0, 80.0), cv::Size(80, 30), 12.0, &l, &r);
  CorrelatorOptions o;
  o.num_disparities = 10;
  auto c = Correlator::Create(o);
  ASSERT_TRUE(c.ok());
  DisparityImage out;
  ASSERT_TRUE(c->Compute(l, r, &out).ok());
  const auto status = [&](int v, int u) {
    return static_cast<PixelStatus>(out.status.at<std::uint8_t>(v, u));
  };
  for (int v = 0; v < l.rows; ++v) {
    for (int u = 0; u < l.cols; ++u) {
      if (v < 3 || v >= l.rows - 3 || u < 3 || u >= l.cols - 3) {
        EXPECT_EQ(status(v, u), PixelStatus::kBorder) << v << "," << u;
      }
    }
  }
  int edge = 0, valid = 0, n = 0;
  for (int v = 3; v < l.rows - 3; ++v) {
    for (int u = 20; u < l.cols - 3; ++u, ++n) {
      edge += status(v, u) == PixelStatus::kRangeEdge;
      valid += status(v, u) == PixelStatus::kValid;
    }
  }
  EXPECT_GT(edge, 0.9 * n);
  EXPECT_LT(valid, 0.02 * n);

  // Disparities 60..69 leave no candidate for the first 63 columns.
  o.min_disparity = 60;
  auto c2 = Correlator::Create(o);
  ASSERT_TRUE(c2.ok());
  ASSERT_TRUE(c2->Compute(l, r, &out).ok());
  EXPECT_EQ(status(10, 40), PixelStatus::kNoMatch);

  o = CorrelatorOptions();
  o.num_disparities = 16;
  o.full_search_only = true;
  auto c3 = Correlator::Create(o);
  ASSERT_TRUE(c3.ok());
  ASSERT_TRUE(c3->Compute(l, r, &out).ok());
  for (int u = 0; u < 18; ++u) EXPECT_EQ(status(10, u), PixelStatus::kBorder) << u;
  EXPECT_EQ(status(10, 30), PixelStatus::kValid);
}

TEST(CorrelatorTest, UniformImageHasNoValidPixel) {
  const cv::Mat l(30, 60, CV_8UC1, cv::Scalar(31));
  CorrelatorOptions o;
  o.num_disparities = 16;
  auto c = Correlator::Create(o);
  ASSERT_TRUE(c.ok());
  DisparityImage out;
  ASSERT_TRUE(c->Compute(l, l, &out).ok());
  EXPECT_EQ(out.CountValid(), 0);
}

TEST(CorrelatorTest, OptionsValidate) {
  CorrelatorOptions o;
  EXPECT_TRUE(o.Validate().ok());
  o.window = 8;
  EXPECT_NE(o.Validate().message().find("window"), std::string::npos);
  o = CorrelatorOptions();
  o.num_disparities = 1;
  EXPECT_NE(o.Validate().message().find("num_disparities"), std::string::npos);
  o = CorrelatorOptions();
  o.uniqueness_ratio = -0.1;
  EXPECT_FALSE(o.Validate().ok());
  o = CorrelatorOptions();
  o.lr_max_diff = -2;
  EXPECT_FALSE(o.Validate().ok());
  o = CorrelatorOptions();
  o.num_threads = 0;
  EXPECT_FALSE(Correlator::Create(o).ok());
  if (DetectSimdLevel() != SimdLevel::kAvx2) {
    o = CorrelatorOptions();
    o.simd = SimdLevel::kAvx2;
    EXPECT_FALSE(Correlator::Create(o).ok());
  }
}

TEST(CorrelatorTest, BadInputsReturnStatusNamingTheProblem) {
  auto c = Correlator::Create(CorrelatorOptions());
  ASSERT_TRUE(c.ok());
  DisparityImage out;
  const cv::Mat ok(40, 100, CV_8UC1, cv::Scalar(10));
  Status s = c->Compute(cv::Mat(), ok, &out);
  EXPECT_NE(s.message().find("left image is empty"), std::string::npos) << s.message();
  s = c->Compute(ok, cv::Mat(), &out);
  EXPECT_NE(s.message().find("right image is empty"), std::string::npos) << s.message();
  s = c->Compute(ok, cv::Mat(40, 100, CV_16UC1), &out);
  EXPECT_NE(s.message().find("CV_16UC1"), std::string::npos) << s.message();
  s = c->Compute(ok, cv::Mat(41, 100, CV_8UC1, cv::Scalar(0)), &out);
  EXPECT_NE(s.message().find("equal sizes"), std::string::npos) << s.message();
  s = c->Compute(cv::Mat(5, 5, CV_8UC1, cv::Scalar(0)), cv::Mat(5, 5, CV_8UC1, cv::Scalar(0)),
                 &out);
  EXPECT_NE(s.message().find("smaller than"), std::string::npos) << s.message();
  const cv::Mat narrow(40, 60, CV_8UC1, cv::Scalar(0));
  CorrelatorOptions far;
  far.min_disparity = 60;
  auto c2 = Correlator::Create(far);
  ASSERT_TRUE(c2.ok());
  s = c2->Compute(narrow, narrow, &out);
  EXPECT_NE(s.message().find("disparity range [60, 123]"), std::string::npos) << s.message();
  const cv::Mat bright(40, 100, CV_8UC1, cv::Scalar(250));
  CorrelatorOptions big;
  big.window = 15;
  auto c3 = Correlator::Create(big);
  ASSERT_TRUE(c3.ok());
  s = c3->Compute(bright, bright, &out);
  EXPECT_NE(s.message().find("overflow"), std::string::npos) << s.message();
  EXPECT_FALSE(c->Compute(ok, ok, nullptr).ok());
}

}  // namespace
}  // namespace rover::dl::stereo
