#include "rover/dl/arm/focus.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

namespace rover::dl::arm {
namespace {

using ::testing::HasSubstr;

constexpr int kFocusTextureSize = 256;

// A 256x256 8-bit texture with structure at 2-16 px scales: octaves of uniform noise drawn on
// 16..128 px grids (fixed seed), each upscaled (cubic) to 256 px and summed with equal weight,
// then stretched to mean 128 and standard deviation 40 DN.
cv::Mat FocusTexture() {
  cv::RNG rng(20240611);
  cv::Mat sum = cv::Mat::zeros(kFocusTextureSize, kFocusTextureSize, CV_64F);
  for (const int grid : {16, 32, 64, 128}) {
    cv::Mat noise(grid, grid, CV_64F);
    rng.fill(noise, cv::RNG::UNIFORM, 0.0, 1.0);
    cv::GaussianBlur(noise, noise, cv::Size(0, 0), 0.5);
    cv::Mat up;
    cv::resize(noise, up, cv::Size(kFocusTextureSize, kFocusTextureSize), 0, 0, cv::INTER_CUBIC);
    sum += up;
  }
  cv::Scalar mean, stddev;
  cv::meanStdDev(sum, mean, stddev);
  cv::Mat out;
  sum.convertTo(out, CV_8U, 40.0 / stddev[0], 128.0 - 40.0 * mean[0] / stddev[0]);
  return out;
}

cv::Mat FocusBlurred(const cv::Mat& image, double sigma) {
  if (sigma <= 0.0) return image.clone();
  cv::Mat out;
  cv::GaussianBlur(image, out, cv::Size(0, 0), sigma, sigma, cv::BORDER_REFLECT101);
  return out;
}

cv::Mat FocusWithNoise(const cv::Mat& image, double sigma_dn, int seed) {
  cv::RNG rng(static_cast<std::uint64_t>(seed));
  cv::Mat noise(image.size(), CV_64F);
  rng.fill(noise, cv::RNG::NORMAL, 0.0, sigma_dn);
  cv::Mat f;
  image.convertTo(f, CV_64F);
  f += noise;
  cv::Mat out;
  f.convertTo(out, CV_8U);  // rounds and saturates
  return out;
}

double FocusMeasureOf(const cv::Mat& image, const FocusMeasureOptions& o = {}) {
  const Result<double> m = WaveletFocusMeasure(image, o);
  EXPECT_TRUE(m.ok()) << m.status().message();
  return m.ok() ? *m : std::numeric_limits<double>::quiet_NaN();
}

// ---------------------------------------------------------------------------------------------
// Options

TEST(FocusMeasureOptions, DefaultsAreValid) {
  const FocusMeasureOptions o;
  EXPECT_TRUE(o.Validate().ok());
  EXPECT_EQ(o.levels, 3);
  EXPECT_EQ(o.first_level, 2);
}

TEST(FocusMeasureOptions, ValidateNamesTheField) {
  FocusMeasureOptions o;
  o.levels = 9;
  Status s = o.Validate();
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(s.message(), "focus.levels = 9 is outside [1, 6]");
  o.levels = 0;
  EXPECT_EQ(o.Validate().message().rfind("focus.levels", 0), 0u);
  o = FocusMeasureOptions{};
  o.first_level = 4;  // > levels = 3
  s = o.Validate();
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.message(), "focus.first_level = 4 is outside [1, 3]");
  o.first_level = 0;
  EXPECT_EQ(o.Validate().message().rfind("focus.first_level", 0), 0u);
}

// ---------------------------------------------------------------------------------------------
// The measure

TEST(WaveletFocusMeasure, FallsStrictlyWithBlur) {
  const cv::Mat sharp = FocusTexture();
  double previous = std::numeric_limits<double>::infinity();
  for (const double sigma : {0.0, 1.0, 2.0, 4.0, 8.0}) {
    const double m = FocusMeasureOf(FocusBlurred(sharp, sigma));
    RecordProperty("measure_sigma_" + std::to_string(static_cast<int>(sigma)), std::to_string(m));
    std::printf("focus measure (levels 2..3) at blur sigma %g px: %.6g\n", sigma, m);
    EXPECT_GT(m, 0.0) << "sigma " << sigma;
    EXPECT_LT(m, previous) << "sigma " << sigma;
    previous = m;
  }
}

TEST(WaveletFocusMeasure, FallsWithBlurAtEveryLevelChoice) {
  const cv::Mat sharp = FocusTexture();
  for (int levels = 1; levels <= 5; ++levels) {
    for (int first = 1; first <= levels; ++first) {
      FocusMeasureOptions o;
      o.levels = levels;
      o.first_level = first;
      double previous = std::numeric_limits<double>::infinity();
      for (const double sigma : {0.0, 1.0, 2.0, 4.0, 8.0}) {
        const double m = FocusMeasureOf(FocusBlurred(sharp, sigma), o);
        EXPECT_LT(m, previous) << "levels " << first << ".." << levels << " sigma " << sigma;
        previous = m;
      }
    }
  }
}

TEST(WaveletFocusMeasure, DoesNotDependOnExposure) {
  const cv::Mat sharp = FocusTexture();
  for (const double sigma : {0.0, 2.0}) {
    const cv::Mat image = FocusBlurred(sharp, sigma);
    cv::Mat dim;
    image.convertTo(dim, CV_8U, 0.5);
    const double m = FocusMeasureOf(image);
    const double m_dim = FocusMeasureOf(dim);
    EXPECT_NEAR(m_dim / m, 1.0, 0.05) << "sigma " << sigma << ": " << m << " vs " << m_dim;
  }
}

TEST(WaveletFocusMeasure, SharpAboveBlurredUnderSensorNoise) {
  const cv::Mat sharp = FocusTexture();
  const double m_sharp = FocusMeasureOf(FocusWithNoise(sharp, 2.0, 7));
  const double m_blurred = FocusMeasureOf(FocusWithNoise(FocusBlurred(sharp, 2.0), 2.0, 7));
  EXPECT_GT(m_sharp, m_blurred);
  // Skipping level 1 keeps the noise out: noise changes the sharp image's measure little.
  EXPECT_NEAR(m_sharp / FocusMeasureOf(sharp), 1.0, 0.05);
}

TEST(WaveletFocusMeasure, UniformAndBlackImagesMeasureZero) {
  EXPECT_EQ(FocusMeasureOf(cv::Mat(64, 64, CV_8UC1, cv::Scalar(0))), 0.0);
  EXPECT_EQ(FocusMeasureOf(cv::Mat(64, 64, CV_8UC1, cv::Scalar(90))), 0.0);
}

TEST(WaveletFocusMeasure, MatchesAHandComputedExample) {
  // 4x4 (levels 2, both counted); level 1 blocks:
  //   [0 4; 0 4] -> A 2, LH 0, HL -2, HH 0  (x2 blocks on the top row)
  //   [8 8; 0 0] -> A 4, LH 4, HL 0, HH 0   (x2 blocks on the bottom row)
  // E_1 = (4 + 4 + 16 + 16) / (3 * 4) = 40 / 12. Level 2 on [2 2; 4 4]: LH -1 -> E_2 = 1 / 3.
  // Mean = (16 + 32) / 16 = 3.
  const cv::Mat image = (cv::Mat_<std::uint8_t>(4, 4) << 0, 4, 0, 4,  //
                         0, 4, 0, 4,                                  //
                         8, 8, 8, 8,                                  //
                         0, 0, 0, 0);
  FocusMeasureOptions o;
  o.levels = 2;
  o.first_level = 1;
  EXPECT_NEAR(FocusMeasureOf(image, o), (40.0 / 12.0 + 1.0 / 3.0) / 9.0, 1e-12);
  o.first_level = 2;
  EXPECT_NEAR(FocusMeasureOf(image, o), (1.0 / 3.0) / 9.0, 1e-12);
}

TEST(WaveletFocusMeasure, CropsOddSizesAndTakesRois) {
  const cv::Mat sharp = FocusTexture();
  // An odd-sized region (last row and column dropped by the decomposition) and a region that is
  // not continuous in memory both work.
  const cv::Mat roi = sharp(cv::Rect(3, 5, 101, 77));
  ASSERT_FALSE(roi.isContinuous());
  EXPECT_GT(FocusMeasureOf(roi), 0.0);
  EXPECT_GT(FocusMeasureOf(sharp(cv::Rect(0, 0, 8, 9))), 0.0);  // just 2^3 px wide
}

TEST(WaveletFocusMeasure, BadInputsNameTheProblem) {
  Result<double> m = WaveletFocusMeasure(cv::Mat());
  ASSERT_FALSE(m.ok());
  EXPECT_EQ(m.status().code(), StatusCode::kInvalidArgument);
  EXPECT_THAT(m.status().message(), HasSubstr("empty"));

  m = WaveletFocusMeasure(cv::Mat(64, 64, CV_8UC3, cv::Scalar(1, 2, 3)));
  ASSERT_FALSE(m.ok());
  EXPECT_THAT(m.status().message(), HasSubstr("CV_8UC3"));
  m = WaveletFocusMeasure(cv::Mat(64, 64, CV_32FC1, cv::Scalar(1)));
  ASSERT_FALSE(m.ok());
  EXPECT_THAT(m.status().message(), HasSubstr("CV_32FC1"));

  m = WaveletFocusMeasure(cv::Mat(7, 64, CV_8UC1, cv::Scalar(1)));  // 64 wide, 7 high
  ASSERT_FALSE(m.ok());
  EXPECT_THAT(m.status().message(), HasSubstr("64x7"));
  EXPECT_THAT(m.status().message(), HasSubstr("at least 8 px"));

  FocusMeasureOptions o;
  o.levels = 9;
  m = WaveletFocusMeasure(FocusTexture(), o);
  ASSERT_FALSE(m.ok());
  EXPECT_THAT(m.status().message(), HasSubstr("focus.levels"));
}

// ---------------------------------------------------------------------------------------------
// The peak of a sweep

constexpr double kFocusStep = 0.0067;  // [m]
constexpr int kFocusSteps = 10;

// m(h) = 1 / (1 + ((h - h0) / w)^2) sampled at 0, step, ..., 9 step.
std::vector<FocusSample> FocusSweep(double h0, double w) {
  std::vector<FocusSample> s;
  for (int i = 0; i < kFocusSteps; ++i) {
    const double h = kFocusStep * i;
    const double u = (h - h0) / w;
    s.push_back({h, 1.0 / (1.0 + u * u)});
  }
  return s;
}

TEST(FindFocusPeak, InterpolatesBetweenSamples) {
  for (const double w : {0.005, 0.01, 0.02}) {
    for (const double frac : {0.1, 0.25, 0.45, 0.55, 0.75, 0.9}) {
      const double h0 = kFocusStep * (4.0 + frac);
      const std::vector<FocusSample> sweep = FocusSweep(h0, w);
      const Result<FocusPeak> p = FindFocusPeak(sweep);
      ASSERT_TRUE(p.ok()) << p.status().message();
      EXPECT_TRUE(p->bracketed);
      EXPECT_EQ(p->peak_index, frac < 0.5 ? 4 : 5) << "w " << w << " frac " << frac;
      EXPECT_NEAR(p->best_height, h0, 0.25 * kFocusStep) << "w " << w << " frac " << frac;
      EXPECT_GT(p->contrast, 1.0);
      std::printf("w %.3f h0 %.5f best %.5f error %.1f %% of the step\n", w, h0, p->best_height,
                  100.0 * (p->best_height - h0) / kFocusStep);
    }
  }
}

TEST(FindFocusPeak, ExactForAGaussianCurveOnUnevenHeights) {
  // log m is a parabola: the fit is exact whatever the spacing.
  const double h0 = 0.0213;
  const std::vector<double> heights = {0.0, 0.004, 0.011, 0.019, 0.0245, 0.031, 0.04};
  std::vector<FocusSample> s;
  for (const double h : heights)
    s.push_back({h, 3.0 * std::exp(-0.5 * std::pow((h - h0) / 0.008, 2))});
  const Result<FocusPeak> p = FindFocusPeak(s);
  ASSERT_TRUE(p.ok()) << p.status().message();
  EXPECT_EQ(p->peak_index, 3);
  EXPECT_NEAR(p->best_height, h0, 1e-12);
}

TEST(FindFocusPeak, PeakBeyondTheSweepIsNotBracketed) {
  const std::vector<FocusSample> sweep = FocusSweep(kFocusStep * 11.3, 0.01);
  const Result<FocusPeak> p = FindFocusPeak(sweep);
  ASSERT_TRUE(p.ok()) << p.status().message();
  EXPECT_FALSE(p->bracketed);
  EXPECT_EQ(p->peak_index, kFocusSteps - 1);
  EXPECT_DOUBLE_EQ(p->best_height, sweep.back().height);

  const Result<FocusPeak> before = FindFocusPeak(FocusSweep(-0.01, 0.01));
  ASSERT_TRUE(before.ok());
  EXPECT_FALSE(before->bracketed);
  EXPECT_EQ(before->peak_index, 0);
  EXPECT_DOUBLE_EQ(before->best_height, 0.0);
}

TEST(FindFocusPeak, DescendingSweepWorksAsWell) {
  // The arm lowers the imager: heights fall along the sweep.
  for (const double frac : {0.2, 0.45, 0.8}) {
    const double h0 = kFocusStep * (6.0 + frac);
    std::vector<FocusSample> sweep = FocusSweep(h0, 0.01);
    std::reverse(sweep.begin(), sweep.end());
    const Result<FocusPeak> p = FindFocusPeak(sweep);
    ASSERT_TRUE(p.ok()) << p.status().message();
    EXPECT_TRUE(p->bracketed);
    EXPECT_EQ(p->peak_index, frac < 0.5 ? 3 : 2) << frac;  // heights 9 - index steps
    EXPECT_NEAR(p->best_height, h0, 0.25 * kFocusStep) << frac;
  }
  std::vector<FocusSample> beyond = FocusSweep(kFocusStep * 11.3, 0.01);
  std::reverse(beyond.begin(), beyond.end());
  const Result<FocusPeak> p = FindFocusPeak(beyond);
  ASSERT_TRUE(p.ok());
  EXPECT_FALSE(p->bracketed);
  EXPECT_EQ(p->peak_index, 0);
}

TEST(FindFocusPeak, ContrastIsMaxOverMinAndFinite) {
  std::vector<FocusSample> s = {{0.0, 1.0}, {0.01, 4.0}, {0.02, 2.0}};
  Result<FocusPeak> p = FindFocusPeak(s);
  ASSERT_TRUE(p.ok());
  EXPECT_DOUBLE_EQ(p->contrast, 4.0);

  s[0].measure = 0.0;  // a black frame: contrast is capped, the peak falls back to its sample
  p = FindFocusPeak(s);
  ASSERT_TRUE(p.ok());
  EXPECT_DOUBLE_EQ(p->contrast, kMaxFocusContrast);
  EXPECT_DOUBLE_EQ(p->best_height, 0.01);

  s = {{0.0, 0.0}, {0.01, 0.0}, {0.02, 0.0}};
  p = FindFocusPeak(s);
  ASSERT_TRUE(p.ok());
  EXPECT_DOUBLE_EQ(p->contrast, 1.0);
  EXPECT_EQ(p->peak_index, 0);
  EXPECT_FALSE(p->bracketed);
}

TEST(FindFocusPeak, BadInputsNameTheProblem) {
  const auto expect_error = [](std::vector<FocusSample> s, const std::vector<std::string>& parts) {
    const Result<FocusPeak> p = FindFocusPeak(s);
    ASSERT_FALSE(p.ok());
    EXPECT_EQ(p.status().code(), StatusCode::kInvalidArgument);
    for (const std::string& part : parts) EXPECT_THAT(p.status().message(), HasSubstr(part));
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  expect_error({{0.0, 1.0}, {0.01, 2.0}}, {"2 samples", "at least 3"});
  expect_error({}, {"0 samples"});
  expect_error({{0.0, 1.0}, {nan, 2.0}, {0.02, 1.0}}, {"samples[1].height", "nan"});
  expect_error({{0.0, 1.0}, {0.01, 2.0}, {0.02, inf}}, {"samples[2].measure", "inf"});
  expect_error({{0.0, 1.0}, {0.01, nan}, {0.02, 1.0}}, {"samples[1].measure", "nan"});
  expect_error({{0.0, 1.0}, {0.01, -2.0}, {0.02, 1.0}}, {"samples[1].measure", "-2"});
  expect_error({{0.0, 1.0}, {0.01, 2.0}, {0.01, 1.0}},
               {"not strictly monotone", "samples[2].height = 0.01", "samples[1].height = 0.01"});
  expect_error({{0.0, 1.0}, {0.01, 2.0}, {0.005, 1.0}, {0.03, 1.0}},
               {"not strictly monotone", "samples[2].height = 0.005", "ascends"});
  expect_error({{0.03, 1.0}, {0.02, 2.0}, {0.025, 1.0}}, {"samples[2].height = 0.025", "descends"});
  expect_error({{0.0, 1.0}, {0.0, 2.0}, {0.01, 1.0}}, {"samples[1].height = 0"});
}

}  // namespace
}  // namespace rover::dl::arm
