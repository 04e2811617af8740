// Every parse error: its line, column and message. A text with an error yields no Sequence.
#include <gtest/gtest.h>

#include "rover/apl/sequencer/parser.hpp"
#include "sequencer_test_util.hpp"

namespace rover::apl::sequencer {
namespace {

using testing::ErrorsOf;

struct Expected {
  int line;
  int column;
  std::string message;
};

/// The text fails with exactly this one error.
void ExpectError(const std::string& text, const Expected& e) {
  SCOPED_TRACE(text);
  const auto errors = ErrorsOf(text);
  ASSERT_EQ(errors.size(), 1u) << FormatErrors(ParseSequenceText(text), "t");
  EXPECT_EQ(errors[0].pos, (SourcePos{e.line, e.column}));
  EXPECT_EQ(errors[0].message, e.message);
}

TEST(ParserErrors, UnknownCommandsSuggestTheClosest) {
  ExpectError("STOP\nDRIV ARC curvature=1 distance=1\n",
              {2, 1, "unknown command 'DRIV ARC' (did you mean 'DRIVE ARC'?)"});
  ExpectError("WIAT 5 s\n", {1, 1, "unknown command 'WIAT' (did you mean 'WAIT'?)"});
  ExpectError("  DRIVE ARK curvature=1\n",
              {1, 3, "unknown command 'DRIVE ARK' (did you mean 'DRIVE ARC'?)"});
  ExpectError("DRIVE distance=1\n", {1, 1, "DRIVE needs one of: DRIVE ARC, DRIVE STRAIGHT"});
  ExpectError("FLY to=(1, 2)\n", {1, 1, "unknown command 'FLY'"});
  ExpectError("distance=5\n", {1, 1, "expected a command, got 'distance'="});
  ExpectError("(1, 2)\n", {1, 1, "expected a statement, got '('"});
  ExpectError("MAX 5\n", {1, 1, "MAX cannot start a statement"});
  // Three words, as written (the hint in the table's spelling).
  ExpectError("VISODM TURN TO (1, 2)\n",
              {1, 1, "unknown command 'VISODM TURN TO' (did you mean 'VISODOM TURN TO'?)"});
  ExpectError("drive arK curvature=1\n",
              {1, 1, "unknown command 'drive arK' (did you mean 'DRIVE ARC'?)"});
  // A positional value after an unknown one-word name is not part of the quoted name.
  ExpectError("TARGET rock1 = (1, 2)\nGOT rock1\n",
              {2, 1, "unknown command 'GOT' (did you mean 'GOTO'?)"});
}

TEST(ParserErrors, UnknownMissingAndRepeatedArguments) {
  ExpectError("DRIVE ARC curvatur=0.5 distance=1\n",
              {1, 11, "DRIVE ARC has no argument 'curvatur' (did you mean 'curvature'?)"});
  ExpectError("DRIVE ARC curvature=0.5\n", {1, 1, "DRIVE ARC needs argument 'distance' (m)"});
  ExpectError("GOTO tolerance=1\n",
              {1, 1, "GOTO needs argument 'goal' (a point (x, y) or a target name)"});
  ExpectError("TURN angle_deg=1 angle_deg=2\n",
              {1, 18, "TURN: argument 'angle_deg' given twice (first at column 6)"});
  ExpectError("DRIVE ARC 0.5 1.0\n",
              {1, 11, "expected an argument name=value of DRIVE ARC (curvature=, distance=, "
                      "speed=, timeout=, on_fault=), got '0.5'"});
  ExpectError("STOP now\n", {1, 6, "STOP takes no arguments but on_fault=, got 'now'"});
}

TEST(ParserErrors, ValuesOutOfRangeNameTheUnit) {
  ExpectError("DRIVE STRAIGHT distance=60\n", {1, 16, "distance = 60 m is outside [-50, 50]"});
  // Converted first, then checked in the argument's unit.
  ExpectError("DRIVE STRAIGHT distance=6000 cm\n",
              {1, 16, "distance = 60 m is outside [-50, 50]"});
  ExpectError("TURN angle_deg=400\n", {1, 6, "angle_deg = 400 deg is outside [-360, 360]"});
  ExpectError("APPROACH_TARGET point=(1, 0, 0) standoff=0.5\n",
              {1, 33, "standoff = 0.5 m is outside [0.8, 3]"});
  ExpectError("APPROACH_TARGET image=1 pixel=(-3, 10)\n",
              {1, 25, "pixel[0] = -3 px is outside [0, inf)"});
  ExpectError("APPROACH_TARGET point=(1, 0, 0) then=DRILL\n",
              {1, 38, "then must be one of NONE, PLACE, FOCUS, PLACE_FOCUS, got 'DRILL'"});
  ExpectError("AUTOFOCUS (1, 0, 0) steps=1\n", {1, 21, "steps = 1 is outside [3, 30]"});
  ExpectError("AUTOFOCUS (1, 0, 0) steps=3.5\n", {1, 21, "steps = 3.5 is not a whole number"});
  ExpectError("WAIT 2 h\nWAIT 25 h\n", {2, 6, "WAIT = 90000 s is outside [0, 86400]"});
  ExpectError("WAIT -1\n", {1, 6, "WAIT = -1 s is outside [0, 86400]"});
  // Positional: at the value, which is where the argument is written.
  ExpectError("GOTO (2e4, 0)\n", {1, 6, "goal[0] = 20000 m is outside [-10000, 10000]"});
  ExpectError("MAST LOOK_AT point=(1, 2, 30 km)\n",
              {1, 14, "point[2] = 30000 m is outside [-10000, 10000]"});
}

TEST(ParserErrors, UnitsOfTheWrongDimensionOrUnknown) {
  ExpectError("DRIVE STRAIGHT distance=5 s\n",
              {1, 27, "unit 's' is a time; distance takes a length (m, cm, mm, km)"});
  ExpectError("DRIVE STRAIGHT distance=5 meters\n",
              {1, 27, "unknown unit 'meters'"});
  ExpectError("REPEAT 3 m\n  STOP\nEND\n",
              {1, 10, "unit 'm' is a length; REPEAT count takes a plain number"});
  ExpectError("CONST step = 30 cm\nTURN angle_deg=step\n",
              {2, 16, "constant step: unit 'cm' is a length; angle_deg takes an angle (deg, rad)"});
}

TEST(ParserErrors, WrongValueShapes) {
  ExpectError("GOTO 5\n", {1, 6, "goal expects (x, y), got '5'"});
  ExpectError("GOTO (1, 2, 3)\n", {1, 6, "goal expects 2 numbers (x, y), got 3"});
  ExpectError("MAST LOOK_AT (1, 2)\n", {1, 14, "point expects 3 numbers (x, y, z), got 2"});
  ExpectError("GOTO (1 2)\n", {1, 9, "expected ',' or ')' in goal, got '2'"});
  ExpectError("ARM MOVE (1, 2, 3)\n", {1, 10, "joints_deg expects 4 numbers (a, b, ...), got 3"});
  ExpectError("TURN angle_deg=(1, 2)\n", {1, 16, "angle_deg expects a number, got '('"});
  ExpectError("TURN angle_deg=1 on_fault=CONTINU\n",
              {1, 27, "on_fault must be one of ABORT, CONTINUE, got 'CONTINU' (did you mean "
                      "'CONTINUE'?)"});
}

TEST(ParserErrors, OneOfAndNeedsRules) {
  ExpectError("APPROACH_TARGET standoff=1\n",
              {1, 1, "APPROACH_TARGET needs one of 'pixel', 'point'"});
  ExpectError("APPROACH_TARGET image=1 pixel=(1, 2) point=(1, 2, 3)\n",
              {1, 1, "APPROACH_TARGET takes only one of 'pixel', 'point' (several given)"});
  ExpectError("APPROACH_TARGET pixel=(1, 2)\n",
              {1, 17, "APPROACH_TARGET: argument 'pixel' needs argument 'image'"});
  ExpectError("APPROACH_TARGET image=4 point=(1, 2, 3)\n",
              {1, 17, "APPROACH_TARGET: argument 'image' needs argument 'pixel'"});
  ExpectError("TURN TO\n", {1, 1, "TURN TO needs one of 'target', 'heading_deg'"});
}

TEST(ParserErrors, UnknownTargetsAndConstants) {
  ExpectError("TARGET rock1 = (1, 2, 0)\nGOTO rok1\n",
              {2, 6, "unknown target 'rok1' (did you mean 'rock1'?)"});
  ExpectError("CONST step = 0.3\nDRIVE STRAIGHT distance=stp\n",
              {2, 25, "unknown constant 'stp' (did you mean 'step'?)"});
  ExpectError("TARGET rock1 = (1, 2, 0)\nDRIVE STRAIGHT distance=rock1\n",
              {2, 25, "'rock1' is a TARGET (a point); distance takes a number"});
  ExpectError("CONST d = 1\nGOTO d\n",
              {2, 6, "'d' is a CONST (a number); goal takes a point or a TARGET name"});
  ExpectError("TARGET a = (1, 2)\nTARGET a = (3, 4)\nSTOP\n",
              {2, 8, "TARGET name 'a' is already defined at line 1"});
  ExpectError("CONST tilt = 3\nSTOP\n", {1, 7, "CONST name 'tilt' is the name of a quantity"});
  ExpectError("TARGET end = (1, 1)\nSTOP\n", {1, 8, "TARGET name 'end' is a reserved word"});
  // Reserved in any case: they separate the parts of a statement or close blocks.
  ExpectError("CONST Max = 3\nSTOP\n", {1, 7, "CONST name 'Max' is a reserved word"});
  ExpectError("CONST timeout = 3\nSTOP\n", {1, 7, "CONST name 'timeout' is a reserved word"});
  ExpectError("TARGET else = (1, 1)\nSTOP\n", {1, 8, "TARGET name 'else' is a reserved word"});
  ExpectError("TARGET a.b = (1, 1)\nSTOP\n", {1, 8, "TARGET name 'a.b' may not contain '.' or '/'"});
  ExpectError("TARGET a (1, 1)\nSTOP\n", {1, 10, "expected '=' after TARGET a, got '('"});
  ExpectError("CONST a = fast\nSTOP\n",
              {1, 11, "CONST a needs a number (with an optional unit), got 'fast'"});
}

TEST(ParserErrors, UnbalancedBlocks) {
  ExpectError("STOP\nEND\n", {2, 1, "END without an open block"});
  ExpectError("STOP\nIF tilt > 5\n  STOP\n", {2, 1, "IF at line 2 has no END"});
  ExpectError("REPEAT 2\n  IF tilt > 5\n    STOP\n  END\n", {1, 1, "REPEAT at line 1 has no END"});
  ExpectError("ELSE\nSTOP\n", {1, 1, "ELSE without IF"});
  ExpectError("REPEAT 2\n  ELSE\nEND\n", {2, 3, "ELSE without IF (inside the REPEAT at line 1)"});
  ExpectError("IF tilt > 5\n  STOP\nELSE\n  STOP\nELSE\n  STOP\nEND\n",
              {5, 1, "a second ELSE for the IF at line 1"});
  ExpectError("IF tilt > 5\nSTOP\nELSE IF tilt > 3\nSTOP\n", {3, 6, "IF at line 3 has no END"});
  ExpectError("STOP\nEND now\n", {2, 5, "unexpected 'now' after END"});
  // Inside a block "END x" is reported for the x and still closes the block.
  ExpectError("IF tilt > 5\n  STOP\nEND now\nSTOP\n", {3, 5, "unexpected 'now' after END"});
  ExpectError("ON_ABORT\n  STOP\n", {1, 1, "ON_ABORT at line 1 has no END"});
  ExpectError("ON_ABORT\nSTOP\nEND\nON_ABORT\nSTOP\nEND\nSTOP\n",
              {4, 1, "a second ON_ABORT block (the first is at line 1)"});
  ExpectError("REPEAT 2\n  ON_ABORT\n    STOP\n  END\nEND\n",
              {2, 3, "ON_ABORT belongs at the top level, outside blocks"});
  ExpectError("IF tilt > 1\n  TARGET a = (1, 1)\nEND\nSTOP\n",
              {2, 3, "TARGET definitions belong at the top level, outside blocks"});
}

TEST(ParserErrors, UnboundedLoopsAndWaits) {
  ExpectError("WHILE tilt < 5\n  STOP\nEND\n",
              {1, 1, "unbounded loop: WHILE needs MAX n (the most times the body runs)"});
  ExpectError("REPEAT\n  STOP\nEND\n", {1, 1, "unbounded loop: REPEAT needs a count (REPEAT n)"});
  ExpectError("REPEAT 0\n  STOP\nEND\n", {1, 8, "REPEAT count = 0 is outside [1, 10000]"});
  ExpectError("WHILE tilt < 5 MAX 1e6\n  STOP\nEND\n", {1, 20, "MAX = 1000000 is outside [1, 10000]"});
  ExpectError("WAIT UNTIL tilt < 5\n",
              {1, 1, "unbounded wait: WAIT UNTIL needs TIMEOUT <duration>"});
  ExpectError("WAIT UNTIL tilt < 5 TIMEOUT 0 s\n", {1, 29, "TIMEOUT = 0 s is outside (0, 86400]"});
  ExpectError("WAIT\n",
              {1, 1, "WAIT needs a duration (WAIT 5 s) or UNTIL <condition> TIMEOUT <duration>"});
}

TEST(ParserErrors, Conditions) {
  ExpectError("IF tlit > 5\n  STOP\nEND\n", {1, 4, "unknown quantity 'tlit' (did you mean 'tilt'?)"});
  ExpectError("IF last.fault = NOPATH\n  STOP\nEND\n", {1, 15, "use '==' to compare, not '='"});
  ExpectError("IF last.fault == NOPROGRES\n  STOP\nEND\n",
              {1, 18, "unknown value 'NOPROGRES' for last.fault (did you mean 'NOPROGRESS'?)"});
  ExpectError("IF last.termination == GOOD\n  STOP\nEND\n",
              {1, 24, "unknown value 'GOOD' for last.termination (one of NONE, NOMINAL, FAULT, "
                      "REJECTED)"});
  ExpectError("IF last.class < GOAL_ERROR\n  STOP\nEND\n",
              {1, 15, "last.class can only be compared with == or !="});
  ExpectError("IF (tilt > 5\n  STOP\nEND\n",
              {1, 13, "expected ')' to close the '(' at column 4, got end of line"});
  ExpectError("IF tilt 5\n  STOP\nEND\n",
              {1, 9, "expected a comparison (==, !=, <, <=, >, >=) after tilt, got '5'"});
  ExpectError("IF distance_to(rock) > 1\n  STOP\nEND\n", {1, 16, "unknown target 'rock'"});
  ExpectError("IF distance_to > 1\n  STOP\nEND\n",
              {1, 16, "distance_to needs a target: distance_to(name) or distance_to((x, y))"});
  ExpectError("IF\n  STOP\nEND\n", {1, 3, "expected a condition, got end of line"});
  ExpectError("IF tilt > 5 deg STOP\n  STOP\nEND\n",
              {1, 17, "unexpected 'STOP' after the IF condition"});
  ExpectError("IF tilt > 5 m\n  STOP\nEND\n",
              {1, 13, "unit 'm' is a length; tilt takes an angle (deg, rad)"});
}

TEST(ParserErrors, BadCharactersEmptyTextsAndOverrides) {
  // A character the language does not use is reported once, wherever the parser meets it.
  ExpectError("TURN angle_deg=90;\n", {1, 18, "unexpected character ';'"});
  ExpectError(";STOP\n", {1, 1, "unexpected character ';'"});
  ExpectError("IF tilt > 5 ;\n  STOP\nEND\n", {1, 13, "unexpected character ';'"});
  ExpectError("GOTO (1; 2)\n", {1, 8, "unexpected character ';'"});
  ExpectError("# only a comment\n\n", {1, 1, "the sequence has no statements to run"});
  ExpectError("ON_ABORT\n  STOP\nEND\n", {1, 1, "the sequence has no statements to run"});

  ParseOptions o;
  o.overrides = {{"tagret", "(1, 2, 3)"}};
  auto errors = ErrorsOf("TARGET target = (6, 0, 0)\nGOTO target\n", o);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0].pos, (SourcePos{0, 0}));
  EXPECT_EQ(errors[0].ToString("approach.seq"),
            "approach.seq: override 'tagret' names no TARGET or CONST of the sequence (did you "
            "mean 'target'?)");
  o.overrides = {{"target", "(1, 2"}};
  errors = ErrorsOf("TARGET target = (6, 0, 0)\nGOTO target\n", o);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0].pos, (SourcePos{1, 1}));
  EXPECT_EQ(errors[0].message,
            "override target=(1, 2: expected ',' or ')' in target, got end of line");
  // A use of a name whose definition failed is not reported again.
  errors = ErrorsOf("CONST step = 3 parsecs\nDRIVE STRAIGHT distance=step\nWAIT step\n");
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0].message, "unknown unit 'parsecs'");
  o.overrides = {{"step", "3 s"}};
  errors = ErrorsOf("CONST step = 1 m\nDRIVE STRAIGHT distance=step\n", o);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0].message,
            "constant step: unit 's' is a time; distance takes a length (m, cm, mm, km)");
}

TEST(ParserErrors, EveryErrorIsReportedAndNothingIsReturned) {
  const std::string text =
      "TURN angle_deg=400\n"
      "IF tlit > 5\n"
      "  DRIV STRAIGHT distance=1\n"
      "END\n"
      "WHILE tilt > 1\n"
      "  STOP\n"
      "END\n"
      "END\n";
  ParseOptions options;
  options.source = "bad.seq";
  ParseReport r = ParseSequenceText(text, options);
  EXPECT_FALSE(r.sequence.has_value());
  ASSERT_EQ(r.errors.size(), 5u) << FormatErrors(r, "bad.seq");
  EXPECT_EQ(r.errors[0].ToString("bad.seq"), "bad.seq:1:6: angle_deg = 400 deg is outside [-360, 360]");
  EXPECT_EQ(r.errors[1].pos, (SourcePos{2, 4}));
  EXPECT_EQ(r.errors[2].pos, (SourcePos{3, 3}));
  EXPECT_EQ(r.errors[3].pos, (SourcePos{5, 1}));
  EXPECT_EQ(r.errors[4].pos, (SourcePos{8, 1}));
  EXPECT_EQ(FormatErrors(r, "bad.seq").substr(0, 21), "bad.seq:1:6: angle_de");

  Result<Sequence> s = ParseSequence(text, options);
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(s.status().message(),
            "bad.seq:1:6: angle_deg = 400 deg is outside [-360, 360] (and 4 more errors)");
}

// The bad input, end to end through ParseSequence / ParseSequenceFile: a syntax error
// with its line and column, an unknown command or argument with the nearest valid name, an
// unbounded loop; each yields no Sequence at all, so no command of the text can run, not even
// the valid ones before the error.
TEST(ParserErrors, BadInputYieldsNoSequenceSoNothingRuns) {
  const std::string valid = "VISODOM TURN TO (6, 0)\nDRIVE STRAIGHT distance=30 cm\n";
  struct Case {
    std::string bad_line;
    std::string message;
  };
  const std::vector<Case> cases = {
      {"IF tilt > 5 deg )", "approach.seq:3:17: unexpected ')' after the IF condition"},
      {"VISODOM STRAIT distance=1",
       "approach.seq:3:1: unknown command 'VISODOM STRAIT' (did you mean 'VISODOM STRAIGHT'?)"},
      {"VISODOM STRAIGHT distanse=1",
       "approach.seq:3:18: VISODOM STRAIGHT has no argument 'distanse' (did you mean "
       "'distance'?)"},
      {"WHILE distance_to((6, 0)) > 1.3 m", "approach.seq:3:1: unbounded loop: WHILE needs MAX "
                                            "n (the most times the body runs)"},
  };
  ParseOptions o;
  o.source = "approach.seq";
  for (const Case& c : cases) {
    SCOPED_TRACE(c.bad_line);
    const std::string text = valid + c.bad_line + "\n  STOP\nEND\n";
    ParseReport r = ParseSequenceText(text, o);
    EXPECT_FALSE(r.sequence.has_value());
    Result<Sequence> s = ParseSequence(text, o);
    ASSERT_FALSE(s.ok());
    EXPECT_EQ(s.status().code(), StatusCode::kInvalidArgument);
    EXPECT_EQ(s.status().message().substr(0, c.message.size()), c.message);
  }
}

TEST(ParserErrors, ReportsAtMostMaxErrors) {
  std::string text;
  for (int i = 0; i < 30; ++i) text += "FLY\n";
  ParseOptions o;
  o.max_errors = 5;
  EXPECT_EQ(ParseSequenceText(text, o).errors.size(), 5u);
}

}  // namespace
}  // namespace rover::apl::sequencer
