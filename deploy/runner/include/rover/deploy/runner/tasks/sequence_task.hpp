#pragma once
/// @file
/// The sequence task: one command sequence (apl/sequencer's text form) sent to apl-sequencer on
/// apl/sequence_command, as an operator would uplink it, then waiting for its terminal
/// apl/sequence_status (DONE or FAILED).
///
///   task:
///     type: sequence
///     file: ../sequences/approach_template.seq   # relative to the scenario file (required)
///     set: {target: "(4, 0.3, 0)"}               # TARGET / CONST values to replace (name: value)
///     time_budget_s: 1500                        # [s] simulated; 0 = none
///     expect: done                               # | failed
///
/// The file is read and the overrides formatted when the scenario is loaded (an unreadable
/// file, a name that is not a word, a value with a newline: errors naming file, line and key);
/// the text itself is parsed by apl-sequencer, whose FAILED status names the line and column.
/// `done` passes on DONE, `failed` on FAILED. Past the budget the runner fails the run (the
/// sequencer has no stop command; the run's end stops the set). Figures: `sequence_done` (1 / 0)
/// and `sequence_steps` (the last status's step).

#include <map>
#include <string>

#include "rover/deploy/runner/task.hpp"

namespace rover::deploy::runner {

struct SequenceSpec {
  std::string file;  ///< resolved path
  std::string text;  ///< the file's contents
  std::map<std::string, std::string> overrides;
  double time_budget_s = 0.0;
  std::string expect = "done";
};

/// Parses and checks the section (names file, line and key on error).
Result<SequenceSpec> ParseSequenceTask(const TaskSource& source);

class SequenceTask : public Task {
 public:
  static constexpr std::uint32_t kSequenceId = 1;

  SequenceTask(SequenceSpec spec, double start_x, double start_y)
      : spec_(std::move(spec)), start_x_(start_x), start_y_(start_y) {}
  Status Open(TaskContext& ctx) override;
  bool Ready() const override;
  TaskOutcome Run(TaskContext& ctx) override;
  std::vector<Eigen::Vector2d> PlannedPath() const override { return {{start_x_, start_y_}}; }
  const SequenceSpec& spec() const { return spec_; }

 private:
  SequenceSpec spec_;
  double start_x_, start_y_;
  dds::Writer<rover_apl_SequenceCommand> command_;
  dds::Reader<rover_apl_SequenceStatus> status_;
};

/// Registers sequence.
void RegisterSequenceTask(TaskRegistry& registry);

}  // namespace rover::deploy::runner
