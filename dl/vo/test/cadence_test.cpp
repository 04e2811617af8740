#include "rover/dl/vo/cadence.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace rover::dl::vo {
namespace {

using Reason = VoCadence::Reason;

Eigen::Quaterniond Yaw(double yaw) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()));
}

// Feeds 10 Hz poses from t0 for `seconds` at `speed` [m/s] and `yaw_rate` [rad/s]; returns the
// reasons seen at each sample (captures are marked at once when due).
struct Drive {
  explicit Drive(CadenceOptions o = {}) : cadence(o) {}
  void Run(double seconds, double speed, double yaw_rate) {
    const int n = static_cast<int>(std::lround(seconds * 10.0));
    for (int i = 0; i < n; ++i) {
      t += 0.1;
      odometer += speed * 0.1;
      yaw += yaw_rate * 0.1;
      const Time now{std::llround(t * 1e9)};
      cadence.OnPose(now, odometer, speed, Yaw(yaw));
      const Reason r = cadence.Due(now);
      if (r != Reason::kNone) {
        reasons +=
            std::string(CadenceReasonName(r)) + "@" + std::to_string(std::lround(t * 10)) + " ";
        cadence.MarkCaptured(now, odometer, Yaw(yaw));
      }
    }
  }
  VoCadence cadence;
  double t = 0.0, odometer = 0.0, yaw = 0.0;
  std::string reasons;
};

TEST(Cadence, OptionsAreValidated) {
  EXPECT_TRUE(CadenceOptions{}.Validate().ok());
  CadenceOptions o;
  o.step_distance = 1.5;
  EXPECT_NE(o.Validate().message().find("step_distance"), std::string::npos);
  o = CadenceOptions{};
  o.min_distance = 0.6;  // larger than the step
  EXPECT_NE(o.Validate().message().find("min_distance"), std::string::npos);
  o = CadenceOptions{};
  o.max_interval_s = 0.0;
  EXPECT_NE(o.Validate().message().find("max_interval_s"), std::string::npos);
}

TEST(Cadence, NothingBeforePosesThenAFirstReferenceAtRest) {
  VoCadence c{CadenceOptions{}};
  EXPECT_EQ(c.Due(Time{0}), Reason::kNone);
  c.OnPose(Time::FromSeconds(1.0), 0.0, 0.0, Yaw(0.0));
  EXPECT_EQ(c.Due(Time::FromSeconds(1.0)), Reason::kFirst);
  c.MarkCaptured(Time::FromSeconds(1.0), 0.0, Yaw(0.0));
  EXPECT_EQ(c.Due(Time::FromSeconds(100.0)), Reason::kNone);  // parked: nothing to measure
  EXPECT_FALSE(c.driving());
}

TEST(Cadence, EveryStepDistanceWhileDrivingAndOnceAtTheEnd) {
  Drive d;
  d.Run(1.0, 0.0, 0.0);     // at rest: the first reference
  d.Run(25.0, 0.045, 0.0);  // 1.125 m at 4.5 cm/s: pairs once 0.5 m past the last one
  EXPECT_TRUE(d.cadence.driving());
  d.Run(5.0, 0.0, 0.0);  // stop: one more pair once settled (1 s)
  EXPECT_FALSE(d.cadence.driving());
  EXPECT_EQ(d.reasons, "first@1 distance@122 distance@234 end_of_drive@270 ");
}

TEST(Cadence, TurnsInPlaceAndSlowDrivesAreCoveredByAngleAndInterval) {
  CadenceOptions o;
  o.max_interval_s = 5.0;
  Drive d(o);
  d.Run(0.1, 0.0, 0.0);
  d.Run(4.0, 0.0, 0.11);   // turn in place at 0.11 rad/s: a pair every 0.3 rad
  d.Run(12.0, 0.01, 0.0);  // crawl 1 cm/s: 12 cm, below step_distance -> every 5 s
  EXPECT_EQ(d.reasons, "first@1 rotation@29 interval@79 interval@129 ");
}

TEST(Cadence, EstimatorJitterAtRestIsNotMotionWhenTheEstimatorSaysStationary) {
  VoCadence c{CadenceOptions{}};
  c.OnPose(Time::FromSeconds(1.0), 0.0, 0.0, Yaw(0.0), true);
  c.MarkCaptured(Time::FromSeconds(1.0), 0.0, Yaw(0.0));
  // Attitude corrections of 0.01 rad per 0.1 s (0.1 rad/s) while the estimator says at rest.
  for (int i = 1; i <= 50; ++i) {
    c.OnPose(Time::FromSeconds(1.0 + 0.1 * i), 0.0, 0.0, Yaw(0.01 * (i % 2)), true);
    EXPECT_FALSE(c.driving());
  }
  // The same samples without the flag look like a turn in place.
  c.OnPose(Time::FromSeconds(6.2), 0.0, 0.0, Yaw(0.01), false);
  EXPECT_TRUE(c.driving());
}

TEST(Cadence, ResetForgetsTheLastPair) {
  Drive d;
  d.Run(0.2, 0.0, 0.0);
  EXPECT_TRUE(d.cadence.has_capture());
  d.cadence.Reset();
  EXPECT_FALSE(d.cadence.has_capture());
  EXPECT_EQ(d.cadence.Due(Time::FromSeconds(1.0)), Reason::kNone);  // no pose yet
}

}  // namespace
}  // namespace rover::dl::vo
