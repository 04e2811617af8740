#pragma once
/// @file
/// dl-locomotion: the service that binds the drive executor (library dl_locomotion) to topics.
///
///   in:  dl/drive_command (command)  -> DriveExecutor::Submit at the run-clock time of arrival
///        ddl/joint_state  (stream)   -> DriveExecutor::OnJointState (wheel/steer/suspension)
///        ddl/motor_status (latched)  -> DriveExecutor::OnMotorStatus
///        dl/pose          (state)    -> DriveExecutor::OnAttitude: ZYX roll, pitch, yaw of the
///                                       EKF quaternion, so turns in place close the loop on the
///                                       estimated heading (as FIDO did)
///   out: ddl/motor_command (command) every motor-group command the executor returns, in order
///        dl/drive_status   (latched) every status the executor returns (acceptance, phase
///                                       changes, the terminal one, rejections) and one per check
///                                       cycle (8 Hz) while a primitive runs
/// A run-clock timer at drive.check_rate_hz (8 Hz) steps the executor; nothing sleeps.
///
/// Bad commands never crash the service and never move the rover: NaN/inf fields, unknown
/// primitive values, out-of-range values -> REJECTED / REJECTED_INVALID with the reason in the
/// message; a command while one runs -> REJECTED_BUSY; stale inputs -> REJECTED / STALE_SENSOR.
/// When idle, a rejection also commands GROUP_STOP so the rover stays braked.
///
/// Run-clock resets (a simulator reset moves sim/clock back): a running primitive is stopped and
/// the executor restarts with empty inputs. Deactivation stops a running primitive too.
///
/// Parameters: geometry.* (DeclareRoverGeometryParams) and drive.* (DeclareDriveParams).
/// The IDL conversions are core/msg's (rover/msg/drive_idl.hpp, motor_idl.hpp, pose_idl.hpp,
/// sensors_idl.hpp): an unknown primitive value is kept for the executor to reject; a joint
/// state with an unknown health value, a motor status with an unknown state or fault, and a
/// dl/pose whose quaternion is not finite or degenerate (norm outside [0.5, 2]) are dropped.

#include <optional>

#include "rover/dl/locomotion/drive_executor.hpp"
#include "rover/runtime/service.hpp"

namespace rover::dl::locomotion {

class LocomotionService final : public Service {
 public:
  LocomotionService() : Service("dl-locomotion") {}

  void DeclareParameters(ParamSet& params) override;
  Status ValidateParameters(const ParamSet& params) const override;
  Status OnConfigure(ServiceContext& ctx, const ParamSet& params) override;
  Status OnDeactivate(ServiceContext& ctx) override;

  /// The executor (for tests); null before configuration.
  const DriveExecutor* drive_executor() const {
    return executor_.has_value() ? &*executor_ : nullptr;
  }

 private:
  void Publish(const DriveOutput& out);
  void OnTimer();
  void StopRunning(const char* why);
  void UpdateHealth(Time now);

  ServiceContext* ctx_ = nullptr;
  RoverGeometry geometry_;
  DriveOptions options_;
  std::optional<DriveExecutor> executor_;
  dds::Writer<rover_ddl_MotorCommand> motor_writer_;
  dds::Writer<rover_dl_DriveStatus> status_writer_;
  std::optional<Time> last_joint_;     // run-clock stamp of the latest healthy joint state
  std::optional<Time> last_attitude_;  // ... of the latest usable dl/pose
  std::optional<Time> last_timer_;     // run-clock time of the previous timer tick
};

}  // namespace rover::dl::locomotion
