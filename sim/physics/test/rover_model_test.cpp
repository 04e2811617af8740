#include "rover/sim/physics/rover_model.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace rover::sim::physics {
namespace {

TEST(RoverModelParams, DefaultsAreValidAndMerLike) {
  const RoverModelParams p;
  ASSERT_TRUE(p.Validate().ok()) << p.Validate().ToString();
  EXPECT_NEAR(p.masses.Total(), 180.0, 5.0);
  EXPECT_DOUBLE_EQ(p.geometry.wheel_radius, 0.125);
  EXPECT_NEAR(p.geometry.front_wheel_x - p.geometry.rear_wheel_x, 1.25, 1e-12);
  EXPECT_NEAR(2 * p.geometry.half_track, 1.0, 1e-12);
  // Mast head (tilt axis) at ~1.5 m and HAZCAMs at ~0.5 m above nominal ground (C origin).
  EXPECT_NEAR(p.geometry.mast.pan_joint.z() + p.geometry.mast.head_height, 1.5, 0.05);
  EXPECT_NEAR(p.geometry.front_hazcam.position.z(), 0.5, 0.05);
  EXPECT_NEAR(p.geometry.rear_hazcam.position.z(), 0.5, 0.05);
  // Equal static wheel loads need the rocker pivot to split front wheel / bogie pivot 2:1.
  const hwconfig::RoverDescription& g = p.geometry;
  EXPECT_NEAR((g.front_wheel_x - g.rocker_pivot_x), 2 * (g.rocker_pivot_x - g.bogie_pivot_x), 1e-9);
  EXPECT_NEAR(g.bogie_pivot_x, 0.5 * (g.middle_wheel_x + g.rear_wheel_x), 1e-9);
}

TEST(RoverModelParams, ValidateRejectsBadValuesWithTheirName) {
  RoverModelParams p;
  p.geometry.wheel_radius = -1.0;
  Status st = p.Validate();
  EXPECT_EQ(st.code(), StatusCode::kInvalidArgument);
  EXPECT_NE(st.message().find("geometry.wheel_radius"), std::string::npos) << st.message();

  p = RoverModelParams{};
  p.geometry.middle_wheel_x = 1.0;  // ahead of the front wheel
  EXPECT_FALSE(p.Validate().ok());

  p = RoverModelParams{};
  p.motors[hw::kSteerRR].kp = std::nan("");
  st = p.Validate();
  EXPECT_NE(st.message().find("steer_rr"), std::string::npos) << st.message();

  p = RoverModelParams{};
  p.contact.soils[2].mu_max = 0.0;
  st = p.Validate();
  EXPECT_NE(st.message().find("loose_sand"), std::string::npos) << st.message();

  p = RoverModelParams{};
  p.integrator.control_rate_hz = 1.0;
  EXPECT_FALSE(p.Validate().ok());
  p = RoverModelParams{};
  p.gravity = -3.7;
  EXPECT_FALSE(p.Validate().ok());
}

TEST(RoverModelParams, DefaultMotorsByKind) {
  const auto m = RoverModelParams::DefaultMotors();
  // Drive: 64 counts/motor rev through 1500:1 -> 96000 counts per wheel turn.
  EXPECT_NEAR(m[hw::kDriveLF].CountsPerRad() * 2 * 3.14159265358979, 96000.0, 1e-3);
  EXPECT_GT(m[hw::kSteerLF].CountsPerRad(), m[hw::kDriveLF].CountsPerRad());
  EXPECT_LT(m[hw::kMastTilt].max_angle, m[hw::kMastPan].max_angle);
}

}  // namespace
}  // namespace rover::sim::physics
