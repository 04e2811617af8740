#include "rover/sim/sensors/sensor_suite.hpp"

#include <gtest/gtest.h>

namespace rover::sim::sensors {
namespace {

SensorTruth Truth(std::int64_t ns) {
  SensorTruth t;
  t.stamp = Time{ns};
  t.imu.specific_force_rover = Eigen::Vector3d(0.0, 0.0, 3.71);
  t.suspension = {0.05, -0.05, 0.1, -0.02};
  for (auto& m : t.motors) {
    m.position_rad = 1e-9 * static_cast<double>(ns);
    m.current_a = 0.2;
    m.temperature_c = -20.0;
  }
  return t;
}

TEST(SensorSuite, EachSensorRunsAtItsOwnRate) {
  auto suite = SensorSuite::Create(HardwareConfig(), SimSensorOptions());
  ASSERT_TRUE(suite.ok()) << suite.status().ToString();
  int motors = 0, pots = 0, imu = 0, sun = 0;
  for (std::int64_t ms = 0; ms < 2000; ++ms) {  // 2 s at 1 kHz physics
    const SensorSamples s = suite->Step(Truth(ms * 1'000'000));
    motors += s.motor_telemetry.has_value();
    pots += s.suspension_pots.has_value();
    imu += s.imu.has_value();
    sun += s.sun_sensor.has_value();
    EXPECT_EQ(s.sun.has_value(), s.sun_sensor.has_value());
    if (s.imu) {
      EXPECT_EQ(s.imu->stamp_ns, ms * 1'000'000);
    }
  }
  EXPECT_EQ(motors, 200);
  EXPECT_EQ(pots, 100);
  EXPECT_EQ(imu, 200);
  EXPECT_EQ(sun, 4);
}

TEST(SensorSuite, SameSeedSameSamplesOtherSeedDifferent) {
  SimSensorOptions o;
  auto a = SensorSuite::Create(HardwareConfig(), o);
  auto b = SensorSuite::Create(HardwareConfig(), o);
  o.seed = 2;
  auto c = SensorSuite::Create(HardwareConfig(), o);
  ASSERT_TRUE(a.ok() && b.ok() && c.ok());
  bool differs = false;
  for (std::int64_t ms = 0; ms < 600; ms += 10) {
    const auto sa = a->Step(Truth(ms * 1'000'000));
    const auto sb = b->Step(Truth(ms * 1'000'000));
    const auto sc = c->Step(Truth(ms * 1'000'000));
    ASSERT_TRUE(sa.imu && sb.imu && sc.imu);
    EXPECT_EQ(sa.imu->gyro, sb.imu->gyro);
    EXPECT_EQ(sa.imu->accel, sb.imu->accel);
    differs |= sa.imu->gyro != sc.imu->gyro;
    if (sa.suspension_pots) {
      EXPECT_EQ(sa.suspension_pots->adc, sb.suspension_pots->adc);
    }
    if (sa.sun_sensor) {
      EXPECT_EQ(sa.sun_sensor->spot, sb.sun_sensor->spot);
      EXPECT_EQ(sa.sun_sensor->intensity, sb.sun_sensor->intensity);
    }
    for (std::size_t i = 0; i < sa.motor_telemetry->motors.size(); ++i) {
      EXPECT_EQ(sa.motor_telemetry->motors[i].current_adc,
                sb.motor_telemetry->motors[i].current_adc);
    }
  }
  EXPECT_TRUE(differs);
}

TEST(SensorSuite, RejectsInvalidConfiguration) {
  HardwareConfig bad;
  bad.imu.rate_hz = 0.0;
  auto s = SensorSuite::Create(bad, SimSensorOptions());
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.status().message().find("imu.rate_hz"), std::string::npos);
  SimSensorOptions o;
  o.noise_scale = -2.0;
  EXPECT_FALSE(SensorSuite::Create(HardwareConfig(), o).ok());
}

TEST(SensorSuite, SunSampleCarriesTheTrueSun) {
  SimSensorOptions o = SimSensorOptions::Ideal();
  o.ephemeris.ltst_hours = 12.0;
  o.ephemeris.latitude_deg = 0.0;
  o.ephemeris.ls_deg = 0.0;  // equinox, equator, noon: sun at the zenith
  auto suite = SensorSuite::Create(HardwareConfig(), o);
  ASSERT_TRUE(suite.ok());
  const SensorSamples s = suite->Step(Truth(0));
  ASSERT_TRUE(s.sun && s.sun_sensor);
  EXPECT_NEAR(s.sun->elevation_rad, M_PI / 2, 1e-9);
  EXPECT_EQ(s.sun_sensor->spot[0], 0);
  EXPECT_EQ(s.sun_sensor->spot[1], 0);
  EXPECT_EQ(s.sun_sensor->intensity, 3500);
}

}  // namespace
}  // namespace rover::sim::sensors
