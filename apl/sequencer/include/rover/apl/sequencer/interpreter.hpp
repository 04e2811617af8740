#pragma once
/// @file
/// The sequence interpreter: MER's event-driven sequencing as a deterministic state machine. A
/// command is dispatched only when the one before it has completed; control statements (IF,
/// REPEAT, WHILE) run at once; WAITs end on the run clock. It never reads a clock or sleeps: time
/// comes in with every call.
///
/// Inputs:  Start(sequence, t), OnCommandResult(id, outcome), OnPose(pose),
///          OnVisOdomFailures(n), Stop(t, reason), Step(t) (from a timer and after each input).
/// Outputs: StepOutput: the command to dispatch (at most one per call), a command to cancel,
///          the status, the time the pending wait ends.
///
/// States: IDLE -> RUNNING -> DONE when the last statement has run; a failing step (an
/// off-nominal outcome not let through by on_fault=CONTINUE, a rejection, a TURN TO or condition
/// without a usable pose, no result in time, a WAIT UNTIL that times out) or Stop() runs the
/// ON_ABORT block (state ABORTING) and ends FAILED (a step failed) or ABORTED (stopped). Without
/// an ON_ABORT block the state goes there at once. A failure inside the ON_ABORT block ends it.
///
/// Results: a command waits for its result up to its `timeout` argument + result_margin_s, or
/// default_result_timeout_s when it has none (0). The pose is usable for a condition or TURN TO
/// when it is valid, stamped no earlier than the last command's end (Outcome::stamp) and at most
/// max_pose_age_s old; otherwise the interpreter waits up to pose_wait_s for such a pose.

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "rover/apl/sequencer/commands.hpp"
#include "rover/apl/sequencer/sequence.hpp"
#include "rover/base/param_binder.hpp"
#include "rover/base/status.hpp"
#include "rover/base/time.hpp"

namespace rover::apl::sequencer {

enum class SequenceState { kIdle, kRunning, kAborting, kDone, kFailed, kAborted };

const char* SequenceStateName(SequenceState s);  ///< "RUNNING"
/// DONE, FAILED or ABORTED.
bool IsTerminal(SequenceState s);

struct SequenceStatus {
  SequenceState state = SequenceState::kIdle;
  int step = 0;               ///< current or last step (1-based), 0 = none yet
  int line = 0;               ///< its source line
  std::string step_text;      ///< as written
  std::uint32_t dispatched = 0;  ///< commands dispatched in this run
  int failed_step = 0;        ///< the step that failed, 0 = none or a condition
  int failed_line = 0;        ///< the line of the step or condition that failed, 0 = none
  /// The failed command's outcome; termination NONE when the sequencer itself failed the step
  /// (no result in time, no pose, a WAIT UNTIL timed out).
  Outcome failed_outcome;
  /// Why the sequence failed or was stopped (step, line, text and reason); "" otherwise.
  std::string message;
};

struct InterpreterOptions {
  double result_margin_s = 60.0;             ///< [s] beyond a command's timeout
  double default_result_timeout_s = 3600.0;  ///< [s] for commands without a timeout
  double pose_wait_s = 5.0;                  ///< [s] wait for a usable pose
  double max_pose_age_s = 2.0;               ///< [s] older poses are not used
  int max_control_steps = 1000000;           ///< control statements per Step() call

  Status Validate() const;
  static void BindParams(ParamBinder<InterpreterOptions>& b);
};

struct StepOutput {
  std::optional<Command> command;  ///< dispatch now; its result comes back by its id
  /// Stop this outstanding command (the service sends its family's stop); its result, if it
  /// comes, is ignored.
  std::optional<Command> cancel;
  SequenceStatus status;
  std::optional<Time> wake_at;  ///< call Step() by then: a WAIT or a pose wait ends
};

class Interpreter {
 public:
  /// Errors: options that fail Validate().
  static Result<Interpreter> Create(const InterpreterOptions& options = {});

  /// Starts `sequence` at run-clock time `t` (the first command goes out at the next Step).
  /// Errors: Busy while a sequence runs; InvalidArgument for a sequence without statements.
  Status Start(Sequence sequence, Time t);
  /// Runs control statements until a command is dispatched, a wait is pending or the sequence
  /// ends.
  StepOutput Step(Time t);
  /// Stops the running sequence: cancels the outstanding command, runs the ON_ABORT block, ends
  /// ABORTED. While the ON_ABORT block runs, a second Stop ends it at once. Idle: no effect.
  StepOutput Stop(Time t, const std::string& reason);

  /// The result of the outstanding command. Errors (the result is ignored): FailedPrecondition
  /// when no command waits for one, InvalidArgument for another id; an outcome that fails
  /// Outcome::Validate() fails the step and is reported as InvalidArgument.
  Status OnCommandResult(std::uint32_t command_id, const Outcome& outcome);
  /// The latest pose estimate. Invalid, non-finite or older samples are ignored.
  void OnPose(const PoseSample& pose);
  /// Visual-odometry failures since the sequence started, as the service counts them (Start
  /// resets the count to 0).
  void OnVisOdomFailures(int failures);

  const SequenceStatus& status() const { return status_; }
  /// RUNNING or ABORTING.
  bool busy() const;
  /// The command waiting for its result, if any.
  std::optional<std::uint32_t> outstanding() const;
  const InterpreterOptions& options() const { return options_; }

 private:
  struct Instr {
    enum class Op { kCommand, kWait, kWaitUntil, kJumpIfNot, kJump, kLoopInit, kLoopTest,
                    kLoopNext, kEnd };
    Op op = Op::kEnd;
    const Statement* stmt = nullptr;
    int target = -1;
    int slot = -1;
  };
  enum class Wait { kNone, kResult, kTimer, kCondition, kPose };
  enum class Cause { kNone, kFailure, kStop };
  enum class Flow { kContinue, kBlocked };

  explicit Interpreter(const InterpreterOptions& o) : options_(o) {}

  void Compile(const std::vector<Statement>& statements);
  Flow Exec(Time t, StepOutput* out);
  Flow PoseBlocked(Time t, const std::string& what, const Statement& at, StepOutput* out);
  const PoseSample* UsablePose(Time t) const;
  void SetStep(const Statement& s);
  /// Fails the current step, or the control statement `at` (an IF or WHILE condition).
  void FailStep(const std::string& reason, const Outcome& outcome = {},
                const Statement* at = nullptr);
  void EnterAbort();
  void Finish();

  InterpreterOptions options_;
  std::shared_ptr<const Sequence> sequence_;
  std::vector<Instr> code_;
  int abort_entry_ = -1;
  std::vector<int> counters_;

  SequenceStatus status_;
  Time start_;
  int pc_ = 0;
  bool in_abort_ = false;
  Cause cause_ = Cause::kNone;
  Wait wait_ = Wait::kNone;
  Time deadline_;
  double result_wait_s_ = 0.0;  // [s] how long the outstanding command may take
  std::optional<Time> pose_wait_since_;
  std::optional<Command> outstanding_;
  bool outstanding_continues_ = false;  // its call has on_fault=CONTINUE
  std::uint32_t next_id_ = 1;

  Outcome last_;
  std::optional<PoseSample> pose_;
  int visodom_failures_ = 0;
};

}  // namespace rover::apl::sequencer
