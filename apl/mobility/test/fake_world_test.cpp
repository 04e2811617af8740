// The test world itself: terrain, synthetic scans, drive integration.
#include "fake_world.hpp"

#include <gtest/gtest.h>

namespace rover::apl::mobility::testing {
namespace {

TEST(FakeWorld, RocksRaiseTheGroundAndHideWhatIsBehind) {
  MobilityManager m = MakeGestaltManager();
  FakeWorld w(&m);
  w.rocks().push_back({2.0, 0.0, 0.3, 0.5});
  EXPECT_NEAR(w.HeightAt(2.0, 0.0), 0.5, 1e-12);
  EXPECT_EQ(w.HeightAt(3.0, 0.0), 0.0);
  const nav_core::RangeScan scan = w.Capture(CameraId::kFrontHazcam);
  ASSERT_TRUE(scan.Validate().ok());
  // The middle column looks straight at the rock: something right behind it is hidden.
  const int u = scan.width / 2;
  int valid_far = 0, valid_near = 0;
  for (int v = 0; v < scan.height; ++v) {
    if (!scan.is_valid(u, v)) continue;
    (scan.point(u, v).x() > 2.4 ? valid_far : valid_near) += 1;
  }
  EXPECT_GT(valid_near, 10);
  const nav_core::RangeScan open = FakeWorld(&m).Capture(CameraId::kFrontHazcam);
  int open_far = 0;
  for (int v = 0; v < open.height; ++v) open_far += open.point(u, v).x() > 2.4 ? 1 : 0;
  EXPECT_LT(valid_far, open_far);
}

TEST(FakeWorld, RearCameraLooksBackward) {
  MobilityManager m = MakeGestaltManager();
  FakeWorld w(&m);
  const nav_core::RangeScan scan = w.Capture(CameraId::kRearHazcam);
  EXPECT_LT(scan.point(scan.width / 2, 0).x(), -4.0);
}

// A caller's scene replaces the rock field for capture, the pose and the clearance.
class SlopeScene : public Scene {
 public:
  Eigen::Isometry3d SiteFromRover(const Pose2& p) const override {
    Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
    t.translation() = Eigen::Vector3d(p.x, p.y, 0.1 * p.x);
    return t;
  }
  nav_core::RangeScan Capture(const Pose2& /*pose*/, CameraId camera) const override {
    nav_core::RangeScan s;
    s.width = s.height = 1;
    s.xyz = {1.0F, 0.0F, camera == CameraId::kRearHazcam ? -1.0F : 1.0F};
    s.valid = {1};
    return s;
  }
  double Clearance(double x, double /*y*/) const override { return 5.0 - x; }
};

TEST(FakeWorld, ASceneReplacesTheRockField) {
  MobilityManager m = MakeGestaltManager();
  const SlopeScene scene;
  FakeWorld w(&m, {}, &scene);
  w.rocks().push_back({0.0, 0.0, 3.0, 1.0});  // ignored: the scene decides
  w.pose() = {2.0, 1.0, 0.0};
  EXPECT_DOUBLE_EQ(w.PoseNow().site_from_rover.translation().z(), 0.2);
  const nav_core::RangeScan scan = w.Capture(CameraId::kRearHazcam);
  ASSERT_EQ(scan.width, 1);
  EXPECT_EQ(scan.xyz[2], -1.0F);
  EXPECT_EQ(scan.camera, std::string(CameraName(CameraId::kRearHazcam)));
  EXPECT_DOUBLE_EQ(scan.site_from_rover.translation().z(), 0.2);
  w.Tick();
  EXPECT_DOUBLE_EQ(w.min_rock_clearance(), 3.0);
}

TEST(FakeWorld, DirectedDriveIntegratesThePrimitive) {
  MobilityManager m = MakeGestaltManager();
  FakeWorld w(&m);
  MobilityCommand c;
  c.command_id = 1;
  c.mode = Mode::kDirected;
  c.primitives = {{PrimitiveKind::kStraight, 0.0, 1.0, 0.0},
                  {PrimitiveKind::kTurnInPlace, 0.0, 0.0, 1.0}};
  const MobilityStatus s = w.Run(c, 100.0);
  EXPECT_EQ(s.state, State::kSucceeded) << s.message;
  EXPECT_NEAR(w.pose().x, 1.0, 1e-9);
  EXPECT_NEAR(w.pose().heading, 1.0, 1e-9);
  EXPECT_EQ(w.drives().size(), 2u);
}

}  // namespace
}  // namespace rover::apl::mobility::testing
