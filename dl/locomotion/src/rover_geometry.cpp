#include "rover/dl/locomotion/rover_geometry.hpp"

#include <cmath>
#include <numbers>

#include "rover/base/check.hpp"
#include "rover/base/format.hpp"
#include "rover/base/param_binder.hpp"
#include "rover/base/units.hpp"
#include "rover/dl/locomotion/ackermann.hpp"

namespace rover::dl::locomotion {
namespace {

using hwconfig::WheelName;

// Point q (x, z) rotated about pivot c (x, z) by the link angle a (front up positive).
Eigen::Vector2d RotateXz(const Eigen::Vector2d& q, const Eigen::Vector2d& c, double a) {
  const Eigen::Vector2d d = q - c;
  const double ca = std::cos(a);
  const double sa = std::sin(a);
  return c + Eigen::Vector2d(ca * d.x() - sa * d.y(), sa * d.x() + ca * d.y());
}

GeometryIssue Issue(std::string field, std::string key, std::string message) {
  return {std::move(field), std::move(key), std::move(message)};
}

}  // namespace

RoverGeometry::RoverGeometry() : RoverGeometry(hwconfig::RoverDescription{}) {}

RoverGeometry::RoverGeometry(const hwconfig::RoverDescription& rover)
    : wheel_radius(rover.wheel_radius),
      rocker_pivot(rover.rocker_pivot_x, rover.rocker_pivot_z),
      bogie_pivot(rover.bogie_pivot_x, rover.bogie_pivot_z),
      max_steer_angle(rover.max_steer_angle),
      min_turn_radius(rover.min_turn_radius),
      max_wheel_speed(rover.max_wheel_speed),
      arm_stow(rover.arm.stow) {
  for (int i = 0; i < kNumWheels; ++i) {
    wheel_centre[static_cast<std::size_t>(i)] = rover.WheelCentre(i);
  }
}

GeometryIssue CheckRoverGeometry(const RoverGeometry& g) {
  if (!std::isfinite(g.wheel_radius) || g.wheel_radius <= 0.0) {
    return Issue("wheel_radius", "wheel_radius", FormatNumber(g.wheel_radius) + " must be > 0");
  }
  for (int i = 0; i < kNumWheels; ++i) {
    if (!g.wheel_centre[static_cast<std::size_t>(i)].allFinite()) {
      return Issue("wheel_centre", "front_wheel_x",
                   std::string("wheel ") + WheelName(i) + " has a non-finite coordinate");
    }
  }
  if (!g.rocker_pivot.allFinite()) return Issue("rocker_pivot", "rocker_pivot_x", "not finite");
  if (!g.bogie_pivot.allFinite()) return Issue("bogie_pivot", "bogie_pivot_x", "not finite");
  const auto& c = g.wheel_centre;
  for (int side = 0; side < 2; ++side) {
    const int f = 3 * side;
    const double sign = side == 0 ? 1.0 : -1.0;
    for (int i = f; i < f + 3; ++i) {
      if (sign * c[static_cast<std::size_t>(i)].y() <= 0.0) {
        return Issue("wheel_centre", "half_track",
                     std::string("wheel ") + WheelName(i) +
                         " y = " + FormatNumber(c[static_cast<std::size_t>(i)].y()) + " must be " +
                         (side == 0 ? "> 0 (left side)" : "< 0 (right side)"));
      }
    }
    const double xf = c[static_cast<std::size_t>(f)].x();
    const double xm = c[static_cast<std::size_t>(f + 1)].x();
    const double xr = c[static_cast<std::size_t>(f + 2)].x();
    if (!(xf > xm && xm > xr)) {
      return Issue("wheel_centre", "middle_wheel_x",
                   std::string("x must decrease front > middle > rear on the ") +
                       (side == 0 ? "left" : "right") + " side (got " + FormatNumber(xf) + ", " +
                       FormatNumber(xm) + ", " + FormatNumber(xr) + ")");
    }
    if (!(g.bogie_pivot.x() > xr && g.bogie_pivot.x() < xm)) {
      return Issue("bogie_pivot", "bogie_pivot_x",
                   "x = " + FormatNumber(g.bogie_pivot.x()) + " must lie between the rear (" +
                       FormatNumber(xr) + ") and middle (" + FormatNumber(xm) + ") wheels");
    }
    if (!(g.rocker_pivot.x() > g.bogie_pivot.x() && g.rocker_pivot.x() < xf)) {
      return Issue("rocker_pivot", "rocker_pivot_x",
                   "x = " + FormatNumber(g.rocker_pivot.x()) +
                       " must lie between the bogie pivot (" + FormatNumber(g.bogie_pivot.x()) +
                       ") and the front wheel (" + FormatNumber(xf) + ")");
    }
  }
  if (std::abs(c[1].x() - c[4].x()) > 1e-9) {
    return Issue("wheel_centre", "middle_wheel_x",
                 "the unsteered middle wheels LM (x = " + FormatNumber(c[1].x()) +
                     ") and RM (x = " + FormatNumber(c[4].x()) + ") must share one axle");
  }
  if (!std::isfinite(g.max_steer_angle) || g.max_steer_angle <= 0.0 ||
      g.max_steer_angle >= std::numbers::pi / 2) {
    return Issue("max_steer_angle", "max_steer_angle_deg",
                 FormatNumber(g.max_steer_angle / kDegree) + " deg must be in (0, 90)");
  }
  double max_abs_y = 0.0;
  for (const auto& w : c) max_abs_y = std::max(max_abs_y, std::abs(w.y()));
  if (!std::isfinite(g.min_turn_radius) || g.min_turn_radius <= max_abs_y) {
    return Issue("min_turn_radius", "min_turn_radius",
                 FormatNumber(g.min_turn_radius) + " must exceed the largest wheel |y| (" +
                     FormatNumber(max_abs_y) + ")");
  }
  if (!std::isfinite(g.max_wheel_speed) || g.max_wheel_speed <= 0.0) {
    return Issue("max_wheel_speed", "max_wheel_speed",
                 FormatNumber(g.max_wheel_speed) + " must be > 0");
  }
  for (double k : {g.MaxCurvature(), -g.MaxCurvature()}) {
    for (int j = 0; j < kNumSteered; ++j) {
      const double a = ArcSteerAngle(g, j, k);
      if (std::abs(a) > g.max_steer_angle) {
        return Issue("max_steer_angle", "max_steer_angle_deg",
                     FormatNumber(g.max_steer_angle / kDegree) + " deg is below the " +
                         FormatNumber(std::abs(a) / kDegree) + " deg the " +
                         WheelName(kSteeredWheel[static_cast<std::size_t>(j)]) +
                         " wheel needs at the minimum turn radius");
      }
    }
  }
  for (int j = 0; j < kNumSteered; ++j) {
    const double a = TurnInPlaceSteerAngle(g, j);
    if (std::abs(a) > g.max_steer_angle) {
      return Issue("max_steer_angle", "max_steer_angle_deg",
                   FormatNumber(g.max_steer_angle / kDegree) + " deg is below the " +
                       FormatNumber(std::abs(a) / kDegree) + " deg the " +
                       WheelName(kSteeredWheel[static_cast<std::size_t>(j)]) +
                       " wheel needs to turn in place");
    }
  }
  return {};
}

Status RoverGeometry::Validate() const {
  const GeometryIssue issue = CheckRoverGeometry(*this);
  if (issue.field.empty()) return Status::Ok();
  return InvalidArgument("RoverGeometry." + issue.field + ": " + issue.message);
}

Eigen::Vector3d RoverGeometry::WheelCentre(int wheel, const SuspensionAngles& s) const {
  ROVER_DEMAND(wheel >= 0 && wheel < kNumWheels);
  const int side = Side(wheel);
  const auto si = static_cast<std::size_t>(side);
  const Eigen::Vector3d& w0 = wheel_centre[static_cast<std::size_t>(wheel)];
  Eigen::Vector2d q(w0.x(), w0.z());
  const bool on_bogie = wheel % 3 != 0;
  if (on_bogie) q = RotateXz(q, bogie_pivot, s.bogie[si]);
  q = RotateXz(q, rocker_pivot, s.rocker[si]);
  return Eigen::Vector3d(q.x(), w0.y(), q.y());
}

double RoverGeometry::LinkPitch(int wheel, const SuspensionAngles& s) {
  ROVER_DEMAND(wheel >= 0 && wheel < kNumWheels);
  const auto si = static_cast<std::size_t>(Side(wheel));
  return wheel % 3 == 0 ? s.rocker[si] : s.rocker[si] + s.bogie[si];
}

void DeclareRoverGeometryParams(ParamSet& params, const std::string& prefix) {
  DeclareParams<hwconfig::RoverDescription>(params, prefix);
}

Result<RoverGeometry> RoverGeometryFromParams(const ParamSet& params, const std::string& prefix) {
  ROVER_ASSIGN_OR_RETURN(const hwconfig::RoverDescription rover,
                         ReadParams<hwconfig::RoverDescription>(params, prefix));
  RoverGeometry g(rover);
  // The description's own checks cover these; a failure here names the closest key.
  const GeometryIssue issue = CheckRoverGeometry(g);
  if (issue.field.empty()) return g;
  const std::string key = prefix + issue.key;
  return InvalidArgument(params.Origin(key).ToString() + ": key '" + key + "': " + issue.message);
}

}  // namespace rover::dl::locomotion
