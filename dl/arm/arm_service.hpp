#pragma once
/// @file
/// dl-arm: the service that binds the instrument-arm state machine (library rover_dl_arm) to
/// topics.
///
///   in:  dl/arm_command   (command) -> ArmExecutor::Submit at the run-clock time of arrival
///        ddl/joint_state  (stream)  -> ArmExecutor::OnJoints (arm_angle, arm_contact); a
///                                      contact that ends a descent is acted on at once
///        ddl/motor_status (latched) -> ArmExecutor::OnMotorStatus (only the arm's groups)
///        ddl/mi_frame     (command) -> ArmExecutor::OnMiFrame (only its own request ids)
///   out: ddl/motor_command (command) position / stop commands for motors 12..15 (azimuth,
///                                    shoulder, elbow, wrist)
///        ddl/mi_request    (command) microscopic-imager frames of an AUTOFOCUS sweep
///        dl/arm_status     (latched) on every change and at arm.status_rate_hz while moving;
///                                    the IDLE status once at activation
/// A run-clock timer at arm.check_rate_hz steps the executor; nothing sleeps.
///
/// Bad input never crashes the service and never moves the arm: NaN/inf, out-of-limit,
/// unreachable or unknown values, moves into the rover, stale joints -> REJECTED with the
/// reason in the message (the field and value, or the link and the rover part). Deactivation
/// and a run clock that goes back stop a running command (FAULT).
///
/// Parameters: geometry.* (hwconfig::RoverDescription, the arm included) and arm.*
/// (ArmOptions). The IDL conversions are core/msg's (rover/msg/arm_idl.hpp, motor_idl.hpp,
/// sensors_idl.hpp); a sample they cannot read is dropped.

#include <optional>

#include "rover/dl/arm/arm_executor.hpp"
#include "rover/runtime/service.hpp"

namespace rover::dl::arm {

class ArmService final : public Service {
 public:
  ArmService() : Service("dl-arm") {}

  /// Staleness limits of the periodic inputs (parameters inputs.*): joint angles (50 Hz) and
  /// motor status (8 Hz).
  std::vector<runtime::InputSpec> Inputs() const override {
    return {{"ddl/joint_state", {.max_age_s = 0.5}}, {"ddl/motor_status", {.max_age_s = 1.0}}};
  }
  void DeclareParameters(ParamSet& params) override;
  Status ValidateParameters(const ParamSet& params) const override;
  Status OnConfigure(ServiceContext& ctx, const ParamSet& params) override;
  Status OnActivate(ServiceContext& ctx) override;
  Status OnDeactivate(ServiceContext& ctx) override;

  /// The executor (for tests); null before configuration.
  const ArmExecutor* executor() const { return executor_.has_value() ? &*executor_ : nullptr; }

 private:
  void Publish(const ArmOutput& out);
  void OnTimer();

  ServiceContext* ctx_ = nullptr;
  hwconfig::RoverDescription rover_;
  ArmOptions options_;
  std::optional<ArmExecutor> executor_;
  dds::Writer<rover_ddl_MotorCommand> motor_writer_;
  dds::Writer<rover_dl_ArmStatus> status_writer_;
  dds::Writer<rover_ddl_MiRequest> mi_writer_;
  std::optional<Time> last_timer_;
};

}  // namespace rover::dl::arm
