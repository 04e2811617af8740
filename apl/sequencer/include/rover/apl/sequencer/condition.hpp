#pragma once
/// @file
/// Conditions of IF, WHILE and WAIT UNTIL, and what they read.
///
/// Quantities (the unit a bare number in a comparison is read in):
///   last.termination  NONE | NOMINAL | FAULT | REJECTED   of the last command that ended
///   last.fault        NONE | a Fault name (commands.hpp)
///   last.class        NONE | GOAL_ERROR | MOTION_ERROR
///   distance_to(p)    [m]   horizontal distance from the rover centre (pose estimate) to p, a
///                           TARGET name or a literal point
///   visodom.failures  count visual-odometry updates that failed, as the service reports them
///   tilt              [deg] acos(cos roll cos pitch) of the pose estimate
///   elapsed           [s]   run-clock time since the sequence started
/// Enumerated quantities compare with == and != only; numeric ones with all six relations
/// (== and != exactly). AND binds tighter than OR; NOT tightest; parentheses group.

#include <optional>
#include <string>

#include "rover/apl/sequencer/commands.hpp"
#include "rover/apl/sequencer/sequence.hpp"

namespace rover::apl::sequencer {

/// The name a quantity is written as ("last.fault", "distance_to", ...).
const char* QuantityName(Quantity q);
/// Every quantity name (for "did you mean").
std::vector<std::string> QuantityNames();
/// The quantity written `name` (case-insensitive), if any.
std::optional<Quantity> FindQuantity(std::string_view name);
/// True for last.termination, last.fault and last.class.
bool IsEnumerated(Quantity q);
/// The unit a numeric quantity is in ("m", "deg", "count" or "s").
std::string_view QuantityUnit(Quantity q);
/// The names an enumerated quantity's values take (index = value).
const std::vector<std::string>& QuantityValueNames(Quantity q);
/// "==", "<=", ...
const char* RelationName(Relation r);
/// True when the condition reads the pose (distance_to, tilt).
bool NeedsPose(const Condition& c);

/// What a condition is evaluated against.
struct ConditionInputs {
  Outcome last;                   ///< termination kNone before any command ended
  const PoseSample* pose = nullptr;  ///< nullptr: no usable pose
  int visodom_failures = 0;
  double elapsed_s = 0.0;
};

/// The value of a condition, or nullopt when it needs the pose and `inputs.pose` is null.
std::optional<bool> Evaluate(const Condition& c, const ConditionInputs& inputs);

}  // namespace rover::apl::sequencer
