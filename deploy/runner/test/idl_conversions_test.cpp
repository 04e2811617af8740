#include "src/idl_conversions.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace rover::deploy::runner {
namespace {

TEST(IdlConversions, PoseBecomesANormalisedIsometry) {
  rover_Pose3 p{};
  p.position = {1, 2, 3};
  // 90 deg about z, scaled by 2: normalised on the way.
  p.orientation = {2 * std::cos(M_PI / 4), 0, 0, 2 * std::sin(M_PI / 4)};  // w, x, y, z
  const Eigen::Isometry3d t = ToIsometry(p);
  EXPECT_TRUE(t.translation().isApprox(Eigen::Vector3d(1, 2, 3)));
  EXPECT_TRUE((t.linear() * Eigen::Vector3d::UnitX()).isApprox(Eigen::Vector3d::UnitY(), 1e-12));
  EXPECT_NEAR(t.linear().determinant(), 1.0, 1e-12);
}

TEST(IdlConversions, PrimitivesAndTerminations) {
  EXPECT_EQ(ToIdl(Primitive::kStraight), rover_dl_PRIMITIVE_STRAIGHT);
  EXPECT_EQ(ToIdl(Primitive::kArc), rover_dl_PRIMITIVE_ARC);
  EXPECT_EQ(ToIdl(Primitive::kTurnInPlace), rover_dl_PRIMITIVE_TURN_IN_PLACE);
  EXPECT_EQ(ToIdl(Primitive::kSteer), rover_dl_PRIMITIVE_STEER);
  EXPECT_EQ(ToIdl(Primitive::kStop), rover_dl_PRIMITIVE_STOP);
  EXPECT_STREQ(TerminationName(rover_dl_TERMINATION_NOMINAL), "nominal");
  EXPECT_STREQ(TerminationName(rover_dl_TERMINATION_MOTOR_STALL), "motor_stall");
  EXPECT_STREQ(TerminationName(rover_dl_TERMINATION_STALE_SENSOR), "stale_sensor");
  EXPECT_STREQ(TerminationName(static_cast<rover_dl_DriveTermination>(99)), "?");
}

}  // namespace
}  // namespace rover::deploy::runner
