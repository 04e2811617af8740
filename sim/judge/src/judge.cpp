#include "rover/sim/judge/judge.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include "rover/geometry/polygon.hpp"
#include "rover/hwconfig/rover_description.hpp"

namespace rover::sim::judge {
namespace {
constexpr double kRadToDeg = 180.0 / std::numbers::pi;

double Yaw(const Eigen::Isometry3d& p) {
  const Eigen::Vector3d x = p.linear().col(0);
  return std::atan2(x.y(), x.x());
}

double WrapAngle(double a) { return std::remainder(a, 2.0 * std::numbers::pi); }

std::string Fmt(const char* f, double a, double b) {
  char buf[160];
  std::snprintf(buf, sizeof buf, f, a, b);
  return buf;
}
std::string Fmt1(const char* f, double a) {
  char buf[160];
  std::snprintf(buf, sizeof buf, f, a);
  return buf;
}
}  // namespace

double JudgeRock::Reach() const {
  double r = 0.5 * diameter;
  if (!outline.empty()) {
    r = 0.0;
    for (const Eigen::Vector2d& v : outline) r = std::max(r, (v - xy).norm());
  }
  return r;
}

bool RockTouches(const JudgeRock& rock, const Eigen::Matrix2d& rot, const Eigen::Vector2d& t,
                 const hwconfig::ContactPart& part, double margin) {
  const Eigen::Vector2d centre = rot.transpose() * (rock.xy - t);
  const double d = part.DistanceTo(centre);
  if (d >= rock.Reach() + margin) return false;
  if (rock.outline.empty()) return d < 0.5 * rock.diameter + margin;
  if (d <= 0.0) return true;  // the centre is on the part
  for (const Eigen::Vector2d& v : rock.outline) {
    if (part.DistanceTo(rot.transpose() * (v - t)) < margin) return true;
  }
  Eigen::Vector2d nearest;
  if (part.is_disc) {
    nearest = part.centre + part.radius * (centre - part.centre).normalized();
  } else {
    nearest = centre.cwiseMax(part.min).cwiseMin(part.max);
  }
  return geometry::InsidePolygon(rock.outline, rot * nearest + t);
}

RoverFootprint RoverFootprint::MerDefault() {
  RoverFootprint f;
  const hwconfig::RoverDescription rover;
  f.parts = rover.ContactParts();
  const hwconfig::Footprint g = rover.GroundFootprint();
  f.body_min = {g.min_x, g.min_y};
  f.body_max = {g.max_x, g.max_y};
  return f;
}

Status JudgeCriteria::Validate() const {
  auto positive = [](double v, const char* name) -> Status {
    if (!(v > 0) || !std::isfinite(v)) {
      return InvalidArgument(std::string("criteria.") + name + ": " + std::to_string(v) +
                             " must be a positive finite number");
    }
    return Status::Ok();
  };
  ROVER_RETURN_IF_ERROR(positive(position_tolerance, "position_tolerance"));
  ROVER_RETURN_IF_ERROR(positive(heading_tolerance, "heading_tolerance"));
  ROVER_RETURN_IF_ERROR(positive(traversable_height, "traversable_height"));
  if (!(max_tilt > 0 && max_tilt < std::numbers::pi / 2)) {
    return InvalidArgument("criteria.max_tilt: " + std::to_string(max_tilt * kRadToDeg) +
                           " deg must be in (0, 90)");
  }
  if (max_estimate_error) ROVER_RETURN_IF_ERROR(positive(*max_estimate_error, "max_estimate_error"));
  if (max_estimate_error_fraction) {
    ROVER_RETURN_IF_ERROR(positive(*max_estimate_error_fraction, "max_estimate_error_fraction"));
  }
  if (max_estimate_heading_error) {
    ROVER_RETURN_IF_ERROR(positive(*max_estimate_heading_error, "max_estimate_heading_error"));
  }
  if (max_hazard_contacts && *max_hazard_contacts < 0) {
    return InvalidArgument("criteria.max_hazard_contacts must be >= 0");
  }
  if (min_distance && (*min_distance < 0 || !std::isfinite(*min_distance))) {
    return InvalidArgument("criteria.min_distance must be >= 0");
  }
  if (target_xy && !target_xy->allFinite()) return InvalidArgument("criteria.target: not finite");
  return Status::Ok();
}

Result<Judge> Judge::Create(JudgeCriteria criteria, std::vector<JudgeRock> rocks,
                            RoverFootprint footprint) {
  ROVER_RETURN_IF_ERROR(criteria.Validate());
  if (footprint.parts.empty()) return InvalidArgument("rover footprint has no contact parts");
  if (!(footprint.clearance_margin >= 0.0) || !std::isfinite(footprint.clearance_margin)) {
    return InvalidArgument("rover footprint clearance_margin " +
                           std::to_string(footprint.clearance_margin) + " must be >= 0");
  }
  Judge j;
  j.criteria_ = criteria;
  j.footprint_ = std::move(footprint);
  for (const auto& r : rocks) {
    if (r.height > criteria.traversable_height) j.rocks_.push_back(r);
  }
  j.hit_.assign(j.rocks_.size(), false);
  j.hit_part_.assign(j.rocks_.size(), -1);
  j.hit_t_.assign(j.rocks_.size(), 0.0);
  j.overlap_.assign(j.rocks_.size(), false);
  if (!j.rocks_.empty()) {
    Eigen::Vector2d lo = j.rocks_[0].xy, hi = lo;
    for (const auto& r : j.rocks_) {
      lo = lo.cwiseMin(r.xy);
      hi = hi.cwiseMax(r.xy);
      j.max_rock_radius_ = std::max(j.max_rock_radius_, r.Reach());
    }
    j.grid_min_ = lo;
    j.grid_nx_ = static_cast<int>((hi.x() - lo.x()) / j.cell_) + 1;
    j.grid_ny_ = static_cast<int>((hi.y() - lo.y()) / j.cell_) + 1;
    j.grid_.resize(static_cast<std::size_t>(j.grid_nx_) * static_cast<std::size_t>(j.grid_ny_));
    for (std::size_t i = 0; i < j.rocks_.size(); ++i) {
      const int cx = static_cast<int>((j.rocks_[i].xy.x() - lo.x()) / j.cell_);
      const int cy = static_cast<int>((j.rocks_[i].xy.y() - lo.y()) / j.cell_);
      j.grid_[static_cast<std::size_t>(cy) * static_cast<std::size_t>(j.grid_nx_) +
              static_cast<std::size_t>(cx)]
          .push_back(i);
    }
  }
  return j;
}

void Judge::CheckRocks(const Eigen::Isometry3d& pose) {
  if (rocks_.empty()) return;
  // The rover's plan view: its yaw (tilt shortens the projection by cos(tilt), ignored).
  const Eigen::Matrix2d r2 = Eigen::Rotation2Dd(Yaw(pose)).toRotationMatrix();
  const Eigen::Vector2d t2 = pose.translation().head<2>();
  hwconfig::ContactPart ground;  // the whole ground-footprint rectangle
  ground.name = "footprint";
  ground.min = footprint_.body_min;
  ground.max = footprint_.body_max;
  // Candidate rocks near the rover: every part lies inside the ground footprint.
  const double reach =
      std::max({footprint_.body_min.norm(), footprint_.body_max.norm(),
                Eigen::Vector2d(footprint_.body_min.x(), footprint_.body_max.y()).norm(),
                Eigen::Vector2d(footprint_.body_max.x(), footprint_.body_min.y()).norm()}) +
      max_rock_radius_;
  const int x0 = std::max(0, static_cast<int>((t2.x() - reach - grid_min_.x()) / cell_));
  const int x1 = std::min(grid_nx_ - 1, static_cast<int>((t2.x() + reach - grid_min_.x()) / cell_));
  const int y0 = std::max(0, static_cast<int>((t2.y() - reach - grid_min_.y()) / cell_));
  const int y1 = std::min(grid_ny_ - 1, static_cast<int>((t2.y() + reach - grid_min_.y()) / cell_));
  for (int cy = y0; cy <= y1; ++cy) {
    for (int cx = x0; cx <= x1; ++cx) {
      for (std::size_t i : grid_[static_cast<std::size_t>(cy) * static_cast<std::size_t>(grid_nx_) +
                                 static_cast<std::size_t>(cx)]) {
        const JudgeRock& rock = rocks_[i];
        if (!overlap_[i]) overlap_[i] = RockTouches(rock, r2, t2, ground);
        if (hit_[i]) continue;
        for (std::size_t p = 0; p < footprint_.parts.size(); ++p) {
          const hwconfig::ContactPart& part = footprint_.parts[p];
          if (rock.height > footprint_.ClearanceOf(part) && RockTouches(rock, r2, t2, part)) {
            hit_[i] = true;
            hit_part_[i] = static_cast<int>(p);
            hit_t_[i] = now_s_;
            break;
          }
        }
      }
    }
  }
}

void Judge::AddTruth(Time t, const Eigen::Isometry3d& pose) {
  if (!truth_.empty() && t <= truth_.back().t) {
    ++out_of_order_;
    return;
  }
  if (!truth_.empty()) {
    distance_ += (pose.translation().head<2>() - truth_.back().pose.translation().head<2>()).norm();
  }
  const double tilt = std::acos(std::clamp(pose.linear()(2, 2), -1.0, 1.0));
  max_tilt_ = std::max(max_tilt_, tilt);
  now_s_ = t.seconds();
  CheckRocks(pose);
  truth_.push_back({t, pose});
}

void Judge::AddEstimate(Time t, const Eigen::Isometry3d& pose) {
  if (!estimates_.empty() && t <= estimates_.back().t) {
    ++out_of_order_;
    return;
  }
  estimates_.push_back({t, pose});
}

void Judge::AddOdometryOnlyEstimate(Time t, const Eigen::Isometry3d& pose) {
  if (!odometry_only_.empty() && t <= odometry_only_.back().t) {
    ++out_of_order_;
    return;
  }
  odometry_only_.push_back({t, pose});
}

std::vector<ErrorSample> Judge::ErrorsOf(const std::vector<Stamped>& estimates) const {
  std::vector<ErrorSample> out;
  out.reserve(estimates.size());
  for (const auto& e : estimates) {
    const auto truth = TruthAt(e.t);
    if (!truth) continue;
    ErrorSample s;
    s.t = e.t;
    s.position_error = (e.pose.translation().head<2>() - truth->translation().head<2>()).norm();
    s.heading_error = WrapAngle(Yaw(e.pose) - Yaw(*truth));
    out.push_back(s);
  }
  return out;
}

std::optional<Eigen::Isometry3d> Judge::TruthAt(Time t) const {
  if (truth_.empty() || t < truth_.front().t || t > truth_.back().t) return std::nullopt;
  auto it = std::lower_bound(truth_.begin(), truth_.end(), t,
                             [](const Stamped& s, Time v) { return s.t < v; });
  if (it == truth_.begin()) return it->pose;
  const Stamped& b = *it;
  const Stamped& a = *(it - 1);
  const double u = ToSeconds(t - a.t) / std::max(1e-12, ToSeconds(b.t - a.t));
  Eigen::Isometry3d p = Eigen::Isometry3d::Identity();
  p.translation() = (1 - u) * a.pose.translation() + u * b.pose.translation();
  p.linear() = Eigen::Quaterniond(a.pose.linear())
                   .slerp(u, Eigen::Quaterniond(b.pose.linear()))
                   .toRotationMatrix();
  return p;
}

const Criterion* Verdict::Find(const std::string& name) const {
  for (const auto& c : criteria) {
    if (c.name == name) return &c;
  }
  return nullptr;
}

std::string Verdict::FailureSummary() const {
  std::string out;
  for (const auto& c : criteria) {
    if (c.pass) continue;
    char buf[256];
    std::snprintf(buf, sizeof buf, "%s: %.4g %s (limit %.4g)%s%s", c.name.c_str(), c.measured,
                  c.unit.c_str(), c.limit, c.detail.empty() ? "" : "; ", c.detail.c_str());
    out += (out.empty() ? "" : "\n") + std::string(buf);
  }
  return out;
}

Verdict Judge::Evaluate() const {
  Verdict v;
  v.distance_driven = distance_;
  v.max_tilt = max_tilt_;
  if (truth_.empty()) {
    v.criteria.push_back({"truth_received", 0, 1, "count", false, "no ground truth was recorded"});
    return v;
  }
  const Eigen::Isometry3d& final_pose = truth_.back().pose;
  if (criteria_.target_xy) {
    const double e = (final_pose.translation().head<2>() - *criteria_.target_xy).norm();
    v.criteria.push_back({"final_position_error", e, criteria_.position_tolerance, "m",
                          e <= criteria_.position_tolerance,
                          Fmt("ended at (%.3f, %.3f)", final_pose.translation().x(),
                              final_pose.translation().y())});
  }
  if (criteria_.target_heading) {
    const double e = std::abs(WrapAngle(Yaw(final_pose) - *criteria_.target_heading));
    v.criteria.push_back({"final_heading_error", e * kRadToDeg,
                          criteria_.heading_tolerance * kRadToDeg, "deg",
                          e <= criteria_.heading_tolerance,
                          Fmt("final heading %.2f deg, goal %.2f deg", Yaw(final_pose) * kRadToDeg,
                              *criteria_.target_heading * kRadToDeg)});
  }
  v.criteria.push_back({"max_tilt", max_tilt_ * kRadToDeg, criteria_.max_tilt * kRadToDeg, "deg",
                        max_tilt_ <= criteria_.max_tilt, ""});
  std::string touched;  // "rocks 3 (0.24 m, wheel_lf), 9 (0.41 m, body)": the first five
  for (std::size_t i = 0; i < rocks_.size(); ++i) {
    if (overlap_[i]) v.footprint_overlaps.push_back(rocks_[i].id);
    if (!hit_[i]) continue;
    if (v.rocks_hit.size() < 5) {
      touched += (v.rocks_hit.empty() ? "rocks " : ", ") + std::to_string(rocks_[i].id) +
                 Fmt1(" (%.2f m, ", rocks_[i].height) +
                 footprint_.parts[static_cast<std::size_t>(hit_part_[i])].name + ")";
    }
    v.rocks_hit.push_back(rocks_[i].id);
    v.contacts.push_back({rocks_[i].id, rocks_[i].xy, rocks_[i].height,
                          footprint_.parts[static_cast<std::size_t>(hit_part_[i])].name,
                          hit_t_[i]});
  }
  const std::string taller = Fmt1("rocks taller than %.2f m", criteria_.traversable_height);
  {
    const double n = static_cast<double>(v.rocks_hit.size());
    const int limit = criteria_.max_hazard_contacts.value_or(0);
    v.criteria.push_back(
        {"hazard_contacts", n, static_cast<double>(limit), "count", n <= limit,
         touched.empty() ? taller + " touched by a wheel, suspension or the body" : touched});
  }
  {
    std::string list;
    for (std::size_t i = 0; i < v.footprint_overlaps.size() && i < 5; ++i) {
      list += (i ? ", " : "rocks ") + std::to_string(v.footprint_overlaps[i]);
    }
    const std::string where = taller + " under the ground-footprint rectangle";
    v.figures.push_back({"footprint_overlaps", static_cast<double>(v.footprint_overlaps.size()),
                         std::numeric_limits<double>::quiet_NaN(), "count", true,
                         list.empty() ? where : list + " (" + where + ")"});
  }
  if (criteria_.min_distance) {
    v.criteria.push_back({"distance_driven", distance_, *criteria_.min_distance, "m",
                          distance_ >= *criteria_.min_distance, "at least"});
  }
  // Estimate error over time.
  v.estimate_error = ErrorsOf(estimates_);
  v.odometry_only_error = ErrorsOf(odometry_only_);
  double max_err = 0, max_heading_err = 0;
  for (const auto& s : v.estimate_error) {
    max_err = std::max(max_err, s.position_error);
    max_heading_err = std::max(max_heading_err, std::abs(s.heading_error));
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  auto add_figures = [&](const std::string& prefix, const std::vector<ErrorSample>& errors,
                         const char* source) {
    if (errors.empty()) return;
    double worst = 0, worst_heading = 0;
    for (const auto& s : errors) {
      worst = std::max(worst, s.position_error);
      worst_heading = std::max(worst_heading, std::abs(s.heading_error));
    }
    const ErrorSample& last = errors.back();
    const std::string vs = std::string(source) + " vs sim/truth";
    v.figures.push_back({prefix + "final_error", last.position_error, nan, "m", true,
                         vs + Fmt1(", horizontal, at t = %.1f s", last.t.seconds())});
    if (distance_ > 0.05) {  // a percentage of a few centimetres says nothing
      v.figures.push_back({prefix + "final_error_percent", 100.0 * last.position_error / distance_,
                           nan, "%", true,
                           vs + Fmt(": %.3f m over %.2f m driven", last.position_error, distance_)});
    }
    v.figures.push_back({prefix + "max_error", worst, nan, "m", true, vs});
    v.figures.push_back({prefix + "final_heading_error", std::abs(last.heading_error) * kRadToDeg,
                         nan, "deg", true, vs});
    v.figures.push_back({prefix + "max_heading_error", worst_heading * kRadToDeg, nan, "deg", true,
                         vs});
  };
  add_figures("estimate_", v.estimate_error, "dl/pose");
  add_figures("odometry_only_", v.odometry_only_error, "dl/pose_odometry");
  if (criteria_.max_estimate_error || criteria_.max_estimate_error_fraction ||
      criteria_.max_estimate_heading_error) {
    if (v.estimate_error.empty()) {
      v.criteria.push_back({"estimate_received", 0, 1, "count", false,
                            "no pose estimate overlapped the truth record"});
    }
  }
  if (criteria_.max_estimate_error && !v.estimate_error.empty()) {
    v.criteria.push_back({"max_estimate_error", max_err, *criteria_.max_estimate_error, "m",
                          max_err <= *criteria_.max_estimate_error, ""});
  }
  if (criteria_.max_estimate_error_fraction && !v.estimate_error.empty()) {
    const double final_err = v.estimate_error.back().position_error;
    const double pct = distance_ > 0 ? 100.0 * final_err / distance_ : 0.0;
    v.criteria.push_back({"estimate_final_error_percent", pct,
                          100.0 * *criteria_.max_estimate_error_fraction, "%",
                          pct <= 100.0 * *criteria_.max_estimate_error_fraction,
                          Fmt("%.3f m over %.2f m driven", final_err, distance_)});
  }
  if (criteria_.max_estimate_heading_error && !v.estimate_error.empty()) {
    v.criteria.push_back({"max_estimate_heading_error", max_heading_err * kRadToDeg,
                          *criteria_.max_estimate_heading_error * kRadToDeg, "deg",
                          max_heading_err <= *criteria_.max_estimate_heading_error,
                          "dl/pose yaw vs sim/truth over the run"});
  }
  v.pass = std::all_of(v.criteria.begin(), v.criteria.end(), [](const Criterion& c) { return c.pass; });
  return v;
}

}  // namespace rover::sim::judge
