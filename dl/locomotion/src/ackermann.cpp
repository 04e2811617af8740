#include "rover/dl/locomotion/ackermann.hpp"

#include <algorithm>
#include <cmath>

#include "rover/base/check.hpp"
#include "rover/base/format.hpp"

namespace rover::dl::locomotion {
namespace {

Eigen::Vector2d Axis(const RoverGeometry& g, int wheel) {
  ROVER_DEMAND(wheel >= 0 && wheel < kNumWheels);
  return g.wheel_centre[static_cast<std::size_t>(wheel)].head<2>();
}

}  // namespace

double ArcSteerAngle(const RoverGeometry& g, int steer, double curvature) {
  ROVER_DEMAND(steer >= 0 && steer < kNumSteered);
  const Eigen::Vector2d p = Axis(g, kSteeredWheel[static_cast<std::size_t>(steer)]);
  return std::atan2(curvature * (p.x() - g.MiddleAxleX()), 1.0 - curvature * p.y());
}

std::array<double, kNumSteered> ArcSteerAngles(const RoverGeometry& g, double curvature) {
  std::array<double, kNumSteered> out{};
  for (int j = 0; j < kNumSteered; ++j) {
    out[static_cast<std::size_t>(j)] = ArcSteerAngle(g, j, curvature);
  }
  return out;
}

double ArcPathRatio(const RoverGeometry& g, int wheel, double curvature) {
  const Eigen::Vector2d p = Axis(g, wheel);
  return std::hypot(curvature * (p.x() - g.MiddleAxleX()), 1.0 - curvature * p.y());
}

std::array<double, kNumWheels> ArcPathRatios(const RoverGeometry& g, double curvature) {
  std::array<double, kNumWheels> out{};
  for (int i = 0; i < kNumWheels; ++i) {
    out[static_cast<std::size_t>(i)] = ArcPathRatio(g, i, curvature);
  }
  return out;
}

double TurnInPlaceSteerAngle(const RoverGeometry& g, int steer) {
  ROVER_DEMAND(steer >= 0 && steer < kNumSteered);
  const Eigen::Vector2d p = Axis(g, kSteeredWheel[static_cast<std::size_t>(steer)]);
  return std::atan(-(p.x() - g.MiddleAxleX()) / p.y());
}

std::array<double, kNumSteered> TurnInPlaceSteerAngles(const RoverGeometry& g) {
  std::array<double, kNumSteered> out{};
  for (int j = 0; j < kNumSteered; ++j) {
    out[static_cast<std::size_t>(j)] = TurnInPlaceSteerAngle(g, j);
  }
  return out;
}

double TurnInPlaceRadius(const RoverGeometry& g, int wheel) {
  const Eigen::Vector2d p = Axis(g, wheel);
  double steer = 0.0;
  for (int j = 0; j < kNumSteered; ++j) {
    if (kSteeredWheel[static_cast<std::size_t>(j)] == wheel) steer = TurnInPlaceSteerAngle(g, j);
  }
  const Eigen::Vector2d t(std::cos(steer), std::sin(steer));
  const Eigen::Vector2d v(-p.y(), p.x() - g.MiddleAxleX());  // velocity for a unit CCW rate
  return t.dot(v);
}

std::array<double, kNumWheels> TurnInPlaceRadii(const RoverGeometry& g) {
  std::array<double, kNumWheels> out{};
  for (int i = 0; i < kNumWheels; ++i) {
    out[static_cast<std::size_t>(i)] = TurnInPlaceRadius(g, i);
  }
  return out;
}

std::array<double, kNumWheels> TurnInPlaceWheelRates(const RoverGeometry& g, double yaw_rate) {
  std::array<double, kNumWheels> out = TurnInPlaceRadii(g);
  for (double& q : out) q = q * yaw_rate / g.wheel_radius;
  return out;
}

Result<DrivePlan> PlanArc(const RoverGeometry& g, double curvature, double distance, double speed) {
  if (!std::isfinite(curvature) || !std::isfinite(distance) || !std::isfinite(speed)) {
    return InvalidArgument("PlanArc: curvature " + FormatNumber(curvature) + ", distance " +
                           FormatNumber(distance) + ", speed " + FormatNumber(speed) +
                           " must be finite");
  }
  if (std::abs(curvature) > g.MaxCurvature() * (1.0 + 1e-12)) {
    return OutOfRange("PlanArc: |curvature| " + FormatNumber(std::abs(curvature)) +
                      " 1/m exceeds " + FormatNumber(g.MaxCurvature()) + " 1/m (min turn radius " +
                      FormatNumber(g.min_turn_radius) + " m)");
  }
  if (speed <= 0.0) return OutOfRange("PlanArc: speed " + FormatNumber(speed) + " m/s must be > 0");

  DrivePlan plan;
  plan.curvature = curvature;
  plan.distance = distance;
  plan.angle = curvature * distance;
  plan.steer_angle = ArcSteerAngles(g, curvature);
  const std::array<double, kNumWheels> ratio = ArcPathRatios(g, curvature);
  const double max_ratio = *std::max_element(ratio.begin(), ratio.end());
  plan.speed = std::min(speed, g.max_wheel_speed / max_ratio);
  plan.yaw_rate = std::abs(curvature) * plan.speed;
  const double dir = distance < 0.0 ? -1.0 : 1.0;
  for (std::size_t i = 0; i < ratio.size(); ++i) {
    plan.wheel_distance[i] = ratio[i] * distance;
    plan.wheel_rotation[i] = plan.wheel_distance[i] / g.wheel_radius;
    plan.wheel_speed[i] = dir * ratio[i] * plan.speed;
    plan.wheel_rate[i] = plan.wheel_speed[i] / g.wheel_radius;
  }
  if (curvature != 0.0) {
    plan.has_centre = true;
    plan.turn_centre = Eigen::Vector2d(g.MiddleAxleX(), 1.0 / curvature);
  }
  return plan;
}

Result<DrivePlan> PlanTurnInPlace(const RoverGeometry& g, double angle, double speed) {
  if (!std::isfinite(angle) || !std::isfinite(speed)) {
    return InvalidArgument("PlanTurnInPlace: angle " + FormatNumber(angle) + ", speed " +
                           FormatNumber(speed) + " must be finite");
  }
  if (speed <= 0.0) {
    return OutOfRange("PlanTurnInPlace: speed " + FormatNumber(speed) + " m/s must be > 0");
  }
  DrivePlan plan;
  plan.turn_in_place = true;
  plan.angle = angle;
  plan.steer_angle = TurnInPlaceSteerAngles(g);
  const std::array<double, kNumWheels> q = TurnInPlaceRadii(g);
  double max_q = 0.0;
  for (double v : q) max_q = std::max(max_q, std::abs(v));
  plan.speed = std::min(speed, g.max_wheel_speed);
  plan.yaw_rate = plan.speed / max_q;
  const double dir = angle < 0.0 ? -1.0 : 1.0;
  for (std::size_t i = 0; i < q.size(); ++i) {
    plan.wheel_distance[i] = q[i] * angle;
    plan.wheel_rotation[i] = plan.wheel_distance[i] / g.wheel_radius;
    plan.wheel_speed[i] = dir * q[i] * plan.yaw_rate;
    plan.wheel_rate[i] = plan.wheel_speed[i] / g.wheel_radius;
  }
  plan.has_centre = true;
  plan.turn_centre = Eigen::Vector2d(g.MiddleAxleX(), 0.0);
  return plan;
}

}  // namespace rover::dl::locomotion
