#pragma once
/// @file
/// dl-mast: the service that binds the mast pointing state machine (library rover_dl_mast) to
/// topics.
///
///   in:  dl/mast_command  (command) -> MastExecutor::Submit at the run-clock time of arrival
///        ddl/joint_state  (stream)  -> MastExecutor::OnJoints (mast_pan, mast_tilt)
///        ddl/motor_status (latched) -> MastExecutor::OnMotorStatus (only the mast's groups)
///        dl/pose          (state)   -> MastExecutor::OnPose (site_from_rover, for look-at)
///   out: ddl/motor_command (command) position / stop commands for motors 10 (pan), 11 (tilt)
///        dl/mast_status    (latched) on every change and at mast.status_rate_hz while moving;
///                                    the IDLE status once at activation
/// A run-clock timer at mast.check_rate_hz steps the executor; nothing sleeps.
///
/// Bad input never crashes the service and never moves the mast: NaN/inf, out-of-limit or
/// unknown values, stale joints or pose -> REJECTED with the reason in the message (the field
/// and value). A dl/pose whose quaternion is not a unit one is ignored (the pose then goes
/// stale). Deactivation and a run clock that goes back stop a running move (FAULT).
///
/// Parameters: geometry.* (hwconfig::RoverDescription) and mast.* (MastOptions).
/// The IDL conversions are core/msg's (rover/msg/mast_idl.hpp, motor_idl.hpp, sensors_idl.hpp,
/// pose_idl.hpp); a sample they cannot read is dropped.

#include <optional>

#include "rover/dl/mast/mast_executor.hpp"
#include "rover/runtime/service.hpp"

namespace rover::dl::mast {

class MastService final : public Service {
 public:
  MastService() : Service("dl-mast") {}

  /// Staleness limits of the periodic inputs (parameters inputs.*): joint angles (50 Hz), pose (10
  /// Hz) and motor status (8 Hz).
  std::vector<runtime::InputSpec> Inputs() const override {
    return {{"ddl/joint_state", {.max_age_s = 0.5}}, {"dl/pose", {.max_age_s = 1.0}},
            {"ddl/motor_status", {.max_age_s = 1.0}}};
  }
  void DeclareParameters(ParamSet& params) override;
  Status ValidateParameters(const ParamSet& params) const override;
  Status OnConfigure(ServiceContext& ctx, const ParamSet& params) override;
  Status OnActivate(ServiceContext& ctx) override;
  Status OnDeactivate(ServiceContext& ctx) override;

  /// The executor (for tests); null before configuration.
  const MastExecutor* executor() const { return executor_.has_value() ? &*executor_ : nullptr; }

 private:
  void Publish(const MastOutput& out);
  void OnTimer();

  ServiceContext* ctx_ = nullptr;
  hwconfig::RoverDescription rover_;
  MastOptions options_;
  std::optional<MastExecutor> executor_;
  dds::Writer<rover_ddl_MotorCommand> motor_writer_;
  dds::Writer<rover_dl_MastStatus> status_writer_;
  std::optional<Time> last_timer_;
};

}  // namespace rover::dl::mast
