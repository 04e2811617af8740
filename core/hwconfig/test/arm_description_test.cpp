#include "rover/hwconfig/arm_description.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "rover/hwconfig/rover_description.hpp"

namespace rover::hwconfig {
namespace {

constexpr double kHalfPi = 0.5 * std::numbers::pi;

TEST(ArmDescription, DefaultsAreValidAndStowIsClearAndInsideTheFootprint) {
  const RoverDescription d;
  ASSERT_TRUE(d.arm.Validate().ok()) << d.arm.Validate().ToString();
  ASSERT_TRUE(d.CheckArmPose(d.arm.stow).ok()) << d.CheckArmPose(d.arm.stow).ToString();
  // Stowed, the arm changes nothing for driving: every point of it lies above the belly and
  // inside the footprint the planners use.
  const ArmPoints p = d.arm.Forward(d.arm.stow);
  const Footprint f = d.GroundFootprint();
  for (const Eigen::Vector3d& x : {p.elbow, p.wrist, p.face}) {
    EXPECT_GT(x.z() - d.arm.link_radius, d.BellyClearance()) << x.transpose();
    EXPECT_LE(x.x() + d.arm.link_radius, f.max_x + 1e-9) << x.transpose();
  }
}

TEST(ArmDescription, ForwardKinematicsOfKnownPoses) {
  const ArmDescription a;
  // Straight out ahead, instrument level: the face is the sum of the lengths ahead.
  ArmPoints p = a.Forward({0.0, 0.0, 0.0, 0.0});
  EXPECT_TRUE(p.face.isApprox(a.shoulder + Eigen::Vector3d(a.upper_arm + a.forearm + a.tool_length, 0, 0)));
  EXPECT_TRUE(p.look.isApprox(Eigen::Vector3d::UnitX()));
  // Azimuth 90 deg left, upper arm straight up, forearm and instrument level to the left.
  p = a.Forward({kHalfPi, kHalfPi, -kHalfPi, 0.0});
  EXPECT_TRUE(p.elbow.isApprox(a.shoulder + Eigen::Vector3d(0, 0, a.upper_arm)));
  EXPECT_TRUE(p.face.isApprox(a.shoulder + Eigen::Vector3d(0, a.forearm + a.tool_length, a.upper_arm)));
  // Face down: look is -z whenever shoulder + elbow + wrist = -pi/2.
  p = a.Forward({0.3, 0.2, -1.0, -kHalfPi + 0.8});
  EXPECT_TRUE(p.look.isApprox(-Eigen::Vector3d::UnitZ(), 1e-12));
}

TEST(ArmDescription, FaceDownRoundTripsOverTheWorkspaceAhead) {
  const ArmDescription a;
  int solved = 0;
  for (double x = 0.85; x <= 1.25; x += 0.05) {
    for (double y = -0.3; y <= 0.3; y += 0.1) {
      for (double z = -0.15; z <= 0.35; z += 0.05) {
        const Eigen::Vector3d target(x, y, z);
        const Result<ArmAngles> q = a.FaceDown(target);
        if (!q.ok()) {
          EXPECT_EQ(q.status().code(), StatusCode::kOutOfRange);
          continue;
        }
        ++solved;
        const ArmPoints p = a.Forward(*q);
        EXPECT_LT((p.face - target).norm(), 1e-9) << target.transpose();
        EXPECT_TRUE(p.look.isApprox(-Eigen::Vector3d::UnitZ(), 1e-9));
        EXPECT_GT(p.elbow.z(), p.wrist.z() - 1e-9);  // elbow above the wrist (elbow-up branch)
      }
    }
  }
  EXPECT_GT(solved, 300);  // the standoff region (1.05 m ahead, +-0.3 m) is reachable
}

TEST(ArmDescription, FaceDownRefusalsNameThePoint) {
  const ArmDescription a;
  Result<ArmAngles> q = a.FaceDown({2.0, 0.0, 0.0});
  ASSERT_FALSE(q.ok());
  EXPECT_NE(q.status().message().find("out of reach"), std::string::npos) << q.status().ToString();
  EXPECT_NE(q.status().message().find("(2, 0, 0)"), std::string::npos) << q.status().ToString();
  q = a.FaceDown({a.shoulder.x(), a.shoulder.y(), 0.2});
  ASSERT_FALSE(q.ok());
  EXPECT_NE(q.status().message().find("azimuth axis"), std::string::npos);
  // Behind the shoulder: the azimuth would be beyond its limit.
  q = a.FaceDown({0.3, 0.05, 0.2});
  ASSERT_FALSE(q.ok());
  EXPECT_NE(q.status().message().find("azimuth angle"), std::string::npos) << q.status().ToString();
  q = a.FaceDown({std::nan(""), 0.0, 0.0});
  ASSERT_FALSE(q.ok());
  EXPECT_EQ(q.status().code(), StatusCode::kInvalidArgument);
}

TEST(ArmDescription, ValidateNamesTheField) {
  ArmDescription a;
  a.forearm = -0.1;
  EXPECT_NE(a.Validate().message().find("arm.forearm"), std::string::npos) << a.Validate().ToString();
  a = ArmDescription{};
  a.stow[2] = 5.0;
  EXPECT_NE(a.Validate().message().find("arm.stow"), std::string::npos) << a.Validate().ToString();
  EXPECT_NE(a.Validate().message().find("elbow"), std::string::npos);
  a = ArmDescription{};
  a.min_angle[3] = 1.0;
  a.max_angle[3] = 0.5;
  EXPECT_NE(a.Validate().message().find("arm.wrist.min_angle"), std::string::npos);
}

TEST(ArmDescription, MovesFromStowToThePlacementsAheadAreClear) {
  const RoverDescription d;
  for (const Eigen::Vector3d& target : {Eigen::Vector3d(1.05, 0.0, 0.0), Eigen::Vector3d(1.05, 0.2, 0.1),
                                        Eigen::Vector3d(1.0, -0.2, -0.05), Eigen::Vector3d(1.15, 0.0, 0.3)}) {
    const Result<ArmAngles> q = d.arm.FaceDown(target);
    ASSERT_TRUE(q.ok()) << q.status().ToString();
    EXPECT_TRUE(d.CheckArmMove(d.arm.stow, *q).ok()) << target.transpose() << ": "
                                                     << d.CheckArmMove(d.arm.stow, *q).ToString();
    EXPECT_TRUE(d.CheckArmMove(*q, d.arm.stow).ok());
  }
}

TEST(ArmDescription, PosesIntoTheRoverOrTheGroundAreRefusedByName) {
  const RoverDescription d;
  // The instrument pressed onto the left front wheel's tread from above.
  const Eigen::Vector3d wheel = d.WheelCentre(kWheelLF);
  Result<ArmAngles> q = d.arm.FaceDown(wheel + Eigen::Vector3d(0, 0, d.wheel_radius + 0.02));
  ASSERT_TRUE(q.ok()) << q.status().ToString();
  Status st = d.CheckArmPose(*q);
  ASSERT_FALSE(st.ok());
  EXPECT_EQ(st.code(), StatusCode::kFailedPrecondition);
  EXPECT_NE(st.message().find("wheel_LF"), std::string::npos) << st.ToString();
  EXPECT_NE(st.message().find("instrument"), std::string::npos) << st.ToString();
  // High enough above it, the same spot is fine.
  q = d.arm.FaceDown(wheel + Eigen::Vector3d(0, 0, d.wheel_radius + 0.1));
  ASSERT_TRUE(q.ok());
  EXPECT_TRUE(d.CheckArmPose(*q).ok()) << d.CheckArmPose(*q).ToString();
  // Upper arm and forearm pointing down into the ground.
  st = d.CheckArmPose({0.0, -1.0, -0.5, 0.0});
  ASSERT_FALSE(st.ok());
  EXPECT_NE(st.message().find("ground"), std::string::npos) << st.ToString();
  // A move whose ends are clear but whose middle is not: swinging low across the wheel.
  const ArmAngles low_right = *d.arm.FaceDown({0.95, -0.45, 0.30});
  const ArmAngles low_left = *d.arm.FaceDown({0.95, 0.45, 0.30});
  ASSERT_TRUE(d.CheckArmPose(low_right).ok()) << d.CheckArmPose(low_right).ToString();
  ASSERT_TRUE(d.CheckArmPose(low_left).ok());
  const ArmAngles into_wheel = *d.arm.FaceDown({0.66, 0.45, 0.27});
  st = d.CheckArmMove(low_right, into_wheel);
  ASSERT_FALSE(st.ok());
  EXPECT_NE(st.message().find("% of the way"), std::string::npos) << st.ToString();
  EXPECT_NE(st.message().find("wheel_LF"), std::string::npos) << st.ToString();
}

}  // namespace
}  // namespace rover::hwconfig
