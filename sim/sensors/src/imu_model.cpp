#include "rover/sim/sensors/imu_model.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "rover/base/check.hpp"
#include "rover/geometry/transforms.hpp"

namespace rover::sim::sensors {
namespace {

Eigen::Vector3d Draw3(NoiseRng& rng, double sigma) {
  const double x = rng.Normal(sigma);
  const double y = rng.Normal(sigma);
  const double z = rng.Normal(sigma);
  return {x, y, z};
}

// Quantise one triad; returns true if any axis saturated.
bool Quantise(const Eigen::Vector3d& y, const InertialSensorSpec& s,
              std::array<std::int32_t, 3>* out) {
  bool saturated = false;
  const double max_lsb = std::floor(s.range / s.lsb);
  for (int i = 0; i < 3; ++i) {
    double v = y[i];
    if (!std::isfinite(v)) v = 0.0;
    if (std::abs(v) > s.range) saturated = true;
    const double lsb = std::clamp(std::round(v / s.lsb), -max_lsb, max_lsb);
    (*out)[static_cast<std::size_t>(i)] = static_cast<std::int32_t>(lsb);
  }
  return saturated;
}

}  // namespace

ImuModel::ImuModel(const ImuSpec& spec, const ImuErrors& errors, double noise_scale,
                   std::uint64_t seed)
    : spec_(spec), noise_scale_(noise_scale), rng_(seed) {
  ROVER_DEMAND(noise_scale >= 0.0 && errors.gyro_bias_sigma >= 0.0 &&
               errors.accel_bias_sigma >= 0.0);
  rover_from_case_ = spec.rover_from_case * geometry::RotationFromRpy(errors.mounting_error_rpy);
  k_gyro_ = (Eigen::Vector3d::Ones() + errors.gyro_scale_error).asDiagonal() *
            spec.gyro.ScaleMisalignment();
  k_accel_ = (Eigen::Vector3d::Ones() + errors.accel_scale_error).asDiagonal() *
             spec.accel.ScaleMisalignment();
  // Turn-on biases are drawn first, so they depend only on the seed.
  gyro_bias_ = spec.gyro.bias + errors.gyro_bias_error + Draw3(rng_, errors.gyro_bias_sigma);
  accel_bias_ = spec.accel.bias + errors.accel_bias_error + Draw3(rng_, errors.accel_bias_sigma);
}

hw::ImuRaw ImuModel::Sample(const ImuTruth& truth, Time stamp) {
  double dt = 0.0;
  if (last_.has_value() && stamp > *last_) dt = ToSeconds(stamp - *last_);
  last_ = stamp;
  const double s = noise_scale_;
  if (dt > 0.0) {
    gyro_drift_ += Draw3(rng_, s * spec_.gyro.bias_random_walk * std::sqrt(dt));
    accel_drift_ += Draw3(rng_, s * spec_.accel.bias_random_walk * std::sqrt(dt));
  }
  const Eigen::Matrix3d case_from_rover = rover_from_case_.transpose();
  const Eigen::Vector3d w = case_from_rover * truth.angular_velocity_rover;
  const Eigen::Vector3d f = case_from_rover * truth.specific_force_rover;
  const Eigen::Vector3d yg =
      k_gyro_ * w + TrueGyroBias() + Draw3(rng_, s * spec_.gyro.SampleSigma(spec_.rate_hz));
  const Eigen::Vector3d ya =
      k_accel_ * f + TrueAccelBias() + Draw3(rng_, s * spec_.accel.SampleSigma(spec_.rate_hz));
  hw::ImuRaw raw;
  raw.stamp_ns = stamp.ns;
  if (Quantise(yg, spec_.gyro, &raw.gyro)) raw.status |= hw::kImuGyroSaturated;
  if (Quantise(ya, spec_.accel, &raw.accel)) raw.status |= hw::kImuAccelSaturated;
  if (truth.self_test_fail) raw.status |= hw::kImuSelfTestFail;
  double t = truth.temperature_c + rng_.Normal(s * spec_.temperature_noise);
  if (!std::isfinite(t)) t = 0.0;
  const double t_lsb = std::clamp(std::round(t / hw::kImuTemperatureLsb),
                                  double{std::numeric_limits<std::int16_t>::min()},
                                  double{std::numeric_limits<std::int16_t>::max()});
  raw.temperature = static_cast<std::int16_t>(t_lsb);
  return raw;
}

}  // namespace rover::sim::sensors
