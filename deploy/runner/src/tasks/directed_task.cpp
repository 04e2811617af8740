#include "rover/deploy/runner/tasks/directed_task.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <numbers>
#include <utility>

#include "rover/base/units.hpp"
#include "rover/msg/drive_idl.hpp"

namespace rover::deploy::runner {
namespace {

constexpr const char* kStep = "task.steps[]";

const std::vector<std::string>& Terminations() {
  static const std::vector<std::string> k = {"nominal",          "tilt",          "suspension",
                                             "motor_stall",      "motor_current", "motor_fault",
                                             "timeout",          "stop_command",  "rejected_busy",
                                             "rejected_invalid", "stale_sensor"};
  return k;
}

Result<DriveStep> ParseStepAt(const YAML::Node& n, const std::string& where,
                              const yaml::FileErrors& err) {
  DriveStep s;
  s.line = yaml::Line(n);
  ROVER_RETURN_IF_ERROR(yaml::CheckKeys(n, where,
                                        {"primitive", "distance", "curvature", "angle_deg", "speed",
                                         "timeout_s", "stop_after_s", "expect"},
                                        err));
  if (const YAML::Node e = n["expect"]) {
    ROVER_ASSIGN_OR_RETURN(s.expect, yaml::OneOf(e, where + ".expect", Terminations(), err));
  }
  ROVER_RETURN_IF_ERROR(yaml::OptionalNumber(n, "timeout_s", where, 0, 86400, err, &s.timeout_s));
  ROVER_RETURN_IF_ERROR(
      yaml::OptionalNumber(n, "stop_after_s", where, 0, 86400, err, &s.stop_after_s));
  ROVER_RETURN_IF_ERROR(yaml::RequireKey(n, where, "primitive", err));
  const std::vector<Primitive> primitives = {Primitive::kStraight, Primitive::kArc,
                                             Primitive::kTurnInPlace, Primitive::kSteer,
                                             Primitive::kStop};
  std::vector<std::string> names;
  for (Primitive p : primitives) names.emplace_back(PrimitiveName(p));
  ROVER_ASSIGN_OR_RETURN(const std::string name,
                         yaml::OneOf(n["primitive"], where + ".primitive", names, err));
  s.primitive = primitives[std::find(names.begin(), names.end(), name) - names.begin()];
  bool has_d = false, has_k = false, has_a = false;
  double angle_deg = 0;
  ROVER_RETURN_IF_ERROR(
      yaml::OptionalNumber(n, "distance", where, -100, 100, err, &s.distance, &has_d));
  ROVER_RETURN_IF_ERROR(
      yaml::OptionalNumber(n, "curvature", where, -1, 1, err, &s.curvature, &has_k));
  ROVER_RETURN_IF_ERROR(
      yaml::OptionalNumber(n, "angle_deg", where, -360, 360, err, &angle_deg, &has_a));
  ROVER_RETURN_IF_ERROR(yaml::OptionalNumber(n, "speed", where, 0, 0.5, err, &s.speed));
  s.angle = angle_deg * kDegree;
  auto need = [&](bool has, const char* what) -> Status {
    return has ? Status::Ok()
               : err.At(n, where + ": '" + name + "' needs '" + what + "'");
  };
  switch (s.primitive) {
    case Primitive::kStraight:
      ROVER_RETURN_IF_ERROR(need(has_d, "distance"));
      break;
    case Primitive::kArc:
      ROVER_RETURN_IF_ERROR(need(has_d, "distance"));
      ROVER_RETURN_IF_ERROR(need(has_k, "curvature"));
      break;
    case Primitive::kTurnInPlace:
      ROVER_RETURN_IF_ERROR(need(has_a, "angle_deg"));
      break;
    case Primitive::kSteer:
      ROVER_RETURN_IF_ERROR(need(has_k, "curvature"));
      break;
    case Primitive::kStop:
      break;
  }
  return s;
}

bool Terminal(msg::DriveState s) {
  return s == msg::DriveState::kDone || s == msg::DriveState::kFailed ||
         s == msg::DriveState::kRejected;
}

}  // namespace

const char* PrimitiveName(Primitive p) {
  switch (p) {
    case Primitive::kStraight:
      return "straight";
    case Primitive::kArc:
      return "arc";
    case Primitive::kTurnInPlace:
      return "turn_in_place";
    case Primitive::kSteer:
      return "steer";
    case Primitive::kStop:
      return "stop";
  }
  return "?";
}

Result<DriveStep> ParseDriveStep(const YAML::Node& n, const std::string& where,
                                 const yaml::FileErrors& err) {
  return ParseStepAt(n, where, err);
}

Result<DirectedTaskSpec> ParseDirectedTask(const TaskSource& source) {
  const YAML::Node& n = source.section;
  const yaml::FileErrors& err = source.errors;
  ROVER_RETURN_IF_ERROR(yaml::CheckKeys(n, "task", {"type", "steps", "goal"}, err));
  DirectedTaskSpec spec;
  ROVER_ASSIGN_OR_RETURN(spec.goal, ParseTaskGoal(source));
  const YAML::Node steps = n["steps"];
  if (!steps || !steps.IsSequence() || steps.size() == 0) {
    return err.At(steps ? steps : n, "task.steps: a directed task needs a non-empty list of steps");
  }
  for (const auto& s : steps) {
    ROVER_ASSIGN_OR_RETURN(DriveStep step, ParseStepAt(s, kStep, err));
    spec.steps.push_back(std::move(step));
  }
  return spec;
}

std::vector<Eigen::Vector2d> DirectedPlannedPath(const DirectedTaskSpec& spec, double start_x,
                                                 double start_y, double start_yaw) {
  std::vector<Eigen::Vector2d> pts{{start_x, start_y}};
  double x = start_x, y = start_y, th = start_yaw;
  for (const auto& st : spec.steps) {
    if (st.primitive == Primitive::kTurnInPlace) {
      th += st.angle;
      continue;
    }
    if (st.primitive != Primitive::kStraight && st.primitive != Primitive::kArc) continue;
    const double k = st.primitive == Primitive::kArc ? st.curvature : 0.0;
    const int n = std::max(1, static_cast<int>(std::abs(st.distance) / 0.1));
    const double ds = st.distance / n;
    for (int i = 0; i < n; ++i) {
      x += ds * std::cos(th + 0.5 * k * ds);
      y += ds * std::sin(th + 0.5 * k * ds);
      th += k * ds;
      pts.emplace_back(x, y);
    }
  }
  if (spec.goal) pts.push_back(spec.goal->xy);
  return pts;
}

Status DirectedTask::Open(TaskContext& ctx) {
  ROVER_ASSIGN_OR_RETURN(command_, ctx.MakeWriter<rover_dl_DriveCommand>("dl/drive_command"));
  ROVER_ASSIGN_OR_RETURN(status_, ctx.MakeReader<rover_dl_DriveStatus>("dl/drive_status"));
  return Status::Ok();
}

bool DirectedTask::Ready() const { return command_.valid() && command_.MatchedReaders() > 0; }

bool DirectedTask::Send(TaskContext& ctx, std::size_t index, StepResult* sr) {
  const DriveStep& step = spec_.steps[index];
  msg::DriveCommand c;
  c.stamp = Time::FromSeconds(ctx.Now());
  c.command_id = static_cast<uint32_t>(index + 1);
  c.primitive = step.primitive;
  c.curvature = step.primitive == Primitive::kStraight ? 0.0 : step.curvature;
  c.distance = step.distance;
  c.angle = step.angle;
  c.speed = step.speed;
  c.timeout_s = step.timeout_s;
  rover_dl_DriveCommand wire{};
  msg::DriveCommandToIdl(c, &wire);
  dds::CopyString(wire.header.frame_id, "rover");
  sr->primitive = PrimitiveName(step.primitive);
  sr->command_id = c.command_id;
  sr->sim_start_s = ctx.Now();
  ctx.Note("step " + std::to_string(index + 1) + "/" + std::to_string(spec_.steps.size()) + " " +
           sr->primitive);
  return command_.Write(wire).ok();
}

std::string DirectedTask::AwaitTerminal(TaskContext& ctx, std::size_t index, StepResult* sr) {
  const DriveStep& step = spec_.steps[index];
  bool terminal = false;
  bool stop_sent = false;
  return ctx.WaitUntil([&] {
    if (step.stop_after_s > 0 && !stop_sent && ctx.Now() - sr->sim_start_s >= step.stop_after_s) {
      msg::DriveCommand stop;
      stop.stamp = Time::FromSeconds(ctx.Now());
      stop.command_id = sr->command_id + kStopIdOffset;
      stop.primitive = Primitive::kStop;
      rover_dl_DriveCommand wire{};
      msg::DriveCommandToIdl(stop, &wire);
      stop_sent = command_.Write(wire).ok();
    }
    status_.TakeEach([&](const dds::Sample<rover_dl_DriveStatus>& s) {
      if (s->command_id != sr->command_id) return;
      const Result<msg::DriveStatus> status = msg::DriveStatusFromIdl(s.data());
      if (!status.ok()) {
        ctx.Note("unreadable dl/drive_status for command " + std::to_string(sr->command_id) +
                 ": " + status.status().message());
        return;
      }
      if (!Terminal(status->state)) return;
      terminal = true;
      sr->state = ScenarioSpelling(msg::DriveStateName(status->state));
      sr->termination = ScenarioSpelling(msg::DriveTerminationName(status->termination));
      sr->message = status->message;
    });
    return terminal;
  });
}

TaskOutcome DirectedTask::Run(TaskContext& ctx) {
  TaskOutcome out;
  for (std::size_t i = 0; i < spec_.steps.size(); ++i) {
    const DriveStep& step = spec_.steps[i];
    StepResult sr;
    if (!Send(ctx, i, &sr)) {
      out.failure = "cannot send the drive command";
      return out;
    }
    out.failure = AwaitTerminal(ctx, i, &sr);
    sr.sim_end_s = ctx.Now();
    if (!out.failure.empty()) {
      // The run ended (crash, budget, Ctrl-C) while the step was under way.
      sr.state = "interrupted";
      out.steps.push_back(sr);
      return out;
    }
    out.steps.push_back(sr);
    if (sr.termination != step.expect) {
      out.failure = "step " + std::to_string(i + 1) + " (" + sr.primitive + ") ended " + sr.state +
                    " (" + sr.termination + ")" +
                    (step.expect == "nominal" ? "" : ", expected " + step.expect) +
                    (sr.message.empty() ? "" : ": " + sr.message);
      return out;
    }
    // An expected fault ends the sequence: the rover is safe and stopped, as on MER.
    if (step.expect != "nominal") return out;
  }
  return out;
}

void RegisterDirectedTask(TaskRegistry& registry) {
  registry.Register(
      "directed",
      "drive primitives in order: one dl/drive_command per step, each waiting for its terminal "
      "dl/drive_status",
      [](const TaskSource& source) -> Result<std::unique_ptr<Task>> {
        ROVER_ASSIGN_OR_RETURN(DirectedTaskSpec spec, ParseDirectedTask(source));
        const Scenario& s = source.scenario;
        return std::unique_ptr<Task>(
            std::make_unique<DirectedTask>(std::move(spec), s.start_x, s.start_y, s.start_yaw));
      });
}

}  // namespace rover::deploy::runner
