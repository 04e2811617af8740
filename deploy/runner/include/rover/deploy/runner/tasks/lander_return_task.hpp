#pragma once
/// @file
/// The lander-return task: one apl/rendezvous_command (RETURN_TO_LANDER) to apl-rendezvous, then
/// waiting for its terminal apl/rendezvous_status (DONE or FAILED), recording every status for
/// the judge (rendezvous_judging.hpp) as an operator would watch them.
///
///   task:
///     type: lander_return
///     estimate: {x: 30, y: 1.5}  # [m] a-priori deck centre, site frame (required)
///     standoff: 1.0              # [m] rover origin before the ramp base; 0 = the service's
///     ramp: 0                    # 0 | 1 | -1 (the first one seen)
///     climb: true                # drive up the ramp onto the deck after the placement
///     time_budget_s: 3000        # [s] the command's budget; 0 = the service's
///     expect: on_deck            # | at_ramp_base | acquired | a fault: NOT_FOUND, ...
///
/// `acquired` (seed 004's phase 1 alone) passes when the rendezvous leaves LONG_RANGE for mid
/// range (the runner then sends STOP and ends the run there).
/// `on_deck` passes on DONE with the rover's last true position inside the deck hexagon (the
/// judge's on_deck figure), `at_ramp_base` on DONE without climbing, a fault name on FAILED
/// with that fault. The runner waits for the terminal status until the budget plus kGraceS
/// simulated seconds (then sends TARGET_STOP and fails the run).

#include <optional>
#include <string>

#include "rover/deploy/runner/rendezvous_judging.hpp"
#include "rover/deploy/runner/task.hpp"

namespace rover::deploy::runner {

struct LanderReturnSpec {
  Eigen::Vector2d estimate = Eigen::Vector2d::Zero();
  double standoff = 0.0;
  int ramp = -1;
  bool climb = true;
  double time_budget_s = 0.0;
  std::string expect = "on_deck";
};

/// Parses and checks the section (names file, line and key on error).
Result<LanderReturnSpec> ParseLanderReturnTask(const TaskSource& source);

class LanderReturnTask : public Task {
 public:
  static constexpr std::uint32_t kCommandId = 1;
  static constexpr std::uint32_t kStopId = 2;
  static constexpr double kGraceS = 60.0;

  LanderReturnTask(LanderReturnSpec spec, double start_x, double start_y)
      : spec_(std::move(spec)), start_x_(start_x), start_y_(start_y) {}
  Status Open(TaskContext& ctx) override;
  bool Ready() const override;
  TaskOutcome Run(TaskContext& ctx) override;
  std::vector<Eigen::Vector2d> PlannedPath() const override;
  const LanderReturnSpec& spec() const { return spec_; }

 private:
  // TARGET_STOP to apl-rendezvous (time budget overrun, or phase 1 done).
  void SendStop(TaskContext& ctx);

  LanderReturnSpec spec_;
  double start_x_, start_y_;
  dds::Writer<rover_apl_RendezvousCommand> command_;
  dds::Reader<rover_apl_RendezvousStatus> status_;
};

/// Registers lander_return.
void RegisterLanderReturnTask(TaskRegistry& registry);

}  // namespace rover::deploy::runner
