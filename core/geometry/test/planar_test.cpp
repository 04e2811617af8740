#include "rover/geometry/planar.hpp"

#include <gtest/gtest.h>

#include <numbers>

namespace rover::geometry {
namespace {

TEST(Pose2, ToRoverUndoesToSite) {
  const Pose2 pose{2.0, -1.0, 0.7};
  const Eigen::Vector2d p(0.3, -1.2);
  EXPECT_TRUE(pose.ToRover(pose.ToSite(p)).isApprox(p, 1e-12));
  // A rover facing west (+y) sees a point 1 m further west 1 m ahead, and one 1 m north of it
  // 1 m to its right.
  const Pose2 west{0.0, 0.0, std::numbers::pi / 2};
  EXPECT_TRUE(west.ToRover({0.0, 1.0}).isApprox(Eigen::Vector2d(1.0, 0.0), 1e-12));
  EXPECT_TRUE(west.ToRover({1.0, 0.0}).isApprox(Eigen::Vector2d(0.0, -1.0), 1e-12));
}

}  // namespace
}  // namespace rover::geometry
