#include "rover/sim/physics/terrain_contact.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>

#include "rover/base/units.hpp"

namespace rover::sim::physics {

using terrain::HeightField;
using terrain::Soil;

namespace {

constexpr double kR = 0.125;
constexpr double kWidth = 0.16;

// A plane z = x tan(slope) on [-2, 2]^2 with one soil.
HeightField Plane(double slope_deg, Soil soil, double res = 0.05) {
  const int n = static_cast<int>(std::lround(4.0 / res)) + 1;
  HeightField h(n, n, res, Eigen::Vector2d(-2.0, -2.0));
  const double t = std::tan(DegToRad(slope_deg));
  for (int j = 0; j < h.ny(); ++j) {
    for (int i = 0; i < h.nx(); ++i) {
      h.at(i, j) = static_cast<float>((h.min_x() + i * res) * t);
      h.soil(i, j) = soil;
    }
  }
  return h;
}

TEST(TerrainContact, FlatGroundNormalForceFromPenetration) {
  const HeightField h = Plane(0.0, Soil::kFirmSoil);
  const ContactParams params;
  WheelKinematics w;
  w.center = Eigen::Vector3d(0.1, 0.2, kR - 0.004);
  const WheelContact c = EvaluateWheelContact(h, params, kR, kWidth, w, Eigen::Vector2d::Zero());
  ASSERT_TRUE(c.in_contact);
  EXPECT_EQ(c.num_samples, params.slices);  // only the bottom point of each slice
  EXPECT_NEAR(c.sinkage, 0.004, 1e-9);
  EXPECT_NEAR(c.normal_force, params.soil(Soil::kFirmSoil).stiffness * 0.004, 1e-6);
  EXPECT_TRUE(c.normal.isApprox(Eigen::Vector3d::UnitZ(), 1e-9));
  EXPECT_NEAR(c.point.z(), -0.004, 1e-9);
  EXPECT_NEAR(c.point.x(), 0.1, 1e-9);
  EXPECT_TRUE(c.force.isApprox(Eigen::Vector3d(0, 0, c.normal_force), 1e-9));
  EXPECT_EQ(c.soil, Soil::kFirmSoil);
  // Moving down into the ground adds Hunt-Crossley damping; moving out removes force.
  w.velocity = Eigen::Vector3d(0, 0, -0.01);
  const WheelContact down = EvaluateWheelContact(h, params, kR, kWidth, w, Eigen::Vector2d::Zero());
  EXPECT_NEAR(down.normal_force,
              c.normal_force * (1.0 + params.soil(Soil::kFirmSoil).damping * 0.01), 1e-6);
  w.velocity = Eigen::Vector3d(0, 0, 1.0);
  EXPECT_DOUBLE_EQ(
      EvaluateWheelContact(h, params, kR, kWidth, w, Eigen::Vector2d::Zero()).normal_force, 0.0);
  // In the air: no contact, the shear state relaxes.
  w.velocity.setZero();
  w.center.z() = kR + 0.01;
  const WheelContact air =
      EvaluateWheelContact(h, params, kR, kWidth, w, Eigen::Vector2d(1.0, 0.0));
  EXPECT_FALSE(air.in_contact);
  EXPECT_LT(air.shear_rate.x(), 0.0);
}

TEST(TerrainContact, SlopeContactFollowsTheSurfaceNormal) {
  const double slope = DegToRad(15.0);
  const HeightField h = Plane(15.0, Soil::kBedrock);
  const ContactParams params;
  const Eigen::Vector3d n(-std::sin(slope), 0.0, std::cos(slope));
  const Eigen::Vector3d surface_point(0.3, 0.0, 0.3 * std::tan(slope));
  WheelKinematics w;
  w.center = surface_point + n * (kR - 0.002);
  const WheelContact c = EvaluateWheelContact(h, params, kR, kWidth, w, Eigen::Vector2d::Zero());
  ASSERT_TRUE(c.in_contact);
  EXPECT_TRUE(c.normal.isApprox(n, 1e-6)) << c.normal.transpose();
  EXPECT_NEAR(c.sinkage, 0.002, 1e-5);
  EXPECT_NEAR(c.normal_force, params.soil(Soil::kBedrock).stiffness * 0.002, 5.0);
  // Rolling direction is up the slope for a wheel whose axle points along +y.
  EXPECT_TRUE(c.forward.isApprox(Eigen::Vector3d(std::cos(slope), 0, std::sin(slope)), 1e-6));
  EXPECT_NEAR(WheelGap(h, kR, w.center, w.axis), -0.002 / std::cos(slope), 1e-5);
}

TEST(TerrainContact, FanSamplesFeelAStepAheadOfTheWheel) {
  HeightField h = Plane(0.0, Soil::kFirmSoil, 0.02);
  for (int j = 0; j < h.ny(); ++j) {
    for (int i = 0; i < h.nx(); ++i) {
      if (i >= 105) h.at(i, j) = 0.3f;  // a wall: a ramp from x = 0.08 up to 0.3 m at x = 0.10
    }
  }
  const ContactParams params;
  WheelKinematics w;
  // Touching the ground; the 75 deg fan point (x + R sin 75, R (1 - cos 75) = 9.3 cm up) 8 mm
  // into the ramp, where the ramp is 12 cm high.
  const double t = 75.0 * std::numbers::pi / 180.0;
  w.center = Eigen::Vector3d(0.08 - kR * std::sin(t) + 0.008, 0.0, kR);
  const WheelContact c = EvaluateWheelContact(h, params, kR, kWidth, w, Eigen::Vector2d::Zero());
  ASSERT_TRUE(c.in_contact);
  EXPECT_LT(c.force.x(), -10.0) << "the wall must push the wheel back";
  EXPECT_GT(c.point.x(), w.center.x() + 0.1);
  // Without the fan the wheel would not notice the wall.
  ContactParams no_fan;
  no_fan.fan_angles_deg = {0.0, 0.0, 0.0};
  EXPECT_FALSE(EvaluateWheelContact(h, no_fan, kR, kWidth, w, Eigen::Vector2d::Zero()).in_contact);
}

// A parked wheel at the foot of a 45 deg bank behind it: the bank pushes on a rim sample behind
// the wheel along the bank's normal, which is not the rim's radius there. That normal force must
// not turn the wheel about its axle (a rigid rim's normal forces pass through the axle). Without
// the correction the moment made a slow inner wheel on uneven ground fight its motor in the
// tightest arc (the MOT stall of the first autonav run).
TEST(TerrainContact, NormalForcesDoNotSpinTheWheel) {
  HeightField h = Plane(0.0, Soil::kFirmSoil, 0.01);
  for (int j = 0; j < h.ny(); ++j) {
    for (int i = 0; i < h.nx(); ++i) {
      const double x = h.min_x() + i * 0.01;
      h.at(i, j) = static_cast<float>(std::max(0.0, -0.08 - x));  // the bank, up towards -x
    }
  }
  const ContactParams params;
  for (double x : {-0.035, -0.04, -0.045}) {
    WheelKinematics w;
    w.center = Eigen::Vector3d(x, 0.0, kR - 0.002);  // 2 mm into the floor
    const WheelContact c = EvaluateWheelContact(h, params, kR, kWidth, w, Eigen::Vector2d::Zero());
    ASSERT_TRUE(c.in_contact);
    ASSERT_GT(c.num_samples, params.slices) << "a fan sample must feel the bank at x = " << x;
    EXPECT_GT(c.force.x(), 1.0) << "the bank pushes the wheel forward at x = " << x;
    // At rest with no shear there is no traction, so no moment about the axle.
    const Eigen::Vector3d moment = (c.point - w.center).cross(c.force) + c.torque;
    EXPECT_NEAR(w.axis.dot(moment), 0.0, 1e-9 * c.normal_force) << "x = " << x;
  }
}

TEST(TerrainContact, SlipTractionCurveAndSteadySlip) {
  const SoilParams firm = DefaultSoilParams(Soil::kFirmSoil);
  EXPECT_DOUBLE_EQ(TractionCoefficient(firm, 0.0), 0.0);
  EXPECT_NEAR(TractionCoefficient(firm, firm.shear_k), firm.mu_max * (1 - std::exp(-1.0)), 1e-12);
  EXPECT_NEAR(TractionCoefficient(firm, -firm.shear_k), -firm.mu_max * (1 - std::exp(-1.0)), 1e-12);
  // The inverse: mu(s) = tan(theta) + c_rr.
  const double s15 = SteadyStateSlip(firm, DegToRad(15.0));
  EXPECT_NEAR(TractionCoefficient(firm, s15), std::tan(DegToRad(15.0)) + firm.rolling_resistance,
              1e-12);
  // The design targets: 3-15% on a 15 deg firm slope, > 50% on 20 deg loose sand, little on
  // flat firm ground, and slip growing with slope and with softer soil.
  EXPECT_GT(s15, 0.03);
  EXPECT_LT(s15, 0.15);
  EXPECT_GT(SteadyStateSlip(DefaultSoilParams(Soil::kLooseSand), DegToRad(20.0)), 0.5);
  EXPECT_LT(SteadyStateSlip(firm, 0.0), 0.01);
  EXPECT_LT(SteadyStateSlip(firm, DegToRad(10.0)), s15);
  EXPECT_LT(SteadyStateSlip(DefaultSoilParams(Soil::kBedrock), DegToRad(15.0)), s15);
  EXPECT_GT(SteadyStateSlip(DefaultSoilParams(Soil::kLooseSand), DegToRad(15.0)), s15);
  EXPECT_TRUE(std::isinf(SteadyStateSlip(DefaultSoilParams(Soil::kLooseSand), DegToRad(30.0))));
}

// Integrates the shear state of a wheel rolling at rim speed V with slip s on flat ground and
// checks that it converges to z = s/K, i.e. traction mu(s) N.
TEST(TerrainContact, ShearStateReachesTheSteadySlipTraction) {
  const HeightField h = Plane(0.0, Soil::kFirmSoil);
  ContactParams params;
  const SoilParams& soil = params.soil(Soil::kFirmSoil);
  const double v_rim = 0.05, slip = 0.06;
  WheelKinematics w;
  w.center = Eigen::Vector3d(0, 0, kR - 0.004);
  w.angular_velocity = Eigen::Vector3d(0, v_rim / kR, 0);
  w.velocity = Eigen::Vector3d(v_rim * (1 - slip), 0, 0);
  Eigen::Vector2d z = Eigen::Vector2d::Zero();
  WheelContact c;
  for (int k = 0; k < 20000; ++k) {  // 20 s at 1 ms
    c = EvaluateWheelContact(h, params, kR, kWidth, w, z);
    z += 1e-3 * c.shear_rate;
  }
  EXPECT_NEAR(z.x(), slip / soil.shear_k, 1e-3);
  EXPECT_NEAR(z.y(), 0.0, 1e-9);
  EXPECT_NEAR(c.slip_ratio, slip, 1e-12);
  const double resistance = soil.rolling_resistance * c.normal_force *
                            std::tanh(w.velocity.x() / params.rolling_speed_eps);
  EXPECT_NEAR(c.longitudinal_force + resistance, TractionCoefficient(soil, slip) * c.normal_force,
              1e-2);
}

TEST(TerrainContact, ParkedWheelHoldsItsShearAndCapLimitsIt) {
  const HeightField h = Plane(0.0, Soil::kLooseSand);
  const ContactParams params;
  WheelKinematics w;
  w.center = Eigen::Vector3d(0, 0, kR - 0.008);
  // At rest a loaded shear state stays (no creep) and keeps pushing.
  const Eigen::Vector2d z(0.7, -0.2);
  const WheelContact c = EvaluateWheelContact(h, params, kR, kWidth, w, z);
  EXPECT_TRUE(c.shear_rate.isZero(1e-12));
  EXPECT_GT(c.longitudinal_force, 0.0);
  EXPECT_LT(c.lateral_force, 0.0);
  // Spinning in place at the cap: the state does not grow further.
  w.angular_velocity = Eigen::Vector3d(0, 0.4, 0);
  const Eigen::Vector2d capped(params.shear_cap, 0.0);
  const WheelContact spin = EvaluateWheelContact(h, params, kR, kWidth, w, capped);
  EXPECT_LE(spin.shear_rate.x(), 1e-12);
  EXPECT_NEAR(spin.slip_ratio, 1.0, 1e-12);
  EXPECT_NEAR(
      spin.longitudinal_force,
      params.soil(Soil::kLooseSand).mu_max * (1 - std::exp(-params.shear_cap)) * spin.normal_force,
      0.05 * spin.normal_force);
}

TEST(TerrainContact, PointContactPushesOutAndRubs) {
  const HeightField h = Plane(0.0, Soil::kBedrock);
  const PointContactParams p;
  EXPECT_TRUE(
      EvaluatePointContact(h, p, Eigen::Vector3d(0, 0, 0.01), Eigen::Vector3d::Zero()).isZero());
  const Eigen::Vector3d f =
      EvaluatePointContact(h, p, Eigen::Vector3d(0, 0, -0.01), Eigen::Vector3d(0.1, 0, 0));
  EXPECT_NEAR(f.z(), p.stiffness * 0.01, 1e-6);
  EXPECT_NEAR(f.x(), -p.friction * f.z() * std::tanh(0.1 / p.slip_speed_eps), 1e-6);
}

TEST(TerrainContact, ParamsValidate) {
  ContactParams p;
  EXPECT_TRUE(p.Validate().ok());
  p.slices = 0;
  EXPECT_FALSE(p.Validate().ok());
  p = ContactParams{};
  p.soils[1].shear_k = -1.0;
  const Status st = p.Validate();
  EXPECT_NE(st.message().find("firm_soil.shear_k"), std::string::npos) << st.message();
  PointContactParams b;
  b.friction = -1.0;
  EXPECT_FALSE(b.Validate().ok());
}

}  // namespace
}  // namespace rover::sim::physics
