#pragma once
/// @file
/// ddl-motor: the motor driver service (after MER's MOT). Binds the MotorGroupManager
/// (ddl_motor) to topics:
///   in:  ddl/motor_command (command), hw/motor_telemetry (stream, 100 Hz)
///   out: hw/motor_goals (command), ddl/motor_status (latched; every status_rate_hz on the run
///        clock from MotorGroupManager::Tick, and on every change: acceptance, rejection, fault,
///        completion, preemption)
/// A rejected command is answered with GROUP_REJECTED (fault BAD_COMMAND or NO_TELEMETRY) and
/// the reason in `message`, and logged as a warning (sys/event). Telemetry stamped more than
/// max_future_s ahead of the run clock is dropped. When the run clock goes back (simulator
/// reset) or the service is deactivated, every group is stopped and every motor braked.
/// Health (heartbeat): STALE while hw/motor_telemetry is older than
/// motor_manager.telemetry_timeout_s, FAILED while writes to hw/motor_goals fail, else OK.
/// See docs/services/ddl-motor.md.

#include <optional>
#include <string>

#include "rover/ddl/driver_support/driver_health.hpp"
#include "rover/ddl/motor/motor_group_manager.hpp"
#include "rover/runtime/service.hpp"

namespace rover::ddl::motor {

class MotorService final : public Service {
 public:
  MotorService() : Service("ddl-motor") {}

  void DeclareParameters(ParamSet& p) override;
  /// Cross-parameter checks that `--validate` (and so `roverctl up`) reports before start-up.
  Status ValidateParameters(const ParamSet& p) const override;
  Status OnConfigure(ServiceContext& ctx, const ParamSet& p) override;
  Status OnDeactivate(ServiceContext& ctx) override;

 private:
  /// The run-clock time; if the clock went back, stops every group and forgets the telemetry.
  Time Now();
  void OnCommand(const rover_ddl_MotorCommand& command);
  void OnTelemetry(const rover_hw_MotorTelemetry& telemetry);
  void OnTick();
  void Publish(const ManagerOutput& out);
  void UpdateHealth(Time now);

  ServiceContext* ctx_ = nullptr;
  std::optional<MotorGroupManager> manager_;
  std::optional<driver_support::InputMonitor> telemetry_;
  driver_support::ClockJumpDetector clock_jump_;
  dds::Writer<rover_hw_MotorGoals> goals_writer_;
  dds::Writer<rover_ddl_MotorStatus> status_writer_;
  std::string write_error_;
};

}  // namespace rover::ddl::motor
