#include "rover/apl/sequencer/interpreter.hpp"

#include <cmath>

#include "rover/apl/sequencer/condition.hpp"
#include "rover/base/check.hpp"
#include "rover/base/format.hpp"
#include "rover/base/range_check.hpp"

namespace rover::apl::sequencer {

const char* SequenceStateName(SequenceState s) {
  switch (s) {
    case SequenceState::kIdle: return "IDLE";
    case SequenceState::kRunning: return "RUNNING";
    case SequenceState::kAborting: return "ABORTING";
    case SequenceState::kDone: return "DONE";
    case SequenceState::kFailed: return "FAILED";
    case SequenceState::kAborted: return "ABORTED";
  }
  ROVER_UNREACHABLE();
}

bool IsTerminal(SequenceState s) {
  return s == SequenceState::kDone || s == SequenceState::kFailed ||
         s == SequenceState::kAborted;
}

Status InterpreterOptions::Validate() const {
  ROVER_RETURN_IF_ERROR(CheckNonNegative("result_margin_s", result_margin_s, "s"));
  ROVER_RETURN_IF_ERROR(CheckPositive("default_result_timeout_s", default_result_timeout_s, "s"));
  ROVER_RETURN_IF_ERROR(CheckNonNegative("pose_wait_s", pose_wait_s, "s"));
  ROVER_RETURN_IF_ERROR(CheckPositive("max_pose_age_s", max_pose_age_s, "s"));
  return CheckIntRange("max_control_steps", max_control_steps, 1, 1000000000);
}

void InterpreterOptions::BindParams(ParamBinder<InterpreterOptions>& b) {
  b.Bind("result_margin_s", &InterpreterOptions::result_margin_s, "s",
         "wait this long beyond a command's timeout for its result")
      .Min(0);
  b.Bind("default_result_timeout_s", &InterpreterOptions::default_result_timeout_s, "s",
         "wait this long for the result of a command without a timeout")
      .Min(0);
  b.Bind("pose_wait_s", &InterpreterOptions::pose_wait_s, "s",
         "wait this long for a usable pose before a condition or TURN TO fails")
      .Min(0);
  b.Bind("max_pose_age_s", &InterpreterOptions::max_pose_age_s, "s",
         "a pose estimate older than this is not used")
      .Min(0);
  b.Bind("max_control_steps", &InterpreterOptions::max_control_steps, "",
         "control statements one Step may run without a command or wait")
      .Min(1);
}

Result<Interpreter> Interpreter::Create(const InterpreterOptions& options) {
  ROVER_RETURN_IF_ERROR(options.Validate());
  return Interpreter(options);
}

bool Interpreter::busy() const {
  return status_.state == SequenceState::kRunning || status_.state == SequenceState::kAborting;
}

std::optional<std::uint32_t> Interpreter::outstanding() const {
  if (wait_ != Wait::kResult || !outstanding_) return std::nullopt;
  return outstanding_->id;
}

void Interpreter::Compile(const std::vector<Statement>& statements) {
  using Op = Instr::Op;
  auto emit = [this](Op op, const Statement* s, int slot = -1) {
    code_.push_back(Instr{op, s, -1, slot});
    return static_cast<int>(code_.size()) - 1;
  };
  auto here = [this] { return static_cast<int>(code_.size()); };
  for (const Statement& s : statements) {
    switch (s.kind) {
      case Statement::Kind::kCommand: emit(Op::kCommand, &s); break;
      case Statement::Kind::kWait: emit(Op::kWait, &s); break;
      case Statement::Kind::kWaitUntil: emit(Op::kWaitUntil, &s); break;
      case Statement::Kind::kIf: {
        const int test = emit(Op::kJumpIfNot, &s);
        Compile(s.body);
        if (s.else_body.empty()) {
          code_[test].target = here();
        } else {
          const int skip = emit(Op::kJump, &s);
          code_[test].target = here();
          Compile(s.else_body);
          code_[skip].target = here();
        }
        break;
      }
      case Statement::Kind::kRepeat:
      case Statement::Kind::kWhile: {
        const int slot = static_cast<int>(counters_.size());
        counters_.push_back(0);
        emit(Op::kLoopInit, &s, slot);
        const int top = here();
        const int bound = emit(Op::kLoopTest, &s, slot);
        int test = -1;
        if (s.kind == Statement::Kind::kWhile) test = emit(Op::kJumpIfNot, &s);
        Compile(s.body);
        code_[emit(Op::kLoopNext, &s, slot)].target = top;
        code_[bound].target = here();
        if (test >= 0) code_[test].target = here();
        break;
      }
    }
  }
}

Status Interpreter::Start(Sequence sequence, Time t) {
  if (busy()) {
    return Busy("a sequence is running (step " + std::to_string(status_.step) +
                "); stop it before starting another");
  }
  if (sequence.statements.empty()) {
    return InvalidArgument("sequence '" + sequence.source + "' has no statements to run");
  }
  sequence_ = std::make_shared<const Sequence>(std::move(sequence));
  code_.clear();
  counters_.clear();
  Compile(sequence_->statements);
  code_.push_back(Instr{Instr::Op::kEnd, nullptr, -1, -1});
  abort_entry_ = -1;
  if (!sequence_->on_abort.empty()) {
    abort_entry_ = static_cast<int>(code_.size());
    Compile(sequence_->on_abort);
    code_.push_back(Instr{Instr::Op::kEnd, nullptr, -1, -1});
  }
  status_ = SequenceStatus{};
  status_.state = SequenceState::kRunning;
  start_ = t;
  pc_ = 0;
  in_abort_ = false;
  cause_ = Cause::kNone;
  wait_ = Wait::kNone;
  pose_wait_since_.reset();
  outstanding_.reset();
  last_ = Outcome{};
  visodom_failures_ = 0;
  return Status::Ok();
}

void Interpreter::OnPose(const PoseSample& pose) {
  if (!pose.valid) return;
  for (double v : {pose.position.x, pose.position.y, pose.position.z, pose.roll, pose.pitch,
                   pose.yaw}) {
    if (!std::isfinite(v)) return;
  }
  if (pose_ && pose.stamp < pose_->stamp) return;
  pose_ = pose;
}

void Interpreter::OnVisOdomFailures(int failures) { visodom_failures_ = failures; }

const PoseSample* Interpreter::UsablePose(Time t) const {
  if (!pose_) return nullptr;
  if (pose_->stamp < last_.stamp) return nullptr;  // from before the last command ended
  if (ToSeconds(t - pose_->stamp) > options_.max_pose_age_s) return nullptr;
  return &*pose_;
}

void Interpreter::SetStep(const Statement& s) {
  status_.step = s.step;
  status_.line = s.pos.line;
  status_.step_text = s.text;
}

Status Interpreter::OnCommandResult(std::uint32_t command_id, const Outcome& outcome) {
  if (wait_ != Wait::kResult || !outstanding_) {
    return FailedPrecondition("result for command " + std::to_string(command_id) +
                              ", but no command is waiting for one");
  }
  if (command_id != outstanding_->id) {
    return InvalidArgument("result for command " + std::to_string(command_id) + ", but command " +
                           std::to_string(outstanding_->id) + " is outstanding");
  }
  wait_ = Wait::kNone;
  last_ = outcome;
  if (last_.fault_class == msg::FaultClass::kNone) last_.fault_class = last_.fault.DefaultClass();
  const Status valid = outcome.Validate();
  if (!valid.ok()) {
    FailStep("its service reported an inconsistent outcome: " + valid.message(), last_);
    return valid;
  }
  switch (last_.termination) {
    case Termination::kNominal: ++pc_; break;
    case Termination::kFault:
      if (outstanding_continues_ && last_.fault_class == msg::FaultClass::kGoalError) {
        ++pc_;
      } else {
        FailStep(last_.Describe(), last_);
      }
      break;
    case Termination::kRejected: FailStep(last_.Describe(), last_); break;
    case Termination::kNone: ROVER_UNREACHABLE();  // Validate() refuses it
  }
  outstanding_.reset();
  return Status::Ok();
}

void Interpreter::FailStep(const std::string& reason, const Outcome& outcome,
                           const Statement* at) {
  wait_ = Wait::kNone;
  pose_wait_since_.reset();
  const bool control = at != nullptr && at->step == 0;
  const std::string where =
      control ? "line " + std::to_string(at->pos.line) + " (" + at->text + ")"
              : "step " + std::to_string(status_.step) + " (line " +
                    std::to_string(status_.line) + ": " + status_.step_text + ")";
  if (in_abort_) {
    status_.message += "; ON_ABORT " + where + " failed: " + reason;
    in_abort_ = false;
    Finish();
    return;
  }
  status_.failed_step = control ? 0 : status_.step;
  status_.failed_line = control ? at->pos.line : status_.line;
  status_.failed_outcome = outcome;
  status_.message = where + " failed: " + reason;
  cause_ = Cause::kFailure;
  EnterAbort();
}

void Interpreter::EnterAbort() {
  wait_ = Wait::kNone;
  pose_wait_since_.reset();
  if (abort_entry_ < 0) {
    Finish();
    return;
  }
  in_abort_ = true;
  pc_ = abort_entry_;
  status_.state = SequenceState::kAborting;
}

void Interpreter::Finish() {
  wait_ = Wait::kNone;
  switch (cause_) {
    case Cause::kNone: status_.state = SequenceState::kDone; break;
    case Cause::kFailure: status_.state = SequenceState::kFailed; break;
    case Cause::kStop: status_.state = SequenceState::kAborted; break;
  }
  in_abort_ = false;
}

StepOutput Interpreter::Stop(Time t, const std::string& reason) {
  StepOutput out;
  if (!busy()) {
    out.status = status_;
    return out;
  }
  if (wait_ == Wait::kResult && outstanding_) out.cancel = outstanding_;
  outstanding_.reset();
  if (in_abort_) {
    status_.message += "; ON_ABORT stopped: " + reason;
    if (cause_ == Cause::kNone) cause_ = Cause::kStop;
    Finish();
    out.status = status_;
    return out;
  }
  cause_ = Cause::kStop;
  status_.message = "stopped at step " + std::to_string(status_.step) + " (line " +
                    std::to_string(status_.line) + "): " + reason;
  EnterAbort();
  StepOutput rest = Step(t);
  rest.cancel = out.cancel;
  return rest;
}

Interpreter::Flow Interpreter::PoseBlocked(Time t, const std::string& what, const Statement& at,
                                           StepOutput* out) {
  if (!pose_wait_since_) pose_wait_since_ = t;
  const Time until = *pose_wait_since_ + Seconds(options_.pose_wait_s);
  if (t >= until) {
    std::string why = !pose_ ? "none has been received"
                             : (pose_->stamp < last_.stamp
                                    ? "the latest is from before the last command ended"
                                    : "the latest is " + FormatNumber(ToSeconds(t - pose_->stamp)) +
                                          " s old");
    FailStep(what + " needs a pose estimate; " + why + " (waited " +
                 FormatNumber(options_.pose_wait_s) + " s)",
             {}, &at);
    return Flow::kContinue;
  }
  wait_ = Wait::kPose;
  out->wake_at = until;
  return Flow::kBlocked;
}

Interpreter::Flow Interpreter::Exec(Time t, StepOutput* out) {
  using Op = Instr::Op;
  ROVER_DEMAND(pc_ >= 0 && pc_ < static_cast<int>(code_.size()));
  const Instr& in = code_[static_cast<std::size_t>(pc_)];
  if (wait_ != Wait::kPose) pose_wait_since_.reset();
  wait_ = Wait::kNone;
  switch (in.op) {
    case Op::kCommand: {
      const CommandCall& call = in.stmt->command;
      SetStep(*in.stmt);
      const PoseSample* pose = UsablePose(t);
      if (NeedsPose(call) && pose == nullptr) return PoseBlocked(t, call.text, *in.stmt, out);
      pose_wait_since_.reset();
      Result<Command> c = BuildCommand(call, pose, next_id_, in.stmt->step);
      if (!c.ok()) {
        FailStep(c.status().message());
        return Flow::kContinue;
      }
      ++next_id_;
      ++status_.dispatched;
      const double budget = call.Has("timeout") ? call.Get("timeout").number : 0.0;
      result_wait_s_ = budget > 0.0 ? budget + options_.result_margin_s
                                    : options_.default_result_timeout_s;
      deadline_ = t + Seconds(result_wait_s_);
      outstanding_ = *c;
      outstanding_continues_ = call.continue_on_goal_error;
      out->command = std::move(*c);
      wait_ = Wait::kResult;
      return Flow::kBlocked;
    }
    case Op::kWait:
      SetStep(*in.stmt);
      wait_ = Wait::kTimer;
      deadline_ = t + Seconds(in.stmt->seconds);
      return Flow::kContinue;
    case Op::kWaitUntil:
      SetStep(*in.stmt);
      wait_ = Wait::kCondition;
      deadline_ = t + Seconds(in.stmt->seconds);
      return Flow::kContinue;
    case Op::kJumpIfNot: {
      const Condition& cond = in.stmt->condition;
      ConditionInputs inputs{last_, UsablePose(t), visodom_failures_, ToSeconds(t - start_)};
      const std::optional<bool> v = Evaluate(cond, inputs);
      if (!v) return PoseBlocked(t, "the condition '" + cond.text + "'", *in.stmt, out);
      pose_wait_since_.reset();
      pc_ = *v ? pc_ + 1 : in.target;
      return Flow::kContinue;
    }
    case Op::kJump: pc_ = in.target; return Flow::kContinue;
    case Op::kLoopInit:
      counters_[static_cast<std::size_t>(in.slot)] = 0;
      ++pc_;
      return Flow::kContinue;
    case Op::kLoopTest:
      pc_ = counters_[static_cast<std::size_t>(in.slot)] >= in.stmt->count ? in.target : pc_ + 1;
      return Flow::kContinue;
    case Op::kLoopNext:
      ++counters_[static_cast<std::size_t>(in.slot)];
      pc_ = in.target;
      return Flow::kContinue;
    case Op::kEnd: Finish(); return Flow::kContinue;
  }
  ROVER_UNREACHABLE();
}

StepOutput Interpreter::Step(Time t) {
  StepOutput out;
  for (int n = 0; busy(); ++n) {
    if (n > options_.max_control_steps) {
      FailStep("more than " + std::to_string(options_.max_control_steps) +
               " control statements without a command or wait");
      continue;
    }
    if (wait_ == Wait::kResult) {
      if (t < deadline_) break;
      out.cancel = outstanding_;
      outstanding_.reset();
      FailStep("no result within " + FormatNumber(result_wait_s_) + " s");
      continue;
    }
    if (wait_ == Wait::kTimer) {
      if (t < deadline_) {
        out.wake_at = deadline_;
        break;
      }
      wait_ = Wait::kNone;
      ++pc_;
      continue;
    }
    if (wait_ == Wait::kCondition) {
      const Statement& s = *code_[static_cast<std::size_t>(pc_)].stmt;
      ConditionInputs inputs{last_, UsablePose(t), visodom_failures_, ToSeconds(t - start_)};
      const std::optional<bool> v = Evaluate(s.condition, inputs);
      if (v.value_or(false)) {
        wait_ = Wait::kNone;
        ++pc_;
        continue;
      }
      if (t >= deadline_) {
        FailStep("WAIT UNTIL timed out after " + FormatNumber(s.seconds) + " s" +
                 (v ? "" : " (no usable pose estimate)"));
        continue;
      }
      break;
    }
    if (Exec(t, &out) == Flow::kBlocked) break;
  }
  out.status = status_;
  return out;
}

}  // namespace rover::apl::sequencer
