#include "rover/dl/locomotion/wheel_odometry.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "rover/base/units.hpp"
#include "rover/dl/locomotion/ackermann.hpp"

namespace rover::dl::locomotion {
namespace {

struct Pose2 {
  double x = 0, y = 0, yaw = 0;
  // this * (dx, dy, dyaw): the increment is expressed in this pose's frame.
  Pose2 Compose(double dx, double dy, double dyaw) const {
    return {x + std::cos(yaw) * dx - std::sin(yaw) * dy,
            y + std::sin(yaw) * dx + std::cos(yaw) * dy, yaw + dyaw};
  }
};

// Emits joint samples for kinematically consistent (no-slip) motions.
class SampleWriter {
 public:
  explicit SampleWriter(const RoverGeometry& g) : g_(g) { sample_.stamp = Time::FromSeconds(1.0); }

  const msg::JointState& sample() const { return sample_; }
  std::vector<msg::JointState>& samples() { return out_; }

  void Emit() { out_.push_back(sample_); }

  // Arc of curvature k, `distance` of the reference point, in `steps` samples at 20 Hz.
  void Arc(double k, double distance, int steps) {
    SteerTo(ArcSteerAngles(g_, k), 1);
    const auto ratio = ArcPathRatios(g_, k);
    for (int n = 0; n < steps; ++n) {
      for (std::size_t i = 0; i < 6; ++i) {
        sample_.wheel_angle[i] += ratio[i] * distance / steps / g_.wheel_radius;
      }
      Advance();
    }
  }
  void TurnInPlace(double angle, int steps) {
    SteerTo(TurnInPlaceSteerAngles(g_), 1);
    const auto q = TurnInPlaceRadii(g_);
    for (int n = 0; n < steps; ++n) {
      for (std::size_t i = 0; i < 6; ++i) {
        sample_.wheel_angle[i] += q[i] * angle / steps / g_.wheel_radius;
      }
      Advance();
    }
  }
  // Steering moves without wheel rotation (the rover does not move); steer first, then drive.
  void SteerTo(const std::array<double, 4>& steer, int steps) {
    const auto start = sample_.steer_angle;
    for (int n = 1; n <= steps; ++n) {
      for (std::size_t j = 0; j < 4; ++j) {
        sample_.steer_angle[j] = start[j] + (steer[j] - start[j]) * n / steps;
      }
      Advance();
    }
  }

 private:
  void Advance() {
    sample_.stamp = sample_.stamp + Seconds(0.05);
    Emit();
  }
  RoverGeometry g_;
  msg::JointState sample_;
  std::vector<msg::JointState> out_;
};

Pose2 Integrate(WheelOdometry& odo, const std::vector<msg::JointState>& samples,
                double* path = nullptr) {
  Pose2 pose;
  double s = 0.0;
  odo.Reset();
  for (const msg::JointState& js : samples) {
    auto inc = odo.Add(js);
    EXPECT_TRUE(inc.ok()) << inc.status().ToString();
    if (inc.ok() && inc->has_value()) {
      const OdometryIncrement& d = **inc;
      pose = pose.Compose(d.dx, d.dy, d.dyaw);
      s += d.path_length;
    }
  }
  if (path != nullptr) *path = s;
  return pose;
}

WheelOdometry MakeOdometry(const RoverGeometry& g = RoverGeometry(),
                           const WheelOdometryOptions& o = WheelOdometryOptions()) {
  Result<WheelOdometry> odo = WheelOdometry::Create(g, o);
  EXPECT_TRUE(odo.ok());
  return std::move(odo).value();
}

TEST(WheelOdometry, RecoversAnArc) {
  const RoverGeometry g;
  WheelOdometry odo = MakeOdometry(g);
  for (double k : {0.5, -1.0, 0.05}) {
    SampleWriter w(g);
    w.Emit();
    w.Arc(k, 1.5, 60);
    const Pose2 p = Integrate(odo, w.samples());
    const double s = 1.5;
    EXPECT_NEAR(p.x, std::sin(k * s) / k, 1e-9) << k;
    EXPECT_NEAR(p.y, (1 - std::cos(k * s)) / k, 1e-9) << k;
    EXPECT_NEAR(p.yaw, k * s, 1e-9) << k;
  }
}

TEST(WheelOdometry, RecoversATurnInPlace) {
  const RoverGeometry g;
  WheelOdometry odo = MakeOdometry(g);
  SampleWriter w(g);
  w.Emit();
  w.TurnInPlace(-75 * kDegree, 50);
  double path = 0.0;
  const Pose2 p = Integrate(odo, w.samples(), &path);
  EXPECT_NEAR(p.x, 0.0, 1e-12);
  EXPECT_NEAR(p.y, 0.0, 1e-12);
  EXPECT_NEAR(p.yaw, -75 * kDegree, 1e-12);
  // Mean wheel path of the turn: (4 corners * 0.8004 m + 2 middles * 0.5 m) / 6 per radian.
  EXPECT_NEAR(path, (4 * std::hypot(0.625, 0.5) + 2 * 0.5) / 6 * 75 * kDegree, 1e-9);
}

TEST(WheelOdometry, RecoversAKnownPlanarPath) {
  // Arc, re-steer in place, turn in place, re-steer, straight: the composed increments equal
  // the analytic end pose.
  const RoverGeometry g;
  WheelOdometry odo = MakeOdometry(g);
  SampleWriter w(g);
  w.Emit();
  w.Arc(0.4, 1.2, 40);
  w.SteerTo(TurnInPlaceSteerAngles(g), 10);
  w.TurnInPlace(1.0, 30);
  w.SteerTo({0, 0, 0, 0}, 10);
  w.Arc(0.0, 0.7, 20);
  const Pose2 p = Integrate(odo, w.samples());
  const Pose2 truth = Pose2()
                          .Compose(std::sin(0.48) / 0.4, (1 - std::cos(0.48)) / 0.4, 0.48)
                          .Compose(0, 0, 1.0)
                          .Compose(0.7, 0, 0);
  EXPECT_NEAR(p.x, truth.x, 1e-9);
  EXPECT_NEAR(p.y, truth.y, 1e-9);
  EXPECT_NEAR(p.yaw, truth.yaw, 1e-9);
}

TEST(WheelOdometry, SuspensionArticulationIsNotMistakenForMotion) {
  // Straight drive over a rock: the left rocker and the right bogie articulate, so the wheels move
  // relative to the body and their rim path is partly vertical. Samples are generated with the
  // model's own contact geometry (no slip); the suspension-aware odometry recovers the body motion
  // exactly, the flat-ground model does not.
  const RoverGeometry g;
  const int steps = 80;
  const double body_step = 0.01;  // [m] per sample
  std::vector<msg::JointState> samples;
  msg::JointState js;
  js.stamp = Time::FromSeconds(3.0);
  samples.push_back(js);
  for (int n = 1; n <= steps; ++n) {
    msg::JointState next = js;
    next.stamp = js.stamp + Seconds(0.05);
    const double a = std::sin(std::numbers::pi * n / steps);
    next.rocker_angle = {12 * kDegree * a, -4 * kDegree * a};
    next.bogie_angle = {-3 * kDegree * a, -9 * kDegree * a};
    SuspensionAngles s0{js.rocker_angle, js.bogie_angle};
    SuspensionAngles s1{next.rocker_angle, next.bogie_angle};
    for (int i = 0; i < 6; ++i) {
      const double dpx = g.WheelCentre(i, s1).x() - g.WheelCentre(i, s0).x();
      const double pitch =
          0.5 * (RoverGeometry::LinkPitch(i, s0) + RoverGeometry::LinkPitch(i, s1));
      next.wheel_angle[static_cast<std::size_t>(i)] +=
          (body_step + dpx) / (g.wheel_radius * std::cos(pitch));
    }
    samples.push_back(next);
    js = next;
  }
  WheelOdometry odo = MakeOdometry(g);
  const Pose2 p = Integrate(odo, samples);
  EXPECT_NEAR(p.x, steps * body_step, 1e-9);
  EXPECT_NEAR(p.y, 0.0, 1e-12);
  EXPECT_NEAR(p.yaw, 0.0, 1e-12);

  WheelOdometryOptions flat;
  flat.use_suspension = false;
  WheelOdometry naive = MakeOdometry(g, flat);
  const Pose2 q = Integrate(naive, samples);
  EXPECT_GT(std::abs(q.x - steps * body_step) + std::abs(q.yaw), 2e-3);
}

TEST(WheelOdometry, CovarianceGrowsWithDistance) {
  const RoverGeometry g;
  WheelOdometryOptions o;
  o.along_variance_per_m = 4e-3;
  o.cross_variance_per_m = 1e-3;
  o.yaw_variance_per_m = 2e-4;
  WheelOdometry odo = MakeOdometry(g, o);
  msg::JointState a;
  a.stamp = Time::FromSeconds(1);
  msg::JointState b = a;
  b.stamp = Time::FromSeconds(1.1);
  for (double& th : b.wheel_angle) th = 0.1 / g.wheel_radius;  // 0.1 m straight
  msg::JointState c = b;
  c.stamp = Time::FromSeconds(1.2);
  for (double& th : c.wheel_angle) th += 0.1 / g.wheel_radius;
  Result<OdometryIncrement> short_inc = odo.Compute(a, b);
  Result<OdometryIncrement> long_inc = odo.Compute(a, c);
  ASSERT_TRUE(short_inc.ok() && long_inc.ok());
  EXPECT_NEAR(short_inc->dx, 0.1, 1e-12);
  EXPECT_NEAR(short_inc->covariance(0, 0), 0.1 * 4e-3, 1e-15);
  EXPECT_NEAR(short_inc->covariance(1, 1), 0.1 * 1e-3, 1e-15);
  EXPECT_NEAR(short_inc->covariance(2, 2), 0.1 * 2e-4, 1e-15);
  EXPECT_TRUE(long_inc->covariance.isApprox(2.0 * short_inc->covariance, 1e-12));
  EXPECT_NEAR(short_inc->residual_rms, 0.0, 1e-12);

  // A turn in place has no translation but the wheels travel, so its heading variance is > 0.
  msg::JointState t = a;
  t.steer_angle = TurnInPlaceSteerAngles(g);
  msg::JointState t2 = t;
  t2.stamp = Time::FromSeconds(1.1);
  const auto q = TurnInPlaceRadii(g);
  for (std::size_t i = 0; i < 6; ++i) t2.wheel_angle[i] = q[i] * 0.1 / g.wheel_radius;
  Result<OdometryIncrement> turn = odo.Compute(t, t2);
  ASSERT_TRUE(turn.ok());
  EXPECT_NEAR(turn->dyaw, 0.1, 1e-12);
  EXPECT_GT(turn->covariance(2, 2), 0.0);
}

TEST(WheelOdometry, SlipShowsInTheResidual) {
  const RoverGeometry g;
  WheelOdometry odo = MakeOdometry(g);
  msg::JointState a;
  a.stamp = Time::FromSeconds(1);
  msg::JointState b = a;
  b.stamp = Time::FromSeconds(1.1);
  for (double& th : b.wheel_angle) th = 0.05 / g.wheel_radius;
  b.wheel_angle[2] += 0.4;  // LR spins in sand
  Result<OdometryIncrement> inc = odo.Compute(a, b);
  ASSERT_TRUE(inc.ok());
  EXPECT_GT(inc->residual_rms, 5e-3);
  // Least squares spreads the spin: the estimate moves by a fraction of it only.
  EXPECT_NEAR(inc->dx, 0.05 + 0.4 * g.wheel_radius / 6, 5e-3);
}

TEST(WheelOdometry, ACalibratedSlipShortensTheDistanceNotTheTurn) {
  const RoverGeometry g;
  WheelOdometryOptions o;
  o.slip_ratio = 0.02;  // the wheels turn 2 % more than the ground they cover
  WheelOdometry odo = MakeOdometry(g, o);
  SampleWriter w(g);
  w.Emit();
  w.Arc(0.0, 10.0, 200);  // 10 m of rim distance straight ahead
  const Pose2 p = Integrate(odo, w.samples());
  EXPECT_NEAR(p.x, 9.8, 1e-9);
  EXPECT_NEAR(p.y, 0.0, 1e-12);
  // A turn in place: every wheel slips alike, so the heading scales too (the solve is linear).
  SampleWriter t(g);
  t.Emit();
  t.TurnInPlace(90 * kDegree, 60);
  EXPECT_NEAR(Integrate(odo, t.samples()).yaw, 0.98 * 90 * kDegree, 1e-9);
  for (const double bad : {-0.01, 0.5, std::nan("")}) {
    o.slip_ratio = bad;
    const Status s = o.Validate();
    EXPECT_FALSE(s.ok()) << bad;
    EXPECT_NE(s.message().find("slip_ratio"), std::string::npos) << s.message();
  }
}

TEST(WheelOdometry, RejectsBadSamples) {
  WheelOdometry odo = MakeOdometry();
  msg::JointState a;
  a.stamp = Time::FromSeconds(1);
  msg::JointState b = a;
  EXPECT_EQ(odo.Compute(a, b).status().code(), StatusCode::kInvalidArgument);  // same stamp
  b.stamp = Time::FromSeconds(5);
  EXPECT_EQ(odo.Compute(a, b).status().code(), StatusCode::kOutOfRange);  // gap
  b.stamp = Time::FromSeconds(1.02);
  b.wheel_angle[0] = 30.0;
  EXPECT_EQ(odo.Compute(a, b).status().code(), StatusCode::kOutOfRange);  // wheel jump
  b.wheel_angle[0] = std::nan("");
  EXPECT_EQ(odo.Compute(a, b).status().code(), StatusCode::kInvalidArgument);

  // Stream: a jump is reported and restarts the stream; a NaN sample is dropped.
  auto r = odo.Add(a);
  ASSERT_TRUE(r.ok());
  EXPECT_FALSE(r->has_value());
  msg::JointState j = a;
  j.stamp = Time::FromSeconds(1.02);
  j.wheel_angle[3] = 50.0;
  EXPECT_FALSE(odo.Add(j).ok());
  msg::JointState n = j;
  n.stamp = Time::FromSeconds(1.04);
  n.wheel_rate[0] = std::nan("");
  EXPECT_FALSE(odo.Add(n).ok());
  msg::JointState k = j;
  k.stamp = Time::FromSeconds(1.06);
  auto r2 = odo.Add(k);
  ASSERT_TRUE(r2.ok());
  ASSERT_TRUE(r2->has_value());
  EXPECT_NEAR((*r2)->dx, 0.0, 1e-12);  // measured from the restarted sample j
  // A long gap restarts silently.
  msg::JointState late = k;
  late.stamp = Time::FromSeconds(60);
  auto r3 = odo.Add(late);
  ASSERT_TRUE(r3.ok());
  EXPECT_FALSE(r3->has_value());
}

TEST(WheelOdometry, Params) {
  ParamSet p("pose");
  DeclareWheelOdometryParams(p);
  ASSERT_TRUE(p.LoadYamlString("odometry:\n  along_variance_per_m: 0.002\n  slip_ratio: 0.021\n",
                               "o.yaml").ok());
  Result<WheelOdometryOptions> o = WheelOdometryOptionsFromParams(p);
  ASSERT_TRUE(o.ok());
  EXPECT_DOUBLE_EQ(o->along_variance_per_m, 0.002);
  EXPECT_DOUBLE_EQ(o->slip_ratio, 0.021);
  ParamSet q("pose");
  DeclareWheelOdometryParams(q);
  ASSERT_TRUE(q.LoadYamlString("odometry:\n  max_interval_s: -1\n", "o.yaml").ok());
  Result<WheelOdometryOptions> bad = WheelOdometryOptionsFromParams(q);
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.status().message().find("o.yaml:2: key 'odometry.max_interval_s'"),
            std::string::npos)
      << bad.status().message();
  WheelOdometryOptions invalid;
  invalid.yaw_variance_per_m = -1;
  EXPECT_FALSE(WheelOdometry::Create(RoverGeometry(), invalid).ok());
}

}  // namespace
}  // namespace rover::dl::locomotion
