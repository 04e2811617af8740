#include "rover/sim/sensors/sun_sensor_model.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "rover/base/units.hpp"
#include "rover/geometry/transforms.hpp"

namespace rover::sim::sensors {
namespace {

// Sun at elevation `el` and azimuth `az` (from north towards east), site frame.
Eigen::Vector3d Sun(double el, double az) {
  return {std::cos(el) * std::cos(az), -std::cos(el) * std::sin(az), std::sin(el)};
}

TEST(SunSensorModel, IdealSpotFollowsThePinholeGeometry) {
  const SunSensorSpec spec;
  SunSensorErrors none;
  none.optical_depth = 0.0;
  SunSensorModel model(spec, none, 0.0, 1);
  const Eigen::Matrix3d level = Eigen::Matrix3d::Identity();
  // Zenith sun: boresight, centre of the detector, full-scale intensity.
  hw::SunSensorRaw raw = model.Sample(Eigen::Vector3d::UnitZ(), level, Time{9});
  EXPECT_EQ(raw.stamp_ns, 9);
  EXPECT_EQ(raw.spot[0], 0);
  EXPECT_EQ(raw.spot[1], 0);
  EXPECT_EQ(raw.intensity, std::lround(spec.full_scale_intensity));
  // Sun 30 deg off zenith towards the rover's front (+x): rows are forward in the sensor.
  raw = model.Sample(Sun(60.0 * kDegree, 0.0), level, Time{});
  EXPECT_EQ(raw.spot[0], 0);
  EXPECT_EQ(raw.spot[1], std::lround(spec.focal_counts * std::tan(30.0 * kDegree)));
  EXPECT_NEAR(raw.intensity, spec.full_scale_intensity * std::cos(30.0 * kDegree), 0.5);
  // Towards the rover's right (-y = east when facing north): columns.
  raw = model.Sample(Sun(60.0 * kDegree, 90.0 * kDegree), level, Time{});
  EXPECT_EQ(raw.spot[0], std::lround(spec.focal_counts * std::tan(30.0 * kDegree)));
  EXPECT_EQ(raw.spot[1], 0);
}

TEST(SunSensorModel, AttitudeRotatesTheSpot) {
  const SunSensorSpec spec;
  SunSensorErrors none;
  none.optical_depth = 0.0;
  SunSensorModel model(spec, none, 0.0, 1);
  // Rover yawed 90 deg left (facing west): a sun in the north is now on the rover's right.
  const Eigen::Matrix3d yawed = geometry::RotationFromRpy(0.0, 0.0, M_PI / 2);
  const hw::SunSensorRaw raw = model.Sample(Sun(60.0 * kDegree, 0.0), yawed, Time{});
  EXPECT_EQ(raw.spot[0], std::lround(spec.focal_counts * std::tan(30.0 * kDegree)));
  EXPECT_EQ(raw.spot[1], 0);
}

TEST(SunSensorModel, InvalidOutsideTheFieldOfViewAndBelowTheHorizon) {
  const SunSensorSpec spec;  // fov 60 deg
  SunSensorModel model(spec, {}, 1.0, 3);
  const Eigen::Matrix3d level = Eigen::Matrix3d::Identity();
  // Elevation 25 deg: 65 deg off the boresight of a level rover.
  hw::SunSensorRaw raw = model.Sample(Sun(25.0 * kDegree, 0.0), level, Time{});
  EXPECT_EQ(raw.intensity, 0);
  EXPECT_EQ(raw.spot[0], 0);
  EXPECT_EQ(raw.spot[1], 0);
  EXPECT_FALSE(model.SunVisible(Sun(25.0 * kDegree, 0.0), level));
  // The same sun (north = ahead) is seen when the rover pitches nose down by 20 deg (pitch + =
  // nose down), which tilts the boresight forward, towards the sun: 45 deg off the boresight.
  const Eigen::Matrix3d nose_down = geometry::RotationFromRpy(0.0, 20.0 * kDegree, 0.0);
  EXPECT_TRUE(model.SunVisible(Sun(25.0 * kDegree, 0.0), nose_down));
  EXPECT_GT(model.Sample(Sun(25.0 * kDegree, 0.0), nose_down, Time{}).intensity, 0);
  EXPECT_FALSE(model.SunVisible(Sun(25.0 * kDegree, 0.0),
                                geometry::RotationFromRpy(0.0, -20.0 * kDegree, 0.0)));
  // Below the horizon: never seen, even by a sensor tilted towards it (12 deg off boresight).
  const Eigen::Matrix3d tilted = geometry::RotationFromRpy(0.0, 80.0 * kDegree, 0.0);
  raw = model.Sample(Sun(-2.0 * kDegree, 0.0), tilted, Time{});
  EXPECT_EQ(raw.intensity, 0);
}

TEST(SunSensorModel, DustAndLowSunDimTheSpot) {
  const SunSensorSpec spec;
  SunSensorErrors clear, dusty;
  clear.optical_depth = 0.3;
  dusty.optical_depth = 3.0;
  SunSensorModel a(spec, clear, 0.0, 1), b(spec, dusty, 0.0, 1);
  const Eigen::Matrix3d level = Eigen::Matrix3d::Identity();
  const auto high_clear = a.Sample(Sun(80.0 * kDegree, 0.0), level, Time{}).intensity;
  const auto low_clear = a.Sample(Sun(35.0 * kDegree, 0.0), level, Time{}).intensity;
  const auto low_dusty = b.Sample(Sun(35.0 * kDegree, 0.0), level, Time{}).intensity;
  EXPECT_GT(high_clear, low_clear);
  EXPECT_GT(low_clear, low_dusty);
  EXPECT_LT(low_dusty, spec.min_intensity);  // a driver would call this too dim
}

TEST(SunSensorModel, SpotNoiseMatchesSigmaAndValuesStayInRange) {
  SunSensorSpec spec;
  spec.spot_noise_counts = 3.0;
  SunSensorModel model(spec, SunSensorErrors{}, 1.0, 77);
  const Eigen::Vector3d sun = Sun(70.0 * kDegree, 30.0 * kDegree);
  const Eigen::Matrix3d level = Eigen::Matrix3d::Identity();
  SunSensorModel ideal(spec, SunSensorErrors{}, 0.0, 77);
  const auto truth = ideal.Sample(sun, level, Time{});
  double sum = 0.0, sum2 = 0.0;
  const int n = 20000;
  for (int k = 0; k < n; ++k) {
    const auto raw = model.Sample(sun, level, Time{});
    ASSERT_LE(raw.intensity, hw::kAdcMax);
    const double e = raw.spot[0] - truth.spot[0];
    sum += e;
    sum2 += e * e;
  }
  const double mean = sum / n;
  // The ideal spot is itself rounded: allow its +-0.5 offset in the mean.
  EXPECT_NEAR(mean, 0.0, 0.55);
  EXPECT_NEAR(std::sqrt(sum2 / n - mean * mean), std::sqrt(9.0 + 1.0 / 12.0), 0.1);
}

TEST(SunSensorModel, MountingErrorShiftsTheSpot) {
  const SunSensorSpec spec;
  SunSensorErrors e;
  e.optical_depth = 0.0;
  e.mounting_error_rpy = Eigen::Vector3d(0.0, 0.0, 0.0);
  SunSensorModel nominal(spec, e, 0.0, 1);
  e.mounting_error_rpy = Eigen::Vector3d(0.5 * kDegree, 0.0, 0.0);
  SunSensorModel tilted(spec, e, 0.0, 1);
  const Eigen::Matrix3d level = Eigen::Matrix3d::Identity();
  const auto a = nominal.Sample(Eigen::Vector3d::UnitZ(), level, Time{});
  const auto b = tilted.Sample(Eigen::Vector3d::UnitZ(), level, Time{});
  // 0.5 deg about the sensor x axis moves the spot ~f * 0.0087 = 17 counts along rows.
  EXPECT_NEAR(std::abs(b.spot[1] - a.spot[1]), spec.focal_counts * std::tan(0.5 * kDegree), 1.0);
}

}  // namespace
}  // namespace rover::sim::sensors
