#pragma once
/// @file
/// JointReader: hw/motor_telemetry encoder counts and hw/suspension_pots ADC counts ->
/// ddl/joint_state (engineering units, ddl sign conventions) with health.
///
///  * wheel_angle [rad]: cumulative since the first telemetry sample's register value:
///    count_k = count_(k-1) + hw::CounterDelta(reg_k, reg_(k-1)), angle = count / counts_per_rad
///    (int32 register wraps are invisible; the first sample's register value is kept as the
///    origin, so the angle equals the controller's absolute angle).
///  * wheel_rate [rad/s]: RateEstimator over `rate_window_s` of counts (not the controller's
///    velocity field).
///  * steer_angle, mast_pan, mast_tilt, arm_angle [rad]: register / counts_per_rad (absolute
///    joints).
///  * arm_contact: the newest hw/arm_contact sample's switch, when it is at most stale_after_s
///    old; false without one (the contact switch does not count in the health: a set without an
///    arm still has joint states; dl-arm treats a descent that never closes it as a fault).
///  * rocker/bogie [rad]: (adc - offset) / gain with the nominal PotSpec calibration.
/// Health (worst wins, the reason names the joint):
///  * STALE   no telemetry or no pots yet, or the newest is older than stale_after_s (run clock);
///  * FAILED  a pot at an ADC rail (0 or 4095: open or shorted wiper, or beyond its travel);
///  * DEGRADED a pot angle beyond its mechanical limit + pot_limit_margin, |left + right rocker|
///            > differential_tolerance (the differential forces left = -right), or a steering /
///            mast angle beyond its limits + joint_limit_margin.

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "rover/base/status.hpp"
#include "rover/base/time.hpp"
#include "rover/ddl/joints/rate_estimator.hpp"
#include "rover/hwconfig/hardware_config.hpp"
#include "rover/msg/sensors.hpp"

namespace rover::ddl::joints {

/// ddl/joint_state (rover/msg/sensors.hpp; stamp = the newest input sample's) and why its
/// health is not OK.
struct JointState : msg::JointState {
  std::string health_reason;  ///< empty when kOk (not in the IDL; for logs)
};

struct JointReaderOptions {
  double rate_window_s = 0.2;        ///< wheel-rate least-squares window
  double stale_after_s = 0.25;       ///< input older than this: STALE
  double pot_limit_margin = 0.05;    ///< [rad] beyond the mechanical stop: DEGRADED
  double joint_limit_margin = 0.05;  ///< [rad] steering / mast beyond limits: DEGRADED
  Status Validate() const;
};

class JointReader {
 public:
  /// Errors: config.Validate() or options.Validate() failures.
  static Result<JointReader> Create(const HardwareConfig& config,
                                    const JointReaderOptions& options = {});

  void OnMotorTelemetry(const hw::MotorTelemetry& telemetry);
  void OnSuspensionPots(const hw::SuspensionPots& pots);
  void OnArmContact(const hw::ArmContact& contact);
  /// The joint state as of `now` (run clock; only used for staleness).
  JointState State(Time now) const;

 private:
  JointReader(const HardwareConfig& config, const JointReaderOptions& options);

  HardwareConfig config_;
  JointReaderOptions options_;
  std::optional<hw::MotorTelemetry> last_telemetry_;
  std::array<std::int64_t, hw::kNumMotors> counts_{};  // unwrapped
  std::vector<RateEstimator> wheel_rates_;
  std::optional<hw::SuspensionPots> last_pots_;
  std::optional<hw::ArmContact> last_contact_;
};

}  // namespace rover::ddl::joints
