#include "rover/deploy/plots.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "rover/sim/terrain/terrain.hpp"

namespace rover::deploy {
namespace {

std::vector<Eigen::Vector2d> Track(const std::vector<std::array<double, 3>>& t) {
  std::vector<Eigen::Vector2d> out;
  out.reserve(t.size());
  for (const auto& p : t) out.emplace_back(p[1], p[2]);
  return out;
}

// A "nice" tick step for a range (1, 2 or 5 times a power of ten).
double TickStep(double range, int target_ticks) {
  const double raw = range / std::max(1, target_ticks);
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0, 10.0}) {
    if (m * mag >= raw) return m * mag;
  }
  return 10 * mag;
}

// A time window to shade in a panel (an injected fault while it acted).
struct Window {
  double t0, t1;
  std::string label;
};

// One panel: y(t) as a polyline with axes, ticks and labels; `limit` (NaN: none) as a dashed red
// line, `windows` shaded behind the curve.
void Panel(cv::Mat& img, cv::Rect area, const std::vector<double>& t, const std::vector<double>& y,
           const std::string& ylabel, const cv::Scalar& color, double limit,
           const std::vector<Window>& windows) {
  const int left = 70, bottom = 40, top = 25, right = 20;
  const cv::Rect plot(area.x + left, area.y + top, area.width - left - right,
                      area.height - top - bottom);
  cv::rectangle(img, plot, cv::Scalar(0, 0, 0), 1);
  cv::putText(img, ylabel, {area.x + 8, area.y + 17}, cv::FONT_HERSHEY_SIMPLEX, 0.5, {0, 0, 0}, 1,
              cv::LINE_AA);
  if (t.empty()) {
    cv::putText(img, "no estimate overlapped the truth record", {plot.x + 20, plot.y + plot.height / 2},
                cv::FONT_HERSHEY_SIMPLEX, 0.5, {0, 0, 200}, 1, cv::LINE_AA);
    return;
  }
  const double t0 = t.front(), t1 = std::max(t.back(), t0 + 1e-6);
  double y0 = *std::min_element(y.begin(), y.end()), y1 = *std::max_element(y.begin(), y.end());
  y0 = std::min(y0, 0.0);
  if (std::isfinite(limit)) y1 = std::max(y1, limit * 1.05);
  if (y1 - y0 < 1e-9) y1 = y0 + 1.0;
  const double ys = TickStep(y1 - y0, 5);
  y0 = std::floor(y0 / ys) * ys;
  y1 = std::ceil(y1 / ys) * ys;
  auto px = [&](double tv, double yv) {
    return cv::Point(plot.x + static_cast<int>((tv - t0) / (t1 - t0) * plot.width),
                     plot.y + plot.height - static_cast<int>((yv - y0) / (y1 - y0) * plot.height));
  };
  for (const Window& w : windows) {  // behind everything else
    const double a = std::clamp(w.t0, t0, t1), b = std::clamp(w.t1 < 0 ? t1 : w.t1, t0, t1);
    if (b <= a) continue;
    const cv::Point pa = px(a, y1), pb = px(b, y0);
    cv::rectangle(img, cv::Rect(pa, pb), {200, 230, 255}, cv::FILLED);
    cv::putText(img, w.label, {pa.x + 3, pa.y + 14}, cv::FONT_HERSHEY_SIMPLEX, 0.4, {0, 90, 200},
                1, cv::LINE_AA);
  }
  char buf[32];
  const int ticks = static_cast<int>(std::lround((y1 - y0) / ys));
  for (int k = 0; k <= ticks; ++k) {
    double v = y0 + k * ys;  // not accumulated: no "-1.39e-17" for zero
    if (std::abs(v) < ys * 1e-6) v = 0.0;
    const cv::Point p = px(t0, v);
    cv::line(img, p, {plot.x + plot.width, p.y}, {225, 225, 225}, 1);
    std::snprintf(buf, sizeof buf, "%.3g", v);
    cv::putText(img, buf, {area.x + 8, p.y + 4}, cv::FONT_HERSHEY_SIMPLEX, 0.4, {0, 0, 0}, 1, cv::LINE_AA);
  }
  const double ts = TickStep(t1 - t0, 8);
  for (double v = std::ceil(t0 / ts) * ts; v <= t1; v += ts) {
    const cv::Point p = px(v, y0);
    cv::line(img, p, {p.x, plot.y}, {225, 225, 225}, 1);
    std::snprintf(buf, sizeof buf, "%.0f", v);
    cv::putText(img, buf, {p.x - 10, plot.y + plot.height + 16}, cv::FONT_HERSHEY_SIMPLEX, 0.4,
                {0, 0, 0}, 1, cv::LINE_AA);
  }
  cv::putText(img, "simulated time [s]", {plot.x + plot.width / 2 - 60, area.y + area.height - 6},
              cv::FONT_HERSHEY_SIMPLEX, 0.45, {0, 0, 0}, 1, cv::LINE_AA);
  if (std::isfinite(limit)) {
    const int yl = px(t0, limit).y;
    for (int x = plot.x; x < plot.x + plot.width; x += 12) {
      cv::line(img, {x, yl}, {std::min(x + 7, plot.x + plot.width), yl}, {0, 0, 220}, 2);
    }
    std::snprintf(buf, sizeof buf, "limit %.3g", limit);
    cv::putText(img, buf, {plot.x + plot.width - 90, yl - 5}, cv::FONT_HERSHEY_SIMPLEX, 0.45,
                {0, 0, 220}, 1, cv::LINE_AA);
  }
  std::vector<cv::Point> pts;
  for (std::size_t i = 0; i < t.size(); ++i) pts.push_back(px(t[i], y[i]));
  cv::polylines(img, pts, false, color, 2, cv::LINE_AA);
}

// The limit a criterion of the run sets (NaN when the scenario has none).
double CriterionLimit(const RunResult& run, const std::string& name) {
  for (const auto& c : run.criteria) {
    if (c.name == name) return c.limit;
  }
  return std::numeric_limits<double>::quiet_NaN();
}

// The chosen arcs: `kArcDrawLength` of each arc from the pose it was chosen at; a point turn as
// a short stroke along its new heading.
constexpr double kArcDrawLength = 1.0;  // [m]

std::vector<Eigen::Vector2d> ArcPoints(const ChosenArc& a) {
  std::vector<Eigen::Vector2d> pts{{a.x, a.y}};
  if (a.point_turn) {
    const double th = a.yaw + a.turn_angle;
    pts.emplace_back(a.x + 0.5 * std::cos(th), a.y + 0.5 * std::sin(th));
    return pts;
  }
  double x = a.x, y = a.y, th = a.yaw;
  const int n = 10;
  const double ds = a.direction * kArcDrawLength / n;
  for (int i = 0; i < n; ++i) {
    x += ds * std::cos(th + 0.5 * a.curvature * ds);
    y += ds * std::sin(th + 0.5 * a.curvature * ds);
    th += a.curvature * ds;
    pts.emplace_back(x, y);
  }
  return pts;
}

}  // namespace

sim::terrain::MapCellLayer GoodnessLayer(const GoodnessGrid& g) {
  sim::terrain::MapCellLayer l;
  l.origin_x = g.origin_x;
  l.origin_y = g.origin_y;
  l.resolution = g.resolution;
  l.width = g.width;
  l.height = g.height;
  l.value = g.goodness;
  l.known.resize(g.flags.size());
  for (std::size_t k = 0; k < g.flags.size(); ++k) l.known[k] = g.flags[k] & 1;
  l.label = "last goodness map (black 0 .. white 255)";
  return l;
}

sim::terrain::MapOptions TrackMapOptions(const RunResult& run,
                                         const std::vector<Eigen::Vector2d>& planned) {
  sim::terrain::MapOptions o;
  o.title = run.scenario + " seed " + std::to_string(run.seed) + (run.pass ? "  PASS" : "  FAIL");
  if (run.mobility) {
    o.title += "  " + run.mobility->task + ": " + run.mobility->outcome;
    if (run.mobility->last_map && run.mobility->last_map->width > 0) {
      o.cell_layers.push_back(GoodnessLayer(*run.mobility->last_map));
    }
  }
  // Wide lines first, thin ones on top, so that no path hides another: truth widest, then the
  // odometry-only path, the estimate, the chosen arcs, and the planned path dashed on top (the
  // paths under it show between its dashes).
  const auto truth = Track(run.truth_track);
  if (truth.size() >= 2) o.polylines.push_back({truth, {20, 170, 40}, "driven (truth)", 5, true});
  const auto odo = Track(run.odometry_only_track);
  if (odo.size() >= 2) o.polylines.push_back({odo, {170, 60, 200}, "odometry only", 3, true});
  const auto est = Track(run.estimate_track);
  if (est.size() >= 2) o.polylines.push_back({est, {255, 140, 0}, "estimated", 2, true});
  if (run.mobility) {
    bool first = true;
    for (const ChosenArc& a : run.mobility->arcs) {
      o.polylines.push_back(
          {ArcPoints(a), {255, 105, 180}, first ? "chosen arcs (1 m)" : "", 2, false});
      first = false;
    }
  }
  // A phased task's phases over the driven path, each in its own colour.
  static const sim::terrain::MapColor kPhaseColors[] = {
      {0, 200, 255}, {255, 220, 0}, {255, 60, 60}, {200, 80, 255}, {255, 255, 255}, {0, 0, 0}};
  for (std::size_t k = 0; k < run.phases.size(); ++k) {
    const double t0 = run.phases[k].first;
    const double t1 = k + 1 < run.phases.size() ? run.phases[k + 1].first : 1e300;
    std::vector<Eigen::Vector2d> seg;
    for (const auto& p : run.truth_track) {
      if (p[0] >= t0 && p[0] <= t1) seg.emplace_back(p[1], p[2]);
    }
    if (seg.size() == 1) seg.push_back(seg.front());
    if (seg.size() >= 2) {
      o.polylines.push_back({seg, kPhaseColors[k % std::size(kPhaseColors)],
                             "phase " + run.phases[k].second, 2, true});
    }
  }
  if (planned.size() >= 2) {
    o.polylines.push_back({planned, {40, 90, 255}, "planned", 2, true, /*dashed=*/true});
  }
  // Each hazard contact: a magenta ring round the rock, labelled with the part that touched.
  for (std::size_t k = 0; k < run.hazard_contacts.size(); ++k) {
    const auto& c = run.hazard_contacts[k];
    std::vector<Eigen::Vector2d> ring;
    const double radius = 0.45;  // [m] round a rock of up to ~0.8 m: seen at any map scale
    for (int a = 0; a <= 24; ++a) {
      const double th = 2.0 * M_PI * a / 24.0;
      ring.emplace_back(c.xy.x() + radius * std::cos(th), c.xy.y() + radius * std::sin(th));
    }
    o.polylines.push_back({ring, {255, 0, 255},
                           k == 0 ? "hazard contact (part, time)" : "", 3, false});
    char label[96];
    std::snprintf(label, sizeof label, "%s %.0f s", c.part.c_str(), c.t_s);
    o.labels.push_back({c.xy + Eigen::Vector2d(radius, radius), label, {255, 0, 255}});
  }
  return o;
}

Status WriteTrackMap(const sim::terrain::Terrain& terrain, const RunResult& run,
                     const std::vector<Eigen::Vector2d>& planned, const std::string& path) {
  return sim::terrain::WriteTopDownMap(terrain, path, TrackMapOptions(run, planned));
}

Status WriteErrorPlot(const RunResult& run, const std::string& path) {
  cv::Mat img(520, 900, CV_8UC3, cv::Scalar(255, 255, 255));
  std::vector<double> t, pos, head;
  for (const auto& e : run.estimate_error) {
    t.push_back(e.t.seconds());
    pos.push_back(e.position_error);
    head.push_back(e.heading_error * 180.0 / M_PI);
  }
  cv::putText(img, run.scenario + " seed " + std::to_string(run.seed) + ": pose estimate - truth",
              {10, 18}, cv::FONT_HERSHEY_SIMPLEX, 0.55, {0, 0, 0}, 1, cv::LINE_AA);
  std::vector<Window> windows;
  for (const auto& f : run.faults) {
    if (f.start_s < 0) continue;  // never started
    windows.push_back({f.start_s, f.end_s, "fault " + std::to_string(f.id) + " " + f.kind});
  }
  Panel(img, cv::Rect(0, 25, 900, 245), t, pos, "position error [m]", {200, 90, 20},
        CriterionLimit(run, "max_estimate_error"), windows);
  Panel(img, cv::Rect(0, 270, 900, 245), t, head, "heading error [deg]", {20, 110, 230},
        CriterionLimit(run, "max_estimate_heading_error"), windows);
  try {
    if (!cv::imwrite(path, img)) return Unavailable(path + ": cannot write PNG");
  } catch (const cv::Exception& e) {
    return Unavailable(path + ": " + e.what());
  }
  return Status::Ok();
}

}  // namespace rover::deploy
