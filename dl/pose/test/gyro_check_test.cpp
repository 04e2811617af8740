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

// A bias fails a window 0.4 to 0.65 s after it starts, and is confirmed by the next disjoint
// window (confirm_s = window_s = 1 s): caught 1.4 to 1.65 s after it starts.
TEST(GyroCheck, CatchesABiasOnceTwoDisjointWindowsDisagree) {
  auto c = GyroCheck::Create({});
  ASSERT_TRUE(c.ok());
  std::mt19937 rng(2);
  const double t0 = Feed(*c, 0.0, 40.0, 0.0, 0.0, rng);
  ASSERT_FALSE(c->failure().has_value());
  Feed(*c, t0, 3.0, 0.0, 0.05, rng);
  ASSERT_TRUE(c->failure().has_value());
  const double delay = c->failure()->window_end.seconds() - t0;
  EXPECT_GT(delay, 1.3);
  EXPECT_LT(delay, 1.8);
  EXPECT_NEAR(c->failure()->gyro_rate, 0.05, 0.005);
  EXPECT_NE(c->failure()->reason.find("disagrees with wheel odometry"), std::string::npos);
  EXPECT_NE(c->failure()->reason.find("in the window 1 s before"), std::string::npos)
      << c->failure()->reason;
}

TEST(GyroCheck, WithoutConfirmationOneWindowCatchesABiasWithinAFractionOfASecond) {
  GyroCheckOptions o;
  o.confirm_s = 0.0;
  auto c = GyroCheck::Create(o);
  ASSERT_TRUE(c.ok());
  std::mt19937 rng(2);
  const double t0 = Feed(*c, 0.0, 40.0, 0.0, 0.0, rng);
  Feed(*c, t0, 2.0, 0.0, 0.05, rng);
  ASSERT_TRUE(c->failure().has_value());
  const double delay = c->failure()->window_end.seconds() - t0;
  EXPECT_GT(delay, 0.3);
  EXPECT_LT(delay, 0.8);
  EXPECT_NEAR(c->failure()->gyro_rate, 0.05 * 0.5, 0.03);
}

// A wheel skidding off a rock yaws the rover 0.035 rad in a quarter of a second that its wheels
// do not see (about the event of an autonav VL-2 run that declared the pose unknown): every
// window holding it disagrees by 0.035 rad/s, more than allowed, but the windows a second
// before and after do not, so the check holds. Without confirmation it fails.
TEST(GyroCheck, ASkidOffARockIsNotAGyroFault) {
  for (const double confirm : {1.0, 0.0}) {
    GyroCheckOptions o;
    o.confirm_s = confirm;
    auto c = GyroCheck::Create(o);
    ASSERT_TRUE(c.ok());
    std::mt19937 rng(7);
    double t = Feed(*c, 0.0, 20.0, -0.015, 0.0, rng);
    t = Feed(*c, t, 0.25, -0.015, -0.14, rng);  // 0.035 rad of yaw the wheels miss
    Feed(*c, t, 20.0, -0.015, 0.0, rng);
    EXPECT_EQ(c->failure().has_value(), confirm == 0.0) << "confirm_s " << confirm;
  }
}

// Two skids a second apart in opposite directions (a rover rocking off a rock and back) are
// not a bias either: confirmation needs the same sign.
TEST(GyroCheck, OppositeSkidsASecondApartDoNotConfirmEachOther) {
  auto c = GyroCheck::Create({});
  ASSERT_TRUE(c.ok());
  std::mt19937 rng(8);
  double t = Feed(*c, 0.0, 20.0, 0.0, 0.0, rng);
  t = Feed(*c, t, 0.25, 0.0, -0.14, rng);
  t = Feed(*c, t, 0.75, 0.0, 0.0, rng);
  t = Feed(*c, t, 0.25, 0.0, 0.14, rng);
  Feed(*c, t, 20.0, 0.0, 0.0, rng);
  EXPECT_FALSE(c->failure().has_value()) << c->failure()->reason;
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
// is caught within two seconds (one to fail a window, one to confirm it), not when the rover
// next stands still; turning wheels are allowed
// their slip (an arc at 0.035 rad/s slipping 40 % holds; a point turn at 0.05 rad/s is not judged).
TEST(GyroCheck, CatchesABiasDuringAnArcAndAllowsTurningWheelsTheirSlip) {
  auto c = GyroCheck::Create({});
  ASSERT_TRUE(c.ok());
  std::mt19937 rng(6);
  double t = Feed(*c, 0.0, 20.0, 0.05, 0.035, rng);
  t = Feed(*c, t, 20.0, 0.035, 0.014, rng);
  t = Feed(*c, t, 20.0, 0.03, 0.008, rng);
  ASSERT_FALSE(c->failure().has_value()) << c->failure()->reason;
  Feed(*c, t, 3.0, 0.03, 0.05, rng);
  ASSERT_TRUE(c->failure().has_value());
  const double delay = c->failure()->window_end.seconds() - t;
  EXPECT_GT(delay, 1.4);
  EXPECT_LE(delay, 2.0);
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
  o = {};
  o.confirm_s = 0.6;
  EXPECT_NE(o.Validate().message().find("gyro_check.confirm_s: 0.6 s is not a whole number"),
            std::string::npos)
      << o.Validate().message();
  o.confirm_s = -1.0;
  EXPECT_NE(o.Validate().message().find("gyro_check.confirm_s"), std::string::npos);
}

}  // namespace
}  // namespace rover::dl::pose
