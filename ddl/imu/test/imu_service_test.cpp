// ddl-imu in-process on an isolated DDS domain under a simulated clock: raw hw/imu samples made
// with the nominal measurement model of rover_hardware.yaml come out of ddl/imu as the rover-frame
// rates and specific force they were made from; status bits and silence set the health.
#include "imu_service.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "rover/testing/service_harness.hpp"

namespace rover::ddl::imu {
namespace {

using testing::ServiceHarness;

class ImuServiceTest : public ::testing::Test {
 protected:
  void SetUp() override {
    harness_ = std::make_unique<ServiceHarness>(service_, "ddl-imu-test");
    ASSERT_TRUE(harness_->ok()) << harness_->status().message();
    raw_ = harness_->Writer<rover_hw_ImuRaw>("hw/imu");
    imu_ = harness_->Reader<rover_ddl_Imu>("ddl/imu");
  }
  void TearDown() override { harness_.reset(); }

  // The nominal model (core/hwconfig): raw lsb = K case_from_rover x + bias.
  rover_hw_ImuRaw Raw(Time t, const Eigen::Vector3d& rate, const Eigen::Vector3d& force,
                      std::uint16_t status = 0) const {
    const ImuSpec& s = hw_.imu;
    const Eigen::Matrix3d case_from_rover = s.rover_from_case.transpose();
    const Eigen::Vector3d g =
        (s.gyro.ScaleMisalignment() * case_from_rover * rate + s.gyro.bias) / s.gyro.lsb;
    const Eigen::Vector3d a =
        (s.accel.ScaleMisalignment() * case_from_rover * force + s.accel.bias) / s.accel.lsb;
    rover_hw_ImuRaw m{};
    m.header.stamp_ns = t.ns;
    for (int i = 0; i < 3; ++i) {
      m.gyro[i] = static_cast<std::int32_t>(std::lround(g[i]));
      m.accel[i] = static_cast<std::int32_t>(std::lround(a[i]));
    }
    m.temperature = 2150;  // 21.50 degC
    m.status = status;
    return m;
  }
  // 10 ms steps, one raw sample each unless `silent`.
  void Run(int steps, bool silent = false, std::uint16_t status = 0) {
    for (int i = 0; i < steps; ++i) {
      now_ = now_ + Seconds(0.01);
      ASSERT_TRUE(harness_->AdvanceTo(now_));
      if (!silent) {
        ASSERT_TRUE(raw_.Write(Raw(now_, rate_, force_, status)).ok());
        ++sent_;
      }
      // Each accepted sample gives exactly one output: wait for it, so every step is complete
      // before simulated time moves on.
      ASSERT_TRUE(harness_->SpinUntil([&] {
        Collect();
        return static_cast<int>(out_.size()) == sent_;
      }));
    }
  }
  void Collect() {
    for (auto& s : imu_.Take()) out_.push_back(s.data());
  }

  HardwareConfig hw_;
  ImuService service_;
  std::unique_ptr<ServiceHarness> harness_;
  dds::Writer<rover_hw_ImuRaw> raw_;
  dds::Reader<rover_ddl_Imu> imu_;
  Time now_ = Time::FromSeconds(1.0);
  Eigen::Vector3d rate_{0.01, -0.02, 0.3};
  Eigen::Vector3d force_{0.5, -0.3, 9.81};
  int sent_ = 0;
  std::vector<rover_ddl_Imu> out_;
};

TEST_F(ImuServiceTest, RawCountsBecomeRoverFrameSiOnePerSample) {
  Run(50);
  EXPECT_EQ(static_cast<int>(out_.size()), 50);
  for (std::size_t i = 0; i < out_.size(); ++i) {
    const rover_ddl_Imu& m = out_[i];
    EXPECT_EQ(m.header.stamp_ns, (Time::FromSeconds(1.0) + Seconds(0.01 * (i + 1))).ns);
    EXPECT_STREQ(m.header.frame_id, "rover");
    // Within a few LSB (1e-6) of the true values, through mounting, scale and misalignment.
    EXPECT_NEAR(m.angular_velocity.x, rate_.x(), 3e-6);
    EXPECT_NEAR(m.angular_velocity.y, rate_.y(), 3e-6);
    EXPECT_NEAR(m.angular_velocity.z, rate_.z(), 3e-6);
    EXPECT_NEAR(m.linear_acceleration.x, force_.x(), 3e-5);
    EXPECT_NEAR(m.linear_acceleration.y, force_.y(), 3e-5);
    EXPECT_NEAR(m.linear_acceleration.z, force_.z(), 3e-5);
    EXPECT_DOUBLE_EQ(m.temperature, 21.5);
    EXPECT_EQ(m.health, rover_HEALTH_OK);
  }
  EXPECT_EQ(harness_->health(), rover_HEALTH_OK);
}

TEST_F(ImuServiceTest, StatusBitsAndSilenceSetTheHealth) {
  Run(20);
  EXPECT_EQ(harness_->health(), rover_HEALTH_OK);
  Run(5, false, hw::kImuGyroSaturated);
  ASSERT_FALSE(out_.empty());
  EXPECT_EQ(out_.back().health, rover_HEALTH_DEGRADED);
  Run(10, false, hw::kImuGyroSaturated);
  EXPECT_EQ(harness_->health(), rover_HEALTH_DEGRADED);
  EXPECT_STREQ(harness_->heartbeats().back().message, "hw/imu: gyro saturated");
  Run(20, false, hw::kImuSelfTestFail);
  EXPECT_EQ(out_.back().health, rover_HEALTH_FAILED);
  EXPECT_EQ(harness_->health(), rover_HEALTH_FAILED);
  Run(20);
  EXPECT_EQ(harness_->health(), rover_HEALTH_OK);
  // Silence: STALE once hw/imu has not arrived for 0.1 s (judged at 10 Hz).
  Run(25, /*silent=*/true);
  EXPECT_EQ(harness_->health(), rover_HEALTH_STALE);
  EXPECT_STREQ(harness_->heartbeats().back().message, "hw/imu: no sample for more than 0.1 s");
  // A sample from the far future is dropped: no output, still STALE.
  const std::size_t before = out_.size();
  ASSERT_TRUE(raw_.Write(Raw(now_ + Seconds(50.0), rate_, force_)).ok());
  Run(15, /*silent=*/true);
  EXPECT_EQ(out_.size(), before);
  EXPECT_EQ(harness_->health(), rover_HEALTH_STALE);
  Run(15);
  EXPECT_EQ(harness_->health(), rover_HEALTH_OK);
}

}  // namespace
}  // namespace rover::ddl::imu
