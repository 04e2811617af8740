#pragma once
/// @file
/// All simulated sensors of the rover, each sampled at its own rate on the run clock
/// (HardwareConfig: motor telemetry 100 Hz, pots 50 Hz, IMU 100 Hz, sun sensor 2 Hz). The
/// simulator calls Step() with the ideal state after every physics step; Step() returns the hw/
/// samples that fell due (publish each on its topic).

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <optional>

#include "rover/base/status.hpp"
#include "rover/base/time.hpp"
#include "rover/hwconfig/hardware_config.hpp"
#include "rover/sim/sensors/imu_model.hpp"
#include "rover/geometry/mars_sun.hpp"
#include "rover/sim/sensors/motor_telemetry_model.hpp"
#include "rover/sim/sensors/pot_model.hpp"
#include "rover/sim/sensors/sampling.hpp"
#include "rover/sim/sensors/sim_sensor_options.hpp"
#include "rover/sim/sensors/sun_sensor_model.hpp"

namespace rover::sim::sensors {

/// Ideal state of the rover at one instant (sign conventions of ddl/JointState).
struct SensorTruth {
  Time stamp;                                          ///< run-clock time of the state
  std::array<MotorPhysical, hw::kNumMotors> motors{};  ///< hw motor order
  std::uint32_t applied_command_id = 0;                ///< last hw MotorGoals::command_id applied
  /// [rad] left rocker, right rocker, left bogie, right bogie; + raises the front.
  std::array<double, hw::kNumPots> suspension{};
  bool arm_contact = false;  ///< the arm instrument's face touches something
  ImuTruth imu;  ///< rover-frame rate and specific force
  Eigen::Matrix3d site_from_rover = Eigen::Matrix3d::Identity();  ///< attitude
};

/// The samples due at one Step (each present only when its sensor sampled).
struct SensorSamples {
  std::optional<hw::MotorTelemetry> motor_telemetry;
  std::optional<hw::SuspensionPots> suspension_pots;
  std::optional<hw::ArmContact> arm_contact;  ///< sampled with the pots (a switch: no noise)
  std::optional<hw::ImuRaw> imu;
  std::optional<hw::SunSensorRaw> sun_sensor;
  std::optional<geometry::SunState> sun;  ///< the true sun when sun_sensor sampled (for the judge)
};

class SensorSuite {
 public:
  /// Errors: config.Validate() or options.Validate() failures (InvalidArgument).
  static Result<SensorSuite> Create(const HardwareConfig& config, const SimSensorOptions& options);

  /// Samples every sensor that is due at truth.stamp. Stamps must not decrease.
  SensorSamples Step(const SensorTruth& truth);

  /// Restart every schedule (the next Step samples all sensors); noise state continues.
  void ResetSchedules();

  const HardwareConfig& config() const { return config_; }
  const SimSensorOptions& options() const { return options_; }
  const ImuModel& imu() const { return imu_; }
  const SunSensorModel& sun_sensor() const { return sun_; }
  const geometry::SunEphemeris& ephemeris() const { return ephemeris_; }

 private:
  SensorSuite(const HardwareConfig& config, const SimSensorOptions& options);

  HardwareConfig config_;
  SimSensorOptions options_;
  MotorTelemetryModel motors_;
  SuspensionPotModel pots_;
  ImuModel imu_;
  SunSensorModel sun_;
  geometry::SunEphemeris ephemeris_;
  SampleClock motor_clock_, pot_clock_, imu_clock_, sun_clock_;
};

}  // namespace rover::sim::sensors
