#include "rover/hwconfig/rover_description.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "rover/base/param_binder.hpp"

namespace rover::hwconfig {
namespace {

TEST(RoverDescription, DefaultsAreValidAndMerLike) {
  const RoverDescription d;
  ASSERT_TRUE(d.Validate().ok()) << d.Validate().ToString();
  EXPECT_DOUBLE_EQ(d.wheel_radius, 0.125);   // MER: 25 cm wheels
  EXPECT_DOUBLE_EQ(d.Wheelbase(), 1.25);     // 1.25 m front to back
  EXPECT_DOUBLE_EQ(d.Track(), 1.0);          // 1 m side to side
  EXPECT_DOUBLE_EQ(d.min_turn_radius, 1.0);  // 1 m tightest arc
  EXPECT_NEAR(d.BellyClearance(), 0.35, 1e-12);
  EXPECT_NEAR(d.mast.HeadPose(0, 0).translation().z(), 1.5, 1e-12);  // head 1.5 m up
  EXPECT_NEAR(d.front_hazcam.position.z(), 0.5, 1e-12);
  EXPECT_DOUBLE_EQ(d.front_hazcam.depression, 45 * kDegree);
  EXPECT_DOUBLE_EQ(d.max_steer_angle, 70 * kDegree);
  // Equal static wheel loads: the rocker pivot splits front wheel : bogie pivot 2 : 1 and the
  // bogie pivot sits midway between the middle and rear wheels.
  EXPECT_NEAR(d.front_wheel_x - d.rocker_pivot_x, 2 * (d.rocker_pivot_x - d.bogie_pivot_x), 1e-12);
  EXPECT_NEAR(d.bogie_pivot_x, 0.5 * (d.middle_wheel_x + d.rear_wheel_x), 1e-12);
}

TEST(RoverDescription, IndicesFollowTheHwOrder) {
  EXPECT_EQ(kSteeredWheel[0], kWheelLF);
  EXPECT_EQ(kSteeredWheel[3], kWheelRR);
  for (int j = 0; j < kNumSteered; ++j) {
    EXPECT_EQ(SteeredWheelOfMotor(SteerMotor(j)), kSteeredWheel[static_cast<std::size_t>(j)]);
  }
  EXPECT_EQ(SteerMotor(0), hw::kSteerLF);
  EXPECT_EQ(SteerMotor(3), hw::kSteerRR);
  EXPECT_EQ(SteeredWheelOfMotor(hw::kDriveLM), -1);
  EXPECT_EQ(SteeredWheelOfMotor(hw::kMastPan), -1);
  EXPECT_EQ(SideOfWheel(kWheelLR), kLeft);
  EXPECT_EQ(SideOfWheel(kWheelRF), kRight);
  EXPECT_STREQ(WheelName(kWheelRM), "RM");
  EXPECT_STREQ(WheelName(6), "?");
  for (int m = 0; m < hw::kNumMotors; ++m) {
    const bool drive = m <= hw::kDriveRR;
    const bool steer = m >= hw::kSteerLF && m <= hw::kSteerRR;
    EXPECT_EQ((kDriveMotorMask >> m) & 1, drive ? 1 : 0) << m;
    EXPECT_EQ((kSteerMotorMask >> m) & 1, steer ? 1 : 0) << m;
  }
}

TEST(RoverDescription, DerivedPointsAreMirrorSymmetric) {
  const RoverDescription d;
  for (int w = 0; w < 3; ++w) {
    const Eigen::Vector3d l = d.WheelCentre(w);
    const Eigen::Vector3d r = d.WheelCentre(w + 3);
    EXPECT_DOUBLE_EQ(l.x(), r.x());
    EXPECT_DOUBLE_EQ(l.y(), -r.y());
    EXPECT_DOUBLE_EQ(l.z(), d.wheel_radius);  // on the ground plane
  }
  EXPECT_DOUBLE_EQ(d.WheelCentre(kWheelLF).x(), 0.625);
  EXPECT_DOUBLE_EQ(d.WheelCentre(kWheelRR).y(), -0.5);
  EXPECT_TRUE(d.RockerPivot(kRight).isApprox(Eigen::Vector3d(0.0, -0.42, 0.45)));
  EXPECT_TRUE(d.BogiePivot(kLeft).isApprox(Eigen::Vector3d(-0.3125, 0.5, 0.30)));
}

TEST(RoverDescription, FootprintAndTurnCircle) {
  const RoverDescription d;
  const Footprint f = d.GroundFootprint();
  // Wheels reach 0.625 + 0.125 fore and aft, 0.5 + 0.08 to the sides; the body is inside.
  EXPECT_DOUBLE_EQ(f.max_x, 0.75);
  EXPECT_DOUBLE_EQ(f.min_x, -0.75);
  EXPECT_DOUBLE_EQ(f.max_y, 0.58);
  EXPECT_DOUBLE_EQ(f.min_y, -0.58);
  EXPECT_TRUE(f.Contains(0.0, 0.0));
  EXPECT_FALSE(f.Contains(0.8, 0.0));
  const TurnCircle c = d.TurnInPlaceCircle();
  EXPECT_TRUE(c.centre.isApprox(Eigen::Vector2d(0.0, 0.0)));
  // Corner wheel centre 0.8004 m out, plus its steering reach hypot(0.125, 0.08).
  EXPECT_NEAR(c.radius, std::hypot(0.625, 0.5) + std::hypot(0.125, 0.08), 1e-12);
  EXPECT_NEAR(c.Diameter(), 1.90, 0.005);
  // Every footprint corner lies in the circle.
  for (double x : {f.min_x, f.max_x}) {
    for (double y : {f.min_y, f.max_y}) {
      EXPECT_LE((Eigen::Vector2d(x, y) - c.centre).norm(), c.radius + 1e-12);
    }
  }
  // A longer body sticking out in front sets both.
  RoverDescription long_body;
  long_body.body_size.x() = 2.0;
  long_body.body_centre.x() = 0.3;
  EXPECT_DOUBLE_EQ(long_body.GroundFootprint().max_x, 1.3);
  EXPECT_NEAR(long_body.TurnInPlaceCircle().radius, std::hypot(1.3, 0.35), 1e-12);
  // The turn centre follows the middle axle.
  RoverDescription shifted;
  shifted.middle_wheel_x = 0.1;
  EXPECT_TRUE(shifted.TurnInPlaceCircle().centre.isApprox(Eigen::Vector2d(0.1, 0.0)));
}

TEST(RoverDescription, ContactParts) {
  const RoverDescription d;
  const std::vector<ContactPart> parts = d.ContactParts();
  ASSERT_EQ(parts.size(), 11u);
  const double reach = std::hypot(0.125, 0.08);
  for (int w = 0; w < kNumWheels; ++w) {
    const ContactPart& p = parts[static_cast<std::size_t>(w)];
    EXPECT_TRUE(p.is_disc) << p.name;
    EXPECT_TRUE(p.centre.isApprox(d.WheelCentre(w).head<2>())) << p.name;
    EXPECT_DOUBLE_EQ(p.radius, reach);
    EXPECT_EQ(p.clearance, 0.0);
  }
  EXPECT_EQ(parts[0].name, "wheel_lf");
  EXPECT_EQ(parts[6].name, "bogie_l");
  EXPECT_EQ(parts[6].clearance, 0.0);
  EXPECT_TRUE(parts[6].min.isApprox(Eigen::Vector2d(-0.625, 0.42)));
  EXPECT_TRUE(parts[6].max.isApprox(Eigen::Vector2d(0.0, 0.58)));
  // Rocker: pivot (0, 0.45) to the front steering joint (0.625, 0.295), left at x = 0.625 - reach.
  EXPECT_EQ(parts[7].name, "rocker_l");
  EXPECT_NEAR(parts[7].clearance, 0.45 + (0.625 - reach) / 0.625 * (0.295 - 0.45), 1e-12);
  EXPECT_EQ(parts[9].name, "rocker_r");
  EXPECT_TRUE(parts[9].min.isApprox(Eigen::Vector2d(0.0, -0.58)));
  const ContactPart& body = parts.back();
  EXPECT_EQ(body.name, "body");
  EXPECT_DOUBLE_EQ(body.clearance, d.BellyClearance());
  EXPECT_TRUE(body.min.isApprox(Eigen::Vector2d(-0.5, -0.35)));
  // Distances: inside is 0, outside the Euclidean distance to the outline.
  EXPECT_EQ(body.DistanceTo({0.2, 0.1}), 0.0);
  EXPECT_NEAR(body.DistanceTo({0.8, 0.75}), 0.5, 1e-12);
  EXPECT_NEAR(parts[0].DistanceTo({0.625 + reach + 0.1, 0.5}), 0.1, 1e-12);
  // Every part lies inside the ground footprint.
  const Footprint f = d.GroundFootprint();
  for (const ContactPart& p : parts) {
    const Eigen::Vector2d lo = p.is_disc ? p.centre : p.min, hi = p.is_disc ? p.centre : p.max;
    EXPECT_TRUE(f.Contains(lo.x(), lo.y()) && f.Contains(hi.x(), hi.y())) << p.name;
  }
}

TEST(RoverDescription, CameraMountsAndMast) {
  const RoverDescription d;
  // Front HAZCAM: boresight forward and 45 deg down; left camera on the left.
  const Eigen::Isometry3d front = d.front_hazcam.Pose();
  EXPECT_TRUE(front.linear().col(0).isApprox(Eigen::Vector3d(std::sqrt(0.5), 0, -std::sqrt(0.5))));
  EXPECT_TRUE(d.front_hazcam.CameraCentre(kLeft).isApprox(Eigen::Vector3d(0.52, 0.05, 0.5)));
  EXPECT_TRUE(d.front_hazcam.CameraCentre(kRight).isApprox(Eigen::Vector3d(0.52, -0.05, 0.5)));
  // Rear HAZCAM looks backwards: its left camera is on the rover's right.
  EXPECT_LT(d.rear_hazcam.Pose().linear().col(0).x(), -0.7);
  EXPECT_LT(d.rear_hazcam.CameraCentre(kLeft).y(), 0.0);
  // Mast: + pan looks left, + tilt looks up; NAVCAM 5 cm in front of the tilt axis.
  const Eigen::Isometry3d left = d.mast.HeadPose(std::numbers::pi / 2, 0.0);
  EXPECT_TRUE(left.linear().col(0).isApprox(Eigen::Vector3d::UnitY()));
  const Eigen::Isometry3d up = d.mast.HeadPose(0.0, 0.4);
  EXPECT_NEAR(up.linear().col(0).z(), std::sin(0.4), 1e-12);
  EXPECT_TRUE(d.NavcamPose(0, 0).translation().isApprox(Eigen::Vector3d(0.40, 0.0, 1.5)));
  EXPECT_TRUE(d.mast.HeadPose(0.3, -0.2).translation().isApprox(
      d.mast.pan_joint + Eigen::Vector3d(0, 0, d.mast.head_height)));
}

TEST(RoverDescription, ValidateNamesTheField) {
  auto message = [](const RoverDescription& d) { return d.Validate().message(); };
  RoverDescription d;
  d.wheel_radius = -1.0;
  EXPECT_EQ(message(d).rfind("wheel_radius = -1 m is outside", 0), 0u) << message(d);
  d = RoverDescription();
  d.middle_wheel_x = 1.0;
  EXPECT_EQ(message(d).rfind("middle_wheel_x", 0), 0u) << message(d);
  d = RoverDescription();
  d.bogie_pivot_x = 0.3;
  EXPECT_EQ(message(d).rfind("bogie_pivot_x", 0), 0u) << message(d);
  d = RoverDescription();
  d.rocker_pivot_x = 0.7;
  EXPECT_EQ(message(d).rfind("rocker_pivot_x", 0), 0u) << message(d);
  d = RoverDescription();
  d.body_centre.z() = 0.1;  // underside below ground
  EXPECT_EQ(message(d).rfind("body_centre", 0), 0u) << message(d);
  d = RoverDescription();
  d.front_hazcam.baseline = 0.0;
  EXPECT_EQ(message(d).rfind("front_hazcam.baseline", 0), 0u) << message(d);
  d = RoverDescription();
  d.mast.pan_joint.y() = std::nan("");
  EXPECT_EQ(message(d).rfind("mast.pan_joint[1] is nan", 0), 0u) << message(d);
  d = RoverDescription();
  d.min_turn_radius = 0.45;  // inside the track
  EXPECT_EQ(message(d),
            "min_turn_radius = 0.45 m must exceed the largest wheel |y|, half_track (0.5)");
  d = RoverDescription();
  d.min_turn_radius = 2.0;           // the tightest arc needs 22.6 deg
  d.max_steer_angle = 45 * kDegree;  // but turning in place needs 51.3 deg
  EXPECT_EQ(message(d),
            "max_steer_angle = 45 deg is below the 51.3 deg the inner corner wheels need to turn "
            "in place");
  d.max_steer_angle = 55 * kDegree;
  d.min_turn_radius = 1.0;  // the tightest arc needs 51.3 deg too
  EXPECT_TRUE(d.Validate().ok());
  d.min_turn_radius = 0.9;  // 57.4 deg
  EXPECT_NE(message(d).find("tightest arc"), std::string::npos) << message(d);
}

TEST(RoverDescription, ParamsDefaultsEqualTheStructAndRoundTripExactly) {
  ParamSet p("rover");
  DeclareParams<RoverDescription>(p, "geometry.");
  EXPECT_TRUE(p.Has("geometry.wheel_radius"));
  EXPECT_TRUE(p.Has("geometry.mast.pan_joint"));
  EXPECT_TRUE(p.Has("geometry.rear_hazcam.yaw_deg"));
  EXPECT_DOUBLE_EQ(p.GetDouble("geometry.rear_hazcam.yaw_deg"), 180.0);
  EXPECT_DOUBLE_EQ(p.GetDouble("geometry.max_steer_angle_deg"), 70.0);
  auto d = ReadParams<RoverDescription>(p, "geometry.");
  ASSERT_TRUE(d.ok()) << d.status().ToString();
  const RoverDescription ref;
  // Bit-exact: the simulator reads its rover through these parameters.
  EXPECT_EQ(d->wheel_radius, ref.wheel_radius);
  EXPECT_EQ(d->front_hazcam.depression, ref.front_hazcam.depression);
  EXPECT_EQ(d->rear_hazcam.yaw, ref.rear_hazcam.yaw);
  EXPECT_EQ(d->max_steer_angle, ref.max_steer_angle);
  EXPECT_EQ(d->mast.pan_joint, ref.mast.pan_joint);
  EXPECT_EQ(d->navcam.position, ref.navcam.position);
  EXPECT_EQ(d->body_size, ref.body_size);
  EXPECT_EQ(d->rocker_pivot_y, ref.rocker_pivot_y);
}

TEST(RoverDescription, ParamErrorsNameFileLineAndKey) {
  ParamSet p("rover");
  DeclareParams<RoverDescription>(p, "geometry.");
  ASSERT_TRUE(
      p.LoadYamlString("geometry:\n  wheel_radius: 0.2\n  min_turn_radius: 0.45\n", "rover.yaml")
          .ok());
  auto d = ReadParams<RoverDescription>(p, "geometry.");
  ASSERT_FALSE(d.ok());
  EXPECT_EQ(d.status().message(),
            "rover.yaml:3: key 'geometry.min_turn_radius': min_turn_radius = 0.45 m must exceed "
            "the largest wheel |y|, half_track (0.5)");

  ParamSet q("rover");
  DeclareParams<RoverDescription>(q, "geometry.");
  ASSERT_TRUE(
      q.LoadYamlString("geometry:\n  front_hazcam:\n    depression_deg: 120\n", "c.yaml").ok());
  d = ReadParams<RoverDescription>(q, "geometry.");
  ASSERT_FALSE(d.ok());
  EXPECT_EQ(d.status().message().rfind("c.yaml:3: key 'geometry.front_hazcam.depression_deg'", 0),
            0u)
      << d.status().message();

  ParamSet r("rover");
  DeclareParams<RoverDescription>(r, "geometry.");
  EXPECT_FALSE(r.LoadYamlString("geometry:\n  body_size: [1, 2]\n", "s.yaml").ok() &&
               ReadParams<RoverDescription>(r, "geometry.").ok());
  ParamSet u("rover");
  DeclareParams<RoverDescription>(u, "geometry.");
  ASSERT_TRUE(
      u.LoadYamlString("geometry:\n  mast:\n    pan_joint: [0.2, 0, 0.7]\n", "m.yaml").ok());
  d = ReadParams<RoverDescription>(u, "geometry.");
  ASSERT_TRUE(d.ok()) << d.status().ToString();
  EXPECT_TRUE(d->mast.pan_joint.isApprox(Eigen::Vector3d(0.2, 0, 0.7)));
}

}  // namespace
}  // namespace rover::hwconfig
