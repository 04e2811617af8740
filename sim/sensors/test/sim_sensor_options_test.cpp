#include "rover/sim/sensors/sim_sensor_options.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace rover::sim::sensors {
namespace {

TEST(SimSensorOptions, DefaultsAndIdealAreValid) {
  const SimSensorOptions d;
  EXPECT_TRUE(d.Validate().ok()) << d.Validate().ToString();
  EXPECT_GT(d.imu.gyro_bias_error.norm(), 0.0);  // calibration matters by default
  const SimSensorOptions ideal = SimSensorOptions::Ideal();
  EXPECT_TRUE(ideal.Validate().ok());
  EXPECT_EQ(ideal.noise_scale, 0.0);
  EXPECT_EQ(ideal.imu.gyro_bias_error.norm(), 0.0);
  EXPECT_EQ(ideal.sun_sensor.optical_depth, 0.0);
}

TEST(SimSensorOptions, ParamsRoundTripTheDefaults) {
  ParamSet ps("sim");
  DeclareSimSensorParams(ps);
  auto o = SimSensorOptionsFromParams(ps);
  ASSERT_TRUE(o.ok()) << o.status().ToString();
  const SimSensorOptions d;
  EXPECT_EQ(o->seed, d.seed);
  EXPECT_LT((o->imu.gyro_bias_error - d.imu.gyro_bias_error).norm(), 1e-18);
  EXPECT_LT((o->imu.mounting_error_rpy - d.imu.mounting_error_rpy).norm(), 1e-15);
  EXPECT_LT((o->sun_sensor.mounting_error_rpy - d.sun_sensor.mounting_error_rpy).norm(), 1e-15);
  EXPECT_EQ(o->pots.offset_error_counts, d.pots.offset_error_counts);
  EXPECT_EQ(o->ephemeris.mode, geometry::SunEphemerisOptions::Mode::kSeason);
}

TEST(SimSensorOptions, YamlValuesAreRead) {
  ParamSet ps("sim");
  DeclareSimSensorParams(ps);
  ASSERT_TRUE(ps.LoadYamlString("sensors:\n"
                                "  seed: 9\n"
                                "  noise_scale: 0\n"
                                "  imu:\n"
                                "    gyro_bias_error: [1.0e-5, 0, 0]\n"
                                "  ephemeris:\n"
                                "    mode: date\n"
                                "    j2000_tt_days: 8000\n",
                                "s.yaml")
                  .ok());
  auto o = SimSensorOptionsFromParams(ps);
  ASSERT_TRUE(o.ok()) << o.status().ToString();
  EXPECT_EQ(o->seed, 9u);
  EXPECT_EQ(o->noise_scale, 0.0);
  EXPECT_EQ(o->imu.gyro_bias_error.x(), 1.0e-5);
  EXPECT_EQ(o->ephemeris.mode, geometry::SunEphemerisOptions::Mode::kDate);
  EXPECT_EQ(o->ephemeris.j2000_tt_days, 8000.0);
}

TEST(SimSensorOptions, ErrorsNameFileLineAndKey) {
  ParamSet ps("sim");
  DeclareSimSensorParams(ps);
  ASSERT_TRUE(ps.LoadYamlString("sensors:\n  sun_sensor:\n    optical_depth: -1\n", "s.yaml").ok());
  auto o = SimSensorOptionsFromParams(ps);
  ASSERT_FALSE(o.ok());
  EXPECT_EQ(o.status().message(),
            "s.yaml:3: key 'sensors.sun_sensor.optical_depth': -1 is out of range [0, 10]");
  ParamSet ps2("sim");
  DeclareSimSensorParams(ps2);
  ASSERT_TRUE(ps2.LoadYamlString("sensors:\n  ephemeris:\n    mode: lunar\n", "s.yaml").ok());
  EXPECT_FALSE(SimSensorOptionsFromParams(ps2).ok());
}

TEST(SimSensorOptions, ValidateCatchesBadStructs) {
  SimSensorOptions o;
  o.noise_scale = -1.0;
  EXPECT_FALSE(o.Validate().ok());
  o = SimSensorOptions{};
  o.imu.gyro_bias_error.x() = std::nan("");
  EXPECT_FALSE(o.Validate().ok());
  o = SimSensorOptions{};
  o.pots.gain_error[2] = -1.5;
  EXPECT_FALSE(o.Validate().ok());
  o = SimSensorOptions{};
  o.ephemeris.latitude_deg = 100.0;
  EXPECT_FALSE(o.Validate().ok());
}

}  // namespace
}  // namespace rover::sim::sensors
