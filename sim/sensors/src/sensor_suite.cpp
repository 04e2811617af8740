#include "rover/sim/sensors/sensor_suite.hpp"

namespace rover::sim::sensors {
namespace {
// Noise streams: changing one sensor's draws never changes another's.
enum Stream : std::uint64_t { kMotorStream = 1, kPotStream = 2, kImuStream = 3, kSunStream = 4 };
}  // namespace

Result<SensorSuite> SensorSuite::Create(const HardwareConfig& config,
                                        const SimSensorOptions& options) {
  ROVER_RETURN_IF_ERROR(config.Validate().WithPrefix("hardware config"));
  ROVER_RETURN_IF_ERROR(options.Validate().WithPrefix("sensor options"));
  return SensorSuite(config, options);
}

SensorSuite::SensorSuite(const HardwareConfig& config, const SimSensorOptions& options)
    : config_(config),
      options_(options),
      motors_(config, options.motors, options.noise_scale, SensorSeed(options.seed, kMotorStream)),
      pots_(config.pots, options.pots, options.noise_scale, SensorSeed(options.seed, kPotStream)),
      imu_(config.imu, options.imu, options.noise_scale, SensorSeed(options.seed, kImuStream)),
      sun_(config.sun_sensor, options.sun_sensor, options.noise_scale,
           SensorSeed(options.seed, kSunStream)),
      ephemeris_(options.ephemeris),
      motor_clock_(config.telemetry.rate_hz),
      pot_clock_(config.pots.rate_hz),
      imu_clock_(config.imu.rate_hz),
      sun_clock_(config.sun_sensor.rate_hz) {}

void SensorSuite::ResetSchedules() {
  motor_clock_.Reset();
  pot_clock_.Reset();
  imu_clock_.Reset();
  sun_clock_.Reset();
}

SensorSamples SensorSuite::Step(const SensorTruth& truth) {
  SensorSamples out;
  if (motor_clock_.Due(truth.stamp)) {
    out.motor_telemetry = motors_.Pack(truth.motors, truth.applied_command_id, truth.stamp);
  }
  if (pot_clock_.Due(truth.stamp)) {
    out.suspension_pots = pots_.Sample(truth.suspension, truth.stamp);
    out.arm_contact = hw::ArmContact{truth.stamp.ns, truth.arm_contact};
  }
  if (imu_clock_.Due(truth.stamp)) out.imu = imu_.Sample(truth.imu, truth.stamp);
  if (sun_clock_.Due(truth.stamp)) {
    const geometry::SunState sun = ephemeris_.At(truth.stamp.seconds());
    out.sun_sensor = sun_.Sample(sun.direction_site, truth.site_from_rover, truth.stamp);
    out.sun = sun;
  }
  return out;
}

}  // namespace rover::sim::sensors
