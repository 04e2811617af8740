#include "rover/msg/pose.hpp"

#include <gtest/gtest.h>

#include <string>

namespace rover::msg {
namespace {

TEST(PoseMessages, NamesAndKnownSources) {
  EXPECT_EQ(std::string(MotionSourceName(MotionSource::kVisualOdometry)), "visual_odometry");
  EXPECT_EQ(std::string(MotionSourceName(static_cast<MotionSource>(7))), "unknown");
  EXPECT_EQ(std::string(RelativePoseStatusName(RelativePoseStatus::kLimitsFailed)),
            "limits_failed");
  EXPECT_EQ(std::string(RelativePoseStatusName(static_cast<RelativePoseStatus>(-1))), "unknown");
  for (int s = 0; s <= 4; ++s) EXPECT_TRUE(IsKnownMotionSource(static_cast<MotionSource>(s)));
  EXPECT_FALSE(IsKnownMotionSource(static_cast<MotionSource>(5)));
}

TEST(PoseMessages, DefaultsAreAnIdentityMeasurement) {
  const RelativePose r;
  EXPECT_EQ(r.status, RelativePoseStatus::kConverged);
  EXPECT_TRUE(r.delta.isApprox(Eigen::Isometry3d::Identity()));
  EXPECT_TRUE(r.covariance.isApprox(Matrix6d::Identity()));
  const PoseEstimate e;
  EXPECT_EQ(e.orientation.w(), 1.0);
}

}  // namespace
}  // namespace rover::msg
