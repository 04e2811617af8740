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

using M = msg::MobilityMode;
using P = msg::DrivePrimitive;

MobilityRequest Mobility(const CommandCall& call, M mode, std::optional<P> primitive) {
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

Result<MobilityRequest> TurnTo(const CommandCall& call, M mode,
                               const PoseSample* pose) {
  if (pose == nullptr) {
    return FailedPrecondition(std::string(call.spec().name) + " needs a pose estimate");
  }
  MobilityRequest r = Mobility(call, mode, P::kTurnInPlace);
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
  switch (call.kind) {
    case K::kDriveArc: return Request{Mobility(call, M::kDirected, P::kArc)};
    case K::kDriveStraight: return Request{Mobility(call, M::kDirected, P::kStraight)};
    case K::kTurn: return Request{Mobility(call, M::kDirected, P::kTurnInPlace)};
    case K::kVisodomArc: return Request{Mobility(call, M::kVisOdom, P::kArc)};
    case K::kVisodomStraight: return Request{Mobility(call, M::kVisOdom, P::kStraight)};
    case K::kVisodomTurn: return Request{Mobility(call, M::kVisOdom, P::kTurnInPlace)};
    case K::kTurnTo:
    case K::kVisodomTurnTo: {
      ROVER_ASSIGN_OR_RETURN(
          MobilityRequest r,
          TurnTo(call, call.kind == K::kTurnTo ? M::kDirected : M::kVisOdom, pose));
      return Request{r};
    }
    case K::kGoto: return Request{Mobility(call, M::kGoToWaypoint, std::nullopt)};
    case K::kVisodomGoto: return Request{Mobility(call, M::kVisOdomGoToWaypoint, std::nullopt)};
    case K::kGuarded: return Request{Mobility(call, M::kGuarded, std::nullopt)};
    case K::kGuardedVisodom: return Request{Mobility(call, M::kGuardedVisOdom, std::nullopt)};
    case K::kGuardedArc: return Request{Mobility(call, M::kGuardedArc, P::kArc)};
    case K::kAutonav: return Request{Mobility(call, M::kAutoNav, std::nullopt)};
    case K::kAutonavVisodom: return Request{Mobility(call, M::kAutoNavVisOdom, std::nullopt)};
    case K::kLongTraverse: return Request{Mobility(call, M::kLongTraverse, std::nullopt)};
    case K::kStop: return Request{Mobility(call, M::kStop, std::nullopt)};
    case K::kClearFault: return Request{Mobility(call, M::kClearFault, std::nullopt)};
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
      if (call.Has("then")) {
        const std::string& then = call.Get("then").word;
        r.place = then == "PLACE" || then == "PLACE_FOCUS";
        r.focus = then == "FOCUS" || then == "PLACE_FOCUS";
      }
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
      r.point = PointOf(call.Get("point"));
      r.focus_steps = static_cast<int>(Num(call, "steps"));
      r.focus_step = Num(call, "step");
      return Request{r};
    }
  }
  ROVER_UNREACHABLE();
}

const std::vector<std::string> kTerminationNames = {"NONE", "NOMINAL", "FAULT", "REJECTED"};
// NONE, core/msg's mobility faults, its rendezvous faults under names not already listed (BUSY,
// STOPPED and BAD_COMMAND are one fault whichever service reports it), OTHER.
struct FaultTable {
  std::vector<std::string> names;
  std::vector<int> of_rendezvous;  // index = msg::RendezvousFault
  int other = 0;
};

const FaultTable& Faults() {
  static const FaultTable table = [] {
    FaultTable t;
    for (int i = 0; i < msg::kMobilityFaultCount; ++i) {
      t.names.emplace_back(msg::MobilityFaultName(static_cast<msg::MobilityFault>(i)));
    }
    for (int i = 0; i < msg::kRendezvousFaultCount; ++i) {
      const std::string name = msg::RendezvousFaultName(static_cast<msg::RendezvousFault>(i));
      const auto it = std::find(t.names.begin(), t.names.end(), name);
      t.of_rendezvous.push_back(static_cast<int>(it - t.names.begin()));
      if (it == t.names.end()) t.names.push_back(name);
    }
    t.other = static_cast<int>(t.names.size());
    t.names.emplace_back("OTHER");
    return t;
  }();
  return table;
}

const std::vector<std::string> kFaultClassNames = [] {
  std::vector<std::string> v;
  for (int i = 0; i < msg::kFaultClassCount; ++i) {
    v.emplace_back(msg::FaultClassName(static_cast<msg::FaultClass>(i)));
  }
  return v;
}();

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
const std::vector<std::string>& TerminationNames() { return kTerminationNames; }
const std::vector<std::string>& FaultClassNames() { return kFaultClassNames; }
const std::vector<std::string>& FaultNames() { return Faults().names; }

Fault::Fault(msg::MobilityFault f) {
  const int i = static_cast<int>(f);
  index_ = i >= 0 && i < msg::kMobilityFaultCount ? i : Faults().other;
}

Fault::Fault(msg::RendezvousFault f) {
  const auto i = static_cast<std::size_t>(f);
  index_ = i < Faults().of_rendezvous.size() ? Faults().of_rendezvous[i] : Faults().other;
}

Fault Fault::Other() { return Fault(Faults().other); }

std::optional<Fault> Fault::Named(std::string_view name) {
  const auto& names = Faults().names;
  const auto it = std::find(names.begin(), names.end(), name);
  if (it == names.end()) return std::nullopt;
  return Fault(static_cast<int>(it - names.begin()));
}

const std::string& Fault::Name() const { return Faults().names[static_cast<std::size_t>(index_)]; }

msg::FaultClass Fault::DefaultClass() const {
  if (IsNone()) return msg::FaultClass::kNone;
  if (index_ < msg::kMobilityFaultCount) {
    return msg::FaultClassOf(static_cast<msg::MobilityFault>(index_));
  }
  return msg::FaultClass::kGoalError;
}

Outcome Outcome::Failed(Fault fault, std::string message, Time stamp) {
  return {Termination::kFault, fault, fault.DefaultClass(), std::move(message), stamp};
}

Outcome Outcome::Rejected(Fault fault, std::string message, Time stamp) {
  return {Termination::kRejected, fault, msg::FaultClass::kGoalError, std::move(message), stamp};
}

Status Outcome::Validate() const {
  switch (termination) {
    case Termination::kNone:
      return InvalidArgument("outcome termination NONE is not an outcome");
    case Termination::kNominal:
      if (!fault.IsNone()) {
        return InvalidArgument("outcome NOMINAL carries fault " + fault.Name());
      }
      return Status::Ok();
    case Termination::kFault:
    case Termination::kRejected:
      if (fault.IsNone()) {
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
  out += fault.Name();
  const msg::FaultClass c =
      fault_class == msg::FaultClass::kNone ? fault.DefaultClass() : fault_class;
  out += c == msg::FaultClass::kMotionError ? " (motion error)" : " (goal error)";
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
