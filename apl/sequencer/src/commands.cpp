#include "rover/apl/sequencer/commands.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "rover/base/check.hpp"
#include "rover/base/units.hpp"

namespace rover::apl::sequencer {
namespace {

double WrapAngle(double a) {
  a = std::remainder(a, 2.0 * std::numbers::pi);  // [-pi, pi]
  return a <= -std::numbers::pi ? a + 2.0 * std::numbers::pi : a;
}

double Num(const CommandCall& call, const char* arg) { return call.Get(arg).number; }

MobilityRequest Mobility(const CommandCall& call, MobilityMode mode, Primitive primitive) {
  MobilityRequest r;
  r.mode = mode;
  r.primitive = primitive;
  if (call.Has("curvature")) r.curvature = Num(call, "curvature");
  if (call.Has("distance")) r.distance = Num(call, "distance");
  if (call.Has("angle_deg")) r.angle = Num(call, "angle_deg") * kDegree;
  if (call.Has("goal")) {
    r.goal_x = call.Get("goal").numbers[0];
    r.goal_y = call.Get("goal").numbers[1];
  }
  if (call.Has("tolerance")) r.tolerance = Num(call, "tolerance");
  if (call.Has("speed")) r.speed = Num(call, "speed");
  if (call.Has("timeout")) r.time_budget_s = Num(call, "timeout");
  return r;
}

Result<MobilityRequest> TurnTo(const CommandCall& call, MobilityMode mode,
                               const PoseSample* pose) {
  if (pose == nullptr) {
    return FailedPrecondition(std::string(call.spec().name) + " needs a pose estimate");
  }
  MobilityRequest r = Mobility(call, mode, Primitive::kTurnInPlace);
  double heading = 0.0;
  if (call.Has("target")) {
    const auto& p = call.Get("target").numbers;
    heading = std::atan2(p[1] - pose->position.y, p[0] - pose->position.x);
  } else {
    heading = Num(call, "heading_deg") * kDegree;
  }
  r.angle = WrapAngle(heading - pose->yaw);
  return r;
}

Vec3 PointOf(const ArgValue& v) {
  return {v.numbers[0], v.numbers[1], v.numbers.size() > 2 ? v.numbers[2] : 0.0};
}

Result<Request> BuildRequest(const CommandCall& call, const PoseSample* pose) {
  using K = CommandKind;
  using M = MobilityMode;
  switch (call.kind) {
    case K::kDriveArc: return Request{Mobility(call, M::kDirected, Primitive::kArc)};
    case K::kDriveStraight: return Request{Mobility(call, M::kDirected, Primitive::kStraight)};
    case K::kTurn: return Request{Mobility(call, M::kDirected, Primitive::kTurnInPlace)};
    case K::kVisodomArc: return Request{Mobility(call, M::kVisodom, Primitive::kArc)};
    case K::kVisodomStraight: return Request{Mobility(call, M::kVisodom, Primitive::kStraight)};
    case K::kVisodomTurn: return Request{Mobility(call, M::kVisodom, Primitive::kTurnInPlace)};
    case K::kTurnTo:
    case K::kVisodomTurnTo: {
      ROVER_ASSIGN_OR_RETURN(
          MobilityRequest r,
          TurnTo(call, call.kind == K::kTurnTo ? M::kDirected : M::kVisodom, pose));
      return Request{r};
    }
    case K::kGoto: return Request{Mobility(call, M::kGoToWaypoint, Primitive::kNone)};
    case K::kVisodomGoto: return Request{Mobility(call, M::kVisodomGoToWaypoint, Primitive::kNone)};
    case K::kGuarded: return Request{Mobility(call, M::kGuarded, Primitive::kNone)};
    case K::kGuardedVisodom: return Request{Mobility(call, M::kGuardedVisodom, Primitive::kNone)};
    case K::kGuardedArc: return Request{Mobility(call, M::kGuardedArc, Primitive::kArc)};
    case K::kAutonav: return Request{Mobility(call, M::kAutonav, Primitive::kNone)};
    case K::kAutonavVisodom: return Request{Mobility(call, M::kAutonavVisodom, Primitive::kNone)};
    case K::kLongTraverse: return Request{Mobility(call, M::kLongTraverse, Primitive::kNone)};
    case K::kStop: return Request{Mobility(call, M::kStop, Primitive::kNone)};
    case K::kClearFault: return Request{Mobility(call, M::kClearFault, Primitive::kNone)};
    case K::kMast: {
      MastRequest r;
      r.kind = MastRequest::Kind::kAngles;
      r.pan = Num(call, "pan_deg") * kDegree;
      r.tilt = Num(call, "tilt_deg") * kDegree;
      return Request{r};
    }
    case K::kMastLookAt: {
      MastRequest r;
      r.kind = MastRequest::Kind::kLookAt;
      r.point = PointOf(call.Get("point"));
      return Request{r};
    }
    case K::kReturnToLander:
    case K::kApproachTarget: {
      RendezvousRequest r;
      r.kind = call.kind == K::kReturnToLander ? RendezvousRequest::Kind::kReturnToLander
                                                : RendezvousRequest::Kind::kApproachTarget;
      if (call.Has("lander")) r.point = PointOf(call.Get("lander"));
      if (call.Has("point")) r.point = PointOf(call.Get("point"));
      if (call.Has("image")) r.image = static_cast<std::uint32_t>(Num(call, "image"));
      if (call.Has("pixel")) {
        r.u = call.Get("pixel").numbers[0];
        r.v = call.Get("pixel").numbers[1];
      }
      r.standoff = Num(call, "standoff");
      r.time_budget_s = Num(call, "timeout");
      return Request{r};
    }
    case K::kArmMove: {
      ArmRequest r;
      r.kind = ArmRequest::Kind::kMove;
      const auto& j = call.Get("joints_deg").numbers;
      for (std::size_t i = 0; i < r.joints.size(); ++i) r.joints[i] = j[i] * kDegree;
      return Request{r};
    }
    case K::kArmPlace: {
      ArmRequest r;
      r.kind = ArmRequest::Kind::kPlace;
      r.point = PointOf(call.Get("point"));
      r.hover = Num(call, "hover");
      return Request{r};
    }
    case K::kArmStow: return Request{ArmRequest{ArmRequest::Kind::kStow, {}, {}, 0.0, 0, 0.0}};
    case K::kArmUnstow:
      return Request{ArmRequest{ArmRequest::Kind::kUnstow, {}, {}, 0.0, 0, 0.0}};
    case K::kAutofocus: {
      ArmRequest r;
      r.kind = ArmRequest::Kind::kAutofocus;
      r.focus_steps = static_cast<int>(Num(call, "steps"));
      r.focus_step = Num(call, "step");
      return Request{r};
    }
  }
  ROVER_UNREACHABLE();
}

const std::vector<std::string> kTerminationNames = {"NONE", "NOMINAL", "FAULT", "REJECTED"};
const std::vector<std::string> kFaultClassNames = {"NONE", "GOAL_ERROR", "MOTION_ERROR"};
const std::vector<std::string> kFaultNames = {
    "NONE",       "ARB",          "ACM",           "POT",         "TOD",
    "STOPPED",    "WAYPT_TIMEOUT", "NOPATH",       "NOPROGRESS",  "BUSY",
    "VISODOM",    "KEEPOUT",      "IMG",           "SAPP",        "MOT",         "IDD",
    "DRIVE_TIMEOUT", "CSW",       "TILT",          "SUSPENSION",  "BAD_TABLES",
    "NORTH",      "TRACKING_LOST", "NO_RANGE",     "ARM_COLLISION", "NO_FOCUS",
    "INVALID",    "OTHER"};

template <class E>
const char* NameIn(const std::vector<std::string>& names, E e) {
  const auto i = static_cast<std::size_t>(e);
  ROVER_DEMAND(i < names.size());
  return names[i].c_str();
}

}  // namespace

const ArgValue& CommandCall::Get(const std::string& arg) const {
  auto it = args.find(arg);
  ROVER_DEMAND_MSG(it != args.end(), "argument read that the call does not have");
  return it->second;
}

const char* TerminationName(Termination t) { return NameIn(kTerminationNames, t); }
const char* FaultClassName(FaultClass c) { return NameIn(kFaultClassNames, c); }
const char* FaultName(Fault f) { return NameIn(kFaultNames, f); }
const std::vector<std::string>& TerminationNames() { return kTerminationNames; }
const std::vector<std::string>& FaultClassNames() { return kFaultClassNames; }
const std::vector<std::string>& FaultNames() { return kFaultNames; }

FaultClass DefaultFaultClass(Fault f) {
  if (f == Fault::kNone) return FaultClass::kNone;
  if (f >= Fault::kImg && f <= Fault::kNorth) return FaultClass::kMotionError;
  return FaultClass::kGoalError;
}

Outcome Outcome::Failed(Fault fault, std::string message, Time stamp) {
  return {Termination::kFault, fault, DefaultFaultClass(fault), std::move(message), stamp};
}

Outcome Outcome::Rejected(Fault fault, std::string message, Time stamp) {
  return {Termination::kRejected, fault, FaultClass::kGoalError, std::move(message), stamp};
}

Status Outcome::Validate() const {
  switch (termination) {
    case Termination::kNone:
      return InvalidArgument("outcome termination NONE is not an outcome");
    case Termination::kNominal:
      if (fault != Fault::kNone) {
        return InvalidArgument(std::string("outcome NOMINAL carries fault ") + FaultName(fault));
      }
      return Status::Ok();
    case Termination::kFault:
    case Termination::kRejected:
      if (fault == Fault::kNone) {
        return InvalidArgument(std::string("outcome ") + TerminationName(termination) +
                               " carries no fault");
      }
      return Status::Ok();
  }
  return InvalidArgument("outcome termination " +
                         std::to_string(static_cast<int>(termination)) + " is unknown");
}

std::string Outcome::Describe() const {
  if (termination == Termination::kNominal) return "NOMINAL";
  std::string out = termination == Termination::kRejected ? "REJECTED " : "";
  out += FaultName(fault);
  const FaultClass c = fault_class == FaultClass::kNone ? DefaultFaultClass(fault) : fault_class;
  out += c == FaultClass::kMotionError ? " (motion error)" : " (goal error)";
  if (!message.empty()) out += ": " + message;
  return out;
}

double TiltOf(const PoseSample& pose) {
  return std::acos(std::clamp(std::cos(pose.roll) * std::cos(pose.pitch), -1.0, 1.0));
}

double DistanceTo(const PoseSample& pose, const Vec3& point) {
  return std::hypot(point.x - pose.position.x, point.y - pose.position.y);
}

bool NeedsPose(const CommandCall& call) {
  return call.kind == CommandKind::kTurnTo || call.kind == CommandKind::kVisodomTurnTo;
}

Result<Command> BuildCommand(const CommandCall& call, const PoseSample* pose, std::uint32_t id,
                             int step) {
  ROVER_ASSIGN_OR_RETURN(Request request, BuildRequest(call, pose));
  Command c;
  c.id = id;
  c.step = step;
  c.line = call.pos.line;
  c.kind = call.kind;
  c.family = call.spec().family;
  c.request = std::move(request);
  c.text = call.text;
  return c;
}

}  // namespace rover::apl::sequencer
