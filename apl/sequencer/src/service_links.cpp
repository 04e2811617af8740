#include "service_links.hpp"

#include <algorithm>
#include <functional>

#include "rover/base/check.hpp"
#include "rover/base/format.hpp"

namespace rover::apl::sequencer {
namespace {

/// The first command of `statements` (in writing order, blocks included) that `pred` holds for.
const CommandCall* FindCommand(const std::vector<Statement>& statements,
                               const std::function<bool(const CommandCall&)>& pred) {
  for (const Statement& s : statements) {
    if (s.kind == Statement::Kind::kCommand && pred(s.command)) return &s.command;
    if (const CommandCall* c = FindCommand(s.body, pred)) return c;
    if (const CommandCall* c = FindCommand(s.else_body, pred)) return c;
  }
  return nullptr;
}

}  // namespace

bool ServiceDispatches(Family f) {
  return f == Family::kMobility || f == Family::kMast || f == Family::kRendezvous ||
         f == Family::kArm;
}

namespace {
// Why apl-sequencer does not dispatch a command, or "" when it does.
std::string NotDispatched(const CommandSpec& s) {
  if (!ServiceDispatches(s.family)) return std::string(FamilyName(s.family)) + " commands";
  if (s.kind == CommandKind::kArmUnstow) return "it (dl-arm has no unstowed pose; ARM MOVE names one)";
  return "";
}
}  // namespace

Status CheckDispatchable(const Sequence& sequence) {
  auto other = [](const CommandCall& c) { return !NotDispatched(c.spec()).empty(); };
  const CommandCall* c = FindCommand(sequence.on_abort, other);
  const CommandCall* first = FindCommand(sequence.statements, other);
  if (first != nullptr && (c == nullptr || first->pos.line < c->pos.line)) c = first;
  if (c == nullptr) return Status::Ok();
  return InvalidArgument("line " + std::to_string(c->pos.line) + ": " +
                         std::string(c->spec().name) + ": apl-sequencer does not dispatch " +
                         NotDispatched(c->spec()));
}

Result<msg::MobilityCommand> MobilityCommandOf(const Command& c, Time stamp) {
  const auto& r = std::get<MobilityRequest>(c.request);
  if (r.speed != 0.0) {
    return InvalidArgument("speed = " + FormatNumber(r.speed) +
                           " m/s: apl/mobility_command carries no speed (the mobility "
                           "manager's drive speed is its parameter); leave speed at 0");
  }
  msg::MobilityCommand m;
  m.stamp = stamp;
  m.command_id = c.id;
  m.mode = r.mode;
  m.goal = Eigen::Vector3d(r.goal_x, r.goal_y, 0.0);
  m.tolerance = r.tolerance;
  m.time_budget_s = r.time_budget_s;
  if (r.primitive) m.primitives.push_back({*r.primitive, r.curvature, r.distance, r.angle});
  return m;
}

msg::MobilityCommand MobilityStopCommand(std::uint32_t cancel_id, Time stamp) {
  msg::MobilityCommand m;
  m.stamp = stamp;
  m.command_id = cancel_id | kCancelIdBit;
  m.mode = msg::MobilityMode::kStop;
  return m;
}

msg::MastCommand MastCommandOf(const Command& c, Time stamp) {
  const auto& r = std::get<MastRequest>(c.request);
  msg::MastCommand m;
  m.stamp = stamp;
  m.command_id = c.id;
  if (r.kind == MastRequest::Kind::kLookAt) {
    m.pointing = msg::MastPointing::kLookAt;
    m.look_at = Eigen::Vector3d(r.point.x, r.point.y, r.point.z);
  } else {
    m.pointing = msg::MastPointing::kAngles;
    m.pan = r.pan;
    m.tilt = r.tilt;
  }
  return m;
}

msg::RendezvousCommand RendezvousCommandOf(const Command& c, Time stamp) {
  const auto& r = std::get<RendezvousRequest>(c.request);
  msg::RendezvousCommand m;
  m.stamp = stamp;
  m.command_id = c.id;
  m.standoff = r.standoff;
  m.time_budget_s = r.time_budget_s;
  if (r.point) m.target_estimate = Eigen::Vector3d(r.point->x, r.point->y, r.point->z);
  if (r.kind == RendezvousRequest::Kind::kReturnToLander) {
    m.target = msg::RendezvousTarget::kLander;
    m.ramp = -1;
    m.climb = false;
  } else {
    m.target = msg::RendezvousTarget::kScience;
    m.image_id = r.image.value_or(0);
    m.pixel_x = r.u;
    m.pixel_y = r.v;
    m.place_instrument = r.place;
    m.autofocus = r.focus;
  }
  return m;
}

msg::RendezvousCommand RendezvousStopCommand(std::uint32_t cancel_id, Time stamp) {
  msg::RendezvousCommand m;
  m.stamp = stamp;
  m.command_id = cancel_id | kCancelIdBit;
  m.target = msg::RendezvousTarget::kStop;
  return m;
}

std::optional<Outcome> OutcomeOfRendezvousStatus(const msg::RendezvousStatus& s) {
  if (s.phase == msg::RendezvousPhase::kDone) return Outcome::Nominal(s.stamp);
  if (s.phase != msg::RendezvousPhase::kFailed) return std::nullopt;
  const Fault fault = s.fault == msg::RendezvousFault::kNone ? Fault::Other() : Fault(s.fault);
  if (s.fault == msg::RendezvousFault::kBadCommand || s.fault == msg::RendezvousFault::kBusy) {
    return Outcome::Rejected(fault, s.message, s.stamp);
  }
  Outcome o = Outcome::Failed(fault, s.message, s.stamp);
  o.fault_class = msg::FaultClass::kGoalError;
  return o;
}

std::optional<Outcome> OutcomeOfMobilityStatus(const msg::MobilityStatus& s) {
  Outcome o;
  o.stamp = s.stamp;
  o.message = s.message;
  switch (s.state) {
    case msg::MobilityState::kSucceeded:
      o.termination = Termination::kNominal;
      return o;
    case msg::MobilityState::kFailed:
      o.termination = Termination::kFault;
      break;
    case msg::MobilityState::kRejected:
      o.termination = Termination::kRejected;
      break;
    default:
      return std::nullopt;
  }
  o.fault = Fault(s.fault);
  if (o.fault.IsNone()) o.fault = Fault::Other();  // an end off nominal names a fault
  o.fault_class = s.fault_class == msg::FaultClass::kNone ? o.fault.DefaultClass() : s.fault_class;
  return o;
}

Result<msg::ArmCommand> ArmCommandOf(const Command& c,
                                     const std::optional<Eigen::Isometry3d>& site_from_rover,
                                     Time stamp) {
  const auto& r = std::get<ArmRequest>(c.request);
  msg::ArmCommand m;
  m.stamp = stamp;
  m.command_id = c.id;
  switch (r.kind) {
    case ArmRequest::Kind::kMove:
      m.mode = msg::ArmMode::kJoints;
      m.joints = r.joints;
      return m;
    case ArmRequest::Kind::kStow:
      m.mode = msg::ArmMode::kStow;
      return m;
    case ArmRequest::Kind::kPlace:
      if (r.hover != 0.0) {
        return InvalidArgument("hover = " + FormatNumber(r.hover) +
                               " m: dl-arm places the instrument until its contact switch "
                               "closes; leave hover at 0");
      }
      if (!site_from_rover) return FailedPrecondition("ARM PLACE needs dl/pose; none heard yet");
      m.mode = msg::ArmMode::kPlace;
      m.target = site_from_rover->inverse() * Eigen::Vector3d(r.point.x, r.point.y, r.point.z);
      return m;
    case ArmRequest::Kind::kAutofocus: {
      if (!site_from_rover) return FailedPrecondition("AUTOFOCUS needs dl/pose; none heard yet");
      const double span = (r.focus_steps - 1) * r.focus_step;
      if (span > 0.3) {
        return InvalidArgument("steps = " + std::to_string(r.focus_steps) + " of step = " +
                               FormatNumber(r.focus_step) + " m sweep " + FormatNumber(span) +
                               " m; dl-arm sweeps at most 0.3 m");
      }
      m.mode = msg::ArmMode::kAutofocus;
      m.target = site_from_rover->inverse() * Eigen::Vector3d(r.point.x, r.point.y, r.point.z);
      m.focus_steps = r.focus_steps;
      m.focus_span = span;
      return m;
    }
    case ArmRequest::Kind::kUnstow:
      break;
  }
  return InvalidArgument(std::string(c.text) + ": apl-sequencer does not dispatch it");
}

msg::ArmCommand ArmStopCommand(std::uint32_t cancel_id, Time stamp) {
  msg::ArmCommand m;
  m.stamp = stamp;
  m.command_id = cancel_id | kCancelIdBit;
  m.mode = msg::ArmMode::kStop;
  return m;
}

std::optional<Outcome> OutcomeOfArmStatus(const msg::ArmStatus& s) {
  switch (s.state) {
    case msg::ArmState::kAtGoal:
    case msg::ArmState::kPlaced:
    case msg::ArmState::kStowed:
    case msg::ArmState::kFocused: return Outcome::Nominal(s.stamp);
    case msg::ArmState::kFault: return Outcome::Failed(Fault::Other(), s.message, s.stamp);
    case msg::ArmState::kRejected:
      return Outcome::Rejected(Fault(msg::MobilityFault::kBadCommand), s.message, s.stamp);
    default: return std::nullopt;
  }
}

std::optional<Outcome> OutcomeOfMastStatus(const msg::MastStatus& s) {
  switch (s.state) {
    case msg::MastState::kAtGoal: return Outcome::Nominal(s.stamp);
    case msg::MastState::kFault: return Outcome::Failed(Fault::Other(), s.message, s.stamp);
    case msg::MastState::kRejected:
      return Outcome::Rejected(Fault(msg::MobilityFault::kBadCommand), s.message, s.stamp);
    default: return std::nullopt;
  }
}

PoseSample PoseOfEstimate(const msg::PoseEstimate& p) {
  PoseSample s;
  s.stamp = p.stamp;
  s.position = {p.position.x(), p.position.y(), p.position.z()};
  s.roll = p.rpy.x();
  s.pitch = p.rpy.y();
  s.yaw = p.rpy.z();
  return s;
}

bool IsVisOdomFailure(const msg::RelativePose& r) {
  return r.source == msg::MotionSource::kVisualOdometry &&
         r.status != msg::RelativePoseStatus::kConverged;
}

msg::SequenceStatus SequenceStatusOf(const SequenceStatus& s, std::uint32_t command_id,
                                     Time stamp) {
  msg::SequenceStatus m;
  m.stamp = stamp;
  m.command_id = command_id;
  switch (s.state) {
    case SequenceState::kIdle: m.state = msg::SequenceState::kIdle; break;
    case SequenceState::kRunning:
    case SequenceState::kAborting: m.state = msg::SequenceState::kRunning; break;
    case SequenceState::kDone: m.state = msg::SequenceState::kDone; break;
    case SequenceState::kFailed:
    case SequenceState::kAborted: m.state = msg::SequenceState::kFailed; break;
  }
  m.step = static_cast<std::uint32_t>(std::max(0, s.step));
  m.message = s.message;
  return m;
}

}  // namespace rover::apl::sequencer
