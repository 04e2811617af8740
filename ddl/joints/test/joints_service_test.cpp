// ddl-joints in-process on an isolated DDS domain under a simulated clock: the test publishes
// hw/motor_telemetry and hw/suspension_pots counts for known joint angles and checks
// ddl/joint_state in radians, its rate, and STALE when the inputs stop.
#include "joints_service.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "rover/testing/service_harness.hpp"

namespace rover::ddl::joints {
namespace {

using testing::ServiceHarness;

class JointsServiceTest : public ::testing::Test {
 protected:
  void SetUp() override {
    harness_ = std::make_unique<ServiceHarness>(service_, "ddl-joints-test");
    ASSERT_TRUE(harness_->ok()) << harness_->status().message();
    telemetry_ = harness_->Writer<rover_hw_MotorTelemetry>("hw/motor_telemetry");
    pots_ = harness_->Writer<rover_hw_SuspensionPots>("hw/suspension_pots");
    joints_ = harness_->Reader<rover_ddl_JointState>("ddl/joint_state");
  }
  void TearDown() override { harness_.reset(); }

  // Counts of the true joint angles at time t: drive LF turns at 0.5 rad/s from 2 rad, the
  // other joints hold still.
  rover_hw_MotorTelemetry Telemetry(Time t) const {
    rover_hw_MotorTelemetry m{};
    m.header.stamp_ns = t.ns;
    auto counts = [&](int motor, double angle) {
      return static_cast<std::int32_t>(
          std::lround(angle * hw_.motors[static_cast<std::size_t>(motor)].CountsPerRad()));
    };
    m.motors[hw::kDriveLF].position = counts(hw::kDriveLF, WheelAngle(t));
    m.motors[hw::kSteerLF].position = counts(hw::kSteerLF, 0.3);
    m.motors[hw::kSteerRR].position = counts(hw::kSteerRR, -0.2);
    m.motors[hw::kMastPan].position = counts(hw::kMastPan, 0.7);
    m.motors[hw::kMastTilt].position = counts(hw::kMastTilt, -0.2);
    return m;
  }
  double WheelAngle(Time t) const { return 2.0 + 0.5 * (t.seconds() - 1.0); }
  rover_hw_SuspensionPots Pots(Time t) const {
    rover_hw_SuspensionPots m{};
    m.header.stamp_ns = t.ns;
    const double angles[4] = {0.1, -0.1, 0.2, -0.05};
    for (int i = 0; i < 4; ++i) {
      m.adc[i] = static_cast<std::uint16_t>(std::lround(hw_.pots.CountsFromAngle(i, angles[i])));
    }
    return m;
  }
  // 10 ms steps: telemetry every `telemetry_every` steps (100 Hz by default), pots every other
  // (50 Hz) unless `silent`.
  void Run(double seconds, bool silent = false, int telemetry_every = 1) {
    const Time end = now_ + Seconds(seconds);
    while (now_ < end) {
      now_ = now_ + Seconds(0.01);
      ++step_;
      ASSERT_TRUE(harness_->AdvanceTo(now_));
      if (!silent && step_ % telemetry_every == 0) {
        ASSERT_TRUE(telemetry_.Write(Telemetry(now_)).ok());
        if (step_ % 2 == 0) {
          ASSERT_TRUE(pots_.Write(Pots(now_)).ok());
        }
      }
      harness_->Spin();
      for (auto& s : joints_.Take()) states_.push_back(s.data());
    }
  }

  HardwareConfig hw_;
  JointsService service_;
  std::unique_ptr<ServiceHarness> harness_;
  dds::Writer<rover_hw_MotorTelemetry> telemetry_;
  dds::Writer<rover_hw_SuspensionPots> pots_;
  dds::Reader<rover_ddl_JointState> joints_;
  Time now_ = Time::FromSeconds(1.0);
  int step_ = 0;
  std::vector<rover_ddl_JointState> states_;
};

TEST_F(JointsServiceTest, CountsBecomeRadiansAt50Hz) {
  Run(1.0);
  ASSERT_FALSE(states_.empty());
  const rover_ddl_JointState& js = states_.back();
  EXPECT_EQ(js.health, rover_HEALTH_OK);
  EXPECT_STREQ(js.header.frame_id, "rover");
  const Time valid{js.header.stamp_ns};  // time of validity: the newest input's stamp
  EXPECT_LE(valid, now_);
  EXPECT_GE(valid, now_ - Seconds(0.03));
  const double drive_lsb = 1.0 / hw_.motors[hw::kDriveLF].CountsPerRad();
  const double steer_lsb = 1.0 / hw_.motors[hw::kSteerLF].CountsPerRad();
  const double mast_lsb = 1.0 / hw_.motors[hw::kMastPan].CountsPerRad();
  EXPECT_NEAR(js.wheel_angle[0], WheelAngle(valid), drive_lsb);
  EXPECT_NEAR(js.wheel_rate[0], 0.5, 1e-3);
  EXPECT_EQ(js.wheel_angle[3], 0.0);
  EXPECT_NEAR(js.steer_angle[0], 0.3, steer_lsb);
  EXPECT_NEAR(js.steer_angle[3], -0.2, steer_lsb);
  EXPECT_NEAR(js.mast_pan, 0.7, mast_lsb);
  EXPECT_NEAR(js.mast_tilt, -0.2, mast_lsb);
  const double pot_lsb = 1.0 / 690.0;
  EXPECT_NEAR(js.rocker_angle[0], 0.1, pot_lsb);
  EXPECT_NEAR(js.rocker_angle[1], -0.1, pot_lsb);
  EXPECT_NEAR(js.bogie_angle[0], 0.2, pot_lsb);
  EXPECT_NEAR(js.bogie_angle[1], -0.05, pot_lsb);

  // 50 Hz on the run clock: one more simulated second gives 50 samples (49..51 at the edges).
  const std::size_t before = states_.size();
  Run(1.0);
  const std::size_t n = states_.size() - before;
  EXPECT_GE(n, 49u);
  EXPECT_LE(n, 51u);
  ASSERT_FALSE(harness_->heartbeats().empty());
  EXPECT_EQ(harness_->heartbeats().back().health, rover_HEALTH_OK);
}

TEST_F(JointsServiceTest, GoesStaleWhenInputsStopAndRecovers) {
  Run(0.5);
  ASSERT_FALSE(states_.empty());
  EXPECT_EQ(states_.back().health, rover_HEALTH_OK);
  const Time silence = now_;
  Run(0.2, /*silent=*/true);  // < stale_after_s (0.25 s)
  EXPECT_EQ(states_.back().health, rover_HEALTH_OK);
  Run(0.1, /*silent=*/true);
  const rover_ddl_JointState& stale = states_.back();
  EXPECT_EQ(stale.health, rover_HEALTH_STALE);
  // The last known values, stamped with the time they were valid at.
  EXPECT_EQ(stale.header.stamp_ns, silence.ns);
  EXPECT_NEAR(stale.wheel_angle[0], WheelAngle(silence),
              1.0 / hw_.motors[hw::kDriveLF].CountsPerRad());
  ASSERT_FALSE(harness_->heartbeats().empty());
  EXPECT_EQ(harness_->heartbeats().back().health, rover_HEALTH_STALE);
  EXPECT_NE(std::string(harness_->heartbeats().back().message).find("s old"), std::string::npos)
      << harness_->heartbeats().back().message;
  Run(0.1);
  EXPECT_EQ(states_.back().health, rover_HEALTH_OK);
}

TEST_F(JointsServiceTest, FutureStampsAreDroppedAndASimulatorResetRestartsTheReader) {
  Run(0.3);
  // A corrupt telemetry sample from the far future would freeze the reader (it ignores samples
  // older than the newest): the service drops it.
  rover_hw_MotorTelemetry bad = Telemetry(now_ + Seconds(1000.0));
  bad.motors[hw::kSteerLF].position = 99999;
  ASSERT_TRUE(telemetry_.Write(bad).ok());
  Run(0.3);
  EXPECT_EQ(states_.back().health, rover_HEALTH_OK);
  EXPECT_NEAR(states_.back().steer_angle[0], 0.3, 1e-3);
  EXPECT_NEAR(states_.back().wheel_rate[0], 0.5, 1e-3);

  // Simulator reset: the run clock restarts near zero; new samples are accepted at once.
  now_ = Time::FromSeconds(0.05);
  Run(0.3);
  EXPECT_EQ(states_.back().health, rover_HEALTH_OK);
  EXPECT_LT(states_.back().header.stamp_ns, Time::FromSeconds(1.0).ns);
  EXPECT_NEAR(states_.back().wheel_angle[0], WheelAngle(Time{states_.back().header.stamp_ns}),
              1e-3);
}


// A timer tick that has no new input since the last sample must not publish the same state
// again: consumers (dl-pose's wheel odometry) reject a sample whose stamp is not after the
// previous one, and logged each rejection.
TEST_F(JointsServiceTest, EachInputStateIsPublishedOnceWithItsOwnStamp) {
  Run(0.2);
  states_.clear();
  Run(1.0, /*silent=*/false, /*telemetry_every=*/4);  // inputs at 25 Hz, the timer at 50 Hz
  ASSERT_GE(states_.size(), 10u);
  for (std::size_t i = 1; i < states_.size(); ++i) {
    EXPECT_GT(states_[i].header.stamp_ns, states_[i - 1].header.stamp_ns)
        << "sample " << i << " repeats the stamp " << states_[i].header.stamp_ns;
  }
  for (const auto& s : states_) EXPECT_EQ(s.health, rover_HEALTH_OK);
}

}  // namespace
}  // namespace rover::ddl::joints
