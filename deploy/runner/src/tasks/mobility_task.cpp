#include "rover/deploy/runner/tasks/mobility_task.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "rover/base/format.hpp"
#include "rover/base/units.hpp"
#include "rover/geometry/polygon.hpp"
#include "rover/msg/drive_idl.hpp"
#include "rover/msg/mobility_idl.hpp"
#include "rover/msg/navigation_idl.hpp"
#include "rover/msg/pose_idl.hpp"

namespace rover::deploy::runner {
namespace {

constexpr std::size_t kMaxPrimitives = 32;  // MobilityCommand.primitives' bound
constexpr std::size_t kMaxZones = 8;        // MobilityCommand.keep_out's bound
constexpr std::size_t kMaxVertices = 16;    // KeepOutZone.vertices' bound
constexpr std::size_t kMaxZoneName = 31;    // KeepOutZone.name's bound

bool NeedsGoal(MobilityTaskType t) {
  return t == MobilityTaskType::kAutonav || t == MobilityTaskType::kGoToWaypoint;
}

Result<KeepOut> ParseZone(const YAML::Node& z, const yaml::FileErrors& err) {
  const char* where = "task.keep_out[]";
  ROVER_RETURN_IF_ERROR(yaml::CheckKeys(z, where, {"name", "vertices"}, err));
  ROVER_RETURN_IF_ERROR(yaml::RequireKey(z, where, "name", err));
  ROVER_RETURN_IF_ERROR(yaml::RequireKey(z, where, "vertices", err));
  KeepOut zone;
  zone.name = yaml::ScalarText(z["name"]);
  if (zone.name.empty() || zone.name.size() > kMaxZoneName) {
    return err.At(z["name"], "task.keep_out[].name: '" + zone.name + "' must be 1.." +
                                 std::to_string(kMaxZoneName) + " characters");
  }
  const YAML::Node vs = z["vertices"];
  if (!vs.IsSequence()) {
    return err.At(vs, "task.keep_out[].vertices: expected a list of [x, y] points");
  }
  for (const auto& p : vs) {
    if (!p.IsSequence() || p.size() != 2) {
      return err.At(p, "task.keep_out[].vertices: expected [x, y], got '" +
                           yaml::ScalarText(p) + "'");
    }
    ROVER_ASSIGN_OR_RETURN(const double x, yaml::Number(p[0], "task.keep_out[].vertices[].x", err));
    ROVER_ASSIGN_OR_RETURN(const double y, yaml::Number(p[1], "task.keep_out[].vertices[].y", err));
    zone.vertices.emplace_back(x, y);
  }
  if (zone.vertices.size() < 3 || zone.vertices.size() > kMaxVertices) {
    return err.At(vs, "task.keep_out[].vertices: zone '" + zone.name + "' has " +
                          std::to_string(zone.vertices.size()) + " vertices, a zone needs 3.." +
                          std::to_string(kMaxVertices));
  }
  if (const std::string why = geometry::WhyNotSimple(zone.vertices); !why.empty()) {
    return err.At(vs, "task.keep_out[].vertices: zone '" + zone.name + "' is not a simple polygon: " +
                          why);
  }
  return zone;
}

Result<std::vector<DriveStep>> ParsePrimitives(const YAML::Node& n, const yaml::FileErrors& err) {
  const char* where = "task.primitives[]";
  std::vector<DriveStep> out;
  for (const auto& p : n) {
    ROVER_RETURN_IF_ERROR(
        yaml::CheckKeys(p, where, {"primitive", "distance", "curvature", "angle_deg"}, err));
    ROVER_ASSIGN_OR_RETURN(DriveStep step, ParseDriveStep(p, where, err));
    if (step.primitive == Primitive::kSteer || step.primitive == Primitive::kStop) {
      return err.At(p["primitive"], std::string(where) + ".primitive: '" +
                                        PrimitiveName(step.primitive) +
                                        "' is not a mobility primitive (straight, arc, turn_in_place)");
    }
    out.push_back(step);
  }
  return out;
}

std::vector<std::string> ExpectChoices(MobilityTaskType type) {
  std::vector<std::string> out = {"reached"};
  if (type == MobilityTaskType::kGuarded || type == MobilityTaskType::kGuardedArc) {
    out.push_back("vetoed");
  }
  const auto& names = MobilityFaultNames();
  out.insert(out.end(), names.begin() + 1, names.end());
  return out;
}

bool Terminal(msg::MobilityState s) {
  return s == msg::MobilityState::kSucceeded || s == msg::MobilityState::kFailed ||
         s == msg::MobilityState::kRejected;
}

}  // namespace

const char* MobilityTaskTypeName(MobilityTaskType t) {
  switch (t) {
    case MobilityTaskType::kAutonav:
      return "autonav";
    case MobilityTaskType::kGoToWaypoint:
      return "goto_waypoint";
    case MobilityTaskType::kGuarded:
      return "guarded";
    case MobilityTaskType::kGuardedArc:
      return "guarded_arc";
  }
  return "?";
}

const std::vector<std::string>& MobilityFaultNames() {
  // core/msg's names, index = msg::MobilityFault.
  static const std::vector<std::string> k = [] {
    std::vector<std::string> v;
    for (int i = 0; i < msg::kMobilityFaultCount; ++i) {
      v.emplace_back(msg::MobilityFaultName(static_cast<msg::MobilityFault>(i)));
    }
    return v;
  }();
  return k;
}

std::string FaultClassProse(msg::FaultClass c) {
  return ScenarioSpelling(msg::FaultClassName(c), /*space=*/true);
}

msg::MobilityMode MobilityModeOf(MobilityTaskType type, bool visodom) {
  using M = msg::MobilityMode;
  switch (type) {
    case MobilityTaskType::kAutonav:
      return visodom ? M::kAutoNavVisOdom : M::kAutoNav;
    case MobilityTaskType::kGoToWaypoint:
      return visodom ? M::kVisOdomGoToWaypoint : M::kGoToWaypoint;
    case MobilityTaskType::kGuarded:
      return visodom ? M::kGuardedVisOdom : M::kGuarded;
    case MobilityTaskType::kGuardedArc:
      return M::kGuardedArc;
  }
  return M::kAutoNav;
}

Result<MobilityTaskSpec> ParseMobilityTask(const TaskSource& source, MobilityTaskType type) {
  const YAML::Node& n = source.section;
  const yaml::FileErrors& err = source.errors;
  const std::string type_name = MobilityTaskTypeName(type);
  std::vector<std::string> keys = {"type",      "visodom",      "think", "time_budget_s",
                                   "max_steps", "max_tilt_deg", "keep_out", "expect"};
  keys.push_back(NeedsGoal(type) ? "goal" : "primitives");
  ROVER_RETURN_IF_ERROR(yaml::CheckKeys(n, "task", keys, err));
  MobilityTaskSpec spec;
  spec.type = type;
  if (NeedsGoal(type)) {
    ROVER_ASSIGN_OR_RETURN(spec.goal, ParseTaskGoal(source));
    if (!spec.goal) return err.At(n, "task: a '" + type_name + "' task needs a 'goal'");
  } else {
    const YAML::Node p = n["primitives"];
    if (!p || !p.IsSequence() || p.size() == 0 || p.size() > kMaxPrimitives) {
      return err.At(p ? p : n, "task.primitives: a '" + type_name + "' task needs a list of 1.." +
                                   std::to_string(kMaxPrimitives) + " primitives");
    }
    ROVER_ASSIGN_OR_RETURN(spec.primitives, ParsePrimitives(p, err));
  }
  if (const YAML::Node v = n["visodom"]) {
    ROVER_ASSIGN_OR_RETURN(const std::string b, yaml::OneOf(v, "task.visodom", {"false", "true"}, err));
    spec.visodom = b == "true";
    if (spec.visodom && type == MobilityTaskType::kGuardedArc) {
      return err.At(v, "task.visodom: 'guarded_arc' has no VisOdom variant");
    }
  }
  if (const YAML::Node t = n["think"]) {
    const std::vector<std::string> modes = {"default", "stop_and_go", "drive_while_thinking"};
    ROVER_ASSIGN_OR_RETURN(const std::string m, yaml::OneOf(t, "task.think", modes, err));
    spec.think = static_cast<msg::ThinkMode>(std::find(modes.begin(), modes.end(), m) -
                                             modes.begin());
  }
  ROVER_RETURN_IF_ERROR(
      yaml::OptionalNumber(n, "time_budget_s", "task", 0, 1e6, err, &spec.time_budget_s));
  double steps = 0;
  ROVER_RETURN_IF_ERROR(yaml::OptionalNumber(n, "max_steps", "task", 0, 65535, err, &steps));
  if (steps != std::floor(steps)) {
    return err.At(n["max_steps"], "task.max_steps: " + yaml::ScalarText(n["max_steps"]) +
                                      " is not a whole number");
  }
  spec.max_steps = static_cast<int>(steps);
  double tilt_deg = 0;
  ROVER_RETURN_IF_ERROR(yaml::OptionalNumber(n, "max_tilt_deg", "task", 0, 89, err, &tilt_deg));
  spec.max_tilt = tilt_deg * kDegree;
  if (const YAML::Node k = n["keep_out"]) {
    if (!k.IsSequence() || k.size() > kMaxZones) {
      return err.At(k, "task.keep_out: expected a list of at most " + std::to_string(kMaxZones) +
                           " zones {name, vertices}");
    }
    for (const auto& z : k) {
      ROVER_ASSIGN_OR_RETURN(KeepOut zone, ParseZone(z, err));
      spec.keep_out.push_back(std::move(zone));
    }
  }
  if (const YAML::Node e = n["expect"]) {
    ROVER_ASSIGN_OR_RETURN(spec.expect, ParseTaskExpect(e, ExpectChoices(type), err));
  }
  return spec;
}

rover_apl_MobilityCommand MakeMobilityCommand(const MobilityTaskSpec& spec,
                                              std::uint32_t command_id, double now_s,
                                              MobilityCommandStorage* storage) {
  msg::MobilityCommand c;
  c.stamp = Time::FromSeconds(now_s);
  c.command_id = command_id;
  c.mode = MobilityModeOf(spec.type, spec.visodom);
  if (spec.goal) {
    c.goal = {spec.goal->xy.x(), spec.goal->xy.y(), 0.0};
    c.tolerance = spec.goal->tolerance;
  }
  c.time_budget_s = spec.time_budget_s;
  c.think = spec.think;
  c.max_tilt = spec.max_tilt;
  c.max_steps = spec.max_steps;
  for (const auto& p : spec.primitives) {
    msg::MobilityPrimitive m;
    m.kind = p.primitive;
    m.curvature = p.primitive == Primitive::kArc ? p.curvature : 0.0;
    m.distance = p.primitive == Primitive::kTurnInPlace ? 0.0 : p.distance;
    m.angle = p.primitive == Primitive::kTurnInPlace ? p.angle : 0.0;
    c.primitives.push_back(m);
  }
  for (const auto& z : spec.keep_out) c.keep_out.push_back({z.name, z.vertices});
  msg::MobilityCommandToIdl(c, storage);
  dds::CopyString(storage->msg.header.frame_id, "site");
  return storage->msg;
}

std::string OutcomeName(const msg::MobilityStatus& s) {
  using F = msg::MobilityFault;
  if (s.state == msg::MobilityState::kSucceeded) return "reached";
  if (s.fault == F::kNone) {
    return s.state == msg::MobilityState::kRejected
               ? std::string(msg::MobilityFaultName(F::kBadCommand))
               : "NONE";
  }
  return std::string(msg::MobilityFaultName(s.fault));
}

bool OutcomeNameMatches(const std::string& expect, const std::string& outcome) {
  return expect == "vetoed" ? outcome == msg::MobilityFaultName(msg::MobilityFault::kNoPath)
                            : CanonicalOutcome(outcome) == CanonicalOutcome(expect);
}

bool OutcomeMatches(const std::string& expect, const msg::MobilityStatus& s) {
  if (!Terminal(s.state)) return false;
  if (expect == "vetoed" && s.state != msg::MobilityState::kFailed) return false;
  return OutcomeNameMatches(expect, OutcomeName(s));
}

Status MobilityTask::Open(TaskContext& ctx) {
  ROVER_ASSIGN_OR_RETURN(command_,
                         ctx.MakeWriter<rover_apl_MobilityCommand>("apl/mobility_command"));
  ROVER_ASSIGN_OR_RETURN(status_,
                         ctx.MakeReader<rover_apl_MobilityStatus>("apl/mobility_status"));
  MobilityOutcome& mob = ctx.recorder.Mobility();
  mob.task = MobilityTaskTypeName(spec_.type);
  mob.mode = ScenarioSpelling(msg::MobilityModeName(MobilityModeOf(spec_.type, spec_.visodom)));
  mob.expect = spec_.expect;
  mob.outcome = "none";
  mob.state = "interrupted";
  mob.fault = "NONE";
  mob.fault_class = "none";
  mob.keep_out.clear();
  for (const auto& z : spec_.keep_out) mob.keep_out.push_back(z.vertices);
  // The last goodness map and the chosen arc of each decision, however the run ends.
  Recorder& rec = ctx.recorder;
  ROVER_RETURN_IF_ERROR(rec.Record<rover_apl_GoodnessMap>(
      "apl/goodness_map", [&rec](const dds::Sample<rover_apl_GoodnessMap>& s) {
        Result<msg::GoodnessMap> map = msg::GoodnessMapFromIdl(s.data());
        if (!map.ok() || !(map->resolution > 0)) return;
        GoodnessGrid g;
        g.origin_x = map->origin_x;
        g.origin_y = map->origin_y;
        g.resolution = map->resolution;
        g.width = map->width;
        g.height = map->height;
        g.unknown_goodness = map->unknown_goodness;
        g.goodness = std::move(map->goodness);
        g.flags = std::move(map->flags);
        rec.Mobility().last_map = std::move(g);
      }));
  ROVER_RETURN_IF_ERROR(rec.Record<rover_apl_ArcVotes>(
      "apl/arc_votes", [&rec](const dds::Sample<rover_apl_ArcVotes>& s) {
        const Result<msg::ArcVotes> votes = msg::ArcVotesFromIdl(s.data());
        if (!votes.ok() || votes->chosen < 0) return;
        const msg::ArcVote& v = votes->votes[static_cast<std::size_t>(votes->chosen)];
        const Eigen::Isometry3d& pose = votes->rover_pose;
        ChosenArc a;
        a.x = pose.translation().x();
        a.y = pose.translation().y();
        a.yaw = std::atan2(pose.linear()(1, 0), pose.linear()(0, 0));
        a.point_turn = v.kind == msg::CandidateKind::kPointTurn;
        a.curvature = v.curvature;
        a.direction = v.direction < 0 ? -1 : 1;
        a.turn_angle = v.turn_angle;
        rec.Mobility().arcs.push_back(a);
      }));
  return Status::Ok();
}

bool MobilityTask::Ready() const { return command_.valid() && command_.MatchedReaders() > 0; }

TaskOutcome MobilityTask::Run(TaskContext& ctx) {
  TaskOutcome out;
  MobilityOutcome& mob = ctx.recorder.Mobility();
  MobilityCommandStorage storage;
  const rover_apl_MobilityCommand c = MakeMobilityCommand(spec_, kCommandId, ctx.Now(), &storage);
  StepResult step;
  step.primitive = mob.mode;
  step.command_id = kCommandId;
  step.sim_start_s = ctx.Now();
  mob.sim_start_s = step.sim_start_s;
  ctx.Note(mob.task);
  if (!command_.Write(c).ok()) {
    out.failure = "cannot send the mobility command";
    return out;
  }
  std::optional<msg::MobilityStatus> terminal;
  bool overdue = false;
  const double deadline = spec_.time_budget_s > 0
                              ? step.sim_start_s + spec_.time_budget_s + kGraceS
                              : std::numeric_limits<double>::infinity();
  out.failure = ctx.WaitUntil([&] {
    status_.TakeEach([&](const dds::Sample<rover_apl_MobilityStatus>& s) {
      if (s->command_id != kCommandId) return;
      Result<msg::MobilityStatus> st = msg::MobilityStatusFromIdl(s.data());
      if (!st.ok()) {
        ctx.Note("unreadable apl/mobility_status: " + st.status().message());
        return;
      }
      mob.steps = st->steps;
      mob.images = st->images;
      mob.distance_to_goal = st->distance_to_goal;
      if (Terminal(st->state) && !terminal) terminal = std::move(*st);
    });
    overdue = !terminal && ctx.Now() > deadline;
    return terminal.has_value() || overdue;
  });
  step.sim_end_s = ctx.Now();
  mob.sim_end_s = step.sim_end_s;
  if (overdue) {
    msg::MobilityCommand stop;
    stop.stamp = Time::FromSeconds(ctx.Now());
    stop.command_id = kStopId;
    stop.mode = msg::MobilityMode::kStop;
    MobilityCommandStorage stop_storage;
    msg::MobilityCommandToIdl(stop, &stop_storage);
    (void)command_.Write(stop_storage.msg);
    out.failure = "no terminal apl/mobility_status within the command's time budget of " +
                  FormatNumber(spec_.time_budget_s) + " s plus " + FormatNumber(kGraceS) +
                  " s (STOP sent)";
  }
  if (!terminal) {
    step.state = "interrupted";
    out.steps.push_back(step);
    return out;
  }
  step.state = ScenarioSpelling(msg::MobilityStateName(terminal->state));
  step.termination = OutcomeName(*terminal);
  step.message = terminal->message;
  out.steps.push_back(step);
  mob.state = step.state;
  mob.outcome = step.termination;
  mob.fault = msg::MobilityFaultName(terminal->fault);
  mob.fault_class = FaultClassProse(terminal->fault_class);
  mob.message = terminal->message;
  if (!OutcomeMatches(spec_.expect, *terminal)) {
    out.failure = mob.task + " ended " + step.state + " " + mob.outcome +
                  (mob.fault_class == "none" ? "" : " (" + mob.fault_class + ")") + ", expected " +
                  spec_.expect + (mob.message.empty() ? "" : ": " + mob.message);
  }
  return out;
}

std::vector<Eigen::Vector2d> MobilityTask::PlannedPath() const {
  if (spec_.goal) return {{start_x_, start_y_}, spec_.goal->xy};
  DirectedTaskSpec directed;
  directed.steps = spec_.primitives;
  return DirectedPlannedPath(directed, start_x_, start_y_, start_yaw_);
}

void RegisterMobilityTasks(TaskRegistry& registry) {
  struct Entry {
    MobilityTaskType type;
    const char* summary;
  };
  const Entry entries[] = {
      {MobilityTaskType::kAutonav,
       "one apl/mobility_command in autonav to `goal`, waiting for its terminal status"},
      {MobilityTaskType::kGoToWaypoint,
       "one apl/mobility_command in go-to-waypoint (blind) to `goal`"},
      {MobilityTaskType::kGuarded,
       "guarded `primitives`: each vetoed if terrain assessment forbids it"},
      {MobilityTaskType::kGuardedArc,
       "guarded arc: a turn, then arcs that run only if the HAZCAMs show them safe"},
  };
  for (const Entry& e : entries) {
    const MobilityTaskType type = e.type;
    registry.Register(MobilityTaskTypeName(type), e.summary,
                      [type](const TaskSource& source) -> Result<std::unique_ptr<Task>> {
                        ROVER_ASSIGN_OR_RETURN(MobilityTaskSpec spec,
                                               ParseMobilityTask(source, type));
                        const Scenario& s = source.scenario;
                        return std::unique_ptr<Task>(std::make_unique<MobilityTask>(
                            std::move(spec), s.start_x, s.start_y, s.start_yaw));
                      });
  }
}

}  // namespace rover::deploy::runner
