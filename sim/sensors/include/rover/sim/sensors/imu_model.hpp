#pragma once
/// @file
/// LN-200-like IMU: ideal angular rate and specific force in the rover frame -> hw/imu raw LSB
/// in the IMU case frame.
///
/// For each triad (gyro: rad/s, accel: m/s^2), with the TRUE calibration (nominal ImuSpec plus
/// the simulator's ImuErrors):
///   x_c  = case_from_rover_true x_r,  rover_from_case_true = rover_from_case R(mounting_error)
///   y    = K_true x_c + b_true + d(t) + w,   K_true = diag(1 + scale_error) K_nominal
///   b_true = bias_nominal + bias_error + N(0, bias_sigma^2)   (turn-on bias, drawn once)
///   d(t_k) = d(t_k-1) + s K_b sqrt(t_k - t_k-1) N(0, I)       (bias random walk: Var = K_b^2 t)
///   w ~ N(0, (s N sqrt(rate_hz))^2 I)                          (white noise, N = noise density)
///   raw  = round(clamp(y, -range, range) / lsb),  saturation flag if any |y_i| > range
/// s = noise_scale. Temperature: round((T + N(0, s temperature_noise^2)) / 0.01 degC), int16.
/// The model keeps d(t) as state: samples must come in time order.

#include <Eigen/Core>
#include <cstdint>
#include <optional>

#include "rover/base/time.hpp"
#include "rover/hwconfig/hardware_config.hpp"
#include "rover/sim/sensors/sampling.hpp"

namespace rover::sim::sensors {

struct ImuErrors {
  Eigen::Vector3d gyro_bias_error = Eigen::Vector3d::Zero();   ///< [rad/s] true - nominal
  Eigen::Vector3d accel_bias_error = Eigen::Vector3d::Zero();  ///< [m/s^2]
  double gyro_bias_sigma = 0.0;   ///< [rad/s] turn-on bias repeatability (drawn from the seed)
  double accel_bias_sigma = 0.0;  ///< [m/s^2]
  Eigen::Vector3d gyro_scale_error = Eigen::Vector3d::Zero();  ///< relative, per case axis
  Eigen::Vector3d accel_scale_error = Eigen::Vector3d::Zero();
  Eigen::Vector3d mounting_error_rpy = Eigen::Vector3d::Zero();  ///< [rad] of the case
};

/// Ideal inertial quantities at the IMU.
struct ImuTruth {
  Eigen::Vector3d angular_velocity_rover = Eigen::Vector3d::Zero();  ///< [rad/s] rover frame
  Eigen::Vector3d specific_force_rover = Eigen::Vector3d::Zero();    ///< [m/s^2] a - g
  double temperature_c = 20.0;
  bool self_test_fail = false;  ///< sets status bit 2 (fault injection)
};

class ImuModel {
 public:
  /// Preconditions: spec valid, noise_scale >= 0, sigmas >= 0.
  ImuModel(const ImuSpec& spec, const ImuErrors& errors, double noise_scale, std::uint64_t seed);

  hw::ImuRaw Sample(const ImuTruth& truth, Time stamp);

  /// Current true biases (turn-on + random walk), case frame.
  Eigen::Vector3d TrueGyroBias() const { return gyro_bias_ + gyro_drift_; }
  Eigen::Vector3d TrueAccelBias() const { return accel_bias_ + accel_drift_; }
  const Eigen::Matrix3d& TrueRoverFromCase() const { return rover_from_case_; }

 private:
  ImuSpec spec_;
  double noise_scale_;
  Eigen::Matrix3d rover_from_case_;
  Eigen::Matrix3d k_gyro_, k_accel_;
  Eigen::Vector3d gyro_bias_, accel_bias_;
  Eigen::Vector3d gyro_drift_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d accel_drift_ = Eigen::Vector3d::Zero();
  std::optional<Time> last_;
  NoiseRng rng_;
};

}  // namespace rover::sim::sensors
