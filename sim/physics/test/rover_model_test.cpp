#include "rover/sim/physics/rover_model.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "rover/sim/physics/motor_controller.hpp"

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

// A steered wheel pushed by the terrain (a rim edge on a bump: ~7 N m about the steering axis)
// must stay inside the 5 mrad band in which ddl-motor counts a steering move done
// (deploy/config/rover_hardware.yaml), or steering times out (MOT). The load: the gearhead's
// reflected inertia plus a wheel, with some viscous scrub, 1 ms steps.
TEST(RoverModelParams, SteerMotorHoldsItsGoalAgainstTerrainTorque) {
  const MotorParams p = DefaultSteerMotorParams();
  MotorController mc(p, -40.0, 0.0);
  const double cpr = p.CountsPerRad();
  const double goal = 0.25;  // [rad]
  ASSERT_TRUE(mc.SetGoal(MotorMode::kPosition, goal * cpr, 0.3 * cpr, p.max_current).ok());
  const double inertia = p.ReflectedInertia() + 0.05, friction = 2.0, dt = 1e-3;
  double angle = 0.0, rate = 0.0;
  auto run = [&](double seconds, double external) {
    for (int k = 0; k < static_cast<int>(seconds / dt); ++k) {
      rate += (mc.Update(angle, rate, dt) + external - friction * rate) / inertia * dt;
      angle += rate * dt;
    }
  };
  run(2.0, 0.0);
  EXPECT_NEAR(angle, goal, 0.002);
  for (const double push : {7.0, -7.0}) {
    run(1.0, push);
    EXPECT_NEAR(angle, goal, 0.005) << "pushed with " << push << " N m";
  }
  EXPECT_EQ(mc.Reading().faults, kMotorFaultNone);
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
