#pragma once
/// @file
/// MotorGroupManager: the motor driver's logic after MER's MOT, as a pure state machine (no
/// threads, no clock reads; the caller passes the run-clock time).
///
/// A ddl/motor_command selects a group of motors (mask) and gives each a position [rad] or
/// velocity [rad/s] goal. The manager
///  1. checks the command (typed CommandError; REJECTED status with fault BAD_COMMAND, or
///     NO_TELEMETRY when there is no fresh telemetry to plan from);
///  2. position groups: plans a synchronised move (sync_planner.hpp) from the latest telemetry
///     so that all motors finish together; the default timeout is
///     timeout_factor * T* + timeout_margin_s (a shorter explicit timeout is rejected);
///  3. emits ONE hw/motor_goals message holding every goal of the group (so they start
///     together; motors outside the group are MOTOR_IDLE, i.e. untouched) and preempts any
///     running group sharing a motor (that group ends FAULT/STOPPED, its other motors brake);
///  4. monitors the group from hw/motor_telemetry: the controller's latched flags and the
///     driver's own limits (current above MotorSpec::current_limit for overcurrent_time_s,
///     temperature above max_temperature for overtemp_time_s) on every sample; progress at the
///     8 Hz Tick: stall (a motor made less than stall_fraction of its planned progress over
///     stall_window_s), done (every motor within position_tolerance and slower than
///     settle_rate), timeout, telemetry silence / goals never acknowledged (NO_TELEMETRY);
///  5. on any fault brakes EVERY motor of the group and reports the fault and the motor index.
/// Velocity groups run until stopped, preempted or their timeout (then DONE and braked).
/// GROUP_STOP brakes the selected motors (all if the mask is 0); running groups it touches end
/// FAULT/STOPPED; the stop command itself is DONE at once.
///
/// Telemetry flags and limits only count once the controller echoes the group's hw command_id
/// (so stale latched flags from before the goals were applied are ignored).
/// Wheel positions are the int32 register value / counts_per_rad (absolute, +-140,000 rad).

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "rover/base/status.hpp"
#include "rover/base/time.hpp"
#include "rover/ddl/motor/motor_types.hpp"
#include "rover/hwconfig/hardware_config.hpp"

namespace rover::ddl::motor {

/// What to publish after a call: hw/motor_goals (if any) and ddl/motor_status samples.
struct ManagerOutput {
  std::optional<hw::MotorGoals> goals;
  std::vector<MotorStatus> statuses;
};

class MotorGroupManager {
 public:
  /// Errors: config.Validate() or options.Validate() failures.
  static Result<MotorGroupManager> Create(const HardwareConfig& config,
                                          const MotorManagerOptions& options = {});

  /// A new ddl/motor_command.
  ManagerOutput HandleCommand(const MotorCommand& command, Time now);
  /// A new hw/motor_telemetry sample (received at `now`); samples older than the newest one
  /// seen are ignored.
  ManagerOutput HandleTelemetry(const hw::MotorTelemetry& telemetry, Time now);
  /// The 8 Hz monitor: progress, completion, timeouts; one status per running group (or the
  /// latest final status when none runs, so the latched topic stays fresh).
  ManagerOutput Tick(Time now);
  /// Brakes every motor and stops every running group (FAULT/STOPPED with `reason`).
  ManagerOutput StopAll(Time now, const std::string& reason);

  /// Forgets the telemetry and its run-clock times, for when the run clock went back (a
  /// simulator reset): later telemetry, stamped before the old, is accepted again. The
  /// hardware command-id sequence continues, so a controller that still echoes an old id is
  /// never taken to have applied a new group's goals. Precondition: no group runs (StopAll
  /// first).
  void ForgetTelemetry();

  /// Command validation alone (no telemetry freshness check). `motor` gets the offending motor
  /// (or mask bit), -1 if none.
  CommandError Check(const MotorCommand& command, std::string* message, int* motor) const;

  bool busy() const { return !groups_.empty(); }
  const std::optional<MotorReadings>& latest() const { return latest_; }
  const HardwareConfig& config() const { return config_; }

 private:
  struct Group {
    std::uint32_t command_id = 0;
    GroupMode mode = GroupMode::kPosition;
    std::uint16_t mask = 0;
    std::array<double, hw::kNumMotors> goal{};       // [rad] or [rad/s]
    std::array<double, hw::kNumMotors> rate{};       // planned |rate| [rad/s]
    std::array<double, hw::kNumMotors> distance{};   // position: |goal - start| [rad]
    std::array<double, hw::kNumMotors> direction{};  // +1 / -1 along the motion
    std::array<double, hw::kNumMotors> overcurrent_s{};
    std::array<double, hw::kNumMotors> overtemp_s{};
    double planned_s = 0.0;  // synchronised duration (position) [s]
    Time started;            // command accepted
    Time deadline;
    std::uint32_t hw_id = 0;  // hw/motor_goals command_id carrying the group's goals
    bool applied = false;     // the controller echoed hw_id
    Time applied_at;
    std::optional<std::int64_t> last_stamp_ns;  // of the last telemetry judged
    std::vector<std::pair<Time, std::array<double, hw::kNumMotors>>> history;  // tick positions
    std::array<double, hw::kNumMotors> start{};  // [rad] positions when the goals were applied
    bool Has(int motor) const { return (mask >> motor) & 1u; }
  };
  MotorGroupManager(const HardwareConfig& config, const MotorManagerOptions& options);

  MotorStatus MakeStatus(std::uint32_t command_id, GroupState state, MotorFault fault,
                         int fault_motor, const std::string& message, Time now) const;
  hw::MotorGoals NewGoals(Time now);
  /// Ends group `index` with a final status; brakes its motors into `goals`.
  void EndGroup(std::size_t index, GroupState state, MotorFault fault, int fault_motor,
                const std::string& message, bool brake, Time now, ManagerOutput* out);
  hw::MotorGoals& GoalsOf(ManagerOutput* out, Time now);
  void CheckProgress(std::size_t index, Time now, ManagerOutput* out);

  HardwareConfig config_;
  MotorManagerOptions options_;
  std::vector<Group> groups_;
  std::optional<MotorReadings> latest_;
  std::optional<Time> latest_rx_;
  std::optional<MotorStatus> last_final_;
  std::uint32_t next_hw_id_ = 1;
};

}  // namespace rover::ddl::motor
