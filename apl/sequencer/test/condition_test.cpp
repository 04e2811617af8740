#include "rover/apl/sequencer/condition.hpp"

#include <gtest/gtest.h>

#include <numbers>

#include "rover/base/units.hpp"
#include "sequencer_test_util.hpp"

namespace rover::apl::sequencer {
namespace {

using MF = msg::MobilityFault;

/// The condition of "IF <text>".
Condition Cond(const std::string& text) {
  Sequence s = testing::MustParse("TARGET rock = (3, 4, 0)\nIF " + text + "\n  STOP\nEND\n");
  return s.statements.empty() ? Condition{} : s.statements[0].condition;
}

TEST(Condition, QuantityNamesAndUnits) {
  EXPECT_EQ(FindQuantity("LAST.Fault"), Quantity::kLastFault);
  EXPECT_EQ(FindQuantity("tilt"), Quantity::kTilt);
  EXPECT_FALSE(FindQuantity("slip").has_value());
  EXPECT_EQ(QuantityNames().size(), 7u);
  EXPECT_TRUE(IsEnumerated(Quantity::kLastClass));
  EXPECT_FALSE(IsEnumerated(Quantity::kDistanceTo));
  EXPECT_EQ(QuantityUnit(Quantity::kDistanceTo), "m");
  EXPECT_EQ(QuantityUnit(Quantity::kTilt), "deg");
  EXPECT_EQ(QuantityUnit(Quantity::kElapsed), "s");
  EXPECT_EQ(QuantityValueNames(Quantity::kLastTermination).size(), 4u);
  EXPECT_STREQ(RelationName(Relation::kGe), ">=");
  EXPECT_STREQ(QuantityName(Quantity::kVisodomFailures), "visodom.failures");
}

TEST(Condition, LastOutcome) {
  ConditionInputs in;
  EXPECT_TRUE(*Evaluate(Cond("last.termination == NONE"), in));
  in.last = Outcome::Failed(Fault(MF::kNoProgress), "stuck");
  EXPECT_TRUE(*Evaluate(Cond("last.termination == FAULT"), in));
  EXPECT_FALSE(*Evaluate(Cond("last.termination == NOMINAL"), in));
  EXPECT_TRUE(*Evaluate(Cond("last.fault == NOPROGRESS"), in));
  EXPECT_TRUE(*Evaluate(Cond("last.fault != NOPATH"), in));
  EXPECT_TRUE(*Evaluate(Cond("last.class == GOAL_ERROR"), in));
  // A class left NONE by the service is the fault's Table 1 class.
  in.last = Outcome{Termination::kFault, Fault(MF::kSuspension), msg::FaultClass::kNone, "", {}};
  EXPECT_TRUE(*Evaluate(Cond("last.class == MOTION_ERROR"), in));
}

TEST(Condition, PoseQuantitiesNeedThePose) {
  ConditionInputs in;
  const Condition near = Cond("distance_to(rock) > 1.3");
  EXPECT_TRUE(NeedsPose(near));
  EXPECT_FALSE(Evaluate(near, in).has_value());
  PoseSample pose;
  in.pose = &pose;
  EXPECT_TRUE(*Evaluate(near, in));  // 5 m from the origin
  pose.position = {3.0, 2.8, 0.0};
  EXPECT_FALSE(*Evaluate(near, in));  // 1.2 m
  EXPECT_TRUE(*Evaluate(Cond("distance_to((3, 2)) <= 80 cm"), in));
  pose.pitch = 16 * kDegree;
  EXPECT_TRUE(*Evaluate(Cond("tilt > 15"), in));
  EXPECT_FALSE(*Evaluate(Cond("tilt > 0.3 rad"), in));
  EXPECT_FALSE(NeedsPose(Cond("elapsed > 5")));
  EXPECT_TRUE(NeedsPose(Cond("elapsed > 5 OR NOT tilt < 3")));
}

TEST(Condition, CountsAndTime) {
  ConditionInputs in;
  in.visodom_failures = 3;
  in.elapsed_s = 600.0;
  EXPECT_TRUE(*Evaluate(Cond("visodom.failures >= 3"), in));
  EXPECT_FALSE(*Evaluate(Cond("visodom.failures < 3"), in));
  EXPECT_TRUE(*Evaluate(Cond("visodom.failures == 3"), in));
  EXPECT_TRUE(*Evaluate(Cond("elapsed == 10 min"), in));
  EXPECT_FALSE(*Evaluate(Cond("elapsed != 600"), in));
}

TEST(Condition, LogicAndUnknownOperands) {
  ConditionInputs in;
  in.visodom_failures = 1;
  EXPECT_TRUE(*Evaluate(Cond("visodom.failures == 1 AND NOT elapsed > 1"), in));
  EXPECT_FALSE(*Evaluate(Cond("visodom.failures == 2 AND elapsed < 1"), in));
  EXPECT_TRUE(*Evaluate(Cond("visodom.failures == 2 OR elapsed < 1"), in));
  EXPECT_TRUE(*Evaluate(Cond("(visodom.failures == 2 OR elapsed < 1) AND last.fault == NONE"), in));
  // Without a pose the value is unknown even when the other operand would decide it.
  EXPECT_FALSE(Evaluate(Cond("visodom.failures == 1 OR tilt > 5"), in).has_value());
  EXPECT_FALSE(Evaluate(Cond("NOT tilt > 5"), in).has_value());
}

}  // namespace
}  // namespace rover::apl::sequencer
