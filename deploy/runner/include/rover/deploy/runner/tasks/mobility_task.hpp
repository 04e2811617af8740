#pragma once
/// @file
/// The mobility tasks: one apl/mobility_command to the mobility manager (apl-mobility), then
/// waiting for that command's terminal apl/mobility_status (SUCCEEDED, FAILED or REJECTED), as an
/// operator would. The run passes when the outcome is the one the scenario expects.
///
///   task:
///     type: autonav             # autonav | goto_waypoint | guarded | guarded_arc
///     goal: {x: 25, y: 0, tolerance: 0.5}   # [m] site frame; autonav and goto_waypoint
///     primitives:               # guarded and guarded_arc (1..32): the directed steps' keys
///       - {primitive: straight, distance: 5}          # [m], negative = backwards
///       - {primitive: arc, curvature: 0.5, distance: 3}
///       - {primitive: turn_in_place, angle_deg: 90}   # positive = left
///     visodom: false            # the VisOdom variant of the mode (seed 000, Table 2)
///     think: drive_while_thinking   # | stop_and_go | default (the service's parameter)
///     time_budget_s: 1200       # [s] the command's own budget (WAYPT_TIMEOUT); 0 = none
///     max_steps: 0              # autonav steps; 0 = the service's parameter
///     max_tilt_deg: 0           # handed to locomotion; 0 = the service's parameter
///     keep_out:                 # site-frame polygons (3..16 vertices, at most 8 zones)
///       - {name: crater, vertices: [[10, -2], [12, -2], [12, 2], [10, 2]]}
///     expect: reached           # | vetoed | a fault code: NOPATH, NOPROGRESS, KEEPOUT, ...
///
/// `expect: reached` passes on SUCCEEDED. A fault code passes on FAILED or REJECTED with that
/// fault (MER's names, seed 000 Table 1, in core/msg's spelling: ARB ACM POT TOD STOPPED
/// WAYPT_TIMEOUT NOPATH NOPROGRESS BUSY VISODOM KEEPOUT BAD_COMMAND IMG SAPP MOT DRIVE_TIMEOUT
/// TILT SUSPENSION NORTH; the paper's hyphens are read too). `vetoed` (guarded modes only) passes on FAILED with NOPATH: terrain assessment
/// forbade a primitive. The modes: autonav -> MOBILITY_AUTONAV (_VISODOM), goto_waypoint ->
/// MOBILITY_GO_TO_WAYPOINT (MOBILITY_VISODOM_GO_TO_WAYPOINT), guarded -> MOBILITY_GUARDED
/// (_VISODOM), guarded_arc -> MOBILITY_GUARDED_ARC (no VisOdom variant: visodom: true is an
/// error).
///
/// The runner waits for the terminal status until the command's time budget plus a grace of
/// kGraceS simulated seconds (then sends MOBILITY_STOP and fails the run), and always within the
/// run's own simulated and wall budgets. The outcome goes to RunResult::mobility (result.json
/// "mobility"), with the last apl/goodness_map and the chosen arc of every apl/arc_votes
/// recorded while the run went (for the judge's figures and the map plot).

#include <optional>
#include <string>
#include <vector>

#include "rover/deploy/runner/task.hpp"
#include "rover/deploy/runner/tasks/directed_task.hpp"
#include "rover/idl/types.hpp"
#include "rover/msg/mobility_idl.hpp"

namespace rover::deploy::runner {

enum class MobilityTaskType { kAutonav, kGoToWaypoint, kGuarded, kGuardedArc };
/// "autonav", "goto_waypoint", "guarded", "guarded_arc".
const char* MobilityTaskTypeName(MobilityTaskType t);

/// A keep-out zone of the task (site frame [m]).
struct KeepOut {
  std::string name;
  std::vector<Eigen::Vector2d> vertices;
};

struct MobilityTaskSpec {
  MobilityTaskType type = MobilityTaskType::kAutonav;
  std::optional<TaskGoal> goal;      ///< required for autonav and goto_waypoint
  std::vector<DriveStep> primitives;  ///< required for guarded and guarded_arc
  bool visodom = false;
  msg::ThinkMode think = msg::ThinkMode::kDefault;
  double time_budget_s = 0;  ///< [s] 0 = none
  int max_steps = 0;
  double max_tilt = 0;  ///< [rad]
  std::vector<KeepOut> keep_out;
  /// "reached", "vetoed" or a fault code name (see the file comment).
  std::string expect = "reached";
};

/// The fault code names, core/msg's (msg::MobilityFaultName: WAYPT_TIMEOUT), index =
/// msg::MobilityFault; "NONE" for kNone.
const std::vector<std::string>& MobilityFaultNames();
/// "none", "goal error", "motion error" (msg::FaultClassName in prose).
std::string FaultClassProse(msg::FaultClass c);
/// The mode of a task type with or without VisOdom.
msg::MobilityMode MobilityModeOf(MobilityTaskType type, bool visodom);

/// Parses a mobility task's section (task.type is one of the four); errors name file, line,
/// key and value ("s.yaml:9: task.keep_out[].vertices: 2 vertices, a zone needs 3..16").
Result<MobilityTaskSpec> ParseMobilityTask(const TaskSource& source, MobilityTaskType type);

/// The command the task sends (command id `command_id`, stamped `now_s`), built as a
/// msg::MobilityCommand and converted by core/msg. The primitives and zones point into
/// `storage`, which must outlive the Write.
using MobilityCommandStorage = msg::MobilityCommandMessage;
rover_apl_MobilityCommand MakeMobilityCommand(const MobilityTaskSpec& spec, std::uint32_t command_id,
                                              double now_s, MobilityCommandStorage* storage);

/// A terminal status as the outcome name `expect` compares with: "reached" for SUCCEEDED, else
/// the fault code name (REJECTED without a fault is "BAD_COMMAND").
std::string OutcomeName(const msg::MobilityStatus& status);
/// True if `outcome` (an OutcomeName) is what `expect` names: "vetoed" is a NOPATH fault (a
/// guarded primitive refused by terrain assessment), anything else must equal the name.
bool OutcomeNameMatches(const std::string& expect, const std::string& outcome);
/// True if the terminal status is the outcome `expect` names.
bool OutcomeMatches(const std::string& expect, const msg::MobilityStatus& status);

class MobilityTask : public Task {
 public:
  static constexpr std::uint32_t kCommandId = 1;
  static constexpr std::uint32_t kStopId = 2;
  /// [s] simulated seconds beyond the command's time budget the runner waits for its verdict.
  static constexpr double kGraceS = 30.0;

  MobilityTask(MobilityTaskSpec spec, double start_x, double start_y, double start_yaw)
      : spec_(std::move(spec)), start_x_(start_x), start_y_(start_y), start_yaw_(start_yaw) {}

  Status Open(TaskContext& ctx) override;
  /// apl-mobility hears apl/mobility_command.
  bool Ready() const override;
  TaskOutcome Run(TaskContext& ctx) override;
  /// Goal modes: start -> goal; guarded modes: the dead-reckoned primitives.
  std::vector<Eigen::Vector2d> PlannedPath() const override;
  const MobilityTaskSpec& spec() const { return spec_; }

 private:
  MobilityTaskSpec spec_;
  double start_x_, start_y_, start_yaw_;
  dds::Writer<rover_apl_MobilityCommand> command_;
  dds::Reader<rover_apl_MobilityStatus> status_;
};

/// Registers autonav, goto_waypoint, guarded and guarded_arc.
void RegisterMobilityTasks(TaskRegistry& registry);

}  // namespace rover::deploy::runner
