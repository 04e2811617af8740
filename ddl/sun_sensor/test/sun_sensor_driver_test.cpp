#include "rover/ddl/sun_sensor/sun_sensor_driver.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>  // cross()
#include <cmath>

#ifdef ROVER_HAVE_SIM_SENSORS
#include "rover/base/units.hpp"
#include "rover/geometry/mars_sun.hpp"
#include "rover/geometry/transforms.hpp"
#include "rover/sim/sensors/sim_sensor_options.hpp"
#include "rover/sim/sensors/sun_sensor_model.hpp"
#endif

namespace rover::ddl::sun_sensor {
namespace {

double Angle(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

hw::SunSensorRaw Raw(double col, double row, int intensity) {
  hw::SunSensorRaw r;
  r.spot = {static_cast<std::int16_t>(std::lround(col)),
            static_cast<std::int16_t>(std::lround(row))};
  r.intensity = static_cast<std::uint16_t>(intensity);
  return r;
}

TEST(SunSensorDriver, SpotToRoverFrameVector) {
  const SunSensorSpec spec;
  auto driver = SunSensorDriver::Create(spec);
  ASSERT_TRUE(driver.ok());
  SunSensor s = driver->Convert(Raw(0, 0, 3500));
  ASSERT_TRUE(s.valid);
  EXPECT_EQ(s.health, msg::SensorHealth::kOk);
  EXPECT_LT(Angle(s.sun_vector, Eigen::Vector3d::UnitZ()), 1e-12);  // boresight = rover up
  EXPECT_NEAR(s.intensity, 1.0, 1e-12);
  // Rows run forward: a spot at +f tan(30 deg) rows is 30 deg forward of the zenith.
  s = driver->Convert(Raw(0, spec.focal_counts * std::tan(30 * kDegree), 2000));
  ASSERT_TRUE(s.valid);
  EXPECT_LT(Angle(s.sun_vector, Eigen::Vector3d(std::sin(30 * kDegree), 0, std::cos(30 * kDegree))),
            0.5 / spec.focal_counts);
  EXPECT_NEAR(s.sun_vector.norm(), 1.0, 1e-12);
  // Columns run to the rover's right (-y).
  s = driver->Convert(Raw(spec.focal_counts * std::tan(20 * kDegree), 0, 2000));
  EXPECT_LT(
      Angle(s.sun_vector, Eigen::Vector3d(0, -std::sin(20 * kDegree), std::cos(20 * kDegree))),
      0.5 / spec.focal_counts);
}

TEST(SunSensorDriver, ValidityAndHealth) {
  const SunSensorSpec spec;
  auto driver = SunSensorDriver::Create(spec);
  ASSERT_TRUE(driver.ok());
  SunSensor s = driver->Convert(Raw(0, 0, 0));
  EXPECT_FALSE(s.valid);
  EXPECT_EQ(s.sun_vector.norm(), 0.0);
  EXPECT_EQ(s.health, msg::SensorHealth::kOk);
  s = driver->Convert(Raw(100, 100, 250));  // below min_intensity 300
  EXPECT_FALSE(s.valid);
  EXPECT_NE(s.reason.find("dim"), std::string::npos);
  // A bright spot 70 deg off the boresight cannot come through 60 deg optics.
  s = driver->Convert(Raw(spec.focal_counts * std::tan(70 * kDegree), 0, 2000));
  EXPECT_FALSE(s.valid);
  EXPECT_EQ(s.health, msg::SensorHealth::kFailed);
  // Right at the edge (59.9 deg) is fine.
  EXPECT_TRUE(driver->Convert(Raw(0, -spec.focal_counts * std::tan(59.9 * kDegree), 500)).valid);
  SunSensorSpec bad = spec;
  bad.focal_counts = -1.0;
  EXPECT_FALSE(SunSensorDriver::Create(bad).ok());
}

#ifdef ROVER_HAVE_SIM_SENSORS
TEST(SunSensorDriver, RoundTripThroughTheSimulatedSensorAndEphemeris) {
  const SunSensorSpec spec;
  auto driver = SunSensorDriver::Create(spec);
  ASSERT_TRUE(driver.ok());
  sim::sensors::SunSensorErrors clear;
  clear.optical_depth = 0.0;
  sim::sensors::SunSensorModel ideal(spec, clear, 0.0, 1);
  geometry::SunEphemerisOptions eo;  // Gusev, Ls 330
  const geometry::SunEphemeris eph(eo);
  const Eigen::Matrix3d attitude = geometry::RotationFromRpy(0.05, -0.1, 1.3);
  int seen = 0;
  for (double h = 0.0; h < 24.0; h += 0.5) {
    const geometry::SunState sun = eph.At((h - eo.ltst_hours + 24.0) * geometry::kMarsSolSeconds / 24.0);
    const SunSensor s = driver->Convert(ideal.Sample(sun.direction_site, attitude, Time{}));
    const Eigen::Vector3d truth_rover = attitude.transpose() * sun.direction_site;
    const bool visible = ideal.SunVisible(sun.direction_site, attitude);
    EXPECT_EQ(s.valid, visible) << "LTST " << h;
    if (sun.elevation_rad < 0.0) {
      EXPECT_FALSE(s.valid) << "night at LTST " << h;
    }
    if (s.valid) {
      ++seen;
      // Within the +-0.5 count quantisation of the centroid.
      EXPECT_LT(Angle(s.sun_vector, truth_rover), 0.75 / spec.focal_counts) << "LTST " << h;
    }
  }
  EXPECT_GT(seen, 8);  // the middle of the day

  // With the simulator's default mounting and principal-point errors the nominal driver is off
  // by a fraction of a degree.
  sim::sensors::SunSensorModel real(spec, sim::sensors::SimSensorOptions().sun_sensor, 0.0, 1);
  const geometry::SunState noon = eph.At((12.0 - eo.ltst_hours) * geometry::kMarsSolSeconds / 24.0);
  const SunSensor s = driver->Convert(real.Sample(noon.direction_site, attitude, Time{}));
  ASSERT_TRUE(s.valid);
  const double err = Angle(s.sun_vector, attitude.transpose() * noon.direction_site);
  EXPECT_GT(err, 0.05 * kDegree);
  EXPECT_LT(err, 0.6 * kDegree);
}
#else
TEST(SunSensorDriver, RoundTripThroughTheSimulatedSensorAndEphemeris) {
  GTEST_SKIP() << "sim/sensors is not part of this build (ROVER_MODULE_FILTER)";
}
#endif

}  // namespace
}  // namespace rover::ddl::sun_sensor
