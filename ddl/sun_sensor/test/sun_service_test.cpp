// ddl-sun-sensor in-process on an isolated DDS domain under a simulated clock: spot centroids made with
// the nominal pinhole model of rover_hardware.yaml come out of ddl/sun_sensor as the rover-frame
// sun direction they were made from; dim spots are not valid, impossible spots FAILED, and
// silence STALE.
#include "sun_service.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "rover/base/units.hpp"
#include "rover/testing/service_harness.hpp"

namespace rover::ddl::sun_sensor {
namespace {

using testing::ServiceHarness;
class SunServiceTest : public ::testing::Test {
 protected:
  void SetUp() override {
    harness_ = std::make_unique<ServiceHarness>(service_, "ddl-sun-sensor-test");
    ASSERT_TRUE(harness_->ok()) << harness_->status().message();
    raw_ = harness_->Writer<rover_hw_SunSensorRaw>("hw/sun_sensor");
    sun_ = harness_->Reader<rover_ddl_SunSensor>("ddl/sun_sensor");
  }
  void TearDown() override { harness_.reset(); }

  // Spot of the sun in direction `sun` (rover frame) with the nominal model.
  rover_hw_SunSensorRaw Raw(Time t, const Eigen::Vector3d& sun, int intensity) const {
    const SunSensorSpec& s = hw_.sun_sensor;
    const Eigen::Vector3d d = s.rover_from_sensor.transpose() * sun;
    rover_hw_SunSensorRaw m{};
    m.header.stamp_ns = t.ns;
    m.spot[0] = static_cast<std::int16_t>(
        std::lround(s.focal_counts * d.x() / d.z() + s.principal_point.x()));
    m.spot[1] = static_cast<std::int16_t>(
        std::lround(s.focal_counts * d.y() / d.z() + s.principal_point.y()));
    m.intensity = static_cast<std::uint16_t>(intensity);
    return m;
  }
  static Eigen::Vector3d Direction(double azimuth_deg, double elevation_deg) {
    const double az = azimuth_deg * kDegree, el = elevation_deg * kDegree;
    return {std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el)};
  }
  // 0.5 s steps (2 Hz); each sample sent waits for its output.
  void Run(int steps, const Eigen::Vector3d& sun, int intensity, bool silent = false) {
    for (int i = 0; i < steps; ++i) {
      now_ = now_ + Seconds(0.5);
      ASSERT_TRUE(harness_->AdvanceTo(now_));
      if (!silent) {
        ASSERT_TRUE(raw_.Write(Raw(now_, sun, intensity)).ok());
        ++sent_;
      }
      ASSERT_TRUE(harness_->SpinUntil([&] {
        for (auto& s : sun_.Take()) out_.push_back(s.data());
        return static_cast<int>(out_.size()) == sent_;
      }));
    }
  }

  HardwareConfig hw_;
  SunService service_;
  std::unique_ptr<ServiceHarness> harness_;
  dds::Writer<rover_hw_SunSensorRaw> raw_;
  dds::Reader<rover_ddl_SunSensor> sun_;
  Time now_ = Time::FromSeconds(10.0);
  int sent_ = 0;
  std::vector<rover_ddl_SunSensor> out_;
};

TEST_F(SunServiceTest, SpotBecomesTheRoverFrameSunVector) {
  const Eigen::Vector3d sun = Direction(30.0, 60.0);  // 30 deg left of forward, 60 deg up
  Run(4, sun, 3000);
  ASSERT_EQ(out_.size(), 4u);
  const rover_ddl_SunSensor& m = out_.back();
  EXPECT_EQ(m.header.stamp_ns, now_.ns);
  EXPECT_STREQ(m.header.frame_id, "rover");
  EXPECT_TRUE(m.valid);
  EXPECT_EQ(m.health, rover_HEALTH_OK);
  EXPECT_NEAR(m.intensity, 3000.0 / 3500.0, 1e-12);
  const Eigen::Vector3d v(m.sun_vector.x, m.sun_vector.y, m.sun_vector.z);
  EXPECT_NEAR(v.norm(), 1.0, 1e-12);
  // Half a count of rounding on a 2000-count focal length: < 0.5/2000 rad off.
  EXPECT_LT(std::acos(std::min(1.0, v.dot(sun))), 0.5 / 2000.0 * std::sqrt(2.0));
  EXPECT_EQ(harness_->health(), rover_HEALTH_OK);
}

TEST_F(SunServiceTest, DimSpotIsNotValidImpossibleSpotFailsSilenceIsStale) {
  Run(2, Direction(0.0, 70.0), 100);  // below min_intensity: no sun, not a fault
  EXPECT_FALSE(out_.back().valid);
  EXPECT_EQ(out_.back().sun_vector.z, 0.0);
  EXPECT_EQ(out_.back().health, rover_HEALTH_OK);
  EXPECT_EQ(harness_->health(), rover_HEALTH_OK);
  // A bright spot 75 deg off the boresight (field of view 60 deg): a detector fault.
  Run(2, Direction(0.0, 15.0), 3000);
  EXPECT_FALSE(out_.back().valid);
  EXPECT_EQ(out_.back().health, rover_HEALTH_FAILED);
  EXPECT_EQ(harness_->health(), rover_HEALTH_FAILED);
  EXPECT_STREQ(harness_->heartbeats().back().message,
               "hw/sun_sensor: bright spot outside the field of view");
  Run(2, Direction(0.0, 70.0), 3000);
  EXPECT_TRUE(out_.back().valid);
  EXPECT_EQ(harness_->health(), rover_HEALTH_OK);
  // Silence: STALE after stale_after_s (1.5 s), judged at 4 Hz.
  Run(3, Direction(0.0, 70.0), 3000, /*silent=*/true);
  EXPECT_EQ(harness_->health(), rover_HEALTH_OK);  // 1.5 s: not yet more than the limit
  Run(1, Direction(0.0, 70.0), 3000, /*silent=*/true);
  EXPECT_EQ(harness_->health(), rover_HEALTH_STALE);
  EXPECT_STREQ(harness_->heartbeats().back().message,
               "hw/sun_sensor: no sample for more than 1.5 s");
}

}  // namespace
}  // namespace rover::ddl::sun_sensor
