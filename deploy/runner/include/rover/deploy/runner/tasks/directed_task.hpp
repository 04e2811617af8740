#pragma once
/// @file
/// The directed task (`task.type: directed`): drive primitives in order, as MER's operators
/// sequenced them. One dl/drive_command per step (command ids 1, 2, ...); the task waits for that
/// command's terminal dl/drive_status (DONE, FAILED or REJECTED) before sending the next. A step
/// must end with the termination it expects ("nominal" unless it says otherwise); a step that
/// ends as expected with a fault ends the sequence (the rover is stopped and safe), one that ends
/// otherwise fails the run.
///
///   task:
///     type: directed
///     steps:
///       - {primitive: straight, distance: 5}            # [m], negative = backwards
///       - {primitive: turn_in_place, angle_deg: 90}     # positive = left
///       - {primitive: arc, curvature: 0.5, distance: 3} # [1/m], |curvature| <= 1
///       - {primitive: steer, curvature: 0.2}
///       - {primitive: stop}
///       # any step: speed [m/s] (0 = the drive service's default), timeout_s [s] (the command's
///       # own time-out), stop_after_s [s] (send STOP this long after the step starts),
///       # expect: nominal | tilt | suspension | motor_stall | motor_current | motor_fault |
///       #         timeout | stop_command | rejected_busy | rejected_invalid | stale_sensor
///     goal: {x: 20, y: 5, tolerance: 1}                 # optional: drawn on the map

#include <optional>
#include <string>
#include <vector>

#include "rover/deploy/runner/task.hpp"

namespace rover::deploy::runner {

enum class Primitive { kStraight, kArc, kTurnInPlace, kSteer, kStop };
const char* PrimitiveName(Primitive p);

struct DriveStep {
  Primitive primitive = Primitive::kStraight;
  double distance = 0;   ///< [m]
  double curvature = 0;  ///< [1/m]
  double angle = 0;      ///< [rad]
  double speed = 0;      ///< [m/s], 0 = default
  double timeout_s = 0;  ///< [s] the command's own time-out; 0 = the drive service's default
  double stop_after_s =
      0;  ///< [s] send STOP this long (simulated) after the step starts; 0 = never
  /// The termination this step must end with (see the file comment).
  std::string expect = "nominal";
  int line = 0;
};

struct DirectedTaskSpec {
  std::vector<DriveStep> steps;  ///< at least one
  std::optional<TaskGoal> goal;  ///< drawn on the map only
};

/// Parses one step (a map with the keys of the file comment); `where` prefixes the messages
/// ("task.steps[]: 'arc' needs 'curvature'").
Result<DriveStep> ParseDriveStep(const YAML::Node& n, const std::string& where,
                                 const yaml::FileErrors& err);

/// Parses a directed task's section; errors name file, line and key
/// ("s.yaml:12: task.steps[]: 'arc' needs 'curvature'").
Result<DirectedTaskSpec> ParseDirectedTask(const TaskSource& source);

/// The dead-reckoned path of the steps from the start pose (x, y [m], yaw [rad]): points every
/// 0.1 m along straights and arcs, turns in place change only the heading; then the goal, if any.
std::vector<Eigen::Vector2d> DirectedPlannedPath(const DirectedTaskSpec& spec, double start_x,
                                                 double start_y, double start_yaw);

class DirectedTask : public Task {
 public:
  /// A step's STOP (stop_after_s) carries the step's command id plus this.
  static constexpr std::uint32_t kStopIdOffset = 1000;

  DirectedTask(DirectedTaskSpec spec, double start_x, double start_y, double start_yaw)
      : spec_(std::move(spec)), start_x_(start_x), start_y_(start_y), start_yaw_(start_yaw) {}

  Status Open(TaskContext& ctx) override;
  /// The drive service hears dl/drive_command.
  bool Ready() const override;
  TaskOutcome Run(TaskContext& ctx) override;
  std::vector<Eigen::Vector2d> PlannedPath() const override {
    return DirectedPlannedPath(spec_, start_x_, start_y_, start_yaw_);
  }
  const DirectedTaskSpec& spec() const { return spec_; }

 private:
  // Sends step `index`' command, filling the start of `*result`; false if the write failed.
  bool Send(TaskContext& ctx, std::size_t index, StepResult* result);
  // Waits for that command's terminal status (sending STOP at stop_after_s) and fills `*result`;
  // returns the run's failure line if the wait was cut short.
  std::string AwaitTerminal(TaskContext& ctx, std::size_t index, StepResult* result);

  DirectedTaskSpec spec_;
  double start_x_, start_y_, start_yaw_;
  dds::Writer<rover_dl_DriveCommand> command_;
  dds::Reader<rover_dl_DriveStatus> status_;
};

/// Registers "directed".
void RegisterDirectedTask(TaskRegistry& registry);

}  // namespace rover::deploy::runner
