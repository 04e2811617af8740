// The simulator's rover and the stack's rover description must be one rover. The simulator
// builds a Simbody model from the `geometry.*` parameters it reads; dl-locomotion and dl-pose
// (and the application layer) read the same keys. This test builds the simulator as rover-sim
// does, poses the Simbody model that was actually built at chosen joint angles and compares
// every part with what the stack derives from its own copy of the parameters: wheel centres,
// pivots and the suspension kinematics with their sign conventions, steering axes, mast head,
// camera mounts, belly and IMU; then the rendered cameras, the camera driver's calibration file
// and the hardware calibration's suspension limits. A change to either side alone fails here.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "rover/base/param_binder.hpp"
#include "rover/ddl/camera/camera_calibration.hpp"
#include "rover/dl/locomotion/rover_geometry.hpp"
#include "rover/hwconfig/hardware_config.hpp"
#include "rover/hwconfig/rover_description.hpp"
#include "rover/sim/physics/rover_simulation.hpp"
#include "rover/sim/render/cameras.hpp"
#include "rover/sim/rover_sim/sim_engine.hpp"
#include "rover/testing/test_support.hpp"

namespace rover {
namespace {

using hwconfig::RoverDescription;

constexpr double kTol = 1e-9;  // [m] / [rad]: the same numbers, up to rounding

// The simulator as rover-sim builds it: its parameters with defaults, on a small flat world.
std::unique_ptr<sim::rover_sim::SimEngine> SimulatorAsDeployed() {
  ParamSet p("rover-sim");
  sim::rover_sim::SimEngine::DeclareParams(p);
  const char* world =
      "terrain: {size_x: 10, size_y: 10, resolution: 0.05, seed: 3, hills: {amplitude: 0},"
      " craters: {count: 0}, rocks: {preset: none}}\n";
  EXPECT_TRUE(p.LoadYamlSections(world, "world.yaml", {"terrain"}).ok());
  auto e = sim::rover_sim::SimEngine::Create(p);
  EXPECT_TRUE(e.ok()) << e.status().message();
  return e.ok() ? std::move(*e) : nullptr;
}

// The description the stack's services read (dl-locomotion and dl-pose declare it through
// DeclareRoverGeometryParams, the application layer through DeclareParams).
RoverDescription StackDescription() {
  ParamSet p("dl-locomotion");
  dl::locomotion::DeclareRoverGeometryParams(p, "geometry.");
  auto d = ReadParams<RoverDescription>(p, "geometry.");
  EXPECT_TRUE(d.ok()) << d.status().message();
  return d.ok() ? *d : RoverDescription{};
}

dl::locomotion::RoverGeometry StackKinematics() {
  ParamSet p("dl-locomotion");
  dl::locomotion::DeclareRoverGeometryParams(p, "geometry.");
  auto g = dl::locomotion::RoverGeometryFromParams(p, "geometry.");
  EXPECT_TRUE(g.ok()) << g.status().message();
  return g.ok() ? *g : dl::locomotion::RoverGeometry{};
}

void ExpectSamePose(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b, const char* what) {
  EXPECT_LT((a.translation() - b.translation()).norm(), kTol)
      << what << ": " << a.translation().transpose() << " vs " << b.translation().transpose();
  EXPECT_LT((a.linear() - b.linear()).norm(), kTol) << what << ":\n"
                                                    << a.linear() << "\nvs\n"
                                                    << b.linear();
}

class RoverDescriptionConsistency : public ::testing::Test {
 protected:
  void SetUp() override {
    engine_ = SimulatorAsDeployed();
    ASSERT_NE(engine_, nullptr);
    stack_ = StackDescription();
    kinematics_ = StackKinematics();
  }
  const sim::physics::RoverSimulation& physics() const { return engine_->physics(); }

  std::unique_ptr<sim::rover_sim::SimEngine> engine_;
  RoverDescription stack_;
  dl::locomotion::RoverGeometry kinematics_;
};

TEST_F(RoverDescriptionConsistency, SimulatorReadsTheSameParameters) {
  const RoverDescription& s = engine_->rover();
  EXPECT_EQ(s.wheel_radius, stack_.wheel_radius);
  EXPECT_EQ(s.wheel_width, stack_.wheel_width);
  EXPECT_EQ(s.half_track, stack_.half_track);
  EXPECT_EQ(s.min_turn_radius, stack_.min_turn_radius);
  EXPECT_EQ(s.mast.pan_joint, stack_.mast.pan_joint);
  EXPECT_EQ(s.front_hazcam.depression, stack_.front_hazcam.depression);
  // The physics model was built from what the engine read.
  EXPECT_EQ(physics().params().geometry.wheel_radius, stack_.wheel_radius);
  EXPECT_EQ(physics().params().geometry.wheel_width, stack_.wheel_width);
}

TEST_F(RoverDescriptionConsistency, WheelsPivotsAndSteeringAxesAtZeroAngles) {
  const sim::physics::ModelGeometry m = physics().PoseModel({});
  for (int w = 0; w < hwconfig::kNumWheels; ++w) {
    SCOPED_TRACE(hwconfig::WheelName(w));
    const Eigen::Isometry3d& wheel = m.bodies.wheels[static_cast<std::size_t>(w)];
    EXPECT_LT((wheel.translation() - stack_.WheelCentre(w)).norm(), kTol);
    EXPECT_LT((wheel.translation() - kinematics_.wheel_centre[static_cast<std::size_t>(w)]).norm(),
              kTol);
    EXPECT_LT((wheel.linear().col(1) - Eigen::Vector3d::UnitY()).norm(), kTol);  // axle along y
  }
  for (int side : {hwconfig::kLeft, hwconfig::kRight}) {
    const auto s = static_cast<std::size_t>(side);
    EXPECT_LT((m.bodies.rockers[s].translation() - stack_.RockerPivot(side)).norm(), kTol);
    EXPECT_LT((m.bodies.bogies[s].translation() - stack_.BogiePivot(side)).norm(), kTol);
    // The stack's suspension kinematics pivot about the same x and z.
    EXPECT_NEAR(kinematics_.rocker_pivot.x(), m.bodies.rockers[s].translation().x(), kTol);
    EXPECT_NEAR(kinematics_.rocker_pivot.y(), m.bodies.rockers[s].translation().z(), kTol);
    EXPECT_NEAR(kinematics_.bogie_pivot.x(), m.bodies.bogies[s].translation().x(), kTol);
    EXPECT_NEAR(kinematics_.bogie_pivot.y(), m.bodies.bogies[s].translation().z(), kTol);
  }
  // Steering joints: steer_height above the corner wheel centres, on a vertical axis.
  for (int j = 0; j < hwconfig::kNumSteered; ++j) {
    const int w = hwconfig::kSteeredWheel[static_cast<std::size_t>(j)];
    const Eigen::Vector3d joint =
        stack_.WheelCentre(w) + Eigen::Vector3d(0, 0, stack_.steer_height);
    EXPECT_LT((m.steer_brackets[static_cast<std::size_t>(j)].translation() - joint).norm(), kTol)
        << hwconfig::WheelName(w);
  }
  EXPECT_LT((m.bodies.mast_pan.translation() - stack_.mast.pan_joint).norm(), kTol);
  EXPECT_LT((m.imu_station - stack_.imu_position).norm(), kTol);
}

TEST_F(RoverDescriptionConsistency, SuspensionKinematicsAndSignsAgree) {
  // Left rocker front up, right rocker down (the differential), bogies either way.
  sim::physics::ModelJointAngles q;
  q.rocker = {0.12, -0.12};
  q.bogie = {0.2, -0.07};
  const sim::physics::ModelGeometry m = physics().PoseModel(q);
  dl::locomotion::SuspensionAngles s;
  s.rocker = q.rocker;
  s.bogie = q.bogie;
  for (int w = 0; w < hwconfig::kNumWheels; ++w) {
    const Eigen::Vector3d model = m.bodies.wheels[static_cast<std::size_t>(w)].translation();
    EXPECT_LT((model - kinematics_.WheelCentre(w, s)).norm(), kTol)
        << hwconfig::WheelName(w) << ": model " << model.transpose() << ", stack "
        << kinematics_.WheelCentre(w, s).transpose();
    // The link pitch the stack assumes is the wheel frame's pitch in the model (front up > 0).
    const Eigen::Vector3d forward = m.bodies.wheels[static_cast<std::size_t>(w)].linear().col(0);
    EXPECT_NEAR(std::atan2(forward.z(), forward.x()),
                dl::locomotion::RoverGeometry::LinkPitch(w, s), kTol)
        << hwconfig::WheelName(w);
  }
  // + raises the front: the left front wheel goes up, the left bogie pivot down.
  EXPECT_GT(m.bodies.wheels[hwconfig::kWheelLF].translation().z(), stack_.wheel_radius);
  EXPECT_LT(m.bodies.bogies[hwconfig::kLeft].translation().z(), stack_.bogie_pivot_z);
}

TEST_F(RoverDescriptionConsistency, SteeringTurnsTheWheelFrontLeftAboutItsCentre) {
  sim::physics::ModelJointAngles q;
  q.steer = {0.5, -0.3, 0.2, -0.9};
  const sim::physics::ModelGeometry m = physics().PoseModel(q);
  for (int j = 0; j < hwconfig::kNumSteered; ++j) {
    const int w = hwconfig::kSteeredWheel[static_cast<std::size_t>(j)];
    const Eigen::Isometry3d& wheel = m.bodies.wheels[static_cast<std::size_t>(w)];
    EXPECT_LT((wheel.translation() - stack_.WheelCentre(w)).norm(), kTol) << hwconfig::WheelName(w);
    const Eigen::Vector3d forward = wheel.linear().col(0);
    EXPECT_NEAR(std::atan2(forward.y(), forward.x()), q.steer[static_cast<std::size_t>(j)], kTol)
        << hwconfig::WheelName(w);
  }
}

TEST_F(RoverDescriptionConsistency, MastHeadAndCameraMounts) {
  for (const auto& [pan, tilt] :
       {std::pair{0.0, 0.0}, std::pair{0.7, -0.4}, std::pair{-2.0, 0.9}}) {
    sim::physics::ModelJointAngles q;
    q.pan = pan;
    q.tilt = tilt;
    const sim::physics::ModelGeometry m = physics().PoseModel(q);
    ExpectSamePose(m.cameras.mast_head_chassis, stack_.mast.HeadPose(pan, tilt), "mast head");
    // The renderer's mast kinematics (rover-sim renders the NAVCAM with them).
    ExpectSamePose(
        sim::render::MastHeadPose(sim::render::MastState{pan, tilt}, engine_->rover().mast),
        stack_.mast.HeadPose(pan, tilt), "rendered mast head");
  }
  const sim::physics::ModelGeometry m = physics().PoseModel({});
  ExpectSamePose(m.cameras.hazcam_front_chassis, stack_.front_hazcam.Pose(), "front HAZCAM");
  ExpectSamePose(m.cameras.hazcam_rear_chassis, stack_.rear_hazcam.Pose(), "rear HAZCAM");
}

TEST_F(RoverDescriptionConsistency, BellyIsTheBodyBox) {
  const sim::physics::ModelGeometry m = physics().PoseModel({});
  ASSERT_FALSE(m.belly_points.empty());
  const Eigen::Vector3d lo = stack_.body_centre - 0.5 * stack_.body_size;
  const Eigen::Vector3d hi = stack_.body_centre + 0.5 * stack_.body_size;
  Eigen::Vector2d min_xy(1e9, 1e9), max_xy(-1e9, -1e9);
  for (const Eigen::Vector3d& p : m.belly_points) {
    EXPECT_NEAR(p.z(), stack_.BellyClearance(), kTol);
    min_xy = min_xy.cwiseMin(p.head<2>());
    max_xy = max_xy.cwiseMax(p.head<2>());
  }
  EXPECT_LT((min_xy - lo.head<2>()).norm(), kTol);
  EXPECT_LT((max_xy - hi.head<2>()).norm(), kTol);
  // Standing on flat ground, the whole model is inside the footprint and the turn circle.
  const hwconfig::Footprint f = stack_.GroundFootprint();
  const hwconfig::TurnCircle c = stack_.TurnInPlaceCircle();
  for (const auto& wheel : m.bodies.wheels) {
    const Eigen::Vector3d p = wheel.translation();
    for (double dx : {-stack_.wheel_radius, stack_.wheel_radius}) {
      EXPECT_TRUE(f.Contains(p.x() + dx, p.y() + 0.5 * stack_.wheel_width * (p.y() > 0 ? 1 : -1)));
      EXPECT_LE((Eigen::Vector2d(p.x() + dx, p.y()) - c.centre).norm(), c.radius);
    }
  }
}

TEST_F(RoverDescriptionConsistency, CamerasAreMountedWhereTheDescriptionSays) {
  // Rendered cameras (what rover-sim renders with) and the camera driver's calibration file
  // (what ddl-camera attaches): optical centres and boresights on the described mounts.
  auto file =
      ddl::camera::LoadCameraCalibration(testing::SourceDir() + "/deploy/config/cameras.yaml");
  ASSERT_TRUE(file.ok()) << file.status().message();
  EXPECT_LT((file->mast.pan_joint - stack_.mast.pan_joint).norm(), kTol);
  EXPECT_NEAR(file->mast.head_height, stack_.mast.head_height, kTol);
  const auto rendered = sim::render::DefaultStereoCameras(1024, engine_->rover());
  const std::pair<const char*, const hwconfig::StereoMount*> mounts[] = {
      {"navcam", &stack_.navcam},
      {"front_hazcam", &stack_.front_hazcam},
      {"rear_hazcam", &stack_.rear_hazcam}};
  for (const auto& [name, mount] : mounts) {
    SCOPED_TRACE(name);
    auto sim_pair = sim::render::FindStereoCamera(rendered, name);
    ASSERT_TRUE(sim_pair.ok());
    const ddl::camera::StereoCameraCalibration* cal = nullptr;
    for (const auto& c : file->cameras) {
      if (c.name == name) cal = &c;
    }
    ASSERT_NE(cal, nullptr);
    const Eigen::Vector3d boresight = mount->Pose().linear().col(0);
    const geometry::CameraModel* models[] = {&sim_pair->left, &sim_pair->right, &cal->left,
                                             &cal->right};
    for (int i = 0; i < 4; ++i) {
      const int side = i % 2 == 0 ? hwconfig::kLeft : hwconfig::kRight;
      const auto ray = models[i]->Unproject(Eigen::Vector2d(511.5, 511.5));  // image centre
      ASSERT_TRUE(ray.has_value());
      EXPECT_LT((ray->origin - mount->CameraCentre(side)).norm(), 1e-6) << i;
      EXPECT_LT((ray->direction - boresight).norm(), 1e-6) << i;
    }
  }
}

TEST_F(RoverDescriptionConsistency, HardwareSuspensionLimitsAreTheMechanicalStops) {
  const HardwareConfig defaults;
  EXPECT_EQ(defaults.pots.rocker_limit, stack_.rocker_limit);
  EXPECT_EQ(defaults.pots.bogie_limit, stack_.bogie_limit);
  auto file = LoadHardwareConfig(testing::SourceDir() + "/deploy/config/rover_hardware.yaml");
  ASSERT_TRUE(file.ok()) << file.status().message();
  EXPECT_EQ(file->pots.rocker_limit, stack_.rocker_limit);
  EXPECT_EQ(file->pots.bogie_limit, stack_.bogie_limit);
}

}  // namespace
}  // namespace rover
