#include "rover/sim/physics/rover_simulation.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <numbers>

#include "rover/base/units.hpp"

namespace rover::sim::physics {

using terrain::HeightField;
using terrain::Soil;

namespace {

constexpr double kSpeed = 0.05;  // [m/s] MER-like drive speed

// Terrain on [x0, x0 + length] x [-width/2, width/2] with height z(x, y) and one soil.
std::shared_ptr<HeightField> MakeTerrain(double x0, double length, double width, double res,
                                         Soil soil,
                                         const std::function<double(double, double)>& z) {
  auto h = std::make_shared<HeightField>(static_cast<int>(std::lround(length / res)) + 1,
                                         static_cast<int>(std::lround(width / res)) + 1, res,
                                         Eigen::Vector2d(x0, -width / 2));
  for (int j = 0; j < h->ny(); ++j) {
    for (int i = 0; i < h->nx(); ++i) {
      h->at(i, j) = static_cast<float>(z(h->min_x() + i * res, h->min_y() + j * res));
      h->soil(i, j) = soil;
    }
  }
  return h;
}

std::shared_ptr<HeightField> Slope(double slope_deg, Soil soil) {
  const double t = std::tan(DegToRad(slope_deg));
  return MakeTerrain(-4.0, 12.0, 6.0, 0.1, soil, [t](double x, double) { return x * t; });
}

std::unique_ptr<RoverSimulation> MakeSim(std::shared_ptr<HeightField> terrain,
                                         const RoverModelParams& params = RoverModelParams{}) {
  auto sim = RoverSimulation::Create(params, std::move(terrain), StartPose{0.0, 0.0, 0.0});
  EXPECT_TRUE(sim.ok()) << sim.status().ToString();
  return sim.ok() ? std::move(sim.value()) : nullptr;
}

double CountsPerRad(const RoverSimulation& sim, int motor) {
  return sim.params().motors[motor].CountsPerRad();
}

// Commands all six drive motors to roll at `speed` [m/s] of rim speed.
void DriveAll(RoverSimulation& sim, double speed, double current_limit = 1.0) {
  const double r = sim.params().geometry.wheel_radius;
  for (int m = hw::kDriveLF; m <= hw::kDriveRR; ++m) {
    ASSERT_TRUE(sim.SetMotorGoal(m, MotorMode::kVelocity, 0.0, speed / r * CountsPerRad(sim, m),
                                 current_limit)
                    .ok());
  }
}

// Mean wheel rim travel [m] from the drive encoders.
double WheelTravel(const RoverSimulation& sim) {
  double sum = 0.0;
  for (int m = hw::kDriveLF; m <= hw::kDriveRR; ++m) {
    sum += sim.Motor(m).position_counts / CountsPerRad(sim, m);
  }
  return sum / 6.0 * sim.params().geometry.wheel_radius;
}

Eigen::Vector3d Position(const RoverSimulation& sim) {
  return sim.Readings().chassis.pose_site.translation();
}

TEST(RoverSimulation, RestsOnFlatGroundWithoutDrift) {
  auto sim =
      MakeSim(MakeTerrain(-3, 6, 4, 0.05, Soil::kFirmSoil, [](double, double) { return 0; }));
  ASSERT_NE(sim, nullptr);
  EXPECT_DOUBLE_EQ(sim->time(), 0.0);
  const RoverReadings r0 = sim->Readings();
  ASSERT_TRUE(sim->Advance(5.0).ok());
  const RoverReadings r1 = sim->Readings();
  EXPECT_NEAR(r1.time_s, 5.0, 1e-9);
  const Eigen::Vector3d drift =
      r1.chassis.pose_site.translation() - r0.chassis.pose_site.translation();
  EXPECT_LT(drift.norm(), 1e-3) << drift.transpose();
  EXPECT_LT(r1.chassis.linear_velocity_site.norm(), 1e-4);

  // The rover stands level on all six wheels, sharing the weight about equally.
  const double weight = sim->params().masses.Total() * sim->params().gravity;
  double total = 0.0;
  for (const WheelReading& w : r1.wheels) {
    EXPECT_TRUE(w.in_contact);
    EXPECT_NEAR(w.normal_force_n, weight / 6, 0.25 * weight / 6);
    total += w.normal_force_n;
  }
  EXPECT_NEAR(total, weight, 0.01 * weight);
  EXPECT_NEAR(r1.rocker_left_rad, 0.0, 0.01);
  EXPECT_NEAR(r1.chassis.pose_site.translation().z(), 0.0, 0.01);  // C origin at ground level
  // Accelerometer truth at rest: +g along the chassis z axis.
  EXPECT_TRUE(
      r1.chassis.specific_force_body.isApprox(Eigen::Vector3d(0, 0, sim->params().gravity), 1e-3))
      << r1.chassis.specific_force_body.transpose();
  // Camera mounts: mast head at ~1.5 m, HAZCAMs at ~0.5 m looking down 45 deg.
  EXPECT_NEAR(r1.cameras.mast_head_site.translation().z(), 1.5, 0.05);
  EXPECT_NEAR(r1.cameras.hazcam_front_site.translation().z(), 0.5, 0.05);
  const Eigen::Vector3d bore = r1.cameras.hazcam_front_site.linear().col(0);
  EXPECT_NEAR(bore.z(), -std::sin(DegToRad(45)), 0.02);
  EXPECT_GT(bore.x(), 0.6);
  EXPECT_LT(r1.cameras.hazcam_rear_site.linear().col(0).x(), -0.6);
  // Part poses: wheel frames at the wheel centres, axles along y.
  const hwconfig::RoverDescription& g = sim->params().geometry;
  EXPECT_TRUE(r1.bodies.wheels[hwconfig::kWheelLF].translation().isApprox(r1.wheels[hwconfig::kWheelLF].center_site));
  EXPECT_NEAR(r1.bodies.wheels[hwconfig::kWheelRR].translation().x(), g.rear_wheel_x, 0.01);
  EXPECT_NEAR(r1.bodies.wheels[hwconfig::kWheelRR].translation().y(), -g.half_track, 0.01);
  EXPECT_NEAR(r1.bodies.wheels[hwconfig::kWheelLM].linear().col(1).y(), 1.0, 1e-3);
  EXPECT_NEAR(r1.bodies.bogies[0].translation().z(), g.bogie_pivot_z, 0.01);
}

TEST(RoverSimulation, RockerDifferentialHoldsWhenOneSideClimbsABump) {
  // A 12 cm bump under the left wheels only.
  auto terrain = MakeTerrain(-3, 7, 4, 0.05, Soil::kBedrock, [](double x, double y) {
    if (y < 0.2 || x < 0.9 || x > 1.5) return 0.0;
    return 0.06 * (1.0 - std::cos(2 * std::numbers::pi * (x - 0.9) / 0.6));
  });
  auto sim = MakeSim(terrain);
  ASSERT_NE(sim, nullptr);
  DriveAll(*sim, 0.1);
  double max_rocker = 0.0, max_mismatch = 0.0, max_bogie = 0.0;
  for (int k = 0; k < 200; ++k) {  // 20 s, about 2 m
    ASSERT_TRUE(sim->Advance(0.1).ok());
    const RoverReadings r = sim->Readings();
    max_rocker = std::max(max_rocker, std::abs(r.rocker_left_rad));
    max_bogie = std::max(max_bogie, std::abs(r.bogie_left_rad));
    max_mismatch = std::max(max_mismatch, std::abs(r.rocker_left_rad + r.rocker_right_rad));
  }
  EXPECT_GT(max_rocker, 0.03);
  EXPECT_GT(max_bogie, 0.05);
  EXPECT_LT(max_mismatch, 0.002);
  EXPECT_LT(max_mismatch, 0.05 * max_rocker);
  EXPECT_GT(Position(*sim).x(), 1.5);
}

TEST(RoverSimulation, StraightDriveOnFlatFirmGroundMatchesOdometry) {
  auto sim =
      MakeSim(MakeTerrain(-3, 8, 4, 0.05, Soil::kFirmSoil, [](double, double) { return 0; }));
  ASSERT_NE(sim, nullptr);
  const Eigen::Vector3d p0 = Position(*sim);
  const double w0 = WheelTravel(*sim);
  DriveAll(*sim, kSpeed);
  ASSERT_TRUE(sim->Advance(20.0).ok());
  for (int m = hw::kDriveLF; m <= hw::kDriveRR; ++m) {
    ASSERT_TRUE(sim->SetMotorGoal(m, MotorMode::kOff, 0, 0, 0).ok());
  }
  ASSERT_TRUE(sim->Advance(1.0).ok());
  const double travelled = (Position(*sim) - p0).norm();
  const double commanded = WheelTravel(*sim) - w0;
  EXPECT_NEAR(commanded, 20.0 * kSpeed, 0.05);
  EXPECT_NEAR(travelled, commanded, 0.01 * commanded);
  EXPECT_LT(travelled, commanded);  // some slip, never more distance than the wheels turned
  const RoverReadings r = sim->Readings();
  EXPECT_NEAR(r.chassis.pose_site.translation().y(), 0.0, 0.01);  // went straight
  for (int m = hw::kDriveLF; m <= hw::kDriveRR; ++m) EXPECT_EQ(r.motors[m].faults, kMotorFaultNone);
}

// Drives uphill on a uniform slope and returns the slip 1 - distance / wheel travel over the
// last 9 s of a 12 s drive (after the shear states have built up).
double UphillSlip(double slope_deg, Soil soil) {
  auto sim = MakeSim(Slope(slope_deg, soil));
  if (sim == nullptr) return std::nan("");
  DriveAll(*sim, kSpeed);
  if (!sim->Advance(3.0).ok()) return std::nan("");
  const Eigen::Vector3d p0 = Position(*sim);
  const double w0 = WheelTravel(*sim);
  if (!sim->Advance(9.0).ok()) return std::nan("");
  const Eigen::Vector3d heading(std::cos(DegToRad(slope_deg)), 0.0, std::sin(DegToRad(slope_deg)));
  const double travelled = (Position(*sim) - p0).dot(heading);
  const double wheel = WheelTravel(*sim) - w0;
  return 1.0 - travelled / wheel;
}

TEST(RoverSimulation, UphillSlipOnFirm15DegreeSlopeIsModerate) {
  const double slip = UphillSlip(15.0, Soil::kFirmSoil);
  EXPECT_GT(slip, 0.03);
  EXPECT_LT(slip, 0.15);
  // Close to the steady-state prediction of the slip-traction curve.
  EXPECT_NEAR(slip, SteadyStateSlip(DefaultSoilParams(Soil::kFirmSoil), DegToRad(15.0)), 0.02);
}

TEST(RoverSimulation, UphillSlipOnLooseSand20DegreeSlopeIsHigh) {
  const double slip = UphillSlip(20.0, Soil::kLooseSand);
  EXPECT_GT(slip, 0.5);
}

TEST(RoverSimulation, DrivingIntoAWallStallsTheDriveMotors) {
  // A 30 cm step 0.3 m ahead of the front wheels' rims.
  auto terrain = MakeTerrain(-3, 6, 4, 0.05, Soil::kFirmSoil,
                             [](double x, double) { return x >= 1.05 ? 0.3 : 0.0; });
  auto sim = MakeSim(terrain);
  ASSERT_NE(sim, nullptr);
  // A low current limit: the wheels cannot spin out on firm soil, so they stop and stall.
  DriveAll(*sim, kSpeed, 0.2);
  int stalled = 0;
  for (int k = 0; k < 200 && stalled < 6; ++k) {  // up to 20 s
    ASSERT_TRUE(sim->Advance(0.1).ok());
    stalled = 0;
    for (int m = hw::kDriveLF; m <= hw::kDriveRR; ++m) {
      if (sim->Motor(m).faults & kMotorFaultStall) ++stalled;
    }
  }
  EXPECT_EQ(stalled, 6);
  const RoverReadings r = sim->Readings();
  EXPECT_LT(r.chassis.pose_site.translation().x(), 1.05 - 0.625 - 0.1);
  for (int m = hw::kDriveLF; m <= hw::kDriveRR; ++m) {
    EXPECT_EQ(r.motors[m].mode, MotorMode::kOff);
    EXPECT_EQ(r.motors[m].faults & (kMotorFaultOverCurrent | kMotorFaultOverTemperature), 0u);
  }
  // Latched: new goals are refused until the faults are cleared.
  EXPECT_EQ(sim->SetMotorGoal(hw::kDriveLF, MotorMode::kVelocity, 0, 100, 0.2).code(),
            StatusCode::kFailedPrecondition);
  ASSERT_TRUE(sim->ClearMotorFaults(hw::kDriveLF).ok());
  EXPECT_TRUE(sim->SetMotorGoal(hw::kDriveLF, MotorMode::kVelocity, 0, -100, 0.2).ok());
}

TEST(RoverSimulation, SteersCornerWheelsToCommandedAngles) {
  auto sim =
      MakeSim(MakeTerrain(-3, 6, 4, 0.05, Soil::kFirmSoil, [](double, double) { return 0; }));
  ASSERT_NE(sim, nullptr);
  // Turn-in-place pattern (MER): corner wheels square to the line to the rover centre.
  const hwconfig::RoverDescription& g = sim->params().geometry;
  const double angle = std::atan2(g.front_wheel_x, g.half_track);  // 51 deg
  const double corner_radius = std::hypot(g.front_wheel_x, g.half_track);
  const double goals[4] = {-angle, angle, angle, -angle};  // LF LR RF RR
  for (int i = 0; i < 4; ++i) {
    const int m = hw::kSteerLF + i;
    const double cpr = CountsPerRad(*sim, m);
    ASSERT_TRUE(sim->SetMotorGoal(m, MotorMode::kPosition, goals[i] * cpr, 0.2 * cpr, 0.8).ok());
  }
  // The mast pans and tilts too.
  const double pan_cpr = CountsPerRad(*sim, hw::kMastPan), tilt_cpr = CountsPerRad(*sim, hw::kMastTilt);
  ASSERT_TRUE(sim->SetMotorGoal(hw::kMastPan, MotorMode::kPosition, DegToRad(90) * pan_cpr,
                                0.5 * pan_cpr, 0.8)
                  .ok());
  ASSERT_TRUE(sim->SetMotorGoal(hw::kMastTilt, MotorMode::kPosition, DegToRad(-30) * tilt_cpr,
                                0.5 * tilt_cpr, 0.8)
                  .ok());
  ASSERT_TRUE(sim->Advance(5.0).ok());
  const RoverReadings r = sim->Readings();
  for (int i = 0; i < 4; ++i) {
    const int m = hw::kSteerLF + i;
    EXPECT_NEAR(r.joint_angle_rad[m], goals[i], DegToRad(0.5)) << hw::MotorName(m);
    EXPECT_NEAR(r.motors[m].position_counts, goals[i] * CountsPerRad(*sim, m),
                DegToRad(0.5) * CountsPerRad(*sim, m));
    EXPECT_TRUE(r.motors[m].goal_reached) << hw::MotorName(m);
    EXPECT_EQ(r.motors[m].faults, kMotorFaultNone);
  }
  EXPECT_NEAR(r.joint_angle_rad[hw::kMastPan], DegToRad(90), DegToRad(0.5));
  EXPECT_NEAR(r.joint_angle_rad[hw::kMastTilt], DegToRad(-30), DegToRad(0.5));
  // The mast head now looks left (+y) and down.
  const Eigen::Vector3d look = r.cameras.mast_head_site.linear().col(0);
  EXPECT_NEAR(look.y(), std::cos(DegToRad(30)), 0.02);
  EXPECT_NEAR(look.z(), -std::sin(DegToRad(30)), 0.02);
  // Then turn in place with the wheels steered: the rover yaws.
  const double yaw0 =
      std::atan2(r.chassis.pose_site.linear()(1, 0), r.chassis.pose_site.linear()(0, 0));
  const double rr = sim->params().geometry.wheel_radius;
  // Left wheels backwards, right wheels forwards: counter-clockwise (positive) yaw; wheel
  // speeds proportional to their distance from the centre.
  for (int m = hw::kDriveLF; m <= hw::kDriveRR; ++m) {
    const double dir = m < hw::kDriveRF ? -1.0 : 1.0;
    const bool middle = m == hw::kDriveLM || m == hw::kDriveRM;
    const double v = kSpeed * (middle ? g.half_track / corner_radius : 1.0);
    ASSERT_TRUE(
        sim->SetMotorGoal(m, MotorMode::kVelocity, 0, dir * v / rr * CountsPerRad(*sim, m), 1.0)
            .ok());
  }
  ASSERT_TRUE(sim->Advance(5.0).ok());
  const RoverReadings r2 = sim->Readings();
  const double yaw1 =
      std::atan2(r2.chassis.pose_site.linear()(1, 0), r2.chassis.pose_site.linear()(0, 0));
  EXPECT_GT(yaw1 - yaw0, DegToRad(10));
  EXPECT_LT(
      (r2.chassis.pose_site.translation() - r.chassis.pose_site.translation()).head<2>().norm(),
      0.05);
}

// Moves the four arm joints to `q` along a straight joint-space line, the joint with the
// largest travel at `rate` [rad/s] (as ddl-motor synchronises a group).
void ArmTo(RoverSimulation& sim, const hwconfig::ArmAngles& q, double rate) {
  const RoverReadings now = sim.Readings();
  double largest = 1e-9;
  for (int j = 0; j < hwconfig::kArmJoints; ++j) {
    largest = std::max(largest, std::abs(q[static_cast<std::size_t>(j)] -
                                         now.joint_angle_rad[hw::kArmAzimuth + j]));
  }
  for (int j = 0; j < hwconfig::kArmJoints; ++j) {
    const int m = hw::kArmAzimuth + j;
    const double cpr = CountsPerRad(sim, m);
    const double travel = std::abs(q[static_cast<std::size_t>(j)] - now.joint_angle_rad[m]);
    ASSERT_TRUE(sim.SetMotorGoal(m, MotorMode::kPosition, q[static_cast<std::size_t>(j)] * cpr,
                                 std::max(1e-3, rate * travel / largest) * cpr, 0.8)
                    .ok());
  }
}

TEST(RoverSimulation, TheKinematicArmFollowsItsMotorsAndItsFaceStopsOnTheGround) {
  // Flat ground with a 10 cm step 1.05 m ahead: the instrument comes down on it.
  auto sim = MakeSim(MakeTerrain(-3, 6, 4, 0.02, Soil::kFirmSoil,
                                 [](double x, double) { return x > 0.95 && x < 1.3 ? 0.10 : 0.0; }));
  ASSERT_NE(sim, nullptr);
  const hwconfig::RoverDescription& g = sim->params().geometry;
  RoverReadings r = sim->Readings();
  for (int j = 0; j < hwconfig::kArmJoints; ++j) {
    EXPECT_NEAR(r.joint_angle_rad[hw::kArmAzimuth + j], g.arm.stow[static_cast<std::size_t>(j)], 1e-6);
  }
  EXPECT_FALSE(r.tool_contact);
  const Eigen::Isometry3d site_from_rover = r.chassis.pose_site;
  // Above the step, face down, 5 cm clear of it.
  const Eigen::Vector3d above_site(1.05, 0.0, 0.15);
  const Result<hwconfig::ArmAngles> hover = g.arm.FaceDown(site_from_rover.inverse() * above_site);
  ASSERT_TRUE(hover.ok()) << hover.status().ToString();
  ArmTo(*sim, *hover, 0.4);
  ASSERT_TRUE(sim->Advance(12.0).ok());
  r = sim->Readings();
  EXPECT_LT((r.tool_point - above_site).norm(), 0.01) << r.tool_point.transpose();
  EXPECT_FALSE(r.tool_contact);
  for (int j = 0; j < hwconfig::kArmJoints; ++j) {
    EXPECT_TRUE(r.motors[hw::kArmAzimuth + j].goal_reached) << j;
  }
  // Then aimed 5 cm into the step: the face rests on it, the switch closes, the joints stop
  // short of their goals and the motors, still pushing, stall.
  const Result<hwconfig::ArmAngles> into =
      g.arm.FaceDown(site_from_rover.inverse() * Eigen::Vector3d(1.05, 0.0, 0.05));
  ASSERT_TRUE(into.ok());
  ArmTo(*sim, *into, 0.05);
  bool contact = false;
  for (int i = 0; i < 100 && !contact; ++i) {
    ASSERT_TRUE(sim->Advance(0.1).ok());
    contact = sim->Readings().tool_contact;
  }
  ASSERT_TRUE(contact);
  r = sim->Readings();
  EXPECT_NEAR(r.tool_point.z(), 0.10, hwconfig::ArmDescription{}.contact_standoff + 1e-3) << r.tool_point.transpose();
  EXPECT_NEAR(r.tool_point.x(), 1.05, 0.01);
  ASSERT_TRUE(sim->Advance(3.0).ok());
  r = sim->Readings();
  EXPECT_GE(r.tool_point.z(), 0.10 - 1e-6);  // never into the ground
  bool stalled = false;
  for (int j = 0; j < hwconfig::kArmJoints; ++j) {
    stalled = stalled || (r.motors[hw::kArmAzimuth + j].faults & kMotorFaultStall) != 0;
  }
  EXPECT_TRUE(stalled);
}

TEST(RoverSimulation, SameInputsGiveTheSameTrajectory) {
  auto terrain = Slope(8.0, Soil::kLooseSand);
  auto a = MakeSim(terrain);
  auto b = MakeSim(terrain);
  ASSERT_NE(a, nullptr);
  ASSERT_NE(b, nullptr);
  DriveAll(*a, kSpeed);
  DriveAll(*b, kSpeed);
  ASSERT_TRUE(a->Advance(2.0).ok());
  ASSERT_TRUE(b->Advance(0.7).ok());  // different chunking, same control ticks
  ASSERT_TRUE(b->Advance(1.3).ok());
  EXPECT_TRUE(Position(*a).isApprox(Position(*b), 1e-9));
  // Reset puts the rover back.
  const Eigen::Vector3d start = Position(*b);
  ASSERT_TRUE(a->Reset({0.0, 0.0, 0.0}).ok());
  EXPECT_DOUBLE_EQ(a->time(), 0.0);
  EXPECT_NEAR(WheelTravel(*a), 0.0, 1e-3);
  EXPECT_GT((Position(*a) - start).norm(), 0.05);
  EXPECT_EQ(a->Motor(hw::kDriveLF).mode, MotorMode::kOff);
}

TEST(RoverSimulation, RejectsBadInput) {
  auto terrain = MakeTerrain(-3, 6, 4, 0.05, Soil::kFirmSoil, [](double, double) { return 0; });
  RoverModelParams bad;
  bad.masses.wheel = -1.0;
  EXPECT_EQ(RoverSimulation::Create(bad, terrain, {}).status().code(),
            StatusCode::kInvalidArgument);
  EXPECT_EQ(RoverSimulation::Create(RoverModelParams{}, nullptr, {}).status().code(),
            StatusCode::kInvalidArgument);
  EXPECT_EQ(RoverSimulation::Create(RoverModelParams{}, terrain, {50.0, 0.0, 0.0}).status().code(),
            StatusCode::kOutOfRange);
  auto sim = MakeSim(terrain);
  ASSERT_NE(sim, nullptr);
  EXPECT_EQ(sim->SetMotorGoal(hw::kNumMotors, MotorMode::kVelocity, 0, 0, 1).code(),
            StatusCode::kOutOfRange);
  EXPECT_EQ(sim->SetMotorGoal(-1, MotorMode::kVelocity, 0, 0, 1).code(), StatusCode::kOutOfRange);
  EXPECT_EQ(sim->SetMotorGoal(hw::kSteerLF, MotorMode::kPosition, 1e9, 100, 0.5).code(),
            StatusCode::kOutOfRange);
  EXPECT_EQ(sim->Advance(0.0).code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(sim->Advance(std::nan("")).code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(sim->Reset({std::nan(""), 0, 0}).code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(sim->SetAmbientTemperature(std::nan("")).code(), StatusCode::kInvalidArgument);
  EXPECT_TRUE(sim->SetAmbientTemperature(-80.0).ok());
}

}  // namespace
}  // namespace rover::sim::physics
