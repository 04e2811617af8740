#include "rover/sim/rover_sim/sim_engine.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace rover::sim::rover_sim {
namespace {

std::unique_ptr<SimEngine> FlatEngine(double slope_deg = 0.0) {
  ParamSet p("rover-sim");
  SimEngine::DeclareParams(p);
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "terrain: {size_x: 20, size_y: 20, resolution: 0.05, seed: 3, hills: {amplitude: 0},"
                " craters: {count: 0}, rocks: {preset: none}, slope: {angle_deg: %g}}\n",
                slope_deg);
  EXPECT_TRUE(p.LoadYamlSections(buf, "t.yaml", {"terrain"}).ok());
  auto e = SimEngine::Create(p);
  EXPECT_TRUE(e.ok()) << e.status().message();
  return e.ok() ? std::move(*e) : nullptr;
}

TEST(SimEngine, PublishesSensorsAtTheirRatesAndTruthAtItsOwn) {
  auto e = FlatEngine();
  ASSERT_NE(e, nullptr);
  int imu = 0, motors = 0, pots = 0, sun = 0, truth = 0;
  for (int i = 0; i < 100; ++i) {  // 1 s
    auto out = e->Step();
    ASSERT_TRUE(out.ok()) << out.status().message();
    imu += out->sensors.imu.has_value();
    motors += out->sensors.motor_telemetry.has_value();
    pots += out->sensors.suspension_pots.has_value();
    sun += out->sensors.sun_sensor.has_value();
    truth += out->truth.has_value();
  }
  EXPECT_NEAR(e->time(), 1.0, 1e-9);
  EXPECT_EQ(imu, 100);
  EXPECT_EQ(motors, 100);
  EXPECT_EQ(pots, 50);
  EXPECT_EQ(truth, 50);
  EXPECT_GE(sun, 2);
  EXPECT_LE(sun, 3);
}

TEST(SimEngine, WheelGoalsInCountsDriveTheRoverAndEncodersAgree) {
  auto e = FlatEngine();
  ASSERT_NE(e, nullptr);
  // All six wheels at 0.2 rad/s for 10 s: 2 rad * 0.125 m = 0.25 m.
  hw::MotorGoals g;
  g.command_id = 7;
  for (int i = 0; i < 6; ++i) {
    const double cpr = e->hardware().motors[static_cast<std::size_t>(i)].CountsPerRad();
    g.goals[static_cast<std::size_t>(i)].mode = hw::MotorMode::kVelocity;
    g.goals[static_cast<std::size_t>(i)].velocity = static_cast<std::int32_t>(0.2 * cpr);
  }
  const Status applied = e->ApplyMotorGoals(g);
  ASSERT_TRUE(applied.ok()) << applied.message();
  std::optional<hw::MotorTelemetry> last;
  std::optional<TruthSample> truth;
  for (int i = 0; i < 1000; ++i) {
    auto out = e->Step();
    ASSERT_TRUE(out.ok());
    if (out->sensors.motor_telemetry) last = out->sensors.motor_telemetry;
    if (out->truth) truth = out->truth;
  }
  ASSERT_TRUE(last && truth);
  EXPECT_EQ(last->command_id, 7u);
  const double cpr = e->hardware().motors[0].CountsPerRad();
  const double wheel_rad = last->motors[0].position / cpr;
  EXPECT_NEAR(wheel_rad, 2.0, 0.1);  // the acceleration ramp costs a little
  EXPECT_NEAR(truth->pose.translation().x() - e->world().start_x, wheel_rad * 0.125, 0.01);
  EXPECT_NEAR(truth->odometer, wheel_rad * 0.125, 0.01);
  EXPECT_EQ(truth->rock_contacts, 0u);
}

TEST(SimEngine, RefusedGoalBrakesThatMotorAndReportsIt) {
  auto e = FlatEngine();
  ASSERT_NE(e, nullptr);
  hw::MotorGoals g;
  const double cpr = e->hardware().motors[6].CountsPerRad();
  g.goals[6].mode = hw::MotorMode::kPosition;
  g.goals[6].position = static_cast<std::int32_t>(3.0 * cpr);  // beyond the steering range
  g.goals[6].velocity = static_cast<std::int32_t>(0.2 * cpr);
  const Status s = e->ApplyMotorGoals(g);
  EXPECT_FALSE(s.ok());
  EXPECT_NE(s.message().find("motor"), std::string::npos) << s.message();
  EXPECT_TRUE(e->Step().ok());
}

// A goal asks a controller to saturate at the motor's configured current limit; a motor held
// there while still turning reads the limit plus its no-load current and must not trip (two
// VL-1 autonav runs ended MOT so when the trip sat at the limit itself). The trip sits 15 %
// above, where ddl-motor's own over-current monitor is.
TEST(SimEngine, TheControllersTripAboveTheCurrentTheySaturateAt) {
  auto e = FlatEngine();
  ASSERT_NE(e, nullptr);
  for (int i = 0; i < hw::kNumMotors; ++i) {
    const auto& m = e->physics().params().motors[static_cast<std::size_t>(i)];
    const double limit = e->hardware().motors[static_cast<std::size_t>(i)].current_limit;
    EXPECT_GT(m.overcurrent_trip, limit + m.no_load_current) << "motor " << i;
    EXPECT_NEAR(m.overcurrent_trip, 1.15 * limit, 1e-9) << "motor " << i;
    EXPECT_GE(m.max_current, m.overcurrent_trip) << "motor " << i;
  }
}

TEST(SimEngine, ResetRestartsTime) {
  auto e = FlatEngine();
  ASSERT_NE(e, nullptr);
  for (int i = 0; i < 10; ++i) ASSERT_TRUE(e->Step().ok());
  ASSERT_TRUE(e->Reset().ok());
  EXPECT_EQ(e->time(), 0.0);
  EXPECT_GT(e->SunDirectionSite().norm(), 0.99);
}

}  // namespace
}  // namespace rover::sim::rover_sim

namespace rover::sim::rover_sim {
namespace {

TEST(EngineOptions, PhysicsRateMustDivideTheStepAndStayInRange) {
  EngineOptions o;
  EXPECT_TRUE(o.Validate().ok());
  o.physics_rate_hz = 500.0;
  EXPECT_TRUE(o.Validate().ok());
  o.physics_rate_hz = 250.0;
  const Status s = o.Validate();
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.message(),
            "sim.physics_rate_hz: 250 Hz does not divide sim.period_s = 0.01 s into whole steps");
  o.physics_rate_hz = 50.0;
  EXPECT_NE(o.Validate().message().find("sim.physics_rate_hz: 50 Hz is out of range"),
            std::string::npos);
}

}  // namespace
}  // namespace rover::sim::rover_sim
