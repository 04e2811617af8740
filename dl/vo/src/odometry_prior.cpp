#include "rover/dl/vo/odometry_prior.hpp"

#include <cmath>
#include <string>

namespace rover::dl::vo {
namespace {

Status Check(const char* name, double v, double lo, double hi, bool open_lo) {
  if (std::isfinite(v) && (open_lo ? v > lo : v >= lo) && v <= hi) return Status::Ok();
  return InvalidArgument(std::string("odometry prior ") + name + " " + std::to_string(v) +
                         " is outside " + (open_lo ? "(" : "[") + std::to_string(lo) + ", " +
                         std::to_string(hi) + "]");
}

}  // namespace

void OdometryPriorOptions::BindParams(ParamBinder<OdometryPriorOptions>& b) {
  b.Bind("translation_sigma_min", &OdometryPriorOptions::translation_sigma_min, "m",
         "wheel-odometry prior: 1-sigma translation floor")
      .Range(0.001, 10.0);
  b.Bind("translation_sigma_fraction", &OdometryPriorOptions::translation_sigma_fraction, "",
         "wheel-odometry prior: added 1-sigma per metre of step (slip)")
      .Range(0.0, 10.0);
  b.BindDegrees("rotation_sigma_min_deg", &OdometryPriorOptions::rotation_sigma_min,
                "wheel-odometry prior: 1-sigma rotation floor")
      .Range(0.01, 90.0);
  b.Bind("rotation_sigma_fraction", &OdometryPriorOptions::rotation_sigma_fraction, "",
         "wheel-odometry prior: added 1-sigma per radian of turn")
      .Range(0.0, 10.0);
  b.Bind("vague_translation_sigma", &OdometryPriorOptions::vague_translation_sigma, "m",
         "prior 1-sigma when dl/pose is missing at a capture time")
      .Range(0.01, 10.0);
  b.BindDegrees("vague_rotation_sigma_deg", &OdometryPriorOptions::vague_rotation_sigma,
                "prior 1-sigma when dl/pose is missing at a capture time")
      .Range(0.1, 90.0);
}

Status OdometryPriorOptions::Validate() const {
  ROVER_RETURN_IF_ERROR(Check("translation_sigma_min", translation_sigma_min, 0.0, 100.0, true));
  ROVER_RETURN_IF_ERROR(
      Check("translation_sigma_fraction", translation_sigma_fraction, 0.0, 10.0, false));
  ROVER_RETURN_IF_ERROR(Check("rotation_sigma_min", rotation_sigma_min, 0.0, 3.2, true));
  ROVER_RETURN_IF_ERROR(
      Check("rotation_sigma_fraction", rotation_sigma_fraction, 0.0, 10.0, false));
  ROVER_RETURN_IF_ERROR(
      Check("vague_translation_sigma", vague_translation_sigma, 0.0, 100.0, true));
  ROVER_RETURN_IF_ERROR(Check("vague_rotation_sigma", vague_rotation_sigma, 0.0, 3.2, true));
  return Status::Ok();
}

MotionPrior OdometryPrior(const Eigen::Isometry3d& site_from_rover_from,
                          const Eigen::Isometry3d& site_from_rover_to,
                          const OdometryPriorOptions& o) {
  const Eigen::Isometry3d delta = site_from_rover_from.inverse() * site_from_rover_to;
  const double sigma_t =
      o.translation_sigma_min + o.translation_sigma_fraction * delta.translation().norm();
  const double sigma_r =
      o.rotation_sigma_min + o.rotation_sigma_fraction * RotationAngle(delta.linear());
  MotionPrior p = MotionPrior::Stationary(sigma_t, sigma_r);
  p.delta = delta;
  return p;
}

MotionPrior VaguePrior(const OdometryPriorOptions& o) {
  return MotionPrior::Stationary(o.vague_translation_sigma, o.vague_rotation_sigma);
}

}  // namespace rover::dl::vo
