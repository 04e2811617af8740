#include "rover/apl/sequencer/command_table.hpp"

#include <algorithm>

#include "rover/base/check.hpp"

namespace rover::apl::sequencer {
namespace {

// ---- argument builders ---------------------------------------------------------------------

ArgSpec Number(std::string_view name, std::string_view unit, Bounds bounds, std::string_view doc) {
  ArgSpec a;
  a.name = name;
  a.type = ArgType::kNumber;
  a.unit = unit;
  a.bounds = bounds;
  a.required = true;
  a.doc = doc;
  return a;
}

ArgSpec Optional(ArgSpec a, double default_value) {
  a.required = false;
  a.default_value = default_value;
  return a;
}

ArgSpec Integer(std::string_view name, Bounds bounds, std::string_view doc) {
  ArgSpec a = Number(name, "", bounds, doc);
  a.type = ArgType::kInteger;
  return a;
}

ArgSpec Point(std::string_view name, ArgType type, std::string_view doc) {
  ArgSpec a;
  a.name = name;
  a.type = type;
  a.unit = "m";
  a.bounds = Bounds::Closed(-1e4, 1e4);
  a.required = true;
  a.doc = doc;
  return a;
}

ArgSpec Tuple(std::string_view name, int size, std::string_view unit, Bounds bounds,
              std::string_view doc) {
  ArgSpec a = Number(name, unit, bounds, doc);
  a.type = ArgType::kTuple;
  a.size = size;
  return a;
}

ArgSpec OneOf(ArgSpec a, std::string_view group) {
  a.required = false;
  a.one_of = group;
  return a;
}

ArgSpec NotRequired(ArgSpec a) {
  a.required = false;
  return a;
}

ArgSpec Pixel(std::string_view name, std::string_view doc) {
  ArgSpec a = Number(name, "px", Bounds::NonNegative(), doc);
  a.type = ArgType::kPixel;
  return a;
}

ArgSpec Needs(ArgSpec a, std::string_view other) {
  a.needs = other;
  return a;
}

ArgSpec Word(std::string_view name, std::vector<std::string_view> choices,
             std::string_view default_word, std::string_view doc) {
  ArgSpec a;
  a.name = name;
  a.type = ArgType::kWord;
  a.choices = std::move(choices);
  a.default_word = default_word;
  a.doc = doc;
  return a;
}

ArgSpec OnFault() {
  ArgSpec a;
  a.name = kOnFaultArg;
  a.type = ArgType::kWord;
  a.choices = {"ABORT", "CONTINUE"};
  a.default_word = "ABORT";
  a.doc = "ABORT: any off-nominal end fails the sequence; CONTINUE: a goal error goes on";
  return a;
}

// Shared argument rows of the mobility commands.
ArgSpec Curvature() {
  return Number("curvature", "1/m", Bounds::Closed(-1.0, 1.0),
                "arc curvature, + turns left (|k| <= 1/min turn radius)");
}
ArgSpec Distance() {
  return Number("distance", "m", Bounds::Closed(-50.0, 50.0),
                "path length, negative drives backwards");
}
ArgSpec Speed() {
  return Optional(Number("speed", "m/s", Bounds::Closed(0.0, 0.1), "0 = the service's default"),
                  0.0);
}
ArgSpec Timeout() {
  return Optional(Number("timeout", "s", Bounds::Closed(0.0, 36000.0),
                         "time budget on the run clock, 0 = the service's default"),
                  0.0);
}
ArgSpec TurnAngle() {
  return Number("angle_deg", "deg", Bounds::Closed(-360.0, 360.0),
                "turn in place, + = left (counter-clockwise)");
}
ArgSpec Goal() { return Point("goal", ArgType::kPoint2, "waypoint, site frame (x, y)"); }
ArgSpec Tolerance() {
  return Optional(Number("tolerance", "m", Bounds::OpenLow(0.0, 10.0), "goal radius"), 0.3);
}

std::vector<ArgSpec> Arc() { return {Curvature(), Distance(), Speed(), Timeout()}; }
std::vector<ArgSpec> Straight() { return {Distance(), Speed(), Timeout()}; }
std::vector<ArgSpec> Turn() { return {TurnAngle(), Timeout()}; }
std::vector<ArgSpec> TurnTo() {
  return {OneOf(Point("target", ArgType::kPoint2, "point to face, site frame"), "facing"),
          OneOf(Number("heading_deg", "deg", Bounds::Closed(-360.0, 360.0),
                       "absolute heading, counter-clockwise from site x"),
                "facing"),
          Timeout()};
}
std::vector<ArgSpec> Waypoint() { return {Goal(), Tolerance(), Timeout()}; }

CommandSpec Row(CommandKind kind, std::string_view name, Family family, std::vector<ArgSpec> args,
                std::string_view positional, std::string_view doc) {
  args.push_back(OnFault());
  return CommandSpec{kind, name, family, std::move(args), positional, doc};
}

std::vector<CommandSpec> BuildTable() {
  const Family kMob = Family::kMobility;
  std::vector<CommandSpec> t;
  // Directed driving (seed 000 Table 2 "Directed Driving").
  t.push_back(Row(CommandKind::kDriveArc, "DRIVE ARC", kMob, Arc(), "",
                  "blind arc of the given curvature and length"));
  t.push_back(Row(CommandKind::kDriveStraight, "DRIVE STRAIGHT", kMob, Straight(), "",
                  "blind straight drive"));
  t.push_back(Row(CommandKind::kTurn, "TURN", kMob, Turn(), "", "blind turn in place"));
  t.push_back(Row(CommandKind::kTurnTo, "TURN TO", kMob, TurnTo(), "target",
                  "turn in place to face a point or to a heading (from the pose estimate)"));
  // Directed driving with visual odometry after each step (Table 2 "Visodom").
  t.push_back(Row(CommandKind::kVisodomArc, "VISODOM ARC", kMob, Arc(), "",
                  "arc with visual-odometry updates"));
  t.push_back(Row(CommandKind::kVisodomStraight, "VISODOM STRAIGHT", kMob, Straight(), "",
                  "straight drive with visual-odometry updates"));
  t.push_back(Row(CommandKind::kVisodomTurn, "VISODOM TURN", kMob, Turn(), "",
                  "turn in place with visual-odometry updates"));
  t.push_back(Row(CommandKind::kVisodomTurnTo, "VISODOM TURN TO", kMob, TurnTo(), "target",
                  "TURN TO with visual-odometry updates"));
  // Goal-directed modes (Table 2 rows 3-8).
  t.push_back(Row(CommandKind::kGoto, "GOTO", kMob, Waypoint(), "goal",
                  "blind go-to-waypoint"));
  t.push_back(Row(CommandKind::kVisodomGoto, "VISODOM GOTO", kMob, Waypoint(), "goal",
                  "go-to-waypoint with visual odometry"));
  t.push_back(Row(CommandKind::kGuarded, "GUARDED", kMob, Waypoint(), "goal",
                  "guarded motion: terrain assessment stops the drive, no path selection"));
  t.push_back(Row(CommandKind::kGuardedVisodom, "GUARDED VISODOM", kMob, Waypoint(), "goal",
                  "guarded motion with visual odometry"));
  t.push_back(Row(CommandKind::kGuardedArc, "GUARDED ARC", kMob, Arc(), "",
                  "arc driven only if the hazard cameras show it safe (seed 003 §2.1)"));
  t.push_back(Row(CommandKind::kAutonav, "AUTONAV", kMob, Waypoint(), "goal",
                  "autonomous navigation with hazard avoidance"));
  t.push_back(Row(CommandKind::kAutonavVisodom, "AUTONAV VISODOM", kMob, Waypoint(), "goal",
                  "autonav with visual odometry"));
  t.push_back(Row(CommandKind::kLongTraverse, "LONG_TRAVERSE", kMob, Waypoint(), "goal",
                  "ROAMAN long-range plan, then autonav legs"));
  t.push_back(Row(CommandKind::kStop, "STOP", kMob, {}, "", "stop driving"));
  t.push_back(Row(CommandKind::kClearFault, "CLEAR_FAULT", kMob, {}, "",
                  "clear a motion error so that the rover may move again"));
  // Mast (dl/mast_command).
  t.push_back(Row(CommandKind::kMast, "MAST", Family::kMast,
                  {Number("pan_deg", "deg", Bounds::Closed(-180.0, 180.0), "+ looks left"),
                   Number("tilt_deg", "deg", Bounds::Closed(-90.0, 90.0), "+ looks up")},
                  "", "point the mast head by angles"));
  t.push_back(Row(CommandKind::kMastLookAt, "MAST LOOK_AT", Family::kMast,
                  {Point("point", ArgType::kPoint3, "site-frame point to look at")}, "point",
                  "point the NAVCAMs at a site-frame point"));
  // Rendezvous (apl/rendezvous_command).
  t.push_back(Row(CommandKind::kReturnToLander, "RETURN_TO_LANDER", Family::kRendezvous,
                  {NotRequired(Point("lander", ArgType::kPoint3,
                                     "a-priori lander position; absent = the service's own")),
                   Optional(Number("standoff", "m", Bounds::Closed(0.3, 10.0),
                                   "stop this far from the ramp"),
                            1.0),
                   Timeout()},
                  "lander", "three-phase visual rendezvous with the lander"));
  t.push_back(Row(
      CommandKind::kApproachTarget, "APPROACH_TARGET", Family::kRendezvous,
      {Needs(NotRequired(Integer("image", Bounds::Closed(0.0, 4294967295.0),
                                 "id of the left NAVCAM image the pixel is in")),
             "pixel"),
       Needs(OneOf(Pixel("pixel", "designated pixel (u, v) in that image"), "designation"),
             "image"),
       OneOf(Point("point", ArgType::kPoint3, "or a site-frame point"), "designation"),
       Optional(Number("standoff", "m", Bounds::Closed(0.8, 3.0),
                       "target this far ahead of the rover centre at the end"),
                1.05),
       Word("then", {"NONE", "PLACE", "FOCUS", "PLACE_FOCUS"}, "NONE",
            "at the standoff: PLACE the instrument on the target, FOCUS the microscopic imager "
            "on it (auto-focus), or PLACE_FOCUS both, in that order"),
       Timeout()},
      "", "single-command science-target approach with visual tracking (FIDO)"));
  // Arm and microscopic imager.
  t.push_back(Row(CommandKind::kArmMove, "ARM MOVE", Family::kArm,
                  {Tuple("joints_deg", 4, "deg", Bounds::Closed(-180.0, 180.0),
                         "the four joint angles")},
                  "joints_deg", "joint-space move"));
  t.push_back(Row(CommandKind::kArmPlace, "ARM PLACE", Family::kArm,
                  {Point("point", ArgType::kPoint3, "site-frame point to place the imager on"),
                   Optional(Number("hover", "m", Bounds::Closed(0.0, 0.1),
                                   "stop this far above the point"),
                            0.0)},
                  "point", "place the instrument on a point"));
  t.push_back(Row(CommandKind::kArmStow, "ARM STOW", Family::kArm, {}, "", "stow the arm"));
  t.push_back(Row(CommandKind::kArmUnstow, "ARM UNSTOW", Family::kArm, {}, "",
                  "unstow the arm"));
  t.push_back(Row(CommandKind::kAutofocus, "AUTOFOCUS", Family::kArm,
                  {Point("point", ArgType::kPoint3,
                         "site-frame surface point the microscopic imager focuses on"),
                   Optional(Integer("steps", Bounds::Closed(3.0, 30.0), "frames in the sweep"),
                            10.0),
                   Optional(Number("step", "m", Bounds::OpenLow(0.0, 0.02),
                                   "lowering between frames"),
                            0.0067)},
                  "point", "auto-focus the microscopic imager on a point (FIDO)"));
  for (std::size_t i = 0; i < t.size(); ++i) {
    ROVER_DEMAND_MSG(static_cast<std::size_t>(t[i].kind) == i, "table out of CommandKind order");
  }
  return t;
}

}  // namespace

const ArgSpec* CommandSpec::FindArg(std::string_view arg) const {
  for (const ArgSpec& a : args) {
    if (a.name == arg) return &a;
  }
  return nullptr;
}

std::vector<std::string> CommandSpec::ArgNames() const {
  std::vector<std::string> out;
  for (const ArgSpec& a : args) out.emplace_back(a.name);
  return out;
}

const std::vector<CommandSpec>& CommandTable() {
  static const std::vector<CommandSpec> table = BuildTable();
  return table;
}

const CommandSpec& SpecOf(CommandKind kind) {
  const auto i = static_cast<std::size_t>(kind);
  ROVER_DEMAND(i < CommandTable().size());
  return CommandTable()[i];
}

const CommandSpec* FindCommand(std::string_view name) {
  for (const CommandSpec& c : CommandTable()) {
    if (c.name == name) return &c;
  }
  return nullptr;
}

std::vector<std::string> CommandNames() {
  std::vector<std::string> out;
  for (const CommandSpec& c : CommandTable()) out.emplace_back(c.name);
  return out;
}

int MaxCommandWords() {
  int most = 0;
  for (const CommandSpec& c : CommandTable()) {
    most = std::max(most, 1 + static_cast<int>(std::count(c.name.begin(), c.name.end(), ' ')));
  }
  return most;
}

const char* FamilyName(Family f) {
  switch (f) {
    case Family::kMobility: return "mobility";
    case Family::kMast: return "mast";
    case Family::kRendezvous: return "rendezvous";
    case Family::kArm: return "arm";
  }
  ROVER_UNREACHABLE();
}

const char* ArgTypeName(ArgType t) {
  switch (t) {
    case ArgType::kNumber: return "a number";
    case ArgType::kInteger: return "a whole number";
    case ArgType::kPoint2: return "a point (x, y) or a target name";
    case ArgType::kPoint3: return "a point (x, y, z) or a target name";
    case ArgType::kPixel: return "a pixel (u, v)";
    case ArgType::kTuple: return "a list of numbers (a, b, ...)";
    case ArgType::kWord: return "a word";
  }
  ROVER_UNREACHABLE();
}

}  // namespace rover::apl::sequencer
