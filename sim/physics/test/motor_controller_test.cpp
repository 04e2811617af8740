#include "rover/sim/physics/motor_controller.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace rover::sim::physics {
namespace {

// A joint of inertia J with viscous friction b and an optional external torque, integrated with
// semi-implicit Euler in 1 ms steps: the load the controller drives in these tests.
struct Load {
  double inertia = 0.05;  // [kg m^2]
  double friction = 0.1;  // [N m s/rad]
  double angle = 0.0, rate = 0.0;
  bool blocked = false;

  void Step(double torque, double external, double dt) {
    if (blocked) {
      rate = 0.0;
      return;
    }
    rate += (torque + external - friction * rate) / inertia * dt;
    angle += rate * dt;
  }
};

constexpr double kDt = 1e-3;

TEST(MotorController, VelocityModeTracksCountRate) {
  MotorParams p;
  MotorController mc(p, -40.0, 0.0);
  Load load;
  const double cpr = p.CountsPerRad();
  ASSERT_TRUE(mc.SetGoal(MotorMode::kVelocity, 0.0, 0.4 * cpr, 1.0).ok());
  for (int k = 0; k < 3000; ++k) load.Step(mc.Update(load.angle, load.rate, kDt), -1.0, kDt);
  EXPECT_NEAR(load.rate, 0.4, 0.01);
  const MotorReading r = mc.Reading();
  EXPECT_NEAR(r.velocity_counts_per_s, 0.4 * cpr, 0.01 * cpr);
  // Torque: friction 0.04 + external 1.0 N m => current = tau / (eta N k_t) + no-load current.
  EXPECT_NEAR(r.torque_nm, 1.04, 0.05);
  EXPECT_NEAR(r.current_a, 1.04 / p.TorquePerAmp() + p.no_load_current, 0.01);
  EXPECT_EQ(r.faults, kMotorFaultNone);
}

TEST(MotorController, PositionModeReachesGoalWithProfile) {
  MotorParams p;
  p.min_angle = -2.0;
  p.max_angle = 2.0;
  MotorController mc(p, 0.0, 0.0);
  Load load;
  const double cpr = p.CountsPerRad();
  ASSERT_TRUE(mc.SetGoal(MotorMode::kPosition, 1.0 * cpr, 0.5 * cpr, 1.0).ok());
  double max_rate = 0.0;
  for (int k = 0; k < 4000; ++k) {
    load.Step(mc.Update(load.angle, load.rate, kDt), 0.0, kDt);
    max_rate = std::max(max_rate, load.rate);
  }
  EXPECT_NEAR(load.angle, 1.0, 2e-3);
  EXPECT_LT(max_rate, 0.5 * 1.1);  // the profile speed was respected
  EXPECT_TRUE(mc.Reading().goal_reached);
  // Out-of-range and malformed goals are rejected.
  EXPECT_EQ(mc.SetGoal(MotorMode::kPosition, 3.0 * cpr, 0.5 * cpr, 1.0).code(),
            StatusCode::kOutOfRange);
  EXPECT_EQ(mc.SetGoal(MotorMode::kPosition, 0.0, 0.0, 1.0).code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(mc.SetGoal(MotorMode::kVelocity, 0.0, 0.1 * cpr, 0.0).code(), StatusCode::kOutOfRange);
  EXPECT_EQ(mc.SetGoal(MotorMode::kVelocity, 0.0, 0.1 * cpr, p.max_current * 2).code(),
            StatusCode::kOutOfRange);
  EXPECT_EQ(mc.SetGoal(MotorMode::kVelocity, 0.0, 10.0 * p.max_speed * cpr, 1.0).code(),
            StatusCode::kOutOfRange);
  EXPECT_EQ(mc.SetGoal(MotorMode::kVelocity, 0.0, std::nan(""), 1.0).code(),
            StatusCode::kInvalidArgument);
}

TEST(MotorController, CurrentLimitBoundsTorque) {
  MotorParams p;
  p.stall_time = 1e6;
  MotorController mc(p, 0.0, 0.0);
  Load load;
  load.blocked = true;
  const double cpr = p.CountsPerRad();
  ASSERT_TRUE(mc.SetGoal(MotorMode::kVelocity, 0.0, 0.4 * cpr, 0.5).ok());
  double max_current = 0.0;
  for (int k = 0; k < 3000; ++k) {
    const double t = mc.Update(load.angle, load.rate, kDt);
    EXPECT_LE(std::abs(t), 0.5 * p.TorquePerAmp() + 1e-9);
    max_current = std::max(max_current, mc.Reading().current_a);
  }
  EXPECT_NEAR(max_current, 0.5, 1e-9);
}

TEST(MotorController, StallTripsAfterStallTimeAndLatches) {
  MotorParams p;
  MotorController mc(p, 0.0, 0.0);
  Load load;
  load.blocked = true;
  const double cpr = p.CountsPerRad();
  ASSERT_TRUE(mc.SetGoal(MotorMode::kVelocity, 0.0, 0.4 * cpr, 1.0).ok());
  int trip_tick = -1;
  for (int k = 0; k < 2000 && trip_tick < 0; ++k) {
    mc.Update(load.angle, load.rate, kDt);
    if (mc.faults() & kMotorFaultStall) trip_tick = k;
  }
  // The reference starts at rest and ramps; stall counting starts once it exceeds stall_speed.
  ASSERT_GE(trip_tick, 0);
  EXPECT_NEAR(trip_tick * kDt, p.stall_time + p.stall_speed / p.max_acceleration, 0.01);
  EXPECT_EQ(mc.mode(), MotorMode::kOff);
  EXPECT_EQ(mc.SetGoal(MotorMode::kVelocity, 0.0, 0.1 * cpr, 1.0).code(),
            StatusCode::kFailedPrecondition);
  mc.ClearFaults();
  EXPECT_TRUE(mc.SetGoal(MotorMode::kVelocity, 0.0, 0.1 * cpr, 1.0).ok());
}

TEST(MotorController, OverCurrentTripsWhenLimitAboveTripLevel) {
  MotorParams p;
  MotorController mc(p, 0.0, 0.0);
  Load load;
  const double cpr = p.CountsPerRad();
  // Current limit above the trip level and a heavy external load: the current exceeds the trip.
  ASSERT_TRUE(mc.SetGoal(MotorMode::kVelocity, 0.0, 0.2 * cpr, p.max_current).ok());
  int trip_tick = -1;
  for (int k = 0; k < 2000 && trip_tick < 0; ++k) {
    load.Step(mc.Update(load.angle, load.rate, kDt), -1.45 * p.TorquePerAmp(), kDt);
    if (mc.faults() & kMotorFaultOverCurrent) trip_tick = k;
  }
  ASSERT_GE(trip_tick, 0);
  EXPECT_EQ(mc.faults() & kMotorFaultStall, 0u);
  // Within a normal limit the same load does not trip over-current.
  MotorController ok(p, 0.0, 0.0);
  Load load2;
  ASSERT_TRUE(ok.SetGoal(MotorMode::kVelocity, 0.0, 0.2 * cpr, 1.0).ok());
  for (int k = 0; k < 2000; ++k) {
    load2.Step(ok.Update(load2.angle, load2.rate, kDt), -0.5 * p.TorquePerAmp(), kDt);
  }
  EXPECT_EQ(ok.faults(), kMotorFaultNone);
}

TEST(MotorController, WindingHeatsWithFirstOrderLagAndTrips) {
  MotorParams p;
  p.stall_time = 1e6;  // keep the stall detector out of the way
  p.thermal_time_constant = 10.0;
  p.thermal_resistance = 40.0;
  p.max_temperature = 60.0;
  p.kp = 1000.0;  // saturate the current at once
  p.max_acceleration = 100.0;
  MotorController mc(p, 20.0, 0.0);
  Load load;
  load.blocked = true;
  const double cpr = p.CountsPerRad();
  ASSERT_TRUE(mc.SetGoal(MotorMode::kVelocity, 0.0, 0.4 * cpr, 1.0).ok());
  // At 1 A into 3 ohm: 3 W, steady rise 120 K, time constant 10 s.
  for (int k = 0; k < 2000; ++k) mc.Update(load.angle, load.rate, kDt);
  const double expected = 20.0 + 120.0 * (1.0 - std::exp(-2.0 / 10.0));
  EXPECT_NEAR(mc.Reading().temperature_c, expected, 1.0);
  int trip_tick = -1;
  for (int k = 0; k < 20000 && trip_tick < 0; ++k) {
    mc.Update(load.angle, load.rate, kDt);
    if (mc.faults() & kMotorFaultOverTemperature) trip_tick = k;
  }
  ASSERT_GE(trip_tick, 0);
  // 60 deg C is reached at t = -10 ln(1 - 40/120) = 4.05 s.
  EXPECT_NEAR(2.0 + trip_tick * kDt, 4.05, 0.05);
  // Off: it cools.
  const double hot = mc.Reading().temperature_c;
  for (int k = 0; k < 5000; ++k) mc.Update(load.angle, load.rate, kDt);
  EXPECT_LT(mc.Reading().temperature_c, hot - 10.0);
  EXPECT_DOUBLE_EQ(mc.Reading().current_a, 0.0);
}

TEST(MotorController, BrakeHoldsWhenOff) {
  MotorParams p;
  MotorController mc(p, 0.0, 0.3);
  Load load;
  load.angle = 0.3;
  // An external torque below the brake torque is held.
  for (int k = 0; k < 3000; ++k) load.Step(mc.Update(load.angle, load.rate, kDt), 5.0, kDt);
  EXPECT_NEAR(load.angle, 0.3, 0.02);
  EXPECT_DOUBLE_EQ(mc.Reading().current_a, 0.0);
  // Above it the brake slips.
  for (int k = 0; k < 1000; ++k) load.Step(mc.Update(load.angle, load.rate, kDt), 60.0, kDt);
  EXPECT_GT(load.angle, 1.0);
}

TEST(MotorParams, ValidateNamesTheField) {
  MotorParams p;
  EXPECT_TRUE(p.Validate("m").ok());
  p.gear_efficiency = 1.5;
  const Status st = p.Validate("motors[2]");
  EXPECT_EQ(st.code(), StatusCode::kInvalidArgument);
  EXPECT_NE(st.message().find("motors[2].gear_efficiency"), std::string::npos) << st.message();
  p = MotorParams{};
  p.min_angle = 1.0;
  p.max_angle = -1.0;
  EXPECT_FALSE(p.Validate("m").ok());
  EXPECT_NEAR(MotorParams{}.CountsPerRad(), 64.0 * 1500.0 / (2 * std::numbers::pi), 1e-9);
}

}  // namespace
}  // namespace rover::sim::physics
