#include "rover/dl/pose/pose_startup.hpp"

#include <algorithm>
#include <cmath>

#include "rover/geometry/transforms.hpp"

namespace rover::dl::pose {

void PoseStartOptions::BindParams(ParamBinder<PoseStartOptions>& b) {
  b.Bind("x", &PoseStartOptions::x, "m",
         "start position, site x (north); the site origin is the start")
      .Range(-1e6, 1e6);
  b.Bind("y", &PoseStartOptions::y, "m", "start position, site y (west)").Range(-1e6, 1e6);
  b.Bind("z", &PoseStartOptions::z, "m", "start position, site z (up)").Range(-1e6, 1e6);
  b.BindDegrees("yaw_deg", &PoseStartOptions::yaw,
                "start heading, from site x (north) towards y (west)")
      .Range(-360.0, 360.0);
  b.Bind("position_sigma", &PoseStartOptions::position_sigma, "m", "initial 1-sigma of x, y, z")
      .Range(0.0, 1e4);
  b.BindDegrees("tilt_sigma_deg", &PoseStartOptions::tilt_sigma,
                "initial 1-sigma of the levelled roll and pitch")
      .Range(0.0, 90.0);
  b.BindDegrees("yaw_sigma_deg", &PoseStartOptions::yaw_sigma, "initial 1-sigma of the heading")
      .Range(0.0, 180.0);
  b.Bind("gyro_bias_sigma", &PoseStartOptions::gyro_bias_sigma, "rad/s",
         "initial 1-sigma of the gyro bias")
      .Range(0.0, 1.0);
  b.Bind("level_samples", &PoseStartOptions::level_samples, "",
         "stationary accelerometer samples averaged to level roll and pitch")
      .Range(1, 100000);
  b.Bind("level_timeout_s", &PoseStartOptions::level_timeout_s, "s",
         "start anyway (from all plausible samples) if no stationary stretch by then")
      .Range(0.0, 3600.0);
  b.Bind("estimate_gyro_bias", &PoseStartOptions::estimate_gyro_bias,
         "initial gyro bias = mean gyro rate over the levelling stretch (else 0)");
}

Eigen::Vector2d LevelFromSpecificForce(const Eigen::Vector3d& f) {
  return {std::atan2(f.y(), f.z()), std::atan2(-f.x(), std::hypot(f.y(), f.z()))};
}

Leveller::Leveller(const PoseStartOptions& start, const EkfOptions& ekf)
    : start_(start), ekf_(ekf) {}

void Leveller::Reset() { *this = Leveller(start_, ekf_); }

std::optional<StartDecision> Leveller::Add(Time t, const Eigen::Vector3d& w,
                                           const Eigen::Vector3d& f) {
  if (!first_.has_value()) first_ = t;
  const bool plausible = std::abs(f.norm() - ekf_.gravity) <= ekf_.accel_magnitude_tolerance;
  const bool still = plausible && w.norm() <= ekf_.stationary_gyro_threshold;
  if (plausible) {
    f_all_ += f;
    ++count_all_;
  }
  if (still) {
    if (count_ == 0) still_since_ = t;
    f_sum_ += f;
    w_sum_ += w;
    ++count_;
  } else {
    f_sum_.setZero();
    w_sum_.setZero();
    count_ = 0;
  }
  std::optional<StartDecision> d;
  const double waited = ToSeconds(t - *first_);
  if (count_ >= start_.level_samples) {
    const double n = static_cast<double>(count_);
    const double span = ToSeconds(t - still_since_);
    d = Decide(t, f_sum_ / n,
               start_.estimate_gyro_bias ? Eigen::Vector3d(w_sum_ / n) : Eigen::Vector3d::Zero(),
               start_.estimate_gyro_bias ? span : 0.0);
    d->at_rest = true;
    d->samples = count_;
  } else if (waited >= start_.level_timeout_s) {
    const Eigen::Vector3d mean = count_all_ > 0
                                     ? Eigen::Vector3d(f_all_ / static_cast<double>(count_all_))
                                     : Eigen::Vector3d(0.0, 0.0, ekf_.gravity);
    d = Decide(t, mean, Eigen::Vector3d::Zero(), 0.0);
    d->at_rest = false;
    d->samples = count_all_;
  }
  if (d.has_value()) {
    d->waited_s = waited;
    Reset();
  }
  return d;
}

StartDecision Leveller::Decide(Time t, const Eigen::Vector3d& f_mean, const Eigen::Vector3d& bias,
                               double bias_span_s) const {
  StartDecision d;
  d.roll_pitch = LevelFromSpecificForce(f_mean);
  EkfInitialState& init = d.init;
  init.stamp = t;
  init.position = Eigen::Vector3d(start_.x, start_.y, start_.z);
  init.attitude = geometry::QuaternionFromRpy(d.roll_pitch.x(), d.roll_pitch.y(), start_.yaw);
  init.gyro_bias = bias;
  init.position_sigma = Eigen::Vector3d::Constant(start_.position_sigma);
  init.rpy_sigma = Eigen::Vector3d(start_.tilt_sigma, start_.tilt_sigma, start_.yaw_sigma);
  init.gyro_bias_sigma = start_.gyro_bias_sigma;
  if (bias_span_s > 0.0) {
    init.gyro_bias_sigma = std::min(
        start_.gyro_bias_sigma, std::max(ekf_.gyro_noise_density / std::sqrt(bias_span_s), 1e-7));
  }
  return d;
}

}  // namespace rover::dl::pose
