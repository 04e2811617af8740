#include "rover/dl/locomotion/ackermann.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "rover/base/units.hpp"

namespace rover::dl::locomotion {
namespace {

Eigen::Vector2d Pos(const RoverGeometry& g, int wheel) {
  return g.wheel_centre[static_cast<std::size_t>(wheel)].head<2>();
}

double SteerOfWheel(const DrivePlan& plan, int wheel) {
  for (int j = 0; j < kNumSteered; ++j) {
    if (kSteeredWheel[static_cast<std::size_t>(j)] == wheel) {
      return plan.steer_angle[static_cast<std::size_t>(j)];
    }
  }
  return 0.0;
}

// A geometry with the middle axle off the origin and an asymmetric layout, to catch formulas that
// only hold for the default rover.
RoverGeometry OddGeometry() {
  RoverGeometry g;
  g.wheel_centre = {Eigen::Vector3d(0.70, 0.52, 0.125),  Eigen::Vector3d(0.05, 0.50, 0.125),
                    Eigen::Vector3d(-0.58, 0.48, 0.125), Eigen::Vector3d(0.66, -0.49, 0.125),
                    Eigen::Vector3d(0.05, -0.51, 0.125), Eigen::Vector3d(-0.60, -0.50, 0.125)};
  g.bogie_pivot = Eigen::Vector2d(-0.27, 0.3);
  g.min_turn_radius = 1.1;
  g.max_steer_angle = 75 * kDegree;
  return g;
}

TEST(Ackermann, KnownArcForTheDefaultRover) {
  const RoverGeometry g;
  Result<DrivePlan> p = PlanArc(g, 0.5, 2.0, 0.04);
  ASSERT_TRUE(p.ok()) << p.status().ToString();
  // Centre (0, 2). LF/LR are 0.625 m fore/aft and 1.5 m from the centre line.
  const double inner_corner = std::hypot(0.3125, 0.75);  // 0.8125
  const double outer_corner = std::hypot(0.3125, 1.25);
  EXPECT_NEAR(p->wheel_distance[0], 2.0 * inner_corner, 1e-12);
  EXPECT_NEAR(p->wheel_distance[2], 2.0 * inner_corner, 1e-12);
  EXPECT_NEAR(p->wheel_distance[1], 2.0 * 0.75, 1e-12);
  EXPECT_NEAR(p->wheel_distance[3], 2.0 * outer_corner, 1e-12);
  EXPECT_NEAR(p->wheel_distance[4], 2.0 * 1.25, 1e-12);
  EXPECT_NEAR(p->wheel_rotation[4], 2.0 * 1.25 / 0.125, 1e-12);
  EXPECT_NEAR(p->steer_angle[0], std::atan2(0.3125, 0.75), 1e-12);   // LF steers left
  EXPECT_NEAR(p->steer_angle[1], -std::atan2(0.3125, 0.75), 1e-12);  // LR steers right
  EXPECT_NEAR(p->steer_angle[2], std::atan2(0.3125, 1.25), 1e-12);   // RF, less than LF
  EXPECT_NEAR(p->angle, 1.0, 1e-12);
  EXPECT_NEAR(p->wheel_speed[1], 0.04 * 0.75, 1e-12);
  EXPECT_NEAR(p->wheel_speed[4], 0.04 * 1.25, 1e-12);
  // Outside (right) wheels are faster than the inside ones.
  EXPECT_GT(p->wheel_speed[3], p->wheel_speed[0]);
  EXPECT_GT(p->wheel_speed[4], p->wheel_speed[1]);
  EXPECT_GT(p->wheel_speed[5], p->wheel_speed[2]);
  ASSERT_TRUE(p->has_centre);
  EXPECT_TRUE(p->turn_centre.isApprox(Eigen::Vector2d(0.0, 2.0)));
}

class AckermannArcs : public ::testing::TestWithParam<double> {};

TEST_P(AckermannArcs, WheelAxesMeetAtTheCentreAndPathsMatchTheRadii) {
  for (const RoverGeometry& g : {RoverGeometry(), OddGeometry()}) {
    ASSERT_TRUE(g.Validate().ok()) << g.Validate().ToString();
    const double k = GetParam() * g.MaxCurvature();
    const double s = 1.7;
    Result<DrivePlan> p = PlanArc(g, k, s, 0.05);
    ASSERT_TRUE(p.ok());
    const Eigen::Vector2d c(g.MiddleAxleX(), 1.0 / k);
    const double ref_radius = 1.0 / std::abs(k);
    for (int i = 0; i < kNumWheels; ++i) {
      const double d = SteerOfWheel(*p, i);
      EXPECT_LE(std::abs(d), g.max_steer_angle);
      // The wheel's axle direction passes through the turn centre.
      const Eigen::Vector2d axle(-std::sin(d), std::cos(d));
      const Eigen::Vector2d to_c = c - Pos(g, i);
      EXPECT_NEAR(axle.x() * to_c.y() - axle.y() * to_c.x(), 0.0, 1e-9) << "wheel " << i;
      // Arc length = radius of the wheel's circle * swept angle.
      EXPECT_NEAR(p->wheel_distance[static_cast<std::size_t>(i)], to_c.norm() / ref_radius * s,
                  1e-9);
      // Rolling direction matches the rigid-body velocity of the wheel for a forward motion.
      const Eigen::Vector2d v(1.0 - k * Pos(g, i).y(), k * (Pos(g, i).x() - g.MiddleAxleX()));
      EXPECT_NEAR(std::atan2(v.y(), v.x()), d, 1e-12);
      EXPECT_NEAR(p->wheel_speed[static_cast<std::size_t>(i)], v.norm() * p->speed, 1e-12);
      // Wheels on the outside of the turn (farther from the centre) turn faster.
      for (int j = 0; j < kNumWheels; ++j) {
        if ((c - Pos(g, j)).norm() > to_c.norm() + 1e-9) {
          EXPECT_GT(p->wheel_speed[static_cast<std::size_t>(j)],
                    p->wheel_speed[static_cast<std::size_t>(i)]);
        }
      }
    }
    EXPECT_NEAR(p->angle, k * s, 1e-12);
  }
}

INSTANTIATE_TEST_SUITE_P(Curvatures, AckermannArcs,
                         ::testing::Values(-1.0, -0.5, -0.1, 0.01, 0.3, 0.99, 1.0));

TEST(Ackermann, StraightLineAndBackwards) {
  const RoverGeometry g;
  Result<DrivePlan> p = PlanArc(g, 0.0, -0.8, 0.05);
  ASSERT_TRUE(p.ok());
  EXPECT_FALSE(p->has_centre);
  for (std::size_t j = 0; j < 4; ++j) EXPECT_EQ(p->steer_angle[j], 0.0);
  for (std::size_t i = 0; i < 6; ++i) {
    EXPECT_DOUBLE_EQ(p->wheel_distance[i], -0.8);
    EXPECT_DOUBLE_EQ(p->wheel_speed[i], -0.05);
    EXPECT_DOUBLE_EQ(p->wheel_rate[i], -0.4);
  }
}

TEST(Ackermann, MirrorSymmetry) {
  const RoverGeometry g;
  const auto left = ArcSteerAngles(g, 0.7);
  const auto right = ArcSteerAngles(g, -0.7);
  EXPECT_NEAR(left[0], -right[2], 1e-12);  // LF <-> RF
  EXPECT_NEAR(left[1], -right[3], 1e-12);  // LR <-> RR
  const auto rl = ArcPathRatios(g, 0.7);
  const auto rr = ArcPathRatios(g, -0.7);
  EXPECT_NEAR(rl[1], rr[4], 1e-12);
}

TEST(Ackermann, SpeedIsLimitedByTheFastestWheel) {
  RoverGeometry g;
  g.max_wheel_speed = 0.05;
  Result<DrivePlan> p = PlanArc(g, 1.0, 1.0, 0.05);
  ASSERT_TRUE(p.ok());
  double fastest = 0.0;
  for (double v : p->wheel_speed) fastest = std::max(fastest, std::abs(v));
  EXPECT_NEAR(fastest, 0.05, 1e-12);
  EXPECT_LT(p->speed, 0.05);
}

TEST(Ackermann, TurnInPlaceWheelsAreTangentToTheCircle) {
  for (const RoverGeometry& g : {RoverGeometry(), OddGeometry()}) {
    const double angle = 0.8;
    Result<DrivePlan> p = PlanTurnInPlace(g, angle, 0.05);
    ASSERT_TRUE(p.ok());
    EXPECT_TRUE(p->turn_in_place);
    const Eigen::Vector2d c(g.MiddleAxleX(), 0.0);
    double fastest = 0.0;
    for (int i = 0; i < kNumWheels; ++i) {
      const auto ui = static_cast<std::size_t>(i);
      const double d = SteerOfWheel(*p, i);
      const Eigen::Vector2d r = Pos(g, i) - c;
      const Eigen::Vector2d t(std::cos(d), std::sin(d));
      // Rolling direction perpendicular to the radius: tangent to the circle about the centre.
      EXPECT_NEAR(t.dot(r), 0.0, 1e-12) << i;
      // Signed path = the wheel's velocity for a CCW rotation, projected on its heading.
      const Eigen::Vector2d v(-r.y(), r.x());
      EXPECT_NEAR(p->wheel_distance[ui], t.dot(v) * angle, 1e-12);
      EXPECT_NEAR(std::abs(p->wheel_distance[ui]), r.norm() * angle, 1e-12);
      fastest = std::max(fastest, std::abs(p->wheel_speed[ui]));
      EXPECT_LE(std::abs(d), g.max_steer_angle);
    }
    EXPECT_NEAR(fastest, 0.05, 1e-12);
    // Counter-clockwise: the left side drives backwards and the right side forwards.
    EXPECT_LT(p->wheel_distance[1], 0.0);
    EXPECT_GT(p->wheel_distance[4], 0.0);
  }
  const RoverGeometry g;
  EXPECT_NEAR(TurnInPlaceSteerAngle(g, 0), -std::atan(0.625 / 0.5), 1e-12);
  const auto rates = TurnInPlaceWheelRates(g, 0.1);
  EXPECT_NEAR(rates[4], 0.5 * 0.1 / 0.125, 1e-12);
}

TEST(Ackermann, RejectsBadInput) {
  const RoverGeometry g;
  EXPECT_EQ(PlanArc(g, std::nan(""), 1.0, 0.05).status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(PlanArc(g, 1.01, 1.0, 0.05).status().code(), StatusCode::kOutOfRange);
  EXPECT_EQ(PlanArc(g, 0.1, 1.0, 0.0).status().code(), StatusCode::kOutOfRange);
  EXPECT_EQ(PlanTurnInPlace(g, INFINITY, 0.05).status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(PlanArc(g, 2.0, 1.0, 0.05).status().message().find("min turn radius"),
            std::string::npos);
}

}  // namespace
}  // namespace rover::dl::locomotion
