// The grammar: every construct of the language parses into the tree it should.
#include "rover/apl/sequencer/parser.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "rover/apl/sequencer/commands.hpp"
#include "sequencer_test_util.hpp"

namespace rover::apl::sequencer {
namespace {

using MF = msg::MobilityFault;

using testing::CallOf;
using testing::MustParse;
using Kind = Statement::Kind;

TEST(Parser, CommandWithNamedArgumentsDefaultsAndText) {
  const CommandCall c = CallOf("DRIVE ARC curvature=0.5 distance=1.0  # a comment");
  EXPECT_EQ(c.kind, CommandKind::kDriveArc);
  EXPECT_EQ(c.text, "DRIVE ARC curvature=0.5 distance=1.0");
  EXPECT_EQ(c.pos, (SourcePos{1, 1}));
  EXPECT_DOUBLE_EQ(c.Get("curvature").number, 0.5);
  EXPECT_TRUE(c.Get("curvature").given);
  EXPECT_EQ(c.Get("distance").pos, (SourcePos{1, 25}));
  // Optional arguments absent from the text get the table's defaults.
  EXPECT_DOUBLE_EQ(c.Get("speed").number, 0.0);
  EXPECT_FALSE(c.Get("speed").given);
  EXPECT_EQ(c.Get("on_fault").word, "ABORT");
  EXPECT_FALSE(c.continue_on_goal_error);
}

TEST(Parser, KeywordsCommandsAndArgumentNamesAreCaseInsensitive) {
  const CommandCall c = CallOf("visodom Straight DISTANCE=0.3 On_Fault=continue");
  EXPECT_EQ(c.kind, CommandKind::kVisodomStraight);
  EXPECT_DOUBLE_EQ(c.Get("distance").number, 0.3);
  EXPECT_TRUE(c.continue_on_goal_error);
}

TEST(Parser, UnitsConvertToTheArgumentsUnit) {
  EXPECT_DOUBLE_EQ(CallOf("DRIVE STRAIGHT distance=30 cm").Get("distance").number, 0.3);
  EXPECT_DOUBLE_EQ(CallOf("DRIVE STRAIGHT distance=30cm").Get("distance").number, 0.3);
  EXPECT_DOUBLE_EQ(CallOf("DRIVE STRAIGHT distance=-250 mm").Get("distance").number, -0.25);
  EXPECT_NEAR(CallOf("TURN angle_deg=0.5 rad").Get("angle_deg").number, 28.6478897565, 1e-9);
  EXPECT_DOUBLE_EQ(CallOf("GOTO (1, 2) timeout=2 min").Get("timeout").number, 120.0);
  EXPECT_DOUBLE_EQ(CallOf("DRIVE STRAIGHT distance=1 speed=5 cm/s").Get("speed").number, 0.05);
  EXPECT_DOUBLE_EQ(CallOf("TURN angle_deg=90 timeout=30 s").Get("timeout").number, 30.0);
}

TEST(Parser, PositionalValuesAndPointsLiteralOrNamed) {
  Sequence s = MustParse(
      "TARGET rock1 = (5, 2, -0.25)\n"
      "TARGET flat = (1, 1)\n"
      "GOTO rock1\n"
      "AUTONAV goal=(5,2) tolerance=0.3\n"
      "MAST LOOK_AT rock1\n"
      "MAST LOOK_AT point=(1, 2, 3 cm)\n"
      "TURN TO flat\n"
      "ARM MOVE (0, 10, 20, 30)\n");
  EXPECT_EQ(s.targets.at("rock1"), (Vec3{5, 2, -0.25}));
  EXPECT_EQ(s.targets.at("flat"), (Vec3{1, 1, 0}));
  ASSERT_EQ(s.statements.size(), 6u);
  EXPECT_EQ(s.statements[0].command.Get("goal").numbers, (std::vector<double>{5, 2}));
  EXPECT_EQ(s.statements[0].command.Get("goal").name, "rock1");
  EXPECT_EQ(s.statements[1].command.Get("goal").numbers, (std::vector<double>{5, 2}));
  EXPECT_EQ(s.statements[2].command.Get("point").numbers, (std::vector<double>{5, 2, -0.25}));
  EXPECT_EQ(s.statements[3].command.Get("point").numbers, (std::vector<double>{1, 2, 0.03}));
  EXPECT_EQ(s.statements[4].command.kind, CommandKind::kTurnTo);
  EXPECT_EQ(s.statements[4].command.Get("target").name, "flat");
  EXPECT_EQ(s.statements[5].command.Get("joints_deg").numbers,
            (std::vector<double>{0, 10, 20, 30}));
}

TEST(Parser, EveryFamilyAndTheLongestCommandName) {
  Sequence s = MustParse(
      "VISODOM TURN TO heading_deg=45\n"
      "VISODOM TURN angle_deg=10\n"
      "TURN angle_deg=10\n"
      "GUARDED ARC curvature=0.5 distance=2\n"
      "GUARDED VISODOM goal=(3, 0)\n"
      "LONG_TRAVERSE goal=(80, 10) timeout=2 h\n"
      "RETURN_TO_LANDER (0, 0, 0) standoff=1.5\n"
      "APPROACH_TARGET image=3 pixel=(512, 384) standoff=1.05\n"
      "APPROACH_TARGET point=(6, 0, 0)\n"
      "ARM UNSTOW\nARM PLACE (1, 0, -0.4)\nAUTOFOCUS (1, 0, -0.4) steps=12 step=4 mm\nARM STOW\n"
      "CLEAR_FAULT\nSTOP\n");
  std::vector<CommandKind> kinds;
  for (const auto& st : s.statements) kinds.push_back(st.command.kind);
  using K = CommandKind;
  EXPECT_EQ(kinds, (std::vector<K>{K::kVisodomTurnTo, K::kVisodomTurn, K::kTurn, K::kGuardedArc,
                                   K::kGuardedVisodom, K::kLongTraverse, K::kReturnToLander,
                                   K::kApproachTarget, K::kApproachTarget, K::kArmUnstow,
                                   K::kArmPlace, K::kAutofocus, K::kArmStow, K::kClearFault,
                                   K::kStop}));
  EXPECT_DOUBLE_EQ(s.statements[5].command.Get("timeout").number, 7200.0);
  EXPECT_DOUBLE_EQ(s.statements[11].command.Get("step").number, 0.004);
  EXPECT_DOUBLE_EQ(s.statements[11].command.Get("steps").number, 12.0);
  EXPECT_FALSE(s.statements[8].command.Has("image"));
}

TEST(Parser, ConstantsKeepTheirUnitAndConvertWhereUsed) {
  Sequence s = MustParse(
      "CONST step = 30 cm\nCONST n = 3\nCONST wait = 2 min\nCONST copy = step\n"
      "REPEAT n\n  DRIVE STRAIGHT distance=step\nEND\nWAIT wait\n"
      "IF distance_to((1, 1)) > copy\n  STOP\nEND\n");
  EXPECT_DOUBLE_EQ(s.constants.at("step").value, 30.0);
  EXPECT_EQ(s.constants.at("step").unit, "cm");
  EXPECT_EQ(s.constants.at("n").unit, "");
  ASSERT_EQ(s.statements.size(), 3u);
  EXPECT_EQ(s.statements[0].count, 3);
  EXPECT_DOUBLE_EQ(s.statements[0].body[0].command.Get("distance").number, 0.3);
  EXPECT_EQ(s.statements[0].body[0].command.Get("distance").name, "step");
  EXPECT_DOUBLE_EQ(s.statements[1].seconds, 120.0);
  EXPECT_DOUBLE_EQ(s.statements[2].condition.compare.number, 0.3);
}

// TARGET, CONST and WAIT are keywords only at the start of a statement and command words only
// in the command name, so they may name targets and constants (the shipped template's
// `target`); names stay case-sensitive.
TEST(Parser, NamesMaySpellStatementKeywordsAndCommandWords) {
  Sequence s = MustParse(
      "TARGET target = (6, 0, 0)\nTARGET Target = (1, 1)\nCONST wait = 2 s\nCONST const = 1.3 m\n"
      "CONST stop = 3\n"
      "VISODOM TURN TO target\nTURN TO target=Target\nWAIT wait\nREPEAT stop\n  STOP\nEND\n"
      "WHILE distance_to(target) > const MAX stop\n  VISODOM STRAIGHT distance=const\nEND\n");
  EXPECT_EQ(s.targets.at("target"), (Vec3{6, 0, 0}));
  EXPECT_EQ(s.targets.at("Target"), (Vec3{1, 1, 0}));
  ASSERT_EQ(s.statements.size(), 5u);
  EXPECT_EQ(s.statements[0].command.kind, CommandKind::kVisodomTurnTo);
  EXPECT_EQ(s.statements[0].command.Get("target").name, "target");
  EXPECT_EQ(s.statements[1].command.Get("target").numbers, (std::vector<double>{1, 1}));
  EXPECT_DOUBLE_EQ(s.statements[2].seconds, 2.0);
  EXPECT_EQ(s.statements[3].count, 3);
  EXPECT_EQ(s.statements[4].count, 3);
  EXPECT_DOUBLE_EQ(s.statements[4].condition.compare.number, 1.3);
  EXPECT_DOUBLE_EQ(s.statements[4].body[0].command.Get("distance").number, 1.3);
}

TEST(Parser, Waits) {
  Sequence s = MustParse(
      "WAIT 5 s\nWAIT 5\nWAIT 250 ms\nWAIT 0\n"
      "WAIT UNTIL visodom.failures >= 2 TIMEOUT 1 min\n");
  ASSERT_EQ(s.statements.size(), 5u);
  EXPECT_EQ(s.statements[0].kind, Kind::kWait);
  EXPECT_DOUBLE_EQ(s.statements[0].seconds, 5.0);
  EXPECT_DOUBLE_EQ(s.statements[1].seconds, 5.0);
  EXPECT_DOUBLE_EQ(s.statements[2].seconds, 0.25);
  EXPECT_DOUBLE_EQ(s.statements[3].seconds, 0.0);
  EXPECT_EQ(s.statements[4].kind, Kind::kWaitUntil);
  EXPECT_DOUBLE_EQ(s.statements[4].seconds, 60.0);
  EXPECT_EQ(s.statements[4].condition.compare.quantity, Quantity::kVisodomFailures);
  EXPECT_EQ(s.statements[4].condition.compare.relation, Relation::kGe);
  EXPECT_DOUBLE_EQ(s.statements[4].condition.compare.number, 2.0);
}

TEST(Parser, IfElseIfElseEnd) {
  Sequence s = MustParse(
      "DRIVE STRAIGHT distance=1 on_fault=CONTINUE\n"
      "IF last.termination == NOMINAL\n"
      "  TURN angle_deg=90\n"
      "ELSE IF last.fault == NOPROGRESS\n"
      "  DRIVE STRAIGHT distance=-0.5\n"
      "  AUTONAV goal=(5, 0)\n"
      "ELSE\n"
      "  STOP\n"
      "END\n"
      "IF last.class != MOTION_ERROR\n"
      "  STOP\n"
      "END\n");
  ASSERT_EQ(s.statements.size(), 3u);
  const Statement& top = s.statements[1];
  EXPECT_EQ(top.kind, Kind::kIf);
  EXPECT_EQ(top.text, "IF last.termination == NOMINAL");
  EXPECT_EQ(top.condition.compare.quantity, Quantity::kLastTermination);
  EXPECT_EQ(top.condition.compare.enum_value, static_cast<int>(Termination::kNominal));
  ASSERT_EQ(top.body.size(), 1u);
  ASSERT_EQ(top.else_body.size(), 1u);
  const Statement& elif = top.else_body[0];
  EXPECT_EQ(elif.kind, Kind::kIf);
  EXPECT_EQ(elif.pos, (SourcePos{4, 6}));
  EXPECT_EQ(elif.condition.compare.enum_value, Fault(MF::kNoProgress).Index());
  EXPECT_EQ(elif.body.size(), 2u);
  ASSERT_EQ(elif.else_body.size(), 1u);
  EXPECT_EQ(elif.else_body[0].command.kind, CommandKind::kStop);
  EXPECT_TRUE(s.statements[2].else_body.empty());
  EXPECT_EQ(s.statements[2].condition.compare.relation, Relation::kNe);
}

TEST(Parser, BoundedLoopsNest) {
  Sequence s = MustParse(
      "TARGET t = (4, 0, 0)\n"
      "REPEAT 3\n"
      "  WHILE distance_to(t) > 1.3 m MAX 40\n"
      "    VISODOM STRAIGHT distance=0.3\n"
      "  END\n"
      "END\n");
  ASSERT_EQ(s.statements.size(), 1u);
  EXPECT_EQ(s.statements[0].kind, Kind::kRepeat);
  EXPECT_EQ(s.statements[0].count, 3);
  const Statement& w = s.statements[0].body[0];
  EXPECT_EQ(w.kind, Kind::kWhile);
  EXPECT_EQ(w.count, 40);
  EXPECT_EQ(w.condition.compare.quantity, Quantity::kDistanceTo);
  EXPECT_EQ(w.condition.compare.name, "t");
  EXPECT_EQ(w.condition.compare.point, (Vec3{4, 0, 0}));
  EXPECT_DOUBLE_EQ(w.condition.compare.number, 1.3);
  EXPECT_EQ(w.condition.text, "distance_to(t) > 1.3 m");
  EXPECT_EQ(w.body[0].command.kind, CommandKind::kVisodomStraight);
}

TEST(Parser, AbortBlockIsKeptApartFromTheStatements) {
  Sequence s = MustParse("ON_ABORT\n  STOP\n  MAST pan_deg=0 tilt_deg=0\nEND\nTURN angle_deg=5\n");
  ASSERT_EQ(s.on_abort.size(), 2u);
  EXPECT_EQ(s.on_abort[1].command.kind, CommandKind::kMast);
  ASSERT_EQ(s.statements.size(), 1u);
  EXPECT_EQ(s.statements[0].command.kind, CommandKind::kTurn);
}

TEST(Parser, ConditionsBindNotThenAndThenOr) {
  Sequence s = MustParse(
      "IF tilt > 15 OR NOT visodom.failures < 3 AND elapsed >= 10 min\n  STOP\nEND\n"
      "IF (tilt > 15 OR visodom.failures >= 3) AND last.fault == NONE\n  STOP\nEND\n");
  const Condition& a = s.statements[0].condition;
  ASSERT_EQ(a.op, Condition::Op::kOr);
  ASSERT_EQ(a.operands.size(), 2u);
  EXPECT_EQ(a.operands[0].compare.quantity, Quantity::kTilt);
  const Condition& conj = a.operands[1];
  ASSERT_EQ(conj.op, Condition::Op::kAnd);
  EXPECT_EQ(conj.operands[0].op, Condition::Op::kNot);
  EXPECT_EQ(conj.operands[0].operands[0].compare.quantity, Quantity::kVisodomFailures);
  EXPECT_DOUBLE_EQ(conj.operands[1].compare.number, 600.0);
  const Condition& b = s.statements[1].condition;
  ASSERT_EQ(b.op, Condition::Op::kAnd);
  EXPECT_EQ(b.operands[0].op, Condition::Op::kOr);
  EXPECT_EQ(b.operands[1].compare.quantity, Quantity::kLastFault);
}

TEST(Parser, ComparisonsConvertUnitsToTheQuantitys) {
  Sequence s = MustParse(
      "IF distance_to((3, 4, 1)) <= 110 cm\n STOP\nEND\nIF tilt < 0.2 rad\n STOP\nEND\n"
      "IF elapsed != 1 h\n STOP\nEND\n");
  EXPECT_DOUBLE_EQ(s.statements[0].condition.compare.number, 1.1);
  EXPECT_EQ(s.statements[0].condition.compare.point, (Vec3{3, 4, 1}));
  EXPECT_NEAR(s.statements[1].condition.compare.number, 11.459155902616464, 1e-9);
  EXPECT_DOUBLE_EQ(s.statements[2].condition.compare.number, 3600.0);
}

TEST(Parser, StepsAreNumberedInWritingOrder) {
  Sequence s = MustParse(
      "# header comment\n\n"
      "ON_ABORT\n  STOP\nEND\n"
      "REPEAT 2\n  TURN angle_deg=1\n  WAIT 1 s\nEND\n"
      "STOP   # trailing\n");
  ASSERT_EQ(s.steps.size(), 4u);
  EXPECT_EQ(s.on_abort[0].step, 1);
  EXPECT_EQ(s.statements[0].body[0].step, 2);
  EXPECT_EQ(s.statements[0].body[1].step, 3);
  EXPECT_EQ(s.statements[1].step, 4);
  EXPECT_EQ(s.steps[3].line, 10);
  EXPECT_EQ(s.steps[3].text, "STOP");
  EXPECT_EQ(s.steps[1].text, "TURN angle_deg=1");
}

TEST(Parser, OverridesReplaceDefinitions) {
  ParseOptions o;
  o.overrides = {{"target", "(2, -1, 0.5)"}, {"step", "10 cm"}};
  Sequence s = MustParse("TARGET target = (6, 0, 0)\nCONST step = 0.3 m\n"
                         "DRIVE STRAIGHT distance=step\nGOTO target\n",
                         o);
  EXPECT_EQ(s.targets.at("target"), (Vec3{2, -1, 0.5}));
  EXPECT_DOUBLE_EQ(s.statements[0].command.Get("distance").number, 0.1);
  EXPECT_EQ(s.statements[1].command.Get("goal").numbers, (std::vector<double>{2, -1}));
}

TEST(Parser, ParseSequenceAndFile) {
  Result<Sequence> ok = ParseSequence("STOP\n");
  ASSERT_TRUE(ok.ok());
  EXPECT_EQ(ok->source, "sequence");
  const std::string path = std::string(ROVER_SOURCE_DIR) + "/deploy/sequences/approach_template.seq";
  Result<Sequence> file = ParseSequenceFile(path);
  ASSERT_TRUE(file.ok()) << file.status().ToString();
  EXPECT_EQ(file->source, path);
  Result<Sequence> missing = ParseSequenceFile("/nonexistent/x.seq");
  ASSERT_FALSE(missing.ok());
  EXPECT_EQ(missing.status().code(), StatusCode::kNotFound);
  EXPECT_EQ(missing.status().message(), "cannot read sequence file '/nonexistent/x.seq'");
}

TEST(Parser, NoTrailingNewlineAndCarriageReturnsAreFine) {
  Sequence s = MustParse("TURN angle_deg=90\r\nSTOP");
  EXPECT_EQ(s.statements.size(), 2u);
  EXPECT_EQ(s.statements[0].text, "TURN angle_deg=90");
}

}  // namespace
}  // namespace rover::apl::sequencer
