#include "rover/deploy/runner/tasks/sequence_task.hpp"

#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>

#include "rover/base/format.hpp"
#include "rover/msg/sequence_idl.hpp"

namespace rover::deploy::runner {

Result<SequenceSpec> ParseSequenceTask(const TaskSource& source) {
  const YAML::Node& n = source.section;
  const yaml::FileErrors& err = source.errors;
  ROVER_RETURN_IF_ERROR(
      yaml::CheckKeys(n, "task", {"type", "file", "set", "time_budget_s", "expect"}, err));
  ROVER_RETURN_IF_ERROR(yaml::RequireKey(n, "task", "file", err));
  SequenceSpec spec;
  const YAML::Node f = n["file"];
  if (!f.IsScalar() || f.Scalar().empty()) {
    return err.At(f, "task.file: " + yaml::ScalarText(f) + " is not a file name");
  }
  spec.file = f.Scalar();
  if (spec.file.front() != '/') {
    const std::string dir = std::filesystem::path(source.scenario.file).parent_path().string();
    spec.file = (dir.empty() ? std::string(".") : dir) + "/" + spec.file;
  }
  std::ifstream in(spec.file);
  if (!in) return err.At(f, "task.file: cannot read '" + spec.file + "'");
  std::stringstream buffer;
  buffer << in.rdbuf();
  spec.text = buffer.str();
  if (const YAML::Node s = n["set"]) {
    if (!s.IsMap()) return err.At(s, "task.set: is not a map of name: value");
    for (const auto& kv : s) {
      const std::string name = kv.first.Scalar();
      if (!kv.second.IsScalar()) {
        return err.At(kv.second, "task.set." + name + ": is not a single value");
      }
      spec.overrides[name] = kv.second.Scalar();
    }
    const Result<std::string> formatted = msg::FormatSequenceOverrides(spec.overrides);
    if (!formatted.ok()) return err.At(s, "task.set: " + formatted.status().message());
  }
  ROVER_RETURN_IF_ERROR(
      yaml::OptionalNumber(n, "time_budget_s", "task", 0, 1e6, err, &spec.time_budget_s));
  if (const YAML::Node x = n["expect"]) {
    ROVER_ASSIGN_OR_RETURN(spec.expect, ParseTaskExpect(x, {"done", "failed"}, err));
  }
  msg::SequenceCommand probe;
  probe.text = spec.text;
  probe.overrides = *msg::FormatSequenceOverrides(spec.overrides);
  rover_apl_SequenceCommand wire{};
  if (Status st = msg::SequenceCommandToIdl(probe, &wire); !st.ok()) {
    return err.At(f, "task.file: " + st.message());
  }
  return spec;
}

Status SequenceTask::Open(TaskContext& ctx) {
  ROVER_ASSIGN_OR_RETURN(command_, ctx.MakeWriter<rover_apl_SequenceCommand>("apl/sequence_command"));
  ROVER_ASSIGN_OR_RETURN(status_, ctx.MakeReader<rover_apl_SequenceStatus>("apl/sequence_status"));
  return Status::Ok();
}

bool SequenceTask::Ready() const { return command_.valid() && command_.MatchedReaders() > 0; }

TaskOutcome SequenceTask::Run(TaskContext& ctx) {
  TaskOutcome out;
  msg::SequenceCommand c;
  c.stamp = Time::FromSeconds(ctx.Now());
  c.command_id = kSequenceId;
  c.text = spec_.text;
  c.overrides = *msg::FormatSequenceOverrides(spec_.overrides);  // checked when parsed
  rover_apl_SequenceCommand wire{};
  if (Status st = msg::SequenceCommandToIdl(c, &wire); !st.ok()) {
    out.failure = "sequence: " + st.message();
    return out;
  }
  dds::CopyString(wire.header.frame_id, "site");
  StepResult step;
  step.primitive = "sequence";
  step.command_id = kSequenceId;
  step.sim_start_s = ctx.Now();
  ctx.Note("sequence " + std::filesystem::path(spec_.file).filename().string());
  if (!command_.Write(wire).ok()) {
    out.failure = "cannot send the sequence";
    return out;
  }
  std::optional<msg::SequenceStatus> end;
  std::optional<std::uint32_t> last_step;
  const double deadline = spec_.time_budget_s > 0 ? step.sim_start_s + spec_.time_budget_s
                                                  : std::numeric_limits<double>::infinity();
  int steps = 0;
  out.failure = ctx.WaitUntil([&] {
    status_.TakeEach([&](const dds::Sample<rover_apl_SequenceStatus>& s) {
      const Result<msg::SequenceStatus> st = msg::SequenceStatusFromIdl(s.data());
      if (!st.ok() || st->command_id != kSequenceId) return;
      steps = static_cast<int>(st->step);
      if (st->step != last_step) ctx.Note("sequence step " + std::to_string(st->step) + ": " + st->message);
      last_step = st->step;
      if (st->state == msg::SequenceState::kDone || st->state == msg::SequenceState::kFailed) end = *st;
    });
    return end.has_value() || ctx.Now() > deadline;
  });
  step.sim_end_s = ctx.Now();
  const bool done = end && end->state == msg::SequenceState::kDone;
  ctx.recorder.AddFigure({"sequence_done", done ? 1.0 : 0.0, kNotJudged, "", true,
                          end ? end->message : "no terminal apl/sequence_status in the budget"});
  ctx.recorder.AddFigure({"sequence_steps", static_cast<double>(steps), kNotJudged, "count", true,
                          "the step of the last apl/sequence_status"});
  if (!out.failure.empty()) {
    step.state = "interrupted";
    out.steps.push_back(step);
    return out;
  }
  if (!end) {
    step.state = "interrupted";
    out.steps.push_back(step);
    out.failure = "no terminal apl/sequence_status within the budget of " +
                  FormatNumber(spec_.time_budget_s) + " s";
    return out;
  }
  step.state = done ? "succeeded" : "failed";
  step.termination = done ? "done" : "failed";
  step.message = end->message;
  out.steps.push_back(step);
  if ((spec_.expect == "done") != done) {
    out.failure = std::string("the sequence ended ") + (done ? "DONE" : "FAILED") + ", expected " +
                  spec_.expect + ": " + end->message;
  }
  return out;
}

void RegisterSequenceTask(TaskRegistry& registry) {
  registry.Register(
      "sequence",
      "one command sequence (a file, with TARGET / CONST overrides) to apl-sequencer; passes "
      "on its expected end, DONE or FAILED",
      [](const TaskSource& source) -> Result<std::unique_ptr<Task>> {
        ROVER_ASSIGN_OR_RETURN(SequenceSpec spec, ParseSequenceTask(source));
        const Scenario& s = source.scenario;
        return std::unique_ptr<Task>(std::make_unique<SequenceTask>(std::move(spec), s.start_x, s.start_y));
      });
}

}  // namespace rover::deploy::runner
