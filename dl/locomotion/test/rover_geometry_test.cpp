#include "rover/dl/locomotion/rover_geometry.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "rover/base/units.hpp"

namespace rover::dl::locomotion {
namespace {

TEST(RoverGeometry, DefaultsAreValidAndMatchTheDesign) {
  const RoverGeometry g;
  ASSERT_TRUE(g.Validate().ok()) << g.Validate().ToString();
  EXPECT_DOUBLE_EQ(g.wheel_centre[0].x() - g.wheel_centre[2].x(), 1.25);  // wheelbase
  EXPECT_DOUBLE_EQ(g.wheel_centre[0].y() - g.wheel_centre[3].y(), 1.0);   // track
  EXPECT_DOUBLE_EQ(g.wheel_radius, 0.125);
  EXPECT_DOUBLE_EQ(g.MaxCurvature(), 1.0);
  EXPECT_DOUBLE_EQ(g.MiddleAxleX(), 0.0);
}

TEST(RoverGeometry, IsBuiltFromTheRoverDescription) {
  ParamSet p("locomotion");
  DeclareRoverGeometryParams(p);
  ASSERT_TRUE(p.LoadYamlString("geometry: {front_wheel_x: 0.7, middle_wheel_x: 0.05, "
                               "half_track: 0.55, rocker_pivot_x: 0.1, min_turn_radius: 1.5}\n",
                               "rover.yaml")
                  .ok());
  const Result<RoverGeometry> from_params = RoverGeometryFromParams(p);
  ASSERT_TRUE(from_params.ok()) << from_params.status().ToString();
  const RoverGeometry& g = *from_params;
  EXPECT_TRUE(g.wheel_centre[0].isApprox(Eigen::Vector3d(0.7, 0.55, 0.125)));
  EXPECT_TRUE(g.wheel_centre[4].isApprox(Eigen::Vector3d(0.05, -0.55, 0.125)));
  EXPECT_TRUE(g.rocker_pivot.isApprox(Eigen::Vector2d(0.1, 0.45)));
  EXPECT_TRUE(g.bogie_pivot.isApprox(Eigen::Vector2d(-0.3125, 0.30)));
  EXPECT_DOUBLE_EQ(g.min_turn_radius, 1.5);
  EXPECT_DOUBLE_EQ(g.MiddleAxleX(), 0.05);
  EXPECT_TRUE(g.Validate().ok()) << g.Validate().ToString();
  // The default geometry is the default description's.
  const RoverGeometry def;
  const hwconfig::RoverDescription nominal;
  for (int i = 0; i < kNumWheels; ++i) {
    EXPECT_EQ(def.wheel_centre[static_cast<std::size_t>(i)], nominal.WheelCentre(i)) << i;
  }
  EXPECT_EQ(def.max_steer_angle, nominal.max_steer_angle);
}

TEST(RoverGeometry, ZeroSuspensionAnglesGiveTheNominalCentres) {
  const RoverGeometry g;
  const SuspensionAngles zero;
  for (int i = 0; i < kNumWheels; ++i) {
    EXPECT_TRUE(g.WheelCentre(i, zero).isApprox(g.wheel_centre[static_cast<std::size_t>(i)])) << i;
  }
}

TEST(RoverGeometry, RockerAndBogieRaiseTheFrontOfTheirLinks) {
  const RoverGeometry g;
  SuspensionAngles s;
  s.rocker[0] = 10 * kDegree;  // left rocker front up
  const Eigen::Vector3d lf = g.WheelCentre(0, s);
  const Eigen::Vector3d lr = g.WheelCentre(2, s);
  EXPECT_GT(lf.z(), g.wheel_centre[0].z());
  EXPECT_LT(lr.z(), g.wheel_centre[2].z());
  // Rigid rotation about the rocker pivot: distances to the pivot are kept.
  const Eigen::Vector3d pivot(g.rocker_pivot.x(), 0.5, g.rocker_pivot.y());
  EXPECT_NEAR((lf - pivot).norm(), (g.wheel_centre[0] - pivot).norm(), 1e-12);
  EXPECT_NEAR((lr - pivot).norm(), (g.wheel_centre[2] - pivot).norm(), 1e-12);
  // The right side is untouched.
  EXPECT_TRUE(g.WheelCentre(3, s).isApprox(g.wheel_centre[3]));

  SuspensionAngles b;
  b.bogie[1] = 5 * kDegree;  // right bogie front up: RM up, RR down
  EXPECT_GT(g.WheelCentre(4, b).z(), g.wheel_centre[4].z());
  EXPECT_LT(g.WheelCentre(5, b).z(), g.wheel_centre[5].z());
  EXPECT_DOUBLE_EQ(RoverGeometry::LinkPitch(3, b), 0.0);
  EXPECT_DOUBLE_EQ(RoverGeometry::LinkPitch(4, b), 5 * kDegree);
  s.bogie[0] = 3 * kDegree;
  EXPECT_DOUBLE_EQ(RoverGeometry::LinkPitch(1, s), 13 * kDegree);
  EXPECT_DOUBLE_EQ(RoverGeometry::LinkPitch(0, s), 10 * kDegree);
}

TEST(RoverGeometry, ValidateNamesTheBadField) {
  RoverGeometry g;
  g.wheel_radius = -1.0;
  EXPECT_NE(g.Validate().message().find("wheel_radius"), std::string::npos);
  g = RoverGeometry();
  g.min_turn_radius = 0.4;  // inside the track
  EXPECT_NE(g.Validate().message().find("min_turn_radius"), std::string::npos);
  g = RoverGeometry();
  g.min_turn_radius = 2.0;        // Ackermann needs 22.6 deg at most
  g.max_steer_angle = 45 * kDegree;  // but turn in place needs 51.3 deg
  const Status s = g.Validate();
  EXPECT_NE(s.message().find("max_steer_angle"), std::string::npos) << s.message();
  EXPECT_NE(s.message().find("turn in place"), std::string::npos) << s.message();
  g = RoverGeometry();
  g.wheel_centre[4].x() = 0.05;  // middle wheels off one axle
  EXPECT_NE(g.Validate().message().find("axle"), std::string::npos);
  g = RoverGeometry();
  g.wheel_centre[3].y() = 0.5;  // right wheel on the left
  EXPECT_NE(g.Validate().message().find("right side"), std::string::npos);
  g = RoverGeometry();
  g.bogie_pivot.x() = 0.3;
  EXPECT_NE(g.Validate().message().find("bogie_pivot"), std::string::npos);
  g = RoverGeometry();
  g.wheel_centre[0].z() = std::nan("");
  EXPECT_FALSE(g.Validate().ok());
}

TEST(RoverGeometry, ParamsDefaultsEqualTheStructDefaults) {
  ParamSet p("locomotion");
  DeclareRoverGeometryParams(p);
  Result<RoverGeometry> g = RoverGeometryFromParams(p);
  ASSERT_TRUE(g.ok()) << g.status().ToString();
  const RoverGeometry d;
  EXPECT_DOUBLE_EQ(g->wheel_radius, d.wheel_radius);
  EXPECT_NEAR(g->max_steer_angle, d.max_steer_angle, 1e-12);
  for (std::size_t i = 0; i < 6; ++i) EXPECT_TRUE(g->wheel_centre[i].isApprox(d.wheel_centre[i]));
}

TEST(RoverGeometry, ParamsYamlErrorsNameFileLineAndKey) {
  ParamSet p("locomotion");
  DeclareRoverGeometryParams(p);
  ASSERT_TRUE(p.LoadYamlString("geometry:\n  wheel_radius: 0.2\n  min_turn_radius: 0.45\n",
                               "params/drive.yaml")
                  .ok());
  Result<RoverGeometry> g = RoverGeometryFromParams(p);
  ASSERT_FALSE(g.ok());
  EXPECT_EQ(g.status().message(),
            "params/drive.yaml:3: key 'geometry.min_turn_radius': min_turn_radius = 0.45 m must "
            "exceed the largest wheel |y|, half_track (0.5)");

  ParamSet q("locomotion");
  DeclareRoverGeometryParams(q);
  ASSERT_TRUE(q.LoadYamlString("geometry:\n  max_steer_angle_deg: 45\n", "d.yaml").ok());
  g = RoverGeometryFromParams(q);
  ASSERT_FALSE(g.ok());
  EXPECT_EQ(g.status().message().rfind("d.yaml:2: key 'geometry.max_steer_angle_deg'", 0), 0u)
      << g.status().message();

  ParamSet r("locomotion");
  DeclareRoverGeometryParams(r);
  ASSERT_TRUE(r.LoadYamlString("geometry:\n  wheel_radius: 7\n", "e.yaml").ok());
  g = RoverGeometryFromParams(r);
  ASSERT_FALSE(g.ok());
  EXPECT_NE(g.status().message().find("e.yaml:2: key 'geometry.wheel_radius'"), std::string::npos)
      << g.status().message();
  ParamSet u("locomotion");
  DeclareRoverGeometryParams(u);
  ASSERT_TRUE(u.LoadYamlString("geometry:\n  mast:\n    pan_joint: [1, 2]\n", "f.yaml").ok());
  g = RoverGeometryFromParams(u);
  ASSERT_FALSE(g.ok());
  EXPECT_NE(g.status().message().find("geometry.mast.pan_joint"), std::string::npos)
      << g.status().message();
}

}  // namespace
}  // namespace rover::dl::locomotion
