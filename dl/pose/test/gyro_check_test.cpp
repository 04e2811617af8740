#include "rover/dl/pose/gyro_check.hpp"

#include <gtest/gtest.h>

#include <random>

namespace rover::dl::pose {
namespace {

// Feeds `seconds` of a rover turning at `odo_rate` by its wheels (50 Hz joint states) with a
// gyro (200 Hz) reading `odo_rate + bias + noise`, from `t0`. Returns the end time.
double Feed(GyroCheck& c, double t0, double seconds, double odo_rate, double bias,
            std::mt19937& rng, double noise = 1e-3) {
  std::normal_distribution<double> n(0.0, noise);
  const double gdt = 0.005, odt = 0.02;
  double t = t0;
  for (int k = 1; t < t0 + seconds - 1e-9; ++k) {
    t = t0 + k * gdt;
    c.AddGyro(Time::FromSeconds(t), gdt, odo_rate + bias + n(rng));
    if (k % 4 == 0) c.AddOdometry(Time::FromSeconds(t - odt), Time::FromSeconds(t), odo_rate * odt);
  }
  return t;
}

TEST(GyroCheck, HoldsWhenTheGyroAgreesAtRestAndOnGentleArcs) {
  auto c = GyroCheck::Create({});
  ASSERT_TRUE(c.ok());
  std::mt19937 rng(1);
  double t = Feed(*c, 10.0, 20.0, 0.0, 0.0, rng);
  t = Feed(*c, t, 20.0, 0.015, 0.005, rng);  // an arc, the gyro 5 mrad/s off (slip)
  EXPECT_FALSE(c->failure().has_value());
  EXPECT_GT(c->judged(), 100u);
  EXPECT_LT(c->worst_disagreement(), 0.01);
}

TEST(GyroCheck, CatchesABiasWithinAFractionOfASecond) {
  auto c = GyroCheck::Create({});
  ASSERT_TRUE(c.ok());
  std::mt19937 rng(2);
  const double t0 = Feed(*c, 0.0, 40.0, 0.0, 0.0, rng);
  ASSERT_FALSE(c->failure().has_value());
  Feed(*c, t0, 2.0, 0.0, 0.05, rng);
  ASSERT_TRUE(c->failure().has_value());
  const double delay = c->failure()->window_end.seconds() - t0;
  EXPECT_GT(delay, 0.3);
  EXPECT_LT(delay, 0.8);
  EXPECT_NEAR(c->failure()->gyro_rate, 0.05 * 0.5, 0.03);
  EXPECT_NE(c->failure()->reason.find("disagrees with wheel odometry"), std::string::npos);
}

TEST(GyroCheck, DoesNotJudgeFastTurnsButCatchesTheBiasOnceStraight) {
  auto c = GyroCheck::Create({});
  ASSERT_TRUE(c.ok());
  std::mt19937 rng(3);
  // A point turn at 0.15 rad/s whose wheels slip 40 %: not judged.
  double t = Feed(*c, 0.0, 10.0, 0.15, 0.06, rng);
  EXPECT_FALSE(c->failure().has_value());
  t = Feed(*c, t, 3.0, 0.0, 0.05, rng);
  EXPECT_TRUE(c->failure().has_value());
}

// Autonav's arcs (0.03 rad/s at 0.1 m/s on a 3 m radius) are judged: a bias that starts mid-arc
// is caught within a second, not when the rover next stands still; turning wheels are allowed
// their slip (an arc at 0.035 rad/s slipping 40 % holds; a point turn at 0.05 rad/s is not judged).
TEST(GyroCheck, CatchesABiasDuringAnArcAndAllowsTurningWheelsTheirSlip) {
  auto c = GyroCheck::Create({});
  ASSERT_TRUE(c.ok());
  std::mt19937 rng(6);
  double t = Feed(*c, 0.0, 20.0, 0.05, 0.035, rng);
  t = Feed(*c, t, 20.0, 0.035, 0.014, rng);
  t = Feed(*c, t, 20.0, 0.03, 0.008, rng);
  ASSERT_FALSE(c->failure().has_value()) << c->failure()->reason;
  Feed(*c, t, 2.0, 0.03, 0.05, rng);
  ASSERT_TRUE(c->failure().has_value());
  const double delay = c->failure()->window_end.seconds() - t;
  EXPECT_GT(delay, 0.4);
  EXPECT_LE(delay, 1.0);
  EXPECT_NE(c->failure()->reason.find("allowed 0.035 rad/s"), std::string::npos)
      << c->failure()->reason;
}

TEST(GyroCheck, LatchesAndResetKeepsTheFailure) {
  auto c = GyroCheck::Create({});
  ASSERT_TRUE(c.ok());
  std::mt19937 rng(4);
  Feed(*c, 0.0, 3.0, 0.0, -0.1, rng);
  ASSERT_TRUE(c->failure().has_value());
  EXPECT_LT(c->failure()->gyro_rate, 0.0);
  c->Reset();
  EXPECT_TRUE(c->failure().has_value());
}

TEST(GyroCheck, DisabledNeverFails) {
  GyroCheckOptions o;
  o.enabled = false;
  auto c = GyroCheck::Create(o);
  ASSERT_TRUE(c.ok());
  std::mt19937 rng(5);
  Feed(*c, 0.0, 3.0, 0.0, 0.5, rng);
  EXPECT_FALSE(c->failure().has_value());
}

TEST(GyroCheck, MissingOdometryIsNotJudged) {
  auto c = GyroCheck::Create({});
  ASSERT_TRUE(c.ok());
  for (int k = 1; k <= 1000; ++k) c->AddGyro(Time::FromSeconds(k * 0.005), 0.005, 0.2);
  EXPECT_FALSE(c->failure().has_value());
  EXPECT_EQ(c->judged(), 0u);
}

TEST(GyroCheckOptions, ValidateNamesTheKey) {
  GyroCheckOptions o;
  EXPECT_TRUE(o.Validate().ok());
  o.window_s = 0.9;
  const Status s = o.Validate();
  EXPECT_FALSE(s.ok());
  EXPECT_NE(s.message().find("gyro_check.window_s"), std::string::npos) << s.message();
  o = {};
  o.min_coverage = 0.0;
  EXPECT_NE(o.Validate().message().find("gyro_check.min_coverage"), std::string::npos);
  o = {};
  o.rate_tolerance = 1.5;
  EXPECT_NE(o.Validate().message().find("gyro_check.rate_tolerance"), std::string::npos);
}

}  // namespace
}  // namespace rover::dl::pose
