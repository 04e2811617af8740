#include "rover/deploy/runner/tasks/lander_return_task.hpp"

#include <cmath>
#include <limits>

#include "rover/base/format.hpp"
#include "rover/msg/rendezvous_idl.hpp"

namespace rover::deploy::runner {
namespace {

std::vector<std::string> ExpectChoices() {
  std::vector<std::string> out = {"on_deck", "at_ramp_base", "acquired"};
  for (int f = 1; f < msg::kRendezvousFaultCount; ++f) {
    out.emplace_back(msg::RendezvousFaultName(static_cast<msg::RendezvousFault>(f)));
  }
  return out;
}

}  // namespace

Result<LanderReturnSpec> ParseLanderReturnTask(const TaskSource& source) {
  const YAML::Node& n = source.section;
  const yaml::FileErrors& err = source.errors;
  ROVER_RETURN_IF_ERROR(yaml::CheckKeys(
      n, "task", {"type", "estimate", "standoff", "ramp", "climb", "time_budget_s", "expect"},
      err));
  ROVER_RETURN_IF_ERROR(yaml::RequireKey(n, "task", "estimate", err));
  const YAML::Node e = n["estimate"];
  ROVER_RETURN_IF_ERROR(yaml::CheckKeys(e, "task.estimate", {"x", "y"}, err));
  LanderReturnSpec spec;
  for (int i = 0; i < 2; ++i) {
    const std::string k = i == 0 ? "x" : "y";
    ROVER_RETURN_IF_ERROR(yaml::RequireKey(e, "task.estimate", k, err));
    ROVER_RETURN_IF_ERROR(yaml::OptionalNumber(e, k, "task.estimate", -1e4, 1e4, err,
                                               i == 0 ? &spec.estimate.x() : &spec.estimate.y()));
  }
  ROVER_RETURN_IF_ERROR(yaml::OptionalNumber(n, "standoff", "task", 0.0, 10.0, err, &spec.standoff));
  double ramp = -1;
  ROVER_RETURN_IF_ERROR(yaml::OptionalNumber(n, "ramp", "task", -1, 1, err, &ramp));
  if (ramp != std::floor(ramp)) {
    return err.At(n["ramp"], "task.ramp: " + yaml::ScalarText(n["ramp"]) + " is not 0, 1 or -1");
  }
  spec.ramp = static_cast<int>(ramp);
  if (const YAML::Node c = n["climb"]) {
    ROVER_ASSIGN_OR_RETURN(const std::string b, yaml::OneOf(c, "task.climb", {"false", "true"}, err));
    spec.climb = b == "true";
  }
  ROVER_RETURN_IF_ERROR(
      yaml::OptionalNumber(n, "time_budget_s", "task", 0, 1e6, err, &spec.time_budget_s));
  spec.expect = spec.climb ? "on_deck" : "at_ramp_base";
  if (const YAML::Node x = n["expect"]) {
    ROVER_ASSIGN_OR_RETURN(spec.expect, ParseTaskExpect(x, ExpectChoices(), err));
  }
  if (spec.expect == "on_deck" && !spec.climb) {
    return err.At(n["expect"], "task.expect: 'on_deck' needs climb: true");
  }
  return spec;
}

Status LanderReturnTask::Open(TaskContext& ctx) {
  ROVER_ASSIGN_OR_RETURN(command_,
                         ctx.MakeWriter<rover_apl_RendezvousCommand>("apl/rendezvous_command"));
  ROVER_ASSIGN_OR_RETURN(status_,
                         ctx.MakeReader<rover_apl_RendezvousStatus>("apl/rendezvous_status"));
  RendezvousLog& log = ctx.recorder.Rendezvous();
  log.standoff = spec_.standoff > 0.0 ? spec_.standoff : 1.0;
  log.ramp = spec_.ramp;
  log.expect_on_deck = spec_.expect == "on_deck";
  log.expect_acquired = spec_.expect == "acquired";
  return Status::Ok();
}

bool LanderReturnTask::Ready() const { return command_.valid() && command_.MatchedReaders() > 0; }

TaskOutcome LanderReturnTask::Run(TaskContext& ctx) {
  TaskOutcome out;
  RendezvousLog& log = ctx.recorder.Rendezvous();
  msg::RendezvousCommand c;
  c.stamp = Time::FromSeconds(ctx.Now());
  c.command_id = kCommandId;
  c.target = msg::RendezvousTarget::kLander;
  c.target_estimate = Eigen::Vector3d(spec_.estimate.x(), spec_.estimate.y(), 0.0);
  c.standoff = spec_.standoff;
  c.ramp = spec_.ramp;
  c.climb = spec_.climb;
  c.time_budget_s = spec_.time_budget_s;
  rover_apl_RendezvousCommand m{};
  msg::RendezvousCommandToIdl(c, &m);
  dds::CopyString(m.header.frame_id, "site");
  StepResult step;
  step.primitive = "lander_return";
  step.command_id = kCommandId;
  step.sim_start_s = ctx.Now();
  ctx.Note("lander_return");
  if (!command_.Write(m).ok()) {
    out.failure = "cannot send the rendezvous command";
    return out;
  }
  std::optional<msg::RendezvousStatus> terminal;
  bool overdue = false;
  const double deadline = spec_.time_budget_s > 0
                              ? step.sim_start_s + spec_.time_budget_s + kGraceS
                              : std::numeric_limits<double>::infinity();
  std::string last_phase;
  bool handed_over = false;
  out.failure = ctx.WaitUntil([&] {
    status_.TakeEach([&](const dds::Sample<rover_apl_RendezvousStatus>& s) {
      if (s->command_id != kCommandId) return;
      const Result<msg::RendezvousStatus> st = msg::RendezvousStatusFromIdl(s.data());
      if (!st.ok()) return;
      RendezvousSample r;
      r.t = ctx.Now();
      r.phase = static_cast<int>(st->phase);
      r.range = st->range;
      r.range_sigma = st->range_sigma;
      r.features = st->features;
      r.target = st->target_position.head<2>();
      r.new_range = st->range > 0.0 && (log.samples.empty() || st->range != log.samples.back().range);
      log.samples.push_back(r);
      if (st->ramp >= 0) log.ramp = st->ramp;
      if (st->phase == msg::RendezvousPhase::kAtRampBase && !log.at_base_t) log.at_base_t = r.t;
      const std::string phase = msg::RendezvousPhaseName(st->phase);
      if (phase != last_phase) ctx.Note("lander_return " + phase);
      last_phase = phase;
      if ((st->phase == msg::RendezvousPhase::kDone ||
           st->phase == msg::RendezvousPhase::kFailed) && !terminal) {
        terminal = *st;
      }
      // Phase 1 only: done when the rendezvous hands over to mid range.
      if (spec_.expect == "acquired" && !terminal && !handed_over &&
          st->phase != msg::RendezvousPhase::kLongRange && st->phase != msg::RendezvousPhase::kFailed) {
        handed_over = true;
      }
    });
    overdue = !terminal && ctx.Now() > deadline;
    return terminal.has_value() || overdue || handed_over;
  });
  step.sim_end_s = ctx.Now();
  if (handed_over && !terminal) {
    // Phase 1 is over: stop the command where it is (the run ends here).
    SendStop(ctx);
    log.end_phase = "MID_RANGE";
    step.state = "succeeded";
    step.termination = "acquired";
    step.message = "long range handed over to mid range";
    out.steps.push_back(step);
    return out;
  }
  if (overdue) {
    SendStop(ctx);
    out.failure = "no terminal apl/rendezvous_status within the command's time budget of " +
                  FormatNumber(spec_.time_budget_s) + " s plus " + FormatNumber(kGraceS) +
                  " s (STOP sent)";
  }
  if (!terminal) {
    step.state = "interrupted";
    out.steps.push_back(step);
    return out;
  }
  log.end_phase = msg::RendezvousPhaseName(terminal->phase);
  log.fault = msg::RendezvousFaultName(terminal->fault);
  log.message = terminal->message;
  step.state = terminal->phase == msg::RendezvousPhase::kDone ? "succeeded" : "failed";
  step.termination = terminal->phase == msg::RendezvousPhase::kDone ? "done" : log.fault;
  step.message = terminal->message;
  out.steps.push_back(step);
  const bool done = terminal->phase == msg::RendezvousPhase::kDone;
  const bool ok = spec_.expect == "on_deck" || spec_.expect == "at_ramp_base" ? done
                                                                              : log.fault == spec_.expect;
  if (!ok) {
    out.failure = "lander_return ended " + log.end_phase +
                  (log.fault == "NONE" ? "" : " " + log.fault) + ", expected " + spec_.expect +
                  (log.message.empty() ? "" : ": " + log.message);
  }
  return out;
}

void LanderReturnTask::SendStop(TaskContext& ctx) {
  msg::RendezvousCommand stop;
  stop.stamp = Time::FromSeconds(ctx.Now());
  stop.command_id = kStopId;
  stop.target = msg::RendezvousTarget::kStop;
  rover_apl_RendezvousCommand wire{};
  msg::RendezvousCommandToIdl(stop, &wire);
  (void)command_.Write(wire);  // best effort: the run ends either way
}

std::vector<Eigen::Vector2d> LanderReturnTask::PlannedPath() const {
  return {{start_x_, start_y_}, spec_.estimate};
}

void RegisterLanderReturnTask(TaskRegistry& registry) {
  registry.Register(
      "lander_return",
      "one apl/rendezvous_command RETURN_TO_LANDER; judged on placement at the ramp base and "
      "ending on the deck",
      [](const TaskSource& source) -> Result<std::unique_ptr<Task>> {
        ROVER_ASSIGN_OR_RETURN(LanderReturnSpec spec, ParseLanderReturnTask(source));
        const Scenario& s = source.scenario;
        return std::unique_ptr<Task>(
            std::make_unique<LanderReturnTask>(std::move(spec), s.start_x, s.start_y));
      });
}

}  // namespace rover::deploy::runner
