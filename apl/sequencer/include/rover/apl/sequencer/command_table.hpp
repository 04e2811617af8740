#pragma once
/// @file
/// The sequence language's command set as data: every command's name, the service family that
/// runs it, and its arguments with type, unit, range, default and whether they are required.
/// The parser checks commands against this table; the sequencer service maps each family to
/// its topic (mobility -> apl/mobility_command, mast -> dl/mast_command, rendezvous ->
/// apl/rendezvous_command, arm -> the arm service's command).
///
/// Ranges are the language's own limits (what a sequence may ask for at all); the service that
/// runs a command applies its configured, possibly tighter, limits and rejects the rest.
/// Arguments are stored in the table's unit (e.g. `angle_deg` in degrees); the typed requests
/// of commands.hpp are in SI units and radians.

#include <string>
#include <string_view>
#include <vector>

#include "rover/base/range_check.hpp"

namespace rover::apl::sequencer {

/// Which service runs a command.
enum class Family { kMobility, kMast, kRendezvous, kArm };

/// One per row of the table, in table order.
enum class CommandKind {
  kDriveArc,
  kDriveStraight,
  kTurn,
  kTurnTo,
  kVisodomArc,
  kVisodomStraight,
  kVisodomTurn,
  kVisodomTurnTo,
  kGoto,
  kVisodomGoto,
  kGuarded,
  kGuardedVisodom,
  kGuardedArc,
  kAutonav,
  kAutonavVisodom,
  kLongTraverse,
  kStop,
  kClearFault,
  kMast,
  kMastLookAt,
  kReturnToLander,
  kApproachTarget,
  kArmMove,
  kArmPlace,
  kArmStow,
  kArmUnstow,
  kAutofocus,
};

enum class ArgType {
  kNumber,   ///< one number in `unit`
  kInteger,  ///< one whole number (no unit)
  kPoint2,   ///< (x, y) in metres, site frame; a TARGET name gives its x, y
  kPoint3,   ///< (x, y, z) in metres, site frame; a TARGET name gives it
  kPixel,    ///< (u, v) in pixels
  kTuple,    ///< `size` numbers in `unit`
  kWord,     ///< one of `choices` (case-insensitive)
};

struct ArgSpec {
  std::string_view name;  ///< lower case, as written: `distance`
  ArgType type = ArgType::kNumber;
  std::string_view unit;  ///< of each number: "m", "deg", "s", "m/s", "1/m", "px", ""
  Bounds bounds;          ///< of each number, in `unit`
  bool required = false;
  double default_value = 0.0;        ///< kNumber / kInteger when absent and not required
  std::string_view default_word;     ///< kWord when absent
  int size = 0;                      ///< kTuple: how many numbers
  std::vector<std::string_view> choices;  ///< kWord, upper case
  /// Arguments sharing a non-empty group name: exactly one of them must be given.
  std::string_view one_of;
  /// Another argument that must be given with this one.
  std::string_view needs;
  std::string_view doc;
};

struct CommandSpec {
  CommandKind kind;
  std::string_view name;  ///< upper case, words separated by one space: "DRIVE ARC"
  Family family;
  std::vector<ArgSpec> args;  ///< including the common `on_fault`
  /// The argument a bare value after the name fills (`MAST LOOK_AT rock1`); "" = none.
  std::string_view positional;
  std::string_view doc;

  /// The argument called `name`, or nullptr.
  const ArgSpec* FindArg(std::string_view name) const;
  /// Argument names, in table order.
  std::vector<std::string> ArgNames() const;
};

/// The argument every command takes: `on_fault=ABORT` (default; any off-nominal end fails the
/// sequence) or `on_fault=CONTINUE` (a goal error lets the sequence go on to the next
/// statement, where `last.*` describe it; motion errors and rejections still fail it).
inline constexpr std::string_view kOnFaultArg = "on_fault";

/// Every command, in CommandKind order.
const std::vector<CommandSpec>& CommandTable();
const CommandSpec& SpecOf(CommandKind kind);
/// The command with this upper-case name ("DRIVE ARC"), or nullptr.
const CommandSpec* FindCommand(std::string_view name);
/// Every command name, in table order.
std::vector<std::string> CommandNames();
/// The longest number of words in a command name.
int MaxCommandWords();

const char* FamilyName(Family f);  ///< "mobility", "mast", "rendezvous", "arm"
const char* ArgTypeName(ArgType t);  ///< "number", "point (x, y)", ...

}  // namespace rover::apl::sequencer
