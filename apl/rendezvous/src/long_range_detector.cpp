#include "rover/apl/rendezvous/long_range_detector.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "rover/base/format.hpp"
#include "rover/base/param_binder.hpp"
#include "rover/base/range_check.hpp"
#include "rover/base/units.hpp"

namespace rover::apl::rendezvous {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;

constexpr double kSizeSigma = 0.30;   // relative: the lit part of the lander against its height
constexpr double kGroundSigma = 0.15;  // [m] the prior's ground height at the lander
constexpr double kMinFeetSigma = 0.08;
constexpr double kWeakLineContrast = 1.0;  // texture-led groups: segments of the median contrast
constexpr double kMinStereoNcc = 0.7;   // lowest correlation of a stereo range
constexpr double kStereoSigmaPx = 0.3;  // [px] 1-sigma of the matched disparity
constexpr double kOverBright = 1.15;   // the lander's brightest part over the band's 90th percentile  // relative: the feet's row against the ground's relief
constexpr double kMaxWidthOverRamps = 1.3;  // group width up to this times the full length
constexpr double kNoPriorHalfFov = 25.0 * kDegree;

struct Seg {
  Vector2d a, b;  // a left of b
  double length = 0.0;
  double contrast = 0.0;  // mean gradient magnitude along it (Sobel units)
};

struct Group {
  std::vector<int> segs;
  cv::Rect box;
  cv::Rect anchor;  // the anchoring segment (deck top?) and the lander's height below it
  int rows = 0;
  double longest = 0.0;
  int longest_seg = -1;
};

cv::Rect Expand(const cv::Rect& r, int dx, int dy) {
  return cv::Rect(r.x - dx, r.y - dy, r.width + 2 * dx, r.height + 2 * dy);
}

double Azimuth(const geometry::CameraModel& m, const Vector2d& px) {
  const auto ray = m.Unproject(px);
  if (!ray) return 0.0;
  return std::atan2(ray->direction.y(), ray->direction.x());
}

// Quantile q in [0, 1] of a float map's values (a copy is partially sorted).
double Percentile(const cv::Mat& m, double q) {
  std::vector<float> v(m.begin<float>(), m.end<float>());
  if (v.empty()) return 0.0;
  auto at = v.begin() + static_cast<std::ptrdiff_t>(std::min(v.size() - 1, static_cast<std::size_t>(q * v.size())));
  std::nth_element(v.begin(), at, v.end());
  return *at;
}

double Median(const cv::Mat& m) { return Percentile(m, 0.5); }

// One level of the orthonormal 2-D Haar transform of `in` (even size): LL, LH (top minus bottom:
// horizontal edges), HL (left minus right: vertical edges), HH.
void Haar(const cv::Mat& in, cv::Mat* ll, cv::Mat* lh, cv::Mat* hl, cv::Mat* hh) {
  const int h = in.rows / 2, w = in.cols / 2;
  *ll = cv::Mat(h, w, CV_32F);
  *lh = cv::Mat(h, w, CV_32F);
  *hl = cv::Mat(h, w, CV_32F);
  *hh = cv::Mat(h, w, CV_32F);
  for (int r = 0; r < h; ++r) {
    const float* t = in.ptr<float>(2 * r);
    const float* b = in.ptr<float>(2 * r + 1);
    for (int c = 0; c < w; ++c) {
      const float a = t[2 * c], bb = t[2 * c + 1], cc = b[2 * c], d = b[2 * c + 1];
      ll->at<float>(r, c) = 0.5F * (a + bb + cc + d);
      lh->at<float>(r, c) = 0.5F * (a + bb - cc - d);
      hl->at<float>(r, c) = 0.5F * (a - bb + cc - d);
      hh->at<float>(r, c) = 0.5F * (a - bb - cc + d);
    }
  }
}

Status CheckImage(const cv::Mat& im, const geometry::CameraModel& m) {
  if (im.empty()) return InvalidArgument("left image: empty image");
  if (im.type() != CV_8UC1) return InvalidArgument("left image: not an 8-bit grey image");
  if (im.cols != m.width() || im.rows != m.height()) {
    return InvalidArgument("left image: " + std::to_string(im.cols) + "x" + std::to_string(im.rows) +
                           " image but a " + std::to_string(m.width()) + "x" +
                           std::to_string(m.height()) + " camera model");
  }
  return Status::Ok();
}

class FarDetector {
 public:
  FarDetector(const cv::Mat& im, const geometry::CameraModel& m, const cv::Mat& right,
              const geometry::CameraModel* right_model, const hwconfig::LanderDescription& lander,
              const LongRangeOptions& o, const std::optional<LanderPrior>& prior)
      : im_(im), m_(m), right_(right), rm_(right_model), lander_(lander), o_(o), prior_(prior) {}

  FarSighting Run() {
    FarSighting s;
    if (!MakeBand(&s)) return s;
    s.band = band_;
    FindSegments();
    s.line_candidates = LineCandidates();
    s.texture_candidates = TextureCandidates();
    // Fusion: a line group whose anchor region (the top segment and the lander's height
    // below it) overlaps a texture candidate. Every group is tried, not only those the line
    // cue's own suppression kept (a wide group on an outcrop may cover the lander's).
    int best = -1;
    double best_score = -1.0;
    for (std::size_t i = 0; i < groups_.size(); ++i) {
      const Group& g = groups_[i];
      double tex = 0.0;
      cv::Rect tex_box;
      for (const CueBox& t : s.texture_candidates) {
        if ((g.anchor & t.box).area() > 0) {
          tex = std::max(tex, t.strength);
          tex_box |= t.box;
        }
      }
      if (tex <= 0.0) continue;
      bool seen = false;
      for (const CueBox& f : s.fused) seen = seen || (f.box & g.anchor).area() > 0;
      if (!seen) s.fused.push_back({g.anchor, static_cast<double>(g.rows)});
      double score = g.rows + 0.5 * static_cast<double>(g.segs.size()) + tex / 3.0;
      if (prior_) {
        const double db = std::abs(Azimuth(m_, Center(g)) - prior_->bearing);
        score -= 2.0 * db / std::max(prior_->bearing_window, 1e-3);
      }
      if (score > best_score) {
        best_score = score;
        best = static_cast<int>(i);
        best_tex_ = tex_box;
      }
    }
    if (best < 0) {
      best = TextureLedGroup(s.texture_candidates, &best_tex_);
      if (best >= 0) {
        texture_led_ = true;
        s.fused.push_back({groups_[static_cast<std::size_t>(best)].anchor, 0.0});
      }
    }
    if (best < 0) {
      s.reason = "no co-located line and texture candidate (" +
                 std::to_string(s.line_candidates.size()) + " line from " +
                 std::to_string(segs_.size()) + " level segments, " +
                 std::to_string(s.texture_candidates.size()) + " texture)";
      // The strong level segments, drawn orange: what the line cue had to work with.
      for (const Seg& sg : segs_) s.lines.push_back({sg.a, sg.b, LanderLine::Kind::kTruss});
      return s;
    }
    Measure(groups_[static_cast<std::size_t>(best)], &s);
    return s;
  }

 private:
  Vector2d Center(const Group& g) const {
    const Seg& l = segs_[static_cast<std::size_t>(g.longest_seg)];
    return 0.5 * (l.a + l.b);
  }

  // The image box of the lander's possible positions; focal length and level direction.
  bool MakeBand(FarSighting* s) {
    double b0 = 0.0, bw = kNoPriorHalfFov, r_lo = o_.min_range, r_hi = o_.max_range;
    const double z0 = prior_ ? prior_->ground_z : 0.0;
    if (prior_) {
      b0 = prior_->bearing;
      bw = prior_->bearing_window;
      r_lo = std::max(o_.min_range, prior_->range - prior_->range_window);
      r_hi = std::min(o_.max_range, prior_->range + prior_->range_window);
    } else {
      b0 = Azimuth(m_, Vector2d(0.5 * (m_.width() - 1), 0.5 * (m_.height() - 1)));
    }
    if (r_hi <= r_lo) {
      s->reason = "the prior's range window is outside [min_range, max_range]";
      return false;
    }
    r_lo_ = r_lo;
    r_mid_ = prior_ ? std::clamp(prior_->range, r_lo, r_hi) : 0.5 * (r_lo + r_hi);
    double u0 = 1e9, u1 = -1e9, v0 = 1e9, v1 = -1e9;
    int projected = 0;
    for (double b : {b0 - bw, b0 - 0.5 * bw, b0, b0 + 0.5 * bw, b0 + bw}) {
      for (double r : {r_lo, r_mid_, r_hi}) {
        for (double z : {z0 - 0.6, z0 + lander_.deck_height + 0.4}) {
          const auto px = m_.Project(Vector3d(r * std::cos(b), r * std::sin(b), z));
          if (!px) continue;
          ++projected;
          u0 = std::min(u0, px->x());
          u1 = std::max(u1, px->x());
          v0 = std::min(v0, px->y());
          v1 = std::max(v1, px->y());
        }
      }
    }
    const cv::Rect image(0, 0, im_.cols, im_.rows);
    const cv::Rect band(static_cast<int>(std::floor(u0)) - 4, static_cast<int>(std::floor(v0)) - 4,
                        static_cast<int>(std::ceil(u1 - u0)) + 9,
                        static_cast<int>(std::ceil(v1 - v0)) + 9);
    band_ = band & image;
    band_.width -= band_.width % 4;
    band_.height -= band_.height % 4;
    if (projected == 0 || band_.width < 16 || band_.height < 8) {
      s->reason = "the search window is outside the image";
      return false;
    }
    // Focal length [px] and the image of a level line at the prior range.
    const Vector3d p(r_mid_ * std::cos(b0), r_mid_ * std::sin(b0), z0 + 0.5);
    const Vector3d lat(-std::sin(b0), std::cos(b0), 0.0);
    const auto a = m_.Project(p - 0.5 * lat), c = m_.Project(p + 0.5 * lat);
    if (!a || !c) {
      s->reason = "the prior direction does not project into the image";
      return false;
    }
    f_ = (*c - *a).norm() * r_mid_;
    level_ = (*c - *a).normalized();
    return true;
  }

  void FindSegments() {
    cv::Mat roi = im_(band_), blurred, edges, gx, gy, mag;
    cv::GaussianBlur(roi, blurred, cv::Size(3, 3), 0.8);
    cv::Canny(blurred, edges, o_.canny_low, o_.canny_high);
    cv::Sobel(blurred, gx, CV_32F, 1, 0);
    cv::Sobel(blurred, gy, CV_32F, 0, 1);
    cv::magnitude(gx, gy, mag);
    std::vector<cv::Vec4i> lines;
    cv::HoughLinesP(edges, lines, 1.0, kDegree, o_.min_line_length, o_.min_line_length, 1.0);
    const double tol = std::sin(o_.level_tolerance_deg * kDegree);
    const double max_len = kMaxWidthOverRamps * 2.0 * (lander_.Apothem() + lander_.ramp_length) * f_ / r_lo_;
    std::vector<Seg> level;
    for (const cv::Vec4i& l : lines) {
      Seg sg;
      sg.a = Vector2d(l[0] + band_.x, l[1] + band_.y);
      sg.b = Vector2d(l[2] + band_.x, l[3] + band_.y);
      if (sg.a.x() > sg.b.x()) std::swap(sg.a, sg.b);
      const Vector2d d = sg.b - sg.a;
      sg.length = d.norm();
      if (sg.length < o_.min_line_length || sg.length > max_len) continue;
      const double cross = std::abs(d.x() * level_.y() - d.y() * level_.x()) / sg.length;
      if (cross > tol) continue;
      // Contrast: the mean gradient magnitude along the segment (the strongest of the row and
      // its two neighbours at each step).
      const int steps = std::max(2, static_cast<int>(sg.length));
      double sum = 0.0;
      for (int k = 0; k <= steps; ++k) {
        const Vector2d p = sg.a + d * (static_cast<double>(k) / steps);
        const int c = std::clamp(static_cast<int>(std::lround(p.x())) - band_.x, 0, mag.cols - 1);
        const int r = static_cast<int>(std::lround(p.y())) - band_.y;
        float best = 0.0F;
        for (int dr = -1; dr <= 1; ++dr) best = std::max(best, mag.at<float>(std::clamp(r + dr, 0, mag.rows - 1), c));
        sum += best;
      }
      sg.contrast = sum / (steps + 1);
      level.push_back(sg);
    }
    // Keep the strong ones: the painted lander's edges stand out of the soil and rock grain.
    std::vector<double> c;
    for (const Seg& sg : level) c.push_back(sg.contrast);
    double median = 0.0;
    if (!c.empty()) {
      std::nth_element(c.begin(), c.begin() + static_cast<std::ptrdiff_t>(c.size() / 2), c.end());
      median = c[c.size() / 2];
    }
    for (const Seg& sg : level) {
      if (sg.contrast >= o_.min_line_contrast * median) {
        segs_.push_back(sg);
      } else if (sg.contrast >= kWeakLineContrast * median) {
        weak_.push_back(sg);
      }
    }
  }

  // Texture-led fusion, when no line group met a texture candidate: the level segments (strong
  // or of at least the band's median contrast) inside a texture candidate, on >= min_group_lines
  // rows. A lander against a bright background (a light sand patch or the far apron behind it)
  // keeps its texture but loses the contrast of its level edges. Returns the group's index.
  int TextureLedGroup(const std::vector<CueBox>& texture, cv::Rect* tex_box) {
    int best = -1;
    double best_score = -1e9;
    for (const CueBox& t : texture) {
      const cv::Rect box = Expand(t.box, 2, 2);
      Group g;
      std::vector<double> ys;
      double x0 = 1e9, x1 = -1e9, y0 = 1e9, y1 = -1e9;
      auto take = [&](const Seg& sg) {
        const Vector2d m = 0.5 * (sg.a + sg.b);
        if (!box.contains(cv::Point(static_cast<int>(m.x()), static_cast<int>(m.y())))) return;
        segs_.push_back(sg);
        const int j = static_cast<int>(segs_.size()) - 1;
        g.segs.push_back(j);
        x0 = std::min(x0, sg.a.x());
        x1 = std::max(x1, sg.b.x());
        y0 = std::min({y0, sg.a.y(), sg.b.y()});
        y1 = std::max({y1, sg.a.y(), sg.b.y()});
        ys.push_back(m.y());
        if (sg.length > g.longest) {
          g.longest = sg.length;
          g.longest_seg = j;
        }
      };
      const std::vector<Seg> strong(segs_.begin(), segs_.end());
      for (const Seg& sg : strong) take(sg);
      for (const Seg& sg : weak_) take(sg);
      std::sort(ys.begin(), ys.end());
      g.rows = ys.empty() ? 0 : 1;
      for (std::size_t k = 1; k < ys.size(); ++k) {
        if (ys[k] - ys[k - 1] >= 2.0) ++g.rows;
      }
      if (g.rows < o_.min_group_lines) continue;
      g.box = cv::Rect(static_cast<int>(std::floor(x0)), static_cast<int>(std::floor(y0)),
                       static_cast<int>(std::ceil(x1 - x0)) + 1, static_cast<int>(std::ceil(y1 - y0)) + 1);
      g.anchor = t.box;
      double score = t.strength;
      if (prior_) {
        const double db = std::abs(Azimuth(m_, Center(g)) - prior_->bearing);
        score -= 2.0 * db / std::max(prior_->bearing_window, 1e-3);
      }
      groups_.push_back(g);
      if (score > best_score) {
        best_score = score;
        best = static_cast<int>(groups_.size()) - 1;
        *tex_box = t.box;
      }
    }
    return best;
  }

  // Line candidates: each long enough level segment anchors a window of the lander's image size
  // at the prior range below it (the deck top is the lander's highest level edge); the level
  // segments with their middle in the window form the group. Overlapping groups keep the one
  // with most rows (no transitive chaining: a cluttered band would chain into one group).
  std::vector<CueBox> LineCandidates() {
    const double span = 2.0 * (lander_.Apothem() + lander_.ramp_length);  // [m] widest silhouette
    const double w_win = kMaxWidthOverRamps * span * f_ / r_mid_;
    const double h_win = (lander_.deck_height + 0.3) * f_ / r_mid_ + 2.0;
    const double anchor_min = std::max(static_cast<double>(o_.min_line_length), 0.25 * 2.0 * lander_.Apothem() * f_ / r_mid_);
    for (std::size_t i = 0; i < segs_.size(); ++i) {
      const Seg& a = segs_[i];
      if (a.length < anchor_min) continue;
        const Vector2d c = 0.5 * (a.a + a.b);
      Group g;
      std::vector<double> ys;
      double x0 = 1e9, x1 = -1e9, y0 = 1e9, y1 = -1e9;
      for (std::size_t j = 0; j < segs_.size(); ++j) {
        const Seg& s = segs_[j];
        const Vector2d m = 0.5 * (s.a + s.b);
        if (std::abs(m.x() - c.x()) > 0.5 * w_win || m.y() < c.y() - 1.5 || m.y() > c.y() + h_win) continue;
        g.segs.push_back(static_cast<int>(j));
        x0 = std::min(x0, s.a.x());
        x1 = std::max(x1, s.b.x());
        y0 = std::min({y0, s.a.y(), s.b.y()});
        y1 = std::max({y1, s.a.y(), s.b.y()});
        ys.push_back(m.y());
        if (s.length > g.longest) {
          g.longest = s.length;
          g.longest_seg = static_cast<int>(j);
        }
      }
      std::sort(ys.begin(), ys.end());
      g.rows = 1;
      for (std::size_t k = 1; k < ys.size(); ++k) {
        if (ys[k] - ys[k - 1] >= 2.0) ++g.rows;
      }
      if (g.rows < o_.min_group_lines) continue;
      g.box = cv::Rect(static_cast<int>(std::floor(x0)), static_cast<int>(std::floor(y0)),
                       static_cast<int>(std::ceil(x1 - x0)) + 1, static_cast<int>(std::ceil(y1 - y0)) + 1);
      g.anchor = cv::Rect(static_cast<int>(std::floor(a.a.x())), static_cast<int>(std::floor(c.y() - 2.0)),
                          static_cast<int>(std::ceil(a.length)) + 1, static_cast<int>(std::ceil(h_win)) + 3);
      groups_.push_back(g);
    }
    std::sort(groups_.begin(), groups_.end(), [](const Group& a, const Group& b) {
      return a.rows != b.rows ? a.rows > b.rows : a.segs.size() > b.segs.size();
    });
    // The line cue alone, as a detector: non-overlapping groups, most rows first.
    std::vector<CueBox> out;
    for (const Group& g : groups_) {
      bool overlaps = false;
      for (const CueBox& k : out) overlaps = overlaps || (g.box & k.box).area() > 0;
      if (!overlaps) out.push_back({g.box, static_cast<double>(g.segs.size())});
    }
    return out;
  }

  std::vector<CueBox> TextureCandidates() const {
    cv::Mat f32;
    im_(band_).convertTo(f32, CV_32F);
    cv::Mat ll1, lh1, hl1, hh1, ll2, lh2, hl2, hh2;
    Haar(f32, &ll1, &lh1, &hl1, &hh1);
    Haar(ll1, &ll2, &lh2, &hl2, &hh2);
    // Energies per level-1 cell: a level-2 coefficient covers 2 x 2 level-1 cells.
    cv::Mat e1 = lh1.mul(lh1) + hl1.mul(hl1) + hh1.mul(hh1);
    cv::Mat e2c = (lh2.mul(lh2) + hl2.mul(hl2) + hh2.mul(hh2)) * 0.25;
    cv::Mat e2, l2;
    cv::resize(e2c, e2, e1.size(), 0, 0, cv::INTER_NEAREST);
    cv::resize(ll2, l2, e1.size(), 0, 0, cv::INTER_NEAREST);
    const double deck_px = 2.0 * lander_.Apothem() * f_ / r_mid_;
    const int wx = std::clamp(static_cast<int>(std::lround(0.25 * deck_px)), 3, 15);
    const int wy = std::clamp(static_cast<int>(std::lround(0.25 * lander_.deck_height * f_ / r_mid_)), 2, 8);
    cv::Mat b1, b2, lmax;
    cv::blur(e1, b1, cv::Size(wx, wy));
    cv::blur(e2, b2, cv::Size(wx, wy));
    cv::dilate(l2, lmax, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(2 * wx + 1, 2 * wy + 1)));
    const double med_e2 = std::max(1.0, Median(b2));
    const double med_l = std::max(1.0, Median(l2));
    median_grey_ = 0.25 * med_l;  // LL2 is 4 x the mean of its 4 x 4 pixels
    // The painted lander outshines the band's bright background too (a far apron or sunlit
    // soil filling a tenth of the band): its brightest part must beat the 90th percentile.
    const double bright = std::max(o_.min_brightness * med_l, kOverBright * Percentile(l2, 0.9));
    cv::Mat mask(b1.size(), CV_8U, cv::Scalar(0));
    cv::Mat contrast(b1.size(), CV_32F, cv::Scalar(0));
    for (int r = 0; r < b1.rows; ++r) {
      for (int c = 0; c < b1.cols; ++c) {
        const double E2 = b2.at<float>(r, c), E1 = b1.at<float>(r, c);
        const double C = std::sqrt(E2 / med_e2);
        contrast.at<float>(r, c) = static_cast<float>(C);
        if (C >= o_.min_contrast && E1 <= o_.max_fine_ratio * E2 &&
            lmax.at<float>(r, c) >= bright) {
          mask.at<std::uint8_t>(r, c) = 255;
        }
      }
    }
    cv::Mat labels, stats, centroids;
    const int n = cv::connectedComponentsWithStats(mask, labels, stats, centroids, 8);
    std::vector<CueBox> out;
    for (int k = 1; k < n; ++k) {
      const int x = stats.at<int>(k, cv::CC_STAT_LEFT), y = stats.at<int>(k, cv::CC_STAT_TOP);
      const int w = stats.at<int>(k, cv::CC_STAT_WIDTH), h = stats.at<int>(k, cv::CC_STAT_HEIGHT);
      double peak = 0.0;
      for (int r = y; r < y + h; ++r) {
        for (int c = x; c < x + w; ++c) {
          if (labels.at<int>(r, c) == k) peak = std::max(peak, static_cast<double>(contrast.at<float>(r, c)));
        }
      }
      // Level-1 cells to pixels, grown by half a window (the mask marks window centres).
      const cv::Rect box(band_.x + 2 * (x - wx / 2), band_.y + 2 * (y - wy / 2), 2 * (w + wx),
                         2 * (h + wy));
      out.push_back({box & cv::Rect(0, 0, im_.cols, im_.rows), peak});
    }
    return out;
  }

  // Range of the left-image patch by correlation along its ray (see Measure). False when the
  // best correlation is below kMinStereoNcc or at the end of the searched range.
  bool StereoRange(const cv::Rect& patch, double* range, double* sigma, double* ncc_out) const {
    if (patch.width < 5 || patch.height < 4) return false;
    const Vector2d c(patch.x + 0.5 * (patch.width - 1), patch.y + 0.5 * (patch.height - 1));
    const auto ray = m_.Unproject(c);
    if (!ray) return false;
    cv::Mat tpl;
    im_(patch).convertTo(tpl, CV_32F);
    cv::Scalar tm, ts;
    cv::meanStdDev(tpl, tm, ts);
    if (ts[0] < 3.0) return false;
    // Hypotheses: distances t along the ray, stepped so the right image moves ~0.25 px.
    const double t_lo = std::max(2.0, (prior_ ? std::max(o_.min_range, prior_->range - prior_->range_window) : o_.min_range) * 0.8);
    const double t_hi = (prior_ ? std::min(o_.max_range, prior_->range + prior_->range_window) : o_.max_range) * 1.25;
    std::vector<double> ts_, scores;
    double t = t_lo;
    const cv::Size sz(patch.width, patch.height);
    while (t <= t_hi && ts_.size() < 2000) {
      const Vector3d p = ray->origin + t * ray->direction;
      const auto pr = rm_->Project(p);
      if (!pr) break;
      cv::Mat win;
      cv::getRectSubPix(right_, sz, cv::Point2f(static_cast<float>(pr->x()), static_cast<float>(pr->y())), win, CV_32F);
      cv::Scalar wm, wsd;
      cv::meanStdDev(win, wm, wsd);
      double score = -1.0;
      if (wsd[0] > 1e-3) {
        score = (tpl - tm[0]).dot(win - wm[0]) / (static_cast<double>(tpl.total()) * ts[0] * wsd[0]);
      }
      ts_.push_back(t);
      scores.push_back(score);
      // Step: the right pixel moves by about f B / t^2 per metre; keep ~0.25 px per step.
      const auto pr2 = rm_->Project(ray->origin + (t * 1.01) * ray->direction);
      const double px_per_m = pr2 ? std::max(1e-4, (*pr2 - *pr).norm() / (0.01 * t)) : 1e-2;
      t += std::max(0.02, 0.25 / px_per_m);
    }
    if (scores.size() < 3) return false;
    const auto best = std::max_element(scores.begin(), scores.end());
    const std::size_t k = static_cast<std::size_t>(best - scores.begin());
    if (*best < kMinStereoNcc || k == 0 || k + 1 == scores.size()) return false;
    // Parabola through the three scores around the peak (in t, unevenly spaced: use the
    // local spacing as equal, the steps change slowly).
    const double ym = scores[k - 1], y0 = scores[k], yp = scores[k + 1];
    const double den = ym - 2.0 * y0 + yp;
    const double off = std::abs(den) > 1e-9 ? std::clamp(0.5 * (ym - yp) / den, -0.5, 0.5) : 0.0;
    const double step = 0.5 * (ts_[k + 1] - ts_[k - 1]);
    const double t_best = ts_[k] + off * step;
    const Vector3d p = ray->origin + t_best * ray->direction;
    *range = std::hypot(p.x(), p.y());
    // 1-sigma: kStereoSigmaPx of disparity, a step being ~0.25 px.
    *sigma = std::max(0.01 * *range, step * (kStereoSigmaPx / 0.25) * (*range / t_best));
    *ncc_out = *best;
    return true;
  }

  void Measure(const Group& g, FarSighting* s) {
    // The lander's painted parts are the brightest in the fused region: their largest bright
    // component spans the deck top to the ramp feet (deck_height), whatever the lander's yaw.
    const cv::Rect region = (Expand(g.box, 2, 2) | best_tex_) & band_;
    cv::Mat bright;
    cv::threshold(im_(region), bright, std::min(254.0, o_.min_brightness * median_grey_), 255,
                  cv::THRESH_BINARY);
    cv::Mat labels, stats, centroids;
    const int n = cv::connectedComponentsWithStats(bright, labels, stats, centroids, 8);
    int k_best = -1, area = 0;
    for (int k = 1; k < n; ++k) {
      if (stats.at<int>(k, cv::CC_STAT_AREA) > area) {
        area = stats.at<int>(k, cv::CC_STAT_AREA);
        k_best = k;
      }
    }
    double h = 0.0, w = 0.0;
    Vector2d mid = Center(g);
    if (k_best > 0) {
      h = stats.at<int>(k_best, cv::CC_STAT_HEIGHT);
      w = stats.at<int>(k_best, cv::CC_STAT_WIDTH);
      mid = Vector2d(region.x + centroids.at<double>(k_best, 0), region.y + centroids.at<double>(k_best, 1));
    }
    const double h_px = std::max(h, 2.0);
    // (a) Angular size: deck top to ramp feet is deck_height; at long range the lit part reads
    // short by a pixel or two, hence the wide sigma.
    const double r_size = lander_.deck_height * f_ / h_px;
    const double s_size = std::hypot(o_.extent_sigma_px / h_px, kSizeSigma) * r_size;
    // (b) Where the feet meet the ground: the row of the component's bottom seen as a point on
    // the ground plane at the prior's ground height (kGroundSigma), by bisection along the ray.
    double range = r_size, range_sigma = s_size;
    if (k_best > 0) {
      // The centre of the component's last row (pixel centres at integer coordinates).
      const double v_feet = region.y + stats.at<int>(k_best, cv::CC_STAT_TOP) + h - 1.0;
      const double b = Azimuth(m_, mid);
      const double z0 = prior_ ? prior_->ground_z : 0.0;
      const auto ground_range = [&](double v, double z) {
        double lo = 1.0, hi = 4.0 * o_.max_range;
        for (int it = 0; it < 60; ++it) {
          const double r = 0.5 * (lo + hi);
          const auto px = m_.Project(Vector3d(r * std::cos(b), r * std::sin(b), z));
          if (!px) return -1.0;
          (px->y() > v ? lo : hi) = r;  // farther ground points image higher (smaller v)
        }
        return 0.5 * (lo + hi);
      };
      const double r_g = ground_range(v_feet, z0);
      const double r_far = ground_range(v_feet - o_.extent_sigma_px, z0 + kGroundSigma);
      const double r_near = ground_range(v_feet + o_.extent_sigma_px, z0 - kGroundSigma);
      // The feet are trusted only where they agree with the size (a bright part that ends
      // above the ground, e.g. a ramp turned away, would put them far beyond).
      if (r_g > 0.0 && r_far > 0.0 && r_near > 0.0 && r_g < 2.0 * o_.max_range &&
          std::abs(r_g - r_size) <= 2.0 * s_size) {
        const double s_g = std::max(0.5 * (r_far - r_near), kMinFeetSigma * r_g);
        const double w_size = 1.0 / (s_size * s_size), w_g = 1.0 / (s_g * s_g);
        range = (w_size * r_size + w_g * r_g) / (w_size + w_g);
        range_sigma = 1.0 / std::sqrt(w_size + w_g);
        ground_range_ = r_g;
      }
    }
    // (c) Stereo: the lit part's patch slid along its left ray, each hypothesised range
    // projected into the right image; the best normalised cross-correlation, refined by a
    // parabola. Replaces (a) and (b) when it correlates: at 125 m the disparity is ~2 px and
    // 0.25 px of it is 12 %, but it does not depend on the ground or on what is lit.
    if (k_best > 0 && rm_ != nullptr && !right_.empty()) {
      const cv::Rect patch = Expand(cv::Rect(region.x + stats.at<int>(k_best, cv::CC_STAT_LEFT),
                                             region.y + stats.at<int>(k_best, cv::CC_STAT_TOP),
                                             static_cast<int>(w), static_cast<int>(h)),
                                    3, 2) &
                             cv::Rect(0, 0, im_.cols, im_.rows);
      double r_st = 0.0, s_st = 0.0, ncc = 0.0;
      if (StereoRange(patch, &r_st, &s_st, &ncc)) {
        // The lit part is mostly a ramp, between the deck edge and its foot: on average half
        // of (apothem + half a ramp) nearer than the deck centre, as much either way.
        const double depth = 0.5 * (lander_.Apothem() + 0.5 * lander_.ramp_length);
        range = r_st + depth;
        range_sigma = std::hypot(s_st, depth);
        stereo_range_ = r_st;
        stereo_ncc_ = ncc;
      }
    }
    const double rel = range_sigma / range;
    s->found = true;
    s->box = k_best > 0 ? cv::Rect(region.x + stats.at<int>(k_best, cv::CC_STAT_LEFT),
                                   region.y + stats.at<int>(k_best, cv::CC_STAT_TOP),
                                   static_cast<int>(w), static_cast<int>(h))
                        : g.box;
    s->bearing = Azimuth(m_, mid);
    s->bearing_sigma = std::max(0.25 * std::max(w, 4.0) / f_, 1.0 / f_);
    s->range = range;
    s->range_sigma = rel * range;
    // The deck top: on the ray through the component's top row at the bearing, at horizontal
    // range `range` from the rover origin (so the rover's pitch and roll carry into its height).
    s->center = Vector3d(range * std::cos(s->bearing), range * std::sin(s->bearing), lander_.deck_height);
    if (k_best > 0) {
      const double v_top = region.y + stats.at<int>(k_best, cv::CC_STAT_TOP);
      if (const auto ray = m_.Unproject(Vector2d(mid.x(), v_top)); ray) {
        const Eigen::Vector2d c(ray->origin.x(), ray->origin.y()), d(ray->direction.x(), ray->direction.y());
        const double a = d.squaredNorm(), b = 2.0 * c.dot(d), cc = c.squaredNorm() - range * range;
        const double disc = b * b - 4.0 * a * cc;
        if (a > 1e-12 && disc >= 0.0) {
          const double t = (-b + std::sqrt(disc)) / (2.0 * a);
          if (t > 0.0) s->center = ray->origin + t * ray->direction;
        }
      }
    }
    const Eigen::Matrix2d R =
        (Eigen::Matrix2d() << std::cos(s->bearing), -std::sin(s->bearing), std::sin(s->bearing),
         std::cos(s->bearing))
            .finished();
    const Eigen::Vector2d sig(s->range_sigma, range * s->bearing_sigma);
    s->center_covariance.setZero();
    s->center_covariance.topLeftCorner<2, 2>() = R * sig.cwiseAbs2().asDiagonal() * R.transpose();
    s->center_covariance(2, 2) = std::pow(0.5 * lander_.deck_height, 2);
    for (int i : g.segs) {
      const Seg& sg = segs_[static_cast<std::size_t>(i)];
      s->lines.push_back({sg.a, sg.b, LanderLine::Kind::kDeck});
    }
    char buf[160];
    std::snprintf(buf, sizeof buf,
                  "far%s: lines %zu on %d rows, lander %.0fx%.0f px (size %.0f m, feet %.0f m, stereo %.0f m ncc %.2f); %zu line / %zu texture candidates",
                  texture_led_ ? " (texture-led)" : "", g.segs.size(), g.rows, w, h, r_size, ground_range_, stereo_range_, stereo_ncc_,
                  s->line_candidates.size(), s->texture_candidates.size());
    s->features = buf;
    s->reason = "lander at " + FormatNumber(range) + " m";
  }

  const cv::Mat& im_;
  const geometry::CameraModel& m_;
  const cv::Mat& right_;
  const geometry::CameraModel* rm_;
  const hwconfig::LanderDescription& lander_;
  const LongRangeOptions& o_;
  const std::optional<LanderPrior>& prior_;
  cv::Rect band_;
  double f_ = 1.0, r_lo_ = 1.0, r_mid_ = 1.0;
  Vector2d level_ = Vector2d::UnitX();
  std::vector<Seg> segs_;
  std::vector<Group> groups_;
  mutable double median_grey_ = 128.0;
  double ground_range_ = 0.0;
  double stereo_range_ = 0.0;
  double stereo_ncc_ = 0.0;
  std::vector<Seg> weak_;  // level segments of at least the median contrast, not strong
  bool texture_led_ = false;
  cv::Rect best_tex_;
};

}  // namespace

Status LongRangeOptions::Validate(const char* prefix) const {
  const std::string p(prefix);
  ROVER_RETURN_IF_ERROR(CheckRange(p + "min_range", min_range, 2.0, 500.0, "m"));
  ROVER_RETURN_IF_ERROR(CheckRange(p + "max_range", max_range, Bounds::OpenLow(min_range, 1000.0), "m"));
  ROVER_RETURN_IF_ERROR(CheckRange(p + "canny_low", canny_low, 1.0, 1000.0));
  ROVER_RETURN_IF_ERROR(CheckRange(p + "canny_high", canny_high, canny_low, 2000.0));
  ROVER_RETURN_IF_ERROR(CheckRange(p + "level_tolerance_deg", level_tolerance_deg, 0.5, 45.0, "deg"));
  ROVER_RETURN_IF_ERROR(CheckRange(p + "min_line_length", min_line_length, 3, 200, "px"));
  ROVER_RETURN_IF_ERROR(CheckRange(p + "min_group_lines", min_group_lines, 1, 20));
  ROVER_RETURN_IF_ERROR(CheckRange(p + "min_line_contrast", min_line_contrast, 0.0, 20.0));
  ROVER_RETURN_IF_ERROR(CheckRange(p + "min_contrast", min_contrast, 0.0, 100.0));
  ROVER_RETURN_IF_ERROR(CheckRange(p + "max_fine_ratio", max_fine_ratio, Bounds::OpenLow(0.0, 100.0)));
  ROVER_RETURN_IF_ERROR(CheckRange(p + "min_brightness", min_brightness, 0.0, 100.0));
  ROVER_RETURN_IF_ERROR(CheckRange(p + "extent_sigma_px", extent_sigma_px, Bounds::OpenLow(0.0, 20.0), "px"));
  return Status::Ok();
}

void LongRangeOptions::BindParams(ParamBinder<LongRangeOptions>& b) {
  using O = LongRangeOptions;
  b.Bind("min_range", &O::min_range, "m", "nearest lander range searched without a prior");
  b.Bind("max_range", &O::max_range, "m", "farthest lander range searched");
  b.Bind("canny_low", &O::canny_low, "", "Canny lower hysteresis threshold [grey levels]");
  b.Bind("canny_high", &O::canny_high, "", "Canny upper hysteresis threshold [grey levels]");
  b.Bind("level_tolerance_deg", &O::level_tolerance_deg, "deg", "level segment: angle to a level line");
  b.Bind("min_line_length", &O::min_line_length, "px", "shortest Hough segment");
  b.Bind("min_group_lines", &O::min_group_lines, "", "segments on distinct rows in a line candidate");
  b.Bind("min_line_contrast", &O::min_line_contrast, "", "segment contrast over the band's median segment");
  b.Bind("min_contrast", &O::min_contrast, "", "texture: coarse detail over the band's median");
  b.Bind("max_fine_ratio", &O::max_fine_ratio, "", "texture: fine over coarse detail energy");
  b.Bind("min_brightness", &O::min_brightness, "", "texture: brightest part over the band's median");
  b.Bind("extent_sigma_px", &O::extent_sigma_px, "px", "1-sigma of a measured width");
}

Result<FarSighting> DetectLanderFar(const cv::Mat& left8, const geometry::CameraModel& left_model,
                                    const cv::Mat& right8, const geometry::CameraModel* right_model,
                                    const hwconfig::LanderDescription& lander,
                                    const LongRangeOptions& options,
                                    const std::optional<LanderPrior>& prior) {
  const auto t0 = std::chrono::steady_clock::now();
  ROVER_RETURN_IF_ERROR(options.Validate());
  ROVER_RETURN_IF_ERROR(lander.Validate());
  ROVER_RETURN_IF_ERROR(CheckImage(left8, left_model));
  if (!right8.empty()) {
    if (right_model == nullptr) return InvalidArgument("right image: given without a right model");
    if (right8.type() != CV_8UC1 || right8.cols != right_model->width() || right8.rows != right_model->height()) {
      return InvalidArgument("right image: not an 8-bit grey image of its model's size");
    }
  }
  if (prior) {
    ROVER_RETURN_IF_ERROR(CheckFinite("prior.bearing", prior->bearing));
    ROVER_RETURN_IF_ERROR(CheckPositive("prior.bearing_window", prior->bearing_window, "rad"));
    ROVER_RETURN_IF_ERROR(CheckPositive("prior.range", prior->range, "m"));
    ROVER_RETURN_IF_ERROR(CheckPositive("prior.range_window", prior->range_window, "m"));
    ROVER_RETURN_IF_ERROR(CheckFinite("prior.ground_z", prior->ground_z));
  }
  FarDetector d(left8, left_model, right8, right8.empty() ? nullptr : right_model, lander, options, prior);
  FarSighting s = d.Run();
  s.elapsed_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return s;
}

void DrawFarSighting(cv::Mat* bgr, const FarSighting& s) {
  if (bgr == nullptr || bgr->empty()) return;
  const double scale = std::max(0.5, bgr->cols / 1024.0);
  const int thick = std::max(1, static_cast<int>(std::lround(scale)));
  cv::rectangle(*bgr, s.band, cv::Scalar(160, 160, 160), thick);
  for (const CueBox& c : s.line_candidates) cv::rectangle(*bgr, c.box, cv::Scalar(0, 255, 255), thick);
  for (const CueBox& c : s.texture_candidates) cv::rectangle(*bgr, c.box, cv::Scalar(255, 0, 255), thick);
  for (const auto& l : s.lines) {
    cv::line(*bgr, cv::Point2d(l.a.x(), l.a.y()), cv::Point2d(l.b.x(), l.b.y()),
             l.kind == LanderLine::Kind::kDeck ? cv::Scalar(0, 255, 255) : cv::Scalar(0, 128, 255), 1);
  }
  const cv::Point org(10, static_cast<int>(30 * scale));
  if (!s.found) {
    cv::putText(*bgr, "no lander: " + s.reason, org, cv::FONT_HERSHEY_SIMPLEX, 0.6 * scale,
                cv::Scalar(0, 0, 255), thick);
    return;
  }
  cv::rectangle(*bgr, Expand(s.box, 3, 3), cv::Scalar(0, 255, 0), 2 * thick);
  char text[160];
  std::snprintf(text, sizeof text, "far: range %.1f +- %.1f m  bearing %.2f +- %.2f deg", s.range,
                s.range_sigma, s.bearing / kDegree, s.bearing_sigma / kDegree);
  cv::putText(*bgr, text, org, cv::FONT_HERSHEY_SIMPLEX, 0.6 * scale, cv::Scalar(0, 255, 0), thick);
  cv::putText(*bgr, s.features, org + cv::Point(0, static_cast<int>(26 * scale)),
              cv::FONT_HERSHEY_SIMPLEX, 0.5 * scale, cv::Scalar(0, 255, 0), thick);
}

}  // namespace rover::apl::rendezvous
