// The camera models the DDL driver attaches (deploy/config/cameras.yaml) must be the ones the
// simulator renders with (sim/render DefaultStereoCameras): otherwise stereo ranges and visual
// odometry in simulation are wrong in a way no unit test of either side can see.
#include <gtest/gtest.h>

#include "rover/ddl/camera/camera_calibration.hpp"
#include "rover/sim/render/cameras.hpp"
#include "rover/testing/test_support.hpp"

namespace {

// Largest pixel difference between two models over rays spread across the image of `a`.
double MaxPixelDifference(const rover::geometry::CameraModel& a,
                          const rover::geometry::CameraModel& b) {
  double worst = 0.0;
  for (double v = 0.0; v < a.height(); v += a.height() / 16.0) {
    for (double u = 0.0; u < a.width(); u += a.width() / 16.0) {
      const auto ray = a.Unproject(Eigen::Vector2d(u, v));
      if (!ray) continue;
      for (double range : {0.7, 3.0, 20.0}) {
        const Eigen::Vector3d p = ray->origin + range * ray->direction;
        const auto pa = a.Project(p);
        const auto pb = b.Project(p);
        if (!pa || !pb) return 1e9;
        worst = std::max(worst, (*pa - *pb).norm());
      }
    }
  }
  return worst;
}

TEST(CameraConsistencyTest, DriverCalibrationEqualsSimulatedCameras) {
  auto calibration = rover::ddl::camera::LoadCameraCalibration(rover::testing::SourceDir() +
                                                               "/deploy/config/cameras.yaml");
  ASSERT_TRUE(calibration.ok()) << calibration.status().message();
  const auto sim_cameras = rover::sim::render::DefaultStereoCameras(1024);
  ASSERT_EQ(calibration->cameras.size(), sim_cameras.size());
  for (const auto& cal : calibration->cameras) {
    SCOPED_TRACE(cal.name);
    auto sim = rover::sim::render::FindStereoCamera(sim_cameras, cal.name);
    ASSERT_TRUE(sim.ok()) << sim.status().message();
    EXPECT_EQ(cal.mount == rover::ddl::camera::CameraMount::kMastHead,
              sim->mount == rover::sim::render::CameraMount::kMastHead);
    EXPECT_EQ(cal.left.width(), sim->left.width());
    EXPECT_EQ(cal.left.height(), sim->left.height());
    EXPECT_LT(MaxPixelDifference(cal.left, sim->left), 1e-3);
    EXPECT_LT(MaxPixelDifference(cal.right, sim->right), 1e-3);
  }
  const rover::hwconfig::MastDescription sim_mast;  // what rover-sim renders with by default
  EXPECT_LT((calibration->mast.pan_joint - sim_mast.pan_joint).norm(), 1e-9);
  EXPECT_NEAR(calibration->mast.head_height, sim_mast.head_height, 1e-9);
}

}  // namespace
