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
