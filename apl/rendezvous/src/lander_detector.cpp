#include "rover/apl/rendezvous/lander_detector.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
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

// Deck silhouette width [m] used for the first range guess: between 2 apothem and 2 radius.
constexpr double kDeckWidthFactor = 2.0 * 0.93;  // times deck_radius

struct Segment {
  Vector2d a, b;  // a left of b for level segments, a above b for truss segments
  double length = 0.0;
  bool level = false;
  bool truss = false;
  double azimuth = 0.0;  // [rad] of the midpoint ray, rover frame
  int polarity = 0;      // level: +1 brighter below (a top edge), -1 brighter above, 0 neither
};

struct Band {
  double u0 = 0.0, u1 = 0.0;      // column extent
  double v_top = 0.0, v_bot = 0.0;
  double level_length = 0.0;
  std::vector<int> level;         // segment indices
  std::vector<int> truss;
  double v_feet = 0.0;
  double range_width = 0.0;       // [m] from the band width
  double score = -1.0;
};

// Stripe edges of one ramp: level segments with aligned ends, stacked down the ramp.
struct RampStack {
  double u0 = 0.0, u1 = 0.0;  // column extent of the longest stripe edge
  double v0 = 0.0, v1 = 0.0;  // row extent of the stack
  std::vector<int> edges;     // segment indices
  int rows = 0;               // distinct edge rows
};

double AngleBetweenLines(const Vector2d& d1, const Vector2d& d2) {
  const double c = std::abs(d1.normalized().dot(d2.normalized()));
  return std::acos(std::min(1.0, c));
}

double HorizontalNorm(const Vector3d& v) { return std::hypot(v.x(), v.y()); }

// Closest approach of two rays; the midpoint, and the gap between them.
bool Triangulate(const geometry::Ray& r1, const geometry::Ray& r2, Vector3d* p, double* gap,
                 double* t1_out) {
  const Vector3d w0 = r1.origin - r2.origin;
  const double a = r1.direction.dot(r1.direction);
  const double b = r1.direction.dot(r2.direction);
  const double c = r2.direction.dot(r2.direction);
  const double d = r1.direction.dot(w0);
  const double e = r2.direction.dot(w0);
  const double den = a * c - b * b;
  if (!(den > 1e-14)) return false;
  const double t1 = (b * e - c * d) / den;
  const double t2 = (a * e - b * d) / den;
  if (t1 <= 0.0 || t2 <= 0.0) return false;
  const Vector3d p1 = r1.origin + t1 * r1.direction;
  const Vector3d p2 = r2.origin + t2 * r2.direction;
  *p = 0.5 * (p1 + p2);
  *gap = (p1 - p2).norm();
  *t1_out = t1;
  return true;
}

double ParabolaPeak(double ym, double y0, double yp) {
  const double den = ym - 2.0 * y0 + yp;
  if (!(std::abs(den) > 1e-12)) return 0.0;
  return std::clamp(0.5 * (ym - yp) / den, -0.5, 0.5);
}

class Detector {
 public:
  Detector(const cv::Mat& left, const cv::Mat& right, const geometry::CameraModel& lm,
           const geometry::CameraModel* rm, const hwconfig::LanderDescription& lander,
           const LanderDetectorOptions& o, const std::optional<LanderPrior>& prior)
      : left_(left), right_(right), lm_(lm), rm_(rm), lander_(lander), o_(o), prior_(prior) {}

  LanderSighting Run();

 private:
  void FindSegments();
  void ClassifySegment(Segment* s) const;
  int Polarity(const Segment& s) const;
  std::vector<Band> MakeBands() const;
  bool CheckTruss(Band* band) const;
  double Elevation(const Vector2d& px) const;
  // Stereo match of the left patch centred at `px` (half sizes hw, hh) with range limits;
  // returns the triangulated point.
  bool MatchStereo(const Vector2d& px, int hw, int hh, double r_lo, double r_hi, Vector3d* p) const;
  // The deck-band hypothesis confirmed by a truss (method steps 2-4).
  LanderSighting FromTruss();
  // The ramp hypothesis (method step 6): a stack of stripe edges on a bright ramp.
  LanderSighting FromRamp();
  std::vector<RampStack> FindRampStacks() const;

  const cv::Mat& left_;
  const cv::Mat& right_;
  const geometry::CameraModel& lm_;
  const geometry::CameraModel* rm_;
  const hwconfig::LanderDescription& lander_;
  const LanderDetectorOptions& o_;
  const std::optional<LanderPrior>& prior_;

  std::vector<Segment> segs_;
  bool ramp_frontal_ = false;  // FromRamp's sighting took the view angle as 0
  mutable int rejected_tall_ = 0, rejected_truss_ = 0, rejected_extent_ = 0;
  double f_ = 1.0;          // [px/rad] near the image centre
  double baseline_ = 0.0;   // [m]
  Vector3d cam_ = Vector3d::Zero();
};

void Detector::ClassifySegment(Segment* s) const {
  const Vector2d mid = 0.5 * (s->a + s->b);
  const auto ray = lm_.Unproject(mid);
  if (!ray) return;
  const Vector3d dh(ray->direction.x(), ray->direction.y(), 0.0);
  if (dh.norm() < 1e-6) return;
  const Vector3d fwd = dh.normalized();
  s->azimuth = std::atan2(fwd.y(), fwd.x());
  const Vector3d p = ray->origin + 15.0 * ray->direction;
  const auto p0 = lm_.Project(p);
  const auto p_across = lm_.Project(p + 0.3 * Vector3d(-fwd.y(), fwd.x(), 0.0));
  const auto p_up = lm_.Project(p + 0.3 * Vector3d::UnitZ());
  if (!p0 || !p_across || !p_up) return;
  const Vector2d dir = s->b - s->a;
  const double to_level = AngleBetweenLines(dir, *p_across - *p0);
  const double to_vertical = AngleBetweenLines(dir, *p_up - *p0);
  s->level = to_level < o_.level_tolerance_deg * kDegree && s->length >= o_.min_level_length;
  s->truss = to_vertical < o_.truss_tolerance_deg * kDegree && s->length >= o_.min_truss_length;
  if (s->level && s->a.x() > s->b.x()) std::swap(s->a, s->b);
  if (s->truss && s->a.y() > s->b.y()) std::swap(s->a, s->b);
}

int Detector::Polarity(const Segment& s) const {
  double above = 0.0, below = 0.0;
  int n = 0;
  for (int k = 1; k <= 5; ++k) {
    const Vector2d p = s.a + (k / 6.0) * (s.b - s.a);
    const int x = static_cast<int>(std::lround(p.x()));
    const int y = static_cast<int>(std::lround(p.y()));
    if (x < 0 || x >= left_.cols || y < 3 || y + 3 >= left_.rows) continue;
    above += left_.at<unsigned char>(y - 3, x) + left_.at<unsigned char>(y - 2, x);
    below += left_.at<unsigned char>(y + 3, x) + left_.at<unsigned char>(y + 2, x);
    ++n;
  }
  if (n == 0) return 0;
  const double diff = (below - above) / (2.0 * n);
  return diff > 5.0 ? 1 : (diff < -5.0 ? -1 : 0);
}

void Detector::FindSegments() {
  cv::Mat smooth;
  cv::GaussianBlur(left_, smooth, cv::Size(3, 3), 0.8);
  auto lsd = cv::createLineSegmentDetector(cv::LSD_REFINE_STD);
  std::vector<cv::Vec4f> lines;
  lsd->detect(smooth, lines);
  segs_.reserve(lines.size());
  for (const auto& l : lines) {
    Segment s;
    s.a = Vector2d(l[0], l[1]);
    s.b = Vector2d(l[2], l[3]);
    s.length = (s.b - s.a).norm();
    if (s.length < std::min(o_.min_level_length, o_.min_truss_length)) continue;
    ClassifySegment(&s);
    if (!s.level && !s.truss) continue;
    if (s.level) s.polarity = Polarity(s);
    if (prior_) {
      const double d = std::remainder(s.azimuth - prior_->bearing, 2.0 * kPi);
      if (std::abs(d) > prior_->bearing_window) continue;
    }
    segs_.push_back(s);
  }
}

std::vector<Band> Detector::MakeBands() const {
  std::vector<int> level;
  for (int i = 0; i < static_cast<int>(segs_.size()); ++i) {
    if (segs_[static_cast<std::size_t>(i)].level) level.push_back(i);
  }
  std::sort(level.begin(), level.end(), [&](int a, int b) {
    return segs_[static_cast<std::size_t>(a)].length > segs_[static_cast<std::size_t>(b)].length;
  });
  const double w_min = f_ * kDeckWidthFactor * lander_.deck_radius / (1.4 * o_.max_range);
  const double w_max = f_ * 2.6 * lander_.deck_radius / o_.min_range;
  const double over_deck = std::max(0.0, cam_.z() - lander_.deck_height);
  std::vector<Band> bands;
  std::vector<char> used(segs_.size(), 0);
  for (int seed : level) {
    const Segment& s = segs_[static_cast<std::size_t>(seed)];
    if (used[static_cast<std::size_t>(seed)] || s.polarity <= 0 || s.length > w_max) continue;
    // The deck top: the seed chained with collinear top-type segments on either side.
    Band band;
    band.u0 = s.a.x();
    band.u1 = s.b.x();
    Vector2d left_end = s.a, right_end = s.b;
    band.level.push_back(seed);
    band.level_length = s.length;
    for (bool grew = true; grew;) {
      grew = false;
      for (int j : level) {
        const Segment& t = segs_[static_cast<std::size_t>(j)];
        if (t.polarity <= 0 || std::find(band.level.begin(), band.level.end(), j) != band.level.end()) continue;
        const double tol_gap = std::max(6.0, 0.08 * (band.u1 - band.u0));
        if (t.b.x() <= left_end.x() + 2.0 && left_end.x() - t.b.x() <= tol_gap &&
            std::abs(t.b.y() - left_end.y()) <= 3.0) {
          left_end = t.a;
        } else if (t.a.x() >= right_end.x() - 2.0 && t.a.x() - right_end.x() <= tol_gap &&
                   std::abs(t.a.y() - right_end.y()) <= 3.0) {
          right_end = t.b;
        } else {
          continue;
        }
        band.level.push_back(j);
        band.level_length += t.length;
        band.u0 = left_end.x();
        band.u1 = right_end.x();
        grew = true;
      }
    }
    const double w = band.u1 - band.u0;
    if (w < w_min || w > w_max) continue;
    for (int j : band.level) used[static_cast<std::size_t>(j)] = 1;
    band.range_width = f_ * kDeckWidthFactor * lander_.deck_radius / w;
    const double r = band.range_width;
    band.v_top = std::min(left_end.y(), right_end.y());
    for (int j : band.level) {
      const Segment& t = segs_[static_cast<std::size_t>(j)];
      band.v_top = std::min({band.v_top, t.a.y(), t.b.y()});
    }
    const double v_top_max = std::max(left_end.y(), right_end.y());
    // The slab bottom: bottom-type level segments under the top, within the slab's thickness
    // plus the visible top face (a slack of 40 %).
    const double dv_max = 1.4 * (lander_.deck_thickness * f_ / r +
                                 over_deck * 2.0 * lander_.Apothem() * f_ / (r * r)) + 3.0;
    band.v_bot = v_top_max;
    double bottom_length = 0.0;
    for (int j : level) {
      const Segment& t = segs_[static_cast<std::size_t>(j)];
      if (t.polarity >= 0) continue;
      const double overlap = std::min(t.b.x(), band.u1) - std::max(t.a.x(), band.u0);
      if (overlap < 0.6 * t.length) continue;
      const double tv = 0.5 * (t.a.y() + t.b.y());
      if (tv <= v_top_max + 1.0 || tv > v_top_max + dv_max) continue;
      band.level.push_back(j);
      bottom_length += t.length;
      band.v_bot = std::max({band.v_bot, t.a.y(), t.b.y()});
    }
    if (bottom_length < 0.15 * w) continue;
    band.level_length = std::min(1.0, band.level_length / w) + std::min(1.0, bottom_length / w);
    bands.push_back(std::move(band));
  }
  return bands;
}

bool Detector::CheckTruss(Band* band) const {
  const double w = band->u1 - band->u0;
  const double h = lander_.deck_height * f_ / band->range_width;  // expected deck-to-feet [px]
  const double thick = lander_.deck_thickness * f_ / band->range_width;
  if (band->v_bot - band->v_top > 0.7 * h + 6.0) {  // too tall for a slab
    ++rejected_tall_;
    return false;
  }
  band->truss.clear();
  std::vector<double> bottoms;
  for (int i = 0; i < static_cast<int>(segs_.size()); ++i) {
    const Segment& s = segs_[static_cast<std::size_t>(i)];
    if (!s.truss) continue;
    const double um = 0.5 * (s.a.x() + s.b.x());
    if (um < band->u0 - 0.15 * w || um > band->u1 + 0.15 * w) continue;
    if (s.a.y() < band->v_top + 0.5 * thick || s.a.y() > band->v_bot + 0.6 * h) continue;
    if (s.b.y() > band->v_top + 1.4 * h) continue;
    if (s.length < std::max(o_.min_truss_length, 0.15 * h)) continue;
    band->truss.push_back(i);
    bottoms.push_back(s.b.y());
  }
  if (static_cast<int>(band->truss.size()) < o_.min_truss_lines) {
    ++rejected_truss_;
    return false;
  }
  std::sort(bottoms.begin(), bottoms.end());
  // The feet: the lowest truss ends (the second lowest, against one stray line).
  band->v_feet = bottoms.size() >= 4 ? bottoms[bottoms.size() - 2] : bottoms.back();
  const double extent = band->v_feet - band->v_top;
  if (extent < 0.55 * h || extent > 1.7 * h) {
    ++rejected_extent_;
    return false;
  }
  const double coverage = band->level_length;
  band->score = coverage + 0.1 * std::min<double>(15.0, static_cast<double>(band->truss.size()));
  return true;
}

double Detector::Elevation(const Vector2d& px) const {
  const auto ray = lm_.Unproject(px);
  if (!ray) return 0.0;
  return std::atan2(ray->direction.z(), HorizontalNorm(ray->direction));
}

bool Detector::MatchStereo(const Vector2d& px, int hw, int hh, double r_lo, double r_hi,
                           Vector3d* p) const {
  if (rm_ == nullptr || right_.empty()) return false;
  const int cx = static_cast<int>(std::lround(px.x()));
  const int cy = static_cast<int>(std::lround(px.y()));
  const cv::Rect tpl_rect(cx - hw, cy - hh, 2 * hw + 1, 2 * hh + 1);
  if ((tpl_rect & cv::Rect(0, 0, left_.cols, left_.rows)) != tpl_rect) return false;
  const cv::Mat tpl = left_(tpl_rect);
  cv::Scalar mean, sd;
  cv::meanStdDev(tpl, mean, sd);
  if (sd[0] < 3.0) return false;
  const auto ray = lm_.Unproject(Vector2d(cx, cy));
  if (!ray) return false;
  const double hn = HorizontalNorm(ray->direction);
  if (hn < 1e-6) return false;
  const auto near = rm_->Project(ray->origin + (r_lo / hn) * ray->direction);
  const auto far = rm_->Project(ray->origin + (r_hi / hn) * ray->direction);
  if (!near || !far) return false;
  const int x0 = static_cast<int>(std::floor(std::min(near->x(), far->x()))) - hw - 2;
  const int x1 = static_cast<int>(std::ceil(std::max(near->x(), far->x()))) + hw + 2;
  const int yc = static_cast<int>(std::lround(0.5 * (near->y() + far->y())));
  const int dy = 3 + static_cast<int>(std::ceil(std::abs(near->y() - far->y())));
  cv::Rect search(x0, yc - hh - dy, x1 - x0 + 1, 2 * (hh + dy) + 1);
  search &= cv::Rect(0, 0, right_.cols, right_.rows);
  if (search.width < tpl_rect.width + 2 || search.height < tpl_rect.height + 2) return false;
  cv::Mat score;
  cv::matchTemplate(right_(search), tpl, score, cv::TM_CCOEFF_NORMED);
  double best = 0.0;
  cv::Point at;
  cv::minMaxLoc(score, nullptr, &best, nullptr, &at);
  if (best < o_.min_correlation) return false;
  if (at.x <= 0 || at.x >= score.cols - 1 || at.y <= 0 || at.y >= score.rows - 1) return false;
  // Ambiguity: a second peak nearly as good away from the best one.
  for (int x = 0; x < score.cols; ++x) {
    if (std::abs(x - at.x) <= 3) continue;
    if (score.at<float>(at.y, x) > best - 0.03 && score.at<float>(at.y, x) >= score.at<float>(at.y, std::max(0, x - 1)) &&
        score.at<float>(at.y, x) >= score.at<float>(at.y, std::min(score.cols - 1, x + 1))) {
      return false;
    }
  }
  const double sx = ParabolaPeak(score.at<float>(at.y, at.x - 1), score.at<float>(at.y, at.x),
                                 score.at<float>(at.y, at.x + 1));
  const double sy = ParabolaPeak(score.at<float>(at.y - 1, at.x), score.at<float>(at.y, at.x),
                                 score.at<float>(at.y + 1, at.x));
  const Vector2d pr(search.x + at.x + hw + sx, search.y + at.y + hh + sy);
  const auto ray_r = rm_->Unproject(pr);
  if (!ray_r) return false;
  double gap = 0.0, t = 0.0;
  if (!Triangulate(*ray, *ray_r, p, &gap, &t)) return false;
  if (gap / t * f_ > 2.0) return false;  // off the epipolar line by more than ~2 px
  const double r = HorizontalNorm(*p - ray->origin);
  return r >= 0.9 * r_lo && r <= 1.1 * r_hi;
}

LanderSighting Detector::Run() {
  LanderSighting out;
  // Local focal length [px/rad] at the image centre; camera centres.
  const Vector2d c0(0.5 * (lm_.width() - 1), 0.5 * (lm_.height() - 1));
  const auto r0 = lm_.Unproject(c0);
  const auto r1 = lm_.Unproject(c0 + Vector2d(10.0, 0.0));
  if (!r0 || !r1) {
    out.reason = "left camera model cannot unproject its image centre";
    return out;
  }
  f_ = 10.0 / std::acos(std::clamp(r0->direction.dot(r1->direction), -1.0, 1.0));
  cam_ = r0->origin;
  if (rm_ != nullptr && !right_.empty()) baseline_ = (rm_->Center() - lm_.Center()).norm();

  FindSegments();
  LanderSighting truss = FromTruss();
  if (baseline_ <= 0.0 || o_.min_ramp_edges == 0) return truss;
  // The ramp hypothesis (stereo only). A frontal ramp gives the deck's bearing exactly (the
  // ramp hangs from the middle of a deck edge) while the deck band is then cut by the ramp and
  // often taken at the wrong scale: a frontal ramp wins; otherwise a deck band with a truss does.
  LanderSighting ramp = FromRamp();
  if (ramp.found && (!truss.found || ramp_frontal_)) return ramp;
  if (truss.found) return truss;
  truss.reason += "; ramp: " + ramp.reason;
  return truss;
}

LanderSighting Detector::FromTruss() {
  LanderSighting out;
  std::vector<Band> bands = MakeBands();
  Band* best = nullptr;
  for (Band& b : bands) {
    if (!CheckTruss(&b)) continue;
    if (best == nullptr || b.score > best->score) best = &b;
  }
  if (best == nullptr) {
    int n_level = 0;
    for (const auto& s : segs_) n_level += s.level ? 1 : 0;
    out.reason = "no deck band with a truss below it (" + std::to_string(n_level) +
                 " level segments, " + std::to_string(bands.size()) + " bands; rejected: " + std::to_string(rejected_tall_) + " too tall, " +
                 std::to_string(rejected_truss_) + " without truss, " +
                 std::to_string(rejected_extent_) + " with a wrong height)";
    return out;
  }
  Band& band = *best;
  const double uc = 0.5 * (band.u0 + band.u1);

  // Monocular range from the vertical extent deck top -> feet.
  const double e_top = Elevation(Vector2d(uc, band.v_top));
  const double e_feet = Elevation(Vector2d(uc, band.v_feet));
  const double dt = std::tan(e_top) - std::tan(e_feet);
  const double r_extent = dt > 1e-6 ? lander_.deck_height / dt : 0.0;
  double r_mono = r_extent;
  if (!(r_extent > 0.6 * band.range_width && r_extent < 1.6 * band.range_width)) {
    r_mono = band.range_width;  // the feet were not found: the deck width alone
  }
  const double r_guess = 0.5 * (r_mono + band.range_width);
  const auto ray_c = lm_.Unproject(Vector2d(uc, 0.5 * (band.v_top + band.v_bot)));
  if (!ray_c) {
    out.reason = "cannot unproject the deck centre";
    return out;
  }
  Vector3d view_h(ray_c->direction.x(), ray_c->direction.y(), 0.0);
  view_h.normalize();

  // Stereo: both deck ends.
  double r_stereo = 0.0, stereo_sigma = 0.0;
  Vector3d center_stereo = Vector3d::Zero();
  int n_stereo = 0;
  if (baseline_ > 0.0) {
    const int hh = std::max(3, static_cast<int>(std::lround(0.5 * (band.v_bot - band.v_top))) + 3);
    const double v_mid = 0.5 * (band.v_top + band.v_bot);
    Vector3d p_left, p_right;
    const bool ok_l = MatchStereo(Vector2d(band.u0, v_mid), o_.stereo_half_width, hh,
                                  0.6 * r_guess, 1.6 * r_guess, &p_left);
    const bool ok_r = MatchStereo(Vector2d(band.u1, v_mid), o_.stereo_half_width, hh,
                                  0.6 * r_guess, 1.6 * r_guess, &p_right);
    n_stereo = (ok_l ? 1 : 0) + (ok_r ? 1 : 0);
    if (ok_l || ok_r) {
      // Both ends: their midpoint; one end: its depth, the deck's bearing from the image.
      const Vector3d mid = ok_l && ok_r ? 0.5 * (p_left + p_right) : (ok_l ? p_left : p_right);
      const double r_mid = HorizontalNorm(mid - cam_) + o_.end_depth_offset;
      center_stereo = ok_l && ok_r ? mid + o_.end_depth_offset * view_h : cam_ + r_mid * view_h;
      r_stereo = HorizontalNorm(center_stereo - cam_);
      const double sd_disp = r_stereo * r_stereo / (f_ * baseline_) * o_.disparity_sigma;
      stereo_sigma = ok_l && ok_r ? std::hypot(sd_disp / std::sqrt(2.0), 0.5 * o_.end_depth_offset)
                                  : std::hypot(sd_disp, 1.5 * o_.end_depth_offset);
      if (std::abs(r_stereo - band.range_width) > o_.max_disagreement * band.range_width) {
        r_stereo = 0.0;  // a mismatch; keep the monocular estimate
      }
    }
  }

  if (baseline_ > 0.0 && r_stereo <= 0.0) {
    // With a right image the deck must be confirmed by stereo: rocks and shadows that mimic
    // a deck band rarely give deck ends whose depth matches the band's width.
    out.reason = "deck-like band at ~" + FormatNumber(band.range_width) +
                 " m not confirmed by stereo (" + std::to_string(n_stereo) + " ends matched)";
    return out;
  }
  // Fuse.
  const double mono_sigma = o_.monocular_sigma * r_mono;
  double range_cam = r_mono, range_cam_sigma = mono_sigma;
  if (r_stereo > 0.0) {
    const double wm = 1.0 / (mono_sigma * mono_sigma);
    const double ws = 1.0 / (stereo_sigma * stereo_sigma);
    range_cam = (wm * r_mono + ws * r_stereo) / (wm + ws);
    range_cam_sigma = 1.0 / std::sqrt(wm + ws);
  }
  if (range_cam < o_.min_range || range_cam > o_.max_range) {
    out.reason = "lander-like structure at " + FormatNumber(range_cam) + " m, outside the range";
    return out;
  }
  Vector3d dir_h = view_h;
  if (n_stereo == 2 && r_stereo > 0.0) {
    dir_h = Vector3d(center_stereo.x() - cam_.x(), center_stereo.y() - cam_.y(), 0.0).normalized();
  }
  Vector3d center = cam_ + range_cam * dir_h;
  center.z() = cam_.z() + range_cam * std::tan(e_top);
  const double range = HorizontalNorm(center);
  if (prior_ && std::abs(range - prior_->range) > prior_->range_window) {
    out.reason = "lander-like structure at " + FormatNumber(range) + " m, outside the prior window";
    return out;
  }

  out.found = true;
  out.range = range;
  out.range_sigma = range_cam_sigma;
  out.range_monocular = r_mono;
  out.range_stereo = r_stereo;
  out.bearing = std::atan2(center.y(), center.x());
  const double lateral_sigma = 0.1 * lander_.deck_radius + range_cam * 1.0 / f_;
  out.bearing_sigma = lateral_sigma / range;
  out.elevation = e_top;
  out.elevation_sigma = 1.5 / f_;
  out.center = center;
  const Vector3d across(-dir_h.y(), dir_h.x(), 0.0);
  const double sz = std::hypot(range_cam * out.elevation_sigma, range_cam_sigma * std::tan(e_top));
  out.center_covariance = range_cam_sigma * range_cam_sigma * dir_h * dir_h.transpose() +
                          lateral_sigma * lateral_sigma * across * across.transpose() +
                          sz * sz * Vector3d::UnitZ() * Vector3d::UnitZ().transpose();
  const int x0 = static_cast<int>(std::floor(band.u0 - 0.1 * (band.u1 - band.u0)));
  const int x1 = static_cast<int>(std::ceil(band.u1 + 0.1 * (band.u1 - band.u0)));
  out.box = cv::Rect(x0, static_cast<int>(std::floor(band.v_top)), x1 - x0,
                     static_cast<int>(std::ceil(band.v_feet - band.v_top)) + 1) &
            cv::Rect(0, 0, left_.cols, left_.rows);
  for (int i : band.level) {
    const auto& s = segs_[static_cast<std::size_t>(i)];
    out.lines.push_back({s.a, s.b, LanderLine::Kind::kDeck});
  }
  for (int i : band.truss) {
    const auto& s = segs_[static_cast<std::size_t>(i)];
    out.lines.push_back({s.a, s.b, LanderLine::Kind::kTruss});
  }
  out.features = "deck lines " + std::to_string(band.level.size()) + ", truss lines " +
                 std::to_string(band.truss.size()) + ", stereo ends " + std::to_string(n_stereo) +
                 (r_stereo > 0.0 ? " (used)" : " (unused)");
  out.reason = "lander at " + FormatNumber(out.range) + " m";
  return out;
}

std::vector<RampStack> Detector::FindRampStacks() const {
  const double stripe_length = lander_.ramp_width - 2.0 * hwconfig::kStripeMargin;
  const double l_max = 1.3 * f_ * stripe_length / o_.min_range;
  std::vector<int> edges;
  for (int i = 0; i < static_cast<int>(segs_.size()); ++i) {
    const Segment& s = segs_[static_cast<std::size_t>(i)];
    if (s.level && s.length <= l_max) edges.push_back(i);
  }
  std::sort(edges.begin(), edges.end(), [&](int a, int b) {
    return segs_[static_cast<std::size_t>(a)].length > segs_[static_cast<std::size_t>(b)].length;
  });
  std::vector<RampStack> stacks;
  std::vector<char> used(segs_.size(), 0);
  for (int seed : edges) {
    const Segment& s = segs_[static_cast<std::size_t>(seed)];
    if (used[static_cast<std::size_t>(seed)] || s.polarity == 0) continue;
    const double tol = std::max(3.0, 0.12 * s.length);
    const double vs = 0.5 * (s.a.y() + s.b.y());
    RampStack st;
    st.u0 = s.a.x();
    st.u1 = s.b.x();
    st.v0 = st.v1 = vs;
    // Candidates: inside the seed's columns, at least 40 % of its length, near-level in the
    // image; then the run of them around the seed's row with no gap wider than a stripe spacing
    // (dark stripe + light gap, <= 0.36 m against 1.2 m of stripe length: ~0.15 in the image, 0.2
    // allowed).
    std::vector<std::pair<double, int>> cand;  // (row, segment)
    for (int j : edges) {
      const Segment& t = segs_[static_cast<std::size_t>(j)];
      if (t.a.x() < st.u0 - tol || t.b.x() > st.u1 + tol || t.length < 0.4 * s.length) continue;
      if (std::abs(t.b.y() - t.a.y()) > 0.1 * t.length + 2.0) continue;
      cand.emplace_back(0.5 * (t.a.y() + t.b.y()), j);
    }
    std::sort(cand.begin(), cand.end());
    const double max_gap = std::max(5.0, 0.2 * s.length);
    std::size_t k_seed = 0;
    while (k_seed < cand.size() && cand[k_seed].second != seed) ++k_seed;
    if (k_seed == cand.size()) continue;  // the seed itself is not level enough in the image
    std::size_t k_lo = k_seed, k_hi = k_seed;
    while (k_lo > 0 && cand[k_lo].first - cand[k_lo - 1].first <= max_gap) --k_lo;
    while (k_hi + 1 < cand.size() && cand[k_hi + 1].first - cand[k_hi].first <= max_gap) ++k_hi;
    std::vector<double> rows;
    int n_top = 0, n_bottom = 0;
    for (std::size_t k = k_lo; k <= k_hi; ++k) {
      const int j = cand[k].second;
      const Segment& t = segs_[static_cast<std::size_t>(j)];
      const double vt = cand[k].first;
      st.edges.push_back(j);
      st.v0 = std::min(st.v0, vt);
      st.v1 = std::max(st.v1, vt);
      // (Thin far stripes give lines dark on both sides: polarity 0.)
      n_top += t.polarity > 0 ? 1 : 0;
      n_bottom += t.polarity < 0 ? 1 : 0;
      rows.push_back(vt);
    }
    std::sort(rows.begin(), rows.end());
    for (std::size_t k = 0; k < rows.size(); ++k) {
      if (k == 0 || rows[k] - rows[k - 1] > 1.5) ++st.rows;
    }
    // Dark stripes on a light ramp: edges of both polarities, and a compact stack (the block is
    // shorter in the image than the stripes are long, seen from a rover's mast).
    if (st.rows < o_.min_ramp_edges || n_top < 1 || n_bottom < 1) continue;
    if (st.v1 - st.v0 > 0.8 * (st.u1 - st.u0)) continue;
    // Stripes all end at the same margin from the ramp's sides: at least three edges aligned at
    // both ends, or two in a stack of five or more rows (far away, where the thin stripes' edges
    // break up); rock shadows stacked by chance are not aligned.
    const double tol_end = std::max(2.5, 0.08 * s.length);
    int aligned = 0;
    for (int j : st.edges) {
      const Segment& t = segs_[static_cast<std::size_t>(j)];
      aligned += std::abs(t.a.x() - st.u0) <= tol_end && std::abs(t.b.x() - st.u1) <= tol_end;
    }
    if (aligned < 3 && !(aligned == 2 && st.rows >= 5)) continue;  // far: thin, merged edges
    // The ramp's side edges: a near-vertical segment just outside each end of the stripes,
    // level with the stack.
    bool side_edge[2] = {false, false};
    for (const Segment& t : segs_) {
      if (!t.truss) continue;
      if (std::max(t.a.y(), t.b.y()) < st.v0 - 2.0 || std::min(t.a.y(), t.b.y()) > st.v1 + 2.0) {
        continue;
      }
      const double um = 0.5 * (t.a.x() + t.b.x());
      const double reach = 0.2 * s.length + 3.0;
      if (um < st.u0 + 2.0 && um > st.u0 - reach) side_edge[0] = true;
      if (um > st.u1 - 2.0 && um < st.u1 + reach) side_edge[1] = true;
    }
    if (!side_edge[0] || !side_edge[1]) continue;
    for (int j : st.edges) used[static_cast<std::size_t>(j)] = 1;
    stacks.push_back(std::move(st));
  }
  return stacks;
}

LanderSighting Detector::FromRamp() {
  LanderSighting out;
  const std::vector<RampStack> stacks = FindRampStacks();
  if (stacks.empty()) {
    out.reason = "no stripe stack";
    return out;
  }
  const double stripe_length = lander_.ramp_width - 2.0 * hwconfig::kStripeMargin;
  const double to_center = lander_.Apothem() + 0.5 * lander_.ramp_length;  // ramp middle -> deck
  std::string last;
  for (const RampStack& st : stacks) {
    const double len = st.u1 - st.u0;
    const double r_len = f_ * stripe_length / len;  // >= the range (shorter when oblique)
    // Light ramp: the bright quarter inside the stack against the ground beside the ramp.
    const cv::Rect inner = cv::Rect(static_cast<int>(st.u0 + 2), static_cast<int>(st.v0),
                                    std::max(1, static_cast<int>(len - 4)),
                                    static_cast<int>(st.v1 - st.v0) + 1) &
                           cv::Rect(0, 0, left_.cols, left_.rows);
    const int side_w = std::max(2, static_cast<int>(0.2 * len));
    const cv::Rect left_side = cv::Rect(static_cast<int>(st.u0 - 0.15 * len) - side_w, inner.y,
                                        side_w, inner.height) & cv::Rect(0, 0, left_.cols, left_.rows);
    const cv::Rect right_side = cv::Rect(static_cast<int>(st.u1 + 0.15 * len), inner.y, side_w,
                                         inner.height) & cv::Rect(0, 0, left_.cols, left_.rows);
    if (inner.area() < 4 || left_side.area() < 4 || right_side.area() < 4) {
      last = "stripe stack at the image border";
      continue;
    }
    auto quantile = [&](const cv::Rect& r, double q) {
      std::vector<unsigned char> px;
      for (int y = r.y; y < r.y + r.height; ++y) {
        for (int x = r.x; x < r.x + r.width; ++x) px.push_back(left_.at<unsigned char>(y, x));
      }
      auto it = px.begin() + static_cast<std::ptrdiff_t>(q * static_cast<double>(px.size() - 1));
      std::nth_element(px.begin(), it, px.end());
      return static_cast<double>(*it);
    };
    const double ramp_light = quantile(inner, 0.75);
    const double ground = std::max(quantile(left_side, 0.5), quantile(right_side, 0.5));
    if (ramp_light - ground < o_.min_ramp_contrast) {
      last = "stripe stack not on a light ramp (" + FormatNumber(ramp_light - ground) + ")";
      continue;
    }
    // Stereo on the stripe ends (with the ramp edges beside them): the whole stack, then each
    // edge row; every match is one horizontal range.
    const double r_lo = 0.45 * r_len, r_hi = 1.25 * r_len;
    const double vm = 0.5 * (st.v0 + st.v1);
    const int hh = static_cast<int>(std::lround(0.5 * (st.v1 - st.v0))) + 3;
    std::vector<Vector3d> ends[2];
    for (int side = 0; side < 2; ++side) {
      const double u = side == 0 ? st.u0 : st.u1;
      Vector3d p;
      if (MatchStereo(Vector2d(u, vm), o_.stereo_half_width, hh, r_lo, r_hi, &p)) {
        ends[side].push_back(p);
      }
      for (int j : st.edges) {
        const Segment& t = segs_[static_cast<std::size_t>(j)];
        const Vector2d e = side == 0 ? t.a : t.b;
        if (std::abs(e.x() - u) > std::max(3.0, 0.06 * len)) continue;  // a fragment's inner end
        if (MatchStereo(e, o_.stereo_half_width, 4, r_lo, r_hi, &p)) ends[side].push_back(p);
      }
    }
    const int n_matched = static_cast<int>(ends[0].size() + ends[1].size());
    if (ends[0].empty() || ends[1].empty() || n_matched < 3) {
      last = "stripe stack at ~" + FormatNumber(r_len) + " m not confirmed by stereo (" +
             std::to_string(ends[0].size()) + "+" + std::to_string(ends[1].size()) + " ends)";
      continue;
    }
    // Per side the match of median range; the ramp middle between the two sides.
    Vector3d side_point[2];
    std::vector<double> all_ranges;
    for (int side = 0; side < 2; ++side) {
      auto& v = ends[side];
      std::sort(v.begin(), v.end(), [&](const Vector3d& a, const Vector3d& b) {
        return HorizontalNorm(a - cam_) < HorizontalNorm(b - cam_);
      });
      side_point[side] = v[v.size() / 2];
      for (const auto& q : v) all_ranges.push_back(HorizontalNorm(q - cam_));
    }
    std::sort(all_ranges.begin(), all_ranges.end());
    const double r_med = all_ranges[all_ranges.size() / 2];
    const double r_sd = r_med * r_med / (f_ * baseline_) * o_.disparity_sigma;
    int n_in = 0;
    double r_sum = 0.0;
    for (double r : all_ranges) {
      if (std::abs(r - r_med) <= 3.0 * r_sd + 0.02 * r_med) {
        r_sum += r;
        ++n_in;
      }
    }
    if (n_in < 3 || n_in * 2 < n_matched) {
      last = "stripe stack: stereo ranges disagree";
      continue;
    }
    const double r_mid = r_sum / n_in;  // camera to the ramp middle, horizontal
    // Consistency: the stripes' length in metres at the stereo range (the cosine of the view
    // angle times the true length) must be a stripe length seen from at most ~65 deg off axis.
    const double seen_length = r_mid * len / f_;
    if (seen_length > 1.15 * stripe_length || seen_length < 0.4 * stripe_length) {
      last = "stripe stack " + FormatNumber(seen_length) + " m long at the stereo range " +
             FormatNumber(r_mid) + " m";
      continue;
    }
    const auto ray_m = lm_.Unproject(Vector2d(0.5 * (st.u0 + st.u1), vm));
    if (!ray_m) continue;
    Vector3d view_h(ray_m->direction.x(), ray_m->direction.y(), 0.0);
    view_h.normalize();
    // Ramp axis: the view angle from the stripes' foreshortening, its sign from the two sides'
    // depths (each side point sits on its own ray, so only the depth difference is uncertain).
    // LSD ends a stripe edge ~1 px short at each end and the cosine is flat near 0, so an angle
    // under ~26 deg (kFrontalCos) cannot be told from a frontal view: taken as 0, with its spread in the
    // covariance.
    constexpr double kFrontalCos = 0.9;  // cos 26 deg
    double cos_a = std::min(1.0, seen_length / stripe_length);
    ramp_frontal_ = cos_a > kFrontalCos;
    if (ramp_frontal_) cos_a = 1.0;
    double sin_a = std::sqrt(std::max(0.0, 1.0 - cos_a * cos_a));
    const double depth_gap =
        HorizontalNorm(side_point[1] - cam_) - HorizontalNorm(side_point[0] - cam_);
    // The stripes run along (-cos a) across + (sin a) view from their left end to their right
    // end; the axis up the ramp is perpendicular: cos a view + sin a across.
    if (depth_gap < 0.0) sin_a = -sin_a;
    if (!ramp_frontal_) {
      // A wrong sign would put the deck 2 x 2.8 m sin a off to the side: the two ends' depths
      // must differ by more than 3 sigma (their medians of n matches each).
      const double sd_gap = r_sd * std::sqrt(1.0 / static_cast<double>(ends[0].size()) +
                                              1.0 / static_cast<double>(ends[1].size()));
      if (std::abs(depth_gap) < 3.0 * sd_gap) {
        last = "ramp seen ~" + FormatNumber(std::round(std::asin(std::abs(sin_a)) / kDegree)) +
               " deg off its axis, side unknown";
        continue;
      }
    }
    const Vector3d across(-view_h.y(), view_h.x(), 0.0);  // to the left of the view
    const Vector3d axis = (cos_a * view_h + sin_a * across).normalized();
    const Vector3d mid = cam_ + r_mid * view_h;
    Vector3d center = mid + to_center * axis;
    const double range_cam = HorizontalNorm(center - cam_);
    if (range_cam < o_.min_range || range_cam > o_.max_range) {
      last = "ramp at " + FormatNumber(range_cam) + " m, outside the range";
      continue;
    }
    // Deck top: the ramp middle is half a deck height above the ground.
    const Vector3d mid3 = 0.5 * (side_point[0] + side_point[1]);
    center.z() = mid3.z() + 0.5 * lander_.deck_height;
    const double range = HorizontalNorm(center);
    if (prior_ && std::abs(range - prior_->range) > prior_->range_window) {
      last = "ramp at " + FormatNumber(range) + " m, outside the prior window";
      continue;
    }
    const Vector3d dir_h = Vector3d(center.x() - cam_.x(), center.y() - cam_.y(), 0.0).normalized();
    out.found = true;
    out.range = range;
    // Range: the ramp-middle disparity and the unknown sign/size of the view angle (its error
    // grows with sin a); lateral: the view angle's error over the ramp-to-deck distance.
    const double sd_mid = r_sd / std::sqrt(static_cast<double>(n_in));
    const double sd_angle = sin_a == 0.0 ? 0.26 : 0.1 + 0.2 * std::abs(sin_a);  // [rad]
    out.range_sigma =
        std::hypot(sd_mid, to_center * (std::abs(sin_a) + 0.5 * sd_angle) * sd_angle + 0.05);
    out.range_monocular = r_len + to_center;
    out.range_stereo = range_cam;
    out.bearing = std::atan2(center.y(), center.x());
    const double lateral_sigma = std::hypot(to_center * sd_angle * cos_a, 0.1);
    out.bearing_sigma = lateral_sigma / range;
    out.elevation = std::atan2(center.z() - cam_.z(), range_cam);
    out.elevation_sigma = 1.5 / f_;
    out.center = center;
    const Vector3d lat(-dir_h.y(), dir_h.x(), 0.0);
    const double sz = range_cam * out.elevation_sigma + 0.1;
    out.center_covariance = out.range_sigma * out.range_sigma * dir_h * dir_h.transpose() +
                            lateral_sigma * lateral_sigma * lat * lat.transpose() +
                            sz * sz * Vector3d::UnitZ() * Vector3d::UnitZ().transpose();
    const auto top = lm_.Project(center);
    const int x0 = static_cast<int>(std::floor(st.u0 - 0.9 * len));
    const int x1 = static_cast<int>(std::ceil(st.u1 + 0.9 * len));
    const int y0 = top ? static_cast<int>(std::floor(std::min(top->y(), st.v0))) - 2
                       : static_cast<int>(st.v0);
    out.box = cv::Rect(x0, y0, x1 - x0, static_cast<int>(st.v1) + 4 - y0) &
              cv::Rect(0, 0, left_.cols, left_.rows);
    for (int j : st.edges) {
      const auto& t = segs_[static_cast<std::size_t>(j)];
      out.lines.push_back({t.a, t.b, LanderLine::Kind::kDeck});
    }
    out.features = "ramp stripe edges " + std::to_string(st.rows) + ", stereo ends " +
                   std::to_string(ends[0].size()) + "+" + std::to_string(ends[1].size()) +
                   " (used " + std::to_string(n_in) + "), view angle " +
                   FormatNumber(std::round(std::asin(sin_a) / kDegree)) + " deg";
    out.reason = "lander at " + FormatNumber(out.range) + " m (ramp)";
    return out;
  }
  out.reason = last.empty() ? "no stripe stack" : last;
  return out;
}

Status CheckImage(const char* name, const cv::Mat& im, const geometry::CameraModel& m) {
  if (im.empty()) return InvalidArgument(std::string(name) + ": empty image");
  if (im.type() != CV_8UC1) return InvalidArgument(std::string(name) + ": not an 8-bit grey image");
  if (im.cols != m.width() || im.rows != m.height()) {
    return InvalidArgument(std::string(name) + ": " + std::to_string(im.cols) + "x" +
                           std::to_string(im.rows) + " image but a " + std::to_string(m.width()) +
                           "x" + std::to_string(m.height()) + " camera model");
  }
  return Status::Ok();
}

}  // namespace

Status LanderDetectorOptions::Validate(const char* prefix) const {
  const std::string p(prefix);
  ROVER_RETURN_IF_ERROR(CheckRange(p + "min_range", min_range, 0.5, 100.0, "m"));
  ROVER_RETURN_IF_ERROR(
      CheckRange(p + "max_range", max_range, Bounds::OpenLow(min_range, 200.0), "m"));
  ROVER_RETURN_IF_ERROR(CheckRange(p + "level_tolerance_deg", level_tolerance_deg, 0.5, 30.0, "deg"));
  ROVER_RETURN_IF_ERROR(CheckRange(p + "truss_tolerance_deg", truss_tolerance_deg, 1.0, 60.0, "deg"));
  ROVER_RETURN_IF_ERROR(CheckRange(p + "min_level_length", min_level_length, 3.0, 500.0, "px"));
  ROVER_RETURN_IF_ERROR(CheckRange(p + "min_truss_length", min_truss_length, 3.0, 500.0, "px"));
  ROVER_RETURN_IF_ERROR(CheckRange(p + "min_truss_lines", min_truss_lines, 1, 50));
  ROVER_RETURN_IF_ERROR(CheckRange(p + "stereo_half_width", stereo_half_width, 2, 64, "px"));
  ROVER_RETURN_IF_ERROR(CheckRange(p + "min_correlation", min_correlation, 0.0, 1.0));
  ROVER_RETURN_IF_ERROR(CheckPositive(p + "disparity_sigma", disparity_sigma, "px"));
  ROVER_RETURN_IF_ERROR(CheckRange(p + "end_depth_offset", end_depth_offset, -2.0, 2.0, "m"));
  ROVER_RETURN_IF_ERROR(CheckRange(p + "monocular_sigma", monocular_sigma, Bounds::OpenLow(0.0, 1.0)));
  ROVER_RETURN_IF_ERROR(CheckRange(p + "max_disagreement", max_disagreement, Bounds::OpenLow(0.0, 1.0)));
  if (min_ramp_edges != 0) {
    ROVER_RETURN_IF_ERROR(CheckRange(p + "min_ramp_edges", min_ramp_edges, 3, 12));
  }
  ROVER_RETURN_IF_ERROR(CheckRange(p + "min_ramp_contrast", min_ramp_contrast, 0.0, 255.0));
  return Status::Ok();
}

void LanderDetectorOptions::BindParams(ParamBinder<LanderDetectorOptions>& b) {
  using O = LanderDetectorOptions;
  b.Bind("min_range", &O::min_range, "m", "nearest lander range searched");
  b.Bind("max_range", &O::max_range, "m", "farthest lander range searched");
  b.Bind("level_tolerance_deg", &O::level_tolerance_deg, "deg", "level segment: angle to horizontal");
  b.Bind("truss_tolerance_deg", &O::truss_tolerance_deg, "deg", "truss segment: angle to vertical");
  b.Bind("min_level_length", &O::min_level_length, "px", "shortest level segment used");
  b.Bind("min_truss_length", &O::min_truss_length, "px", "shortest truss segment used");
  b.Bind("min_truss_lines", &O::min_truss_lines, "", "truss segments needed under a deck band");
  b.Bind("stereo_half_width", &O::stereo_half_width, "px", "half width of a stereo patch");
  b.Bind("min_correlation", &O::min_correlation, "", "lowest accepted stereo correlation");
  b.Bind("disparity_sigma", &O::disparity_sigma, "px", "1-sigma of a matched disparity");
  b.Bind("end_depth_offset", &O::end_depth_offset, "m", "deck ends to deck centre along the view");
  b.Bind("monocular_sigma", &O::monocular_sigma, "", "relative 1-sigma of the monocular range");
  b.Bind("max_disagreement", &O::max_disagreement, "", "relative stereo-monocular gap tolerated");
  b.Bind("min_ramp_edges", &O::min_ramp_edges, "", "stripe-edge rows for the ramp hypothesis (0: off)");
  b.Bind("min_ramp_contrast", &O::min_ramp_contrast, "", "light ramp over ground [grey levels]");
}

Result<LanderSighting> DetectLander(const cv::Mat& left8, const cv::Mat& right8,
                                    const geometry::CameraModel& left_model,
                                    const geometry::CameraModel* right_model,
                                    const hwconfig::LanderDescription& lander,
                                    const LanderDetectorOptions& options,
                                    const std::optional<LanderPrior>& prior) {
  const auto t0 = std::chrono::steady_clock::now();
  ROVER_RETURN_IF_ERROR(options.Validate());
  ROVER_RETURN_IF_ERROR(lander.Validate());
  ROVER_RETURN_IF_ERROR(CheckImage("left image", left8, left_model));
  if (!right8.empty()) {
    if (right_model == nullptr) return InvalidArgument("right image: given without a right model");
    ROVER_RETURN_IF_ERROR(CheckImage("right image", right8, *right_model));
  }
  if (prior) {
    ROVER_RETURN_IF_ERROR(CheckFinite("prior.bearing", prior->bearing));
    ROVER_RETURN_IF_ERROR(CheckPositive("prior.bearing_window", prior->bearing_window, "rad"));
    ROVER_RETURN_IF_ERROR(CheckPositive("prior.range", prior->range, "m"));
    ROVER_RETURN_IF_ERROR(CheckPositive("prior.range_window", prior->range_window, "m"));
  }
  Detector d(left8, right8, left_model, right8.empty() ? nullptr : right_model, lander, options,
             prior);
  LanderSighting s = d.Run();
  s.elapsed_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return s;
}

void DrawLanderSighting(cv::Mat* bgr, const LanderSighting& s) {
  if (bgr == nullptr || bgr->empty()) return;
  const double scale = std::max(0.5, bgr->cols / 1024.0);
  const int thick = std::max(1, static_cast<int>(std::lround(2 * scale)));
  if (!s.found) {
    cv::putText(*bgr, "no lander: " + s.reason, cv::Point(10, static_cast<int>(30 * scale)),
                cv::FONT_HERSHEY_SIMPLEX, 0.7 * scale, cv::Scalar(0, 0, 255), thick);
    return;
  }
  for (const auto& l : s.lines) {
    const cv::Scalar colour = l.kind == LanderLine::Kind::kDeck ? cv::Scalar(0, 255, 255)
                                                                : cv::Scalar(255, 255, 0);
    cv::line(*bgr, cv::Point2d(l.a.x(), l.a.y()), cv::Point2d(l.b.x(), l.b.y()), colour, thick,
             cv::LINE_AA);
  }
  cv::rectangle(*bgr, s.box, cv::Scalar(0, 255, 0), thick);
  char text[160];
  std::snprintf(text, sizeof(text), "range %.2f +- %.2f m  bearing %.2f +- %.2f deg", s.range,
                s.range_sigma, s.bearing / kDegree, s.bearing_sigma / kDegree);
  const cv::Point org(std::max(0, s.box.x), std::max(static_cast<int>(20 * scale), s.box.y - 10));
  cv::putText(*bgr, text, org, cv::FONT_HERSHEY_SIMPLEX, 0.6 * scale, cv::Scalar(0, 255, 0), thick);
  cv::putText(*bgr, s.features, org + cv::Point(0, static_cast<int>(-24 * scale)),
              cv::FONT_HERSHEY_SIMPLEX, 0.6 * scale, cv::Scalar(0, 255, 0), thick);
}

}  // namespace rover::apl::rendezvous
