#include "rover/apl/rendezvous/stripe_detector.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <numbers>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Eigenvalues>
#include <opencv2/imgproc.hpp>

#include "rover/base/check.hpp"
#include "rover/base/format.hpp"
#include "rover/base/param_binder.hpp"
#include "rover/base/range_check.hpp"
#include "rover/hwconfig/lander_description.hpp"

namespace rover::apl::rendezvous {
namespace {

using Eigen::Vector2d;

/// A line m.x = k with unit normal m.
struct Line {
  Vector2d m = Vector2d::UnitY();
  double k = 0.0;
  double Signed(const Vector2d& p) const { return m.dot(p) - k; }
};

std::optional<Vector2d> Intersect(const Line& a, const Line& b) {
  Eigen::Matrix2d A;
  A.row(0) = a.m.transpose();
  A.row(1) = b.m.transpose();
  const double det = A.determinant();
  if (std::abs(det) < 1e-9) return std::nullopt;
  return A.inverse() * Vector2d(a.k, b.k);
}

/// Total-least-squares line through points; nullopt for fewer than 2 points or no spread.
/// `rms` gets the rms perpendicular residual.
std::optional<Line> FitLine(const std::vector<Vector2d>& pts, double* rms) {
  if (pts.size() < 2) return std::nullopt;
  Vector2d mean = Vector2d::Zero();
  for (const auto& p : pts) mean += p;
  mean /= static_cast<double>(pts.size());
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (const auto& p : pts) cov += (p - mean) * (p - mean).transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(cov);
  if (es.eigenvalues()(1) <= 1e-12) return std::nullopt;
  Line l;
  l.m = es.eigenvectors().col(0);  // smallest eigenvalue: the normal
  l.k = l.m.dot(mean);
  if (rms) *rms = std::sqrt(std::max(0.0, es.eigenvalues()(0)) / static_cast<double>(pts.size()));
  return l;
}

/// FitLine with two rounds of dropping points beyond max(2.5 rms, 0.35 px).
std::optional<Line> FitLineRobust(std::vector<Vector2d> pts, double* rms) {
  double r = 0.0;
  std::optional<Line> l = FitLine(pts, &r);
  for (int round = 0; round < 2 && l; ++round) {
    const double limit = std::max(2.5 * r, 0.35);
    std::vector<Vector2d> kept;
    for (const auto& p : pts) {
      if (std::abs(l->Signed(p)) <= limit) kept.push_back(p);
    }
    if (kept.size() == pts.size() || kept.size() < 3) break;
    pts = std::move(kept);
    l = FitLine(pts, &r);
  }
  if (rms) *rms = r;
  return l;
}

/// Bilinear sample of an 8-bit image; -1 outside.
double Sample(const cv::Mat& img, double x, double y) {
  if (!(x >= 0.0 && y >= 0.0 && x <= img.cols - 1.001 && y <= img.rows - 1.001)) return -1.0;
  const int x0 = static_cast<int>(x), y0 = static_cast<int>(y);
  const double fx = x - x0, fy = y - y0;
  const std::uint8_t* r0 = img.ptr<std::uint8_t>(y0);
  const std::uint8_t* r1 = img.ptr<std::uint8_t>(y0 + 1);
  return (1 - fy) * ((1 - fx) * r0[x0] + fx * r0[x0 + 1]) +
         fy * ((1 - fx) * r1[x0] + fx * r1[x0 + 1]);
}

/// Samples `img` along p0 + t dir for t in [t0, t1] step dt; nullopt if any sample is outside.
std::optional<std::vector<double>> Profile(const cv::Mat& img, const Vector2d& p0,
                                           const Vector2d& dir, double t0, double t1, double dt) {
  std::vector<double> v;
  for (double t = t0; t <= t1 + 1e-9; t += dt) {
    const Vector2d p = p0 + t * dir;
    const double s = Sample(img, p.x(), p.y());
    if (s < 0) return std::nullopt;
    v.push_back(s);
  }
  return v;
}

/// Half-level crossing walking from index `from` (inside the dark stripe) in direction `step`
/// (+1/-1): the first place the profile rises above (dark + bright) / 2, where bright is the
/// profile's maximum beyond `from` on that side. Returns the fractional index, and the bright
/// level in *bright; nullopt if the profile never rises.
std::optional<double> HalfCrossing(const std::vector<double>& p, int from, int step, double dark,
                                   double* bright) {
  double hi = -1.0;
  for (int i = from; i >= 0 && i < static_cast<int>(p.size()); i += step) hi = std::max(hi, p[i]);
  const double level = 0.5 * (dark + hi);
  for (int i = from; i + step >= 0 && i + step < static_cast<int>(p.size()); i += step) {
    const double a = p[static_cast<std::size_t>(i)], b = p[static_cast<std::size_t>(i + step)];
    if (a <= level && b > level) {
      *bright = hi;
      return i + step * (level - a) / (b - a);
    }
  }
  return std::nullopt;
}

struct Candidate {
  Vector2d c = Vector2d::Zero();  ///< centroid
  Vector2d a = Vector2d::UnitX(); ///< long axis, a.x >= 0 (image right)
  Vector2d n = -Vector2d::UnitY();///< normal, n.y <= 0 (image up)
  double length = 0.0, thickness = 0.0;
  bool border_lo = false, border_hi = false;  ///< the -a / +a end touches the image border
  Line lower, upper;  ///< long edges (normals = n)
  double width = 0.0;  ///< [px] between the edges at c
  double rms = 0.0;
  std::vector<Vector2d> end_lo, end_hi;  ///< end points
  int up = -1, down = -1;  ///< neighbour links
  double code = 0.0;
  int ramp = -1, index = -1;
};

struct Moments {
  double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0, syy = 0;
};

/// Long-edge fitting of one candidate. False if it is not a dark band between two bright flanks.
bool FitEdges(const cv::Mat& img, const StripeDetectorOptions& o, Candidate* cand) {
  Candidate& c = *cand;
  const double half_t = 0.5 * c.thickness;
  const double flank = std::max(3.0, 0.6 * c.thickness);
  const double dt = 0.5;
  const double s_max = 0.5 * c.length - std::max(3.0, 0.1 * c.length);
  if (s_max <= 0) return false;
  const double ds = std::max(1.5, s_max / 60.0);
  std::vector<Vector2d> lo_pts, hi_pts;
  int tried = 0;
  for (double s = -s_max; s <= s_max + 1e-9; s += ds) {
    ++tried;
    const Vector2d p0 = c.c + s * c.a;
    const double t0 = -(half_t + flank);
    auto prof = Profile(img, p0, c.n, t0, half_t + flank, dt);
    if (!prof) continue;
    const auto& p = *prof;
    // Dark level: minimum over the central part.
    const int i_lo = static_cast<int>((-0.5 * half_t - t0) / dt);
    const int i_hi = static_cast<int>((0.5 * half_t - t0) / dt);
    int i_min = i_lo;
    for (int i = i_lo; i <= i_hi && i < static_cast<int>(p.size()); ++i) {
      if (p[static_cast<std::size_t>(i)] < p[static_cast<std::size_t>(i_min)]) i_min = i;
    }
    const double dark = p[static_cast<std::size_t>(i_min)];
    double b_lo = 0, b_hi = 0;
    const auto x_lo = HalfCrossing(p, i_min, -1, dark, &b_lo);
    const auto x_hi = HalfCrossing(p, i_min, +1, dark, &b_hi);
    if (!x_lo || !x_hi) continue;
    const double floor_dn = std::max(dark, 2.0);
    if (b_lo < o.min_contrast * floor_dn || b_hi < o.min_contrast * floor_dn) continue;
    lo_pts.push_back(p0 + (t0 + *x_lo * dt) * c.n);
    hi_pts.push_back(p0 + (t0 + *x_hi * dt) * c.n);
  }
  if (tried == 0 || lo_pts.size() < 4 || lo_pts.size() < 0.5 * tried) return false;
  double r_lo = 0, r_hi = 0;
  auto lower = FitLineRobust(lo_pts, &r_lo);
  auto upper = FitLineRobust(hi_pts, &r_hi);
  if (!lower || !upper) return false;
  // Orient both normals like n (towards the top of the image).
  if (lower->m.dot(c.n) < 0) { lower->m = -lower->m; lower->k = -lower->k; }
  if (upper->m.dot(c.n) < 0) { upper->m = -upper->m; upper->k = -upper->k; }
  c.lower = *lower;
  c.upper = *upper;
  c.rms = std::sqrt(0.5 * (r_lo * r_lo + r_hi * r_hi));
  c.width = c.lower.Signed(c.c) - c.upper.Signed(c.c);
  // Re-centre on the edges' midline.
  c.c -= 0.5 * (c.lower.Signed(c.c) + c.upper.Signed(c.c)) * c.n;
  return c.width > 1.0 && c.rms < 1.0;
}

/// End points of one candidate (half-level crossings along the long axis near both ends).
void FitEnds(const cv::Mat& img, const StripeDetectorOptions& o, Candidate* cand) {
  Candidate& c = *cand;
  const double inner = std::max(4.0, 0.12 * c.length);
  const double outer = std::max(6.0, 0.1 * c.length);
  const double dt = 0.5;
  const double half_w = 0.35 * c.width;
  for (int side = -1; side <= 1; side += 2) {
    if ((side < 0 && c.border_lo) || (side > 0 && c.border_hi)) continue;
    auto& pts = side < 0 ? c.end_lo : c.end_hi;
    for (double t = -half_w; t <= half_w + 1e-9; t += 0.5) {
      const Vector2d p0 = c.c + t * c.n;
      const Vector2d dir = side * c.a;
      const double t0 = 0.5 * c.length - inner;
      auto prof = Profile(img, p0, dir, t0, 0.5 * c.length + outer, dt);
      if (!prof) continue;
      const auto& p = *prof;
      double dark = p[0];
      for (int i = 0; i < 4 && i < static_cast<int>(p.size()); ++i) dark = std::min(dark, p[static_cast<std::size_t>(i)]);
      double bright = 0.0;
      const auto x = HalfCrossing(p, 0, +1, dark, &bright);
      if (!x || bright < o.min_contrast * std::max(dark, 2.0)) continue;
      pts.push_back(p0 + (t0 + *x * dt) * dir);
    }
  }
}

struct Placement {
  int ramp = -1, start = -1;
  double mse = std::numeric_limits<double>::infinity();
  double max_err = std::numeric_limits<double>::infinity();
};

}  // namespace

Status StripeDetectorOptions::Validate(const char* prefix) const {
  const std::string p(prefix);
  ROVER_RETURN_IF_ERROR(CheckRange(p + "dark_ratio", dark_ratio, Bounds{0.0, 1.0, true, true}));
  ROVER_RETURN_IF_ERROR(CheckIntRange(p + "bright_window_px", bright_window_px, 9, 1001));
  if (bright_window_px % 2 == 0) {
    return InvalidArgument(p + "bright_window_px: " + std::to_string(bright_window_px) +
                           " is even (the window needs a centre pixel)");
  }
  ROVER_RETURN_IF_ERROR(CheckRange(p + "min_bright_dn", min_bright_dn, 0.0, 255.0, "DN"));
  ROVER_RETURN_IF_ERROR(CheckIntRange(p + "min_area_px", min_area_px, 3, 1000000));
  ROVER_RETURN_IF_ERROR(CheckRange(p + "min_elongation", min_elongation, 1.0, 1000.0));
  ROVER_RETURN_IF_ERROR(CheckRange(p + "min_fill", min_fill, 0.0, 1.0));
  ROVER_RETURN_IF_ERROR(CheckRange(p + "min_contrast", min_contrast, 1.0, 100.0));
  ROVER_RETURN_IF_ERROR(
      CheckRange(p + "max_neighbour_angle_deg", max_neighbour_angle_deg, 0.0, 45.0, "deg"));
  ROVER_RETURN_IF_ERROR(CheckRange(p + "max_code_error", max_code_error, Bounds::OpenLow(0.0, 3.0)));
  ROVER_RETURN_IF_ERROR(CheckRange(p + "min_code_margin", min_code_margin, 0.0, 10.0));
  ROVER_RETURN_IF_ERROR(CheckIntRange(p + "gap_units", gap_units, 1, 100));
  return Status::Ok();
}

void StripeDetectorOptions::BindParams(ParamBinder<StripeDetectorOptions>& b) {
  using O = StripeDetectorOptions;
  b.Bind("dark_ratio", &O::dark_ratio, "", "dark pixel: below this fraction of the local bright level");
  b.Bind("bright_window_px", &O::bright_window_px, "px", "side of the local bright-level window (odd)");
  b.Bind("min_bright_dn", &O::min_bright_dn, "DN", "local bright level a stripe needs around it");
  b.Bind("min_area_px", &O::min_area_px, "px", "smallest dark component examined");
  b.Bind("min_elongation", &O::min_elongation, "", "length / thickness of a stripe candidate");
  b.Bind("min_fill", &O::min_fill, "", "component area / its rectangle's area");
  b.Bind("min_contrast", &O::min_contrast, "", "bright flank / dark level on both long edges");
  b.Bind("max_neighbour_angle_deg", &O::max_neighbour_angle_deg, "deg",
         "neighbouring stripes' long axes within this angle");
  b.Bind("max_code_error", &O::max_code_error, "", "worst stripe code error of an accepted match");
  b.Bind("min_code_margin", &O::min_code_margin, "",
         "mean squared code error margin of the best match over the runner-up");
  b.Bind("gap_units", &O::gap_units, "", "stripe gap in stripe-width units (0.15 / 0.03 = 5)");
}

std::vector<DetectedStripe> StripeDetection::OfRamp(int ramp) const {
  std::vector<DetectedStripe> out;
  for (const auto& s : stripes) {
    if (s.ramp == ramp) out.push_back(s);
  }
  return out;
}

int StripeDetection::BestRamp() const {
  int n0 = 0, n1 = 0;
  for (const auto& s : stripes) (s.ramp == 0 ? n0 : n1)++;
  if (n0 == 0 && n1 == 0) return -1;
  return n1 > n0 ? 1 : 0;
}

Result<StripeDetection> DetectStripes(const cv::Mat& gray8, const StripeDetectorOptions& o) {
  const auto t_start = std::chrono::steady_clock::now();
  if (gray8.empty()) return InvalidArgument("gray8: the image is empty");
  if (gray8.type() != CV_8UC1) {
    return InvalidArgument("gray8: type " + std::to_string(gray8.type()) +
                           " is not CV_8UC1 (8-bit, one channel)");
  }
  if (gray8.cols < 32 || gray8.rows < 32) {
    return InvalidArgument("gray8: " + std::to_string(gray8.cols) + " x " +
                           std::to_string(gray8.rows) + " is smaller than 32 x 32");
  }
  ROVER_RETURN_IF_ERROR(o.Validate());
  const cv::Mat& img = gray8;
  const int W = img.cols, H = img.rows;
  StripeDetection det;

  // 1. Local bright level: max over 4 x 4 blocks, max filter, back to full size.
  const int bw = (W + 3) / 4, bh = (H + 3) / 4;
  cv::Mat small(bh, bw, CV_8UC1, cv::Scalar(0));
  for (int y = 0; y < H; ++y) {
    const std::uint8_t* row = img.ptr<std::uint8_t>(y);
    std::uint8_t* srow = small.ptr<std::uint8_t>(y / 4);
    for (int x = 0; x < W; ++x) srow[x / 4] = std::max(srow[x / 4], row[x]);
  }
  const int k = std::max(3, (o.bright_window_px / 4) | 1);
  cv::dilate(small, small, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(k, k)));
  cv::Mat bright;
  cv::resize(small, bright, img.size(), 0, 0, cv::INTER_LINEAR);
  cv::Mat mask(H, W, CV_8UC1);
  for (int y = 0; y < H; ++y) {
    const std::uint8_t* r = img.ptr<std::uint8_t>(y);
    const std::uint8_t* b = bright.ptr<std::uint8_t>(y);
    std::uint8_t* m = mask.ptr<std::uint8_t>(y);
    for (int x = 0; x < W; ++x) {
      m[x] = (b[x] >= o.min_bright_dn && r[x] < o.dark_ratio * b[x]) ? 255 : 0;
    }
  }

  // 2. Components and their second moments.
  cv::Mat labels, stats, centroids;
  const int n_labels = cv::connectedComponentsWithStats(mask, labels, stats, centroids, 8, CV_32S);
  std::vector<Moments> mom(static_cast<std::size_t>(n_labels));
  for (int y = 0; y < H; ++y) {
    const int* l = labels.ptr<int>(y);
    for (int x = 0; x < W; ++x) {
      if (l[x] == 0) continue;
      Moments& m = mom[static_cast<std::size_t>(l[x])];
      m.n += 1;
      m.sx += x;
      m.sy += y;
      m.sxx += double(x) * x;
      m.sxy += double(x) * y;
      m.syy += double(y) * y;
    }
  }
  std::vector<Candidate> cands;
  const double max_area = 0.25 * W * H;
  for (int i = 1; i < n_labels; ++i) {
    const Moments& m = mom[static_cast<std::size_t>(i)];
    if (m.n < o.min_area_px || m.n > max_area) continue;
    Candidate c;
    c.c = Vector2d(m.sx / m.n, m.sy / m.n);
    Eigen::Matrix2d cov;
    cov(0, 0) = m.sxx / m.n - c.c.x() * c.c.x();
    cov(0, 1) = cov(1, 0) = m.sxy / m.n - c.c.x() * c.c.y();
    cov(1, 1) = m.syy / m.n - c.c.y() * c.c.y();
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(cov);
    const double l1 = std::max(es.eigenvalues()(1), 1e-6), l2 = std::max(es.eigenvalues()(0), 1.0 / 12.0);
    c.length = std::sqrt(12.0 * l1);
    c.thickness = std::sqrt(12.0 * l2);
    if (c.length < o.min_elongation * c.thickness) continue;
    if (m.n < o.min_fill * c.length * c.thickness) continue;
    c.a = es.eigenvectors().col(1);
    if (c.a.x() < 0) c.a = -c.a;
    if (c.a.x() < 0.5) continue;  // long axis more than 60 deg from the image rows
    c.n = Vector2d(c.a.y(), -c.a.x());
    const int bx = stats.at<int>(i, cv::CC_STAT_LEFT), by = stats.at<int>(i, cv::CC_STAT_TOP);
    const int bx1 = bx + stats.at<int>(i, cv::CC_STAT_WIDTH) - 1;
    const int by1 = by + stats.at<int>(i, cv::CC_STAT_HEIGHT) - 1;
    const bool on_border = bx <= 1 || by <= 1 || bx1 >= W - 2 || by1 >= H - 2;
    if (on_border) {
      // Which end: the end point nearer the border it touches.
      const Vector2d lo = c.c - 0.5 * c.length * c.a, hi = c.c + 0.5 * c.length * c.a;
      auto border_dist = [&](const Vector2d& p) {
        return std::min({p.x(), p.y(), W - 1 - p.x(), H - 1 - p.y()});
      };
      (border_dist(lo) < border_dist(hi) ? c.border_lo : c.border_hi) = true;
    }
    ++det.candidates;
    if (!FitEdges(img, o, &c)) continue;
    cands.push_back(std::move(c));
  }
  if (cands.size() < 2) {
    det.why = cands.empty() ? "no dark band between two light flanks (" +
                                  std::to_string(det.candidates) + " dark elongated regions)"
                            : "only one dark band between light flanks: no neighbour pair";
    det.elapsed_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t_start).count();
    return det;
  }

  // 4. Neighbour links: each stripe to the nearest compatible one above it.
  const double cos_max = std::cos(o.max_neighbour_angle_deg * std::numbers::pi / 180.0);
  const int nc = static_cast<int>(cands.size());
  std::vector<double> up_dist(static_cast<std::size_t>(nc), std::numeric_limits<double>::infinity());
  for (int i = 0; i < nc; ++i) {
    Candidate& ci = cands[static_cast<std::size_t>(i)];
    for (int j = 0; j < nc; ++j) {
      if (i == j) continue;
      const Candidate& cj = cands[static_cast<std::size_t>(j)];
      if (std::abs(ci.a.dot(cj.a)) < cos_max) continue;
      const Vector2d d = cj.c - ci.c;
      const double across = ci.n.dot(d), along = ci.a.dot(d);
      if (across <= 0) continue;
      if (std::abs(along) > 0.35 * std::max(ci.length, cj.length)) continue;
      const double ratio = cj.length / ci.length;
      if (ratio < 0.6 || ratio > 1.0 / 0.6) continue;
      const double mean_w = 0.5 * (ci.width + cj.width);
      const double gap = across - mean_w;
      if (gap < 0.35 * mean_w || gap > 4.0 * mean_w || gap < 0.8) continue;
      if (across < up_dist[static_cast<std::size_t>(i)]) {
        up_dist[static_cast<std::size_t>(i)] = across;
        ci.up = j;
      }
    }
  }
  // Resolve two stripes claiming the same upper neighbour: keep the nearer.
  for (int i = 0; i < nc; ++i) {
    const int j = cands[static_cast<std::size_t>(i)].up;
    if (j < 0) continue;
    const int prev = cands[static_cast<std::size_t>(j)].down;
    if (prev < 0 || up_dist[static_cast<std::size_t>(i)] < up_dist[static_cast<std::size_t>(prev)]) {
      if (prev >= 0) cands[static_cast<std::size_t>(prev)].up = -1;
      cands[static_cast<std::size_t>(j)].down = i;
    } else {
      cands[static_cast<std::size_t>(i)].up = -1;
    }
  }

  // Chains, bottom to top; codes from widths and gaps; placements.
  int best_chain_len = 0;
  std::vector<std::pair<int, std::vector<int>>> assigned;  // (sub-chain length, candidate ids)
  for (int start = 0; start < nc; ++start) {
    if (cands[static_cast<std::size_t>(start)].down >= 0 || cands[static_cast<std::size_t>(start)].up < 0) continue;
    std::vector<int> chain;
    for (int i = start; i >= 0 && chain.size() < 16; i = cands[static_cast<std::size_t>(i)].up) chain.push_back(i);
    const int m = static_cast<int>(chain.size());
    best_chain_len = std::max(best_chain_len, m);
    std::vector<double> unit(static_cast<std::size_t>(m - 1));  // px per stripe unit from gaps
    for (int q = 0; q + 1 < m; ++q) {
      const Candidate& lo = cands[static_cast<std::size_t>(chain[static_cast<std::size_t>(q)])];
      const Candidate& hi = cands[static_cast<std::size_t>(chain[static_cast<std::size_t>(q + 1)])];
      const Vector2d mid = 0.5 * (lo.c + hi.c);
      const double gap = lo.upper.Signed(mid) - hi.lower.Signed(mid);
      unit[static_cast<std::size_t>(q)] = std::max(gap, 1e-3) / o.gap_units;
    }
    // Local scale at each stripe: the gaps' px-per-unit, linear in the position across the
    // stripes (perspective), constant with a single gap.
    const Vector2d axis = cands[static_cast<std::size_t>(chain[0])].n;
    std::vector<double> gap_pos(static_cast<std::size_t>(m - 1));
    for (int q = 0; q + 1 < m; ++q) {
      gap_pos[static_cast<std::size_t>(q)] =
          0.5 * axis.dot(cands[static_cast<std::size_t>(chain[static_cast<std::size_t>(q)])].c +
                         cands[static_cast<std::size_t>(chain[static_cast<std::size_t>(q + 1)])].c);
    }
    double alpha = 0.0, beta = 0.0;
    {
      double sp = 0, su = 0, spp = 0, spu = 0;
      for (int q = 0; q + 1 < m; ++q) {
        const double p = gap_pos[static_cast<std::size_t>(q)], u = unit[static_cast<std::size_t>(q)];
        sp += p; su += u; spp += p * p; spu += p * u;
      }
      const double ng = m - 1;
      const double den = ng * spp - sp * sp;
      if (m >= 3 && den > 1e-6) {
        beta = (ng * spu - sp * su) / den;
        alpha = (su - beta * sp) / ng;
      } else {
        alpha = su / ng;
      }
    }
    std::vector<double> code(static_cast<std::size_t>(m));
    for (int q = 0; q < m; ++q) {
      Candidate& c = cands[static_cast<std::size_t>(chain[static_cast<std::size_t>(q)])];
      const double u = std::max(alpha + beta * axis.dot(c.c), 1e-3);
      c.code = c.width / u;
      code[static_cast<std::size_t>(q)] = c.code;
    }
    // Longest contiguous part with an unambiguous placement.
    bool done = false;
    for (int len = m; len >= 2 && !done; --len) {
      int best_a = -1;
      Placement best_p;
      for (int a0 = 0; a0 + len <= m; ++a0) {
        Placement first, second;
        for (int r = 0; r < 2; ++r) {
          for (int s0 = 0; s0 + len <= hwconfig::kStripesPerRamp; ++s0) {
            Placement p{r, s0, 0.0, 0.0};
            for (int q = 0; q < len; ++q) {
              const double e = code[static_cast<std::size_t>(a0 + q)] -
                               hwconfig::kRampStripeCodes[static_cast<std::size_t>(r)][static_cast<std::size_t>(s0 + q)];
              p.mse += e * e / len;
              p.max_err = std::max(p.max_err, std::abs(e));
            }
            if (p.mse < first.mse) {
              second = first;
              first = p;
            } else if (p.mse < second.mse) {
              second = p;
            }
          }
        }
        if (first.max_err > o.max_code_error || second.mse - first.mse < o.min_code_margin) continue;
        if (first.mse < best_p.mse) {
          best_p = first;
          best_a = a0;
        }
      }
      if (best_a < 0) continue;
      std::vector<int> ids;
      for (int q = 0; q < len; ++q) {
        Candidate& c = cands[static_cast<std::size_t>(chain[static_cast<std::size_t>(best_a + q)])];
        c.ramp = best_p.ramp;
        c.index = best_p.start + q;
        ids.push_back(chain[static_cast<std::size_t>(best_a + q)]);
      }
      assigned.emplace_back(len, std::move(ids));
      done = true;
    }
  }
  // A (ramp, index) named twice: the longer chain wins.
  std::sort(assigned.begin(), assigned.end(), [](const auto& x, const auto& y) { return x.first > y.first; });
  std::array<std::array<int, hwconfig::kStripesPerRamp>, 2> owner{};
  for (auto& r : owner) r.fill(-1);
  for (const auto& [len, ids] : assigned) {
    for (int id : ids) {
      const Candidate& c = cands[static_cast<std::size_t>(id)];
      int& slot = owner[static_cast<std::size_t>(c.ramp)][static_cast<std::size_t>(c.index)];
      if (slot < 0) slot = id;
    }
  }

  // 5. Ends: one line per ramp side through the end points of all its stripes.
  for (int r = 0; r < 2; ++r) {
    std::vector<int> ids;
    for (int s = 0; s < hwconfig::kStripesPerRamp; ++s) {
      if (owner[static_cast<std::size_t>(r)][static_cast<std::size_t>(s)] >= 0) ids.push_back(owner[static_cast<std::size_t>(r)][static_cast<std::size_t>(s)]);
    }
    if (ids.empty()) continue;
    for (int id : ids) FitEnds(img, o, &cands[static_cast<std::size_t>(id)]);
    std::array<std::optional<Line>, 2> end_line;  // 0: -a (v+), 1: +a (v-)
    for (int side = 0; side < 2; ++side) {
      std::vector<Vector2d> pts;
      int contributing = 0;
      for (int id : ids) {
        const auto& e = side == 0 ? cands[static_cast<std::size_t>(id)].end_lo : cands[static_cast<std::size_t>(id)].end_hi;
        if (!e.empty()) ++contributing;
        pts.insert(pts.end(), e.begin(), e.end());
      }
      double rms = 0.0;
      if (contributing >= 2) end_line[static_cast<std::size_t>(side)] = FitLineRobust(pts, &rms);
    }
    for (int id : ids) {
      const Candidate& c = cands[static_cast<std::size_t>(id)];
      DetectedStripe d;
      d.ramp = c.ramp;
      d.index = c.index;
      d.code_measured = c.code;
      d.edge_rms_px = c.rms;
      for (int side = 0; side < 2; ++side) {
        const auto& e = side == 0 ? c.end_lo : c.end_hi;
        std::optional<Line> line = end_line[static_cast<std::size_t>(side)];
        bool valid = line.has_value() && !e.empty();
        if (!line) {
          // No common line: this stripe's own end points if they span enough of its width,
          // else a line across the stripe's axis through them (an estimate, not valid).
          double rms = 0.0;
          std::optional<Line> own;
          if (e.size() >= 5 && (e.front() - e.back()).norm() >= 4.0) own = FitLineRobust(e, &rms);
          valid = own.has_value() && rms < 0.5;
          if (!own) {
            Line l;
            l.m = c.a;
            if (!e.empty()) {
              Vector2d mean = Vector2d::Zero();
              for (const auto& p : e) mean += p;
              l.k = l.m.dot(mean / static_cast<double>(e.size()));
            } else {
              l.k = l.m.dot(c.c) + (side == 0 ? -0.5 : 0.5) * c.length;
            }
            own = l;
          }
          line = own;
        }
        const auto lowc = Intersect(c.lower, *line), upc = Intersect(c.upper, *line);
        const int i_low = side == 0 ? 0 : 1, i_up = side == 0 ? 3 : 2;
        d.corners[static_cast<std::size_t>(i_low)] = lowc.value_or(c.c);
        d.corners[static_cast<std::size_t>(i_up)] = upc.value_or(c.c);
        for (int i : {i_low, i_up}) {
          const Vector2d& p = d.corners[static_cast<std::size_t>(i)];
          d.corner_valid[static_cast<std::size_t>(i)] =
              valid && lowc && upc && p.x() >= 0 && p.y() >= 0 && p.x() <= W - 1 && p.y() <= H - 1;
        }
      }
      det.stripes.push_back(d);
    }
  }
  std::sort(det.stripes.begin(), det.stripes.end(), [](const auto& x, const auto& y) {
    return x.ramp != y.ramp ? x.ramp < y.ramp : x.index < y.index;
  });
  if (det.stripes.empty()) {
    det.why = "no neighbouring dark bands whose widths match the stripe codes (" +
              std::to_string(cands.size()) + " bands, longest chain " +
              std::to_string(best_chain_len) + ")";
  } else if (det.OfRamp(det.BestRamp()).size() < hwconfig::kStripesPerRamp) {
    det.why = std::to_string(det.OfRamp(det.BestRamp()).size()) + " of " +
              std::to_string(hwconfig::kStripesPerRamp) + " stripes of ramp " +
              std::to_string(det.BestRamp()) + " identified";
  }
  det.elapsed_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t_start).count();
  return det;
}

void DrawStripeDetection(cv::Mat* bgr, const StripeDetection& detection) {
  ROVER_DEMAND(bgr != nullptr && bgr->type() == CV_8UC3);
  for (const auto& s : detection.stripes) {
    const cv::Scalar colour = s.ramp == 0 ? cv::Scalar(60, 220, 60) : cv::Scalar(0, 140, 255);
    std::vector<cv::Point> poly;
    for (const auto& c : s.corners) {
      poly.emplace_back(static_cast<int>(std::lround(c.x() * 4)), static_cast<int>(std::lround(c.y() * 4)));
    }
    cv::polylines(*bgr, poly, true, colour, 1, cv::LINE_AA, 2);
    for (int i = 0; i < 4; ++i) {
      if (!s.corner_valid[static_cast<std::size_t>(i)]) continue;
      cv::circle(*bgr, poly[static_cast<std::size_t>(i)], 4 * 4, cv::Scalar(0, 0, 255), 1, cv::LINE_AA, 2);
    }
    char label[64];
    std::snprintf(label, sizeof label, "r%ds%d c%.1f", s.ramp, s.index, s.code_measured);
    const Eigen::Vector2d at = s.corners[1] + Eigen::Vector2d(6.0, 0.0);
    cv::putText(*bgr, label, cv::Point(static_cast<int>(at.x()), static_cast<int>(at.y())),
                cv::FONT_HERSHEY_SIMPLEX, 0.45, colour, 1, cv::LINE_AA);
  }
}

}  // namespace rover::apl::rendezvous
