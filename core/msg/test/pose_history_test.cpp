#include "rover/msg/pose_history.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace rover::msg {
namespace {

PoseSample Sample(double t, double x, double yaw, double odometer) {
  PoseSample s;
  s.stamp = Time{std::llround(t * 1e9)};
  s.site_from_rover.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  s.site_from_rover.translation() = Eigen::Vector3d(x, 0.0, 0.0);
  s.odometer = odometer;
  return s;
}

double Yaw(const Eigen::Isometry3d& t) { return std::atan2(t.linear()(1, 0), t.linear()(0, 0)); }

TEST(PoseHistory, InterpolatesBetweenTheSamplesAroundTheTime) {
  PoseHistory h(8);
  ASSERT_TRUE(h.Add(Sample(1.0, 0.0, 0.0, 0.0)).ok());
  ASSERT_TRUE(h.Add(Sample(1.1, 0.01, 0.02, 0.01)).ok());
  auto p = h.At(Time{1'025'000'000}, Seconds(0.5));
  ASSERT_TRUE(p.ok()) << p.status().ToString();
  EXPECT_NEAR(p->site_from_rover.translation().x(), 0.0025, 1e-12);
  EXPECT_NEAR(Yaw(p->site_from_rover), 0.005, 1e-12);
  EXPECT_NEAR(p->odometer, 0.0025, 1e-12);
  EXPECT_EQ(p->stamp.ns, 1'025'000'000);
  // Exactly at a sample.
  p = h.At(Time::FromSeconds(1.1), Seconds(0.0));
  ASSERT_TRUE(p.ok());
  EXPECT_DOUBLE_EQ(p->odometer, 0.01);
}

TEST(PoseHistory, NearestSampleMustBeWithinTheGap) {
  PoseHistory h(8);
  EXPECT_EQ(h.At(Time::FromSeconds(1.0), Seconds(1.0)).status().code(), StatusCode::kNotFound);
  ASSERT_TRUE(h.Add(Sample(1.0, 1.0, 0.0, 1.0)).ok());
  ASSERT_TRUE(h.Add(Sample(3.0, 3.0, 0.0, 3.0)).ok());
  // After the newest: the newest if close enough.
  auto p = h.At(Time::FromSeconds(3.4), Seconds(0.5));
  ASSERT_TRUE(p.ok());
  EXPECT_DOUBLE_EQ(p->odometer, 3.0);
  const auto late = h.At(Time::FromSeconds(3.6), Seconds(0.5));
  ASSERT_FALSE(late.ok());
  EXPECT_EQ(late.status().code(), StatusCode::kNotFound);
  EXPECT_NE(late.status().message().find("nearest at 3 s"), std::string::npos)
      << late.status().message();
  // In a gap between two samples that are both far away: unknown, not interpolated.
  EXPECT_FALSE(h.At(Time::FromSeconds(2.0), Seconds(0.5)).ok());
  // Before the oldest.
  EXPECT_TRUE(h.At(Time::FromSeconds(0.8), Seconds(0.5)).ok());
}

TEST(PoseHistory, RejectsOutOfOrderAndBadSamplesAndDropsTheOldest) {
  PoseHistory h(3);
  ASSERT_TRUE(h.Add(Sample(1.0, 0.0, 0.0, 0.0)).ok());
  EXPECT_EQ(h.Add(Sample(0.5, 0.0, 0.0, 0.0)).code(), StatusCode::kOutOfRange);
  PoseSample nan = Sample(2.0, 0.0, 0.0, 0.0);
  nan.odometer = std::nan("");
  EXPECT_EQ(h.Add(nan).code(), StatusCode::kInvalidArgument);
  PoseSample skew = Sample(2.0, 0.0, 0.0, 0.0);
  skew.site_from_rover.linear()(0, 1) = 0.3;
  EXPECT_EQ(h.Add(skew).code(), StatusCode::kInvalidArgument);
  // Same stamp replaces.
  ASSERT_TRUE(h.Add(Sample(1.0, 5.0, 0.0, 5.0)).ok());
  EXPECT_EQ(h.size(), 1u);
  EXPECT_DOUBLE_EQ(h.Latest()->odometer, 5.0);
  for (int i = 2; i <= 5; ++i) ASSERT_TRUE(h.Add(Sample(i, 0.0, 0.0, i)).ok());
  EXPECT_EQ(h.size(), 3u);
  EXPECT_FALSE(h.At(Time::FromSeconds(1.0), Seconds(0.5)).ok());  // dropped
}

TEST(PoseHistory, TellsARunClockResetFromAReorderedSample) {
  PoseHistory h(8);
  EXPECT_FALSE(h.WentBackBy(Time::FromSeconds(0.0), Seconds(1.0)));  // empty
  ASSERT_TRUE(h.Add(Sample(10.0, 0.0, 0.0, 0.0)).ok());
  EXPECT_FALSE(h.WentBackBy(Time::FromSeconds(9.5), Seconds(1.0)));  // reordered
  EXPECT_EQ(h.Add(Sample(9.5, 0.0, 0.0, 0.0)).code(), StatusCode::kOutOfRange);
  EXPECT_TRUE(h.WentBackBy(Time::FromSeconds(0.2), Seconds(1.0)));  // a new run
}

// Reading dl/pose messages: core/msg/test/pose_idl_test.cpp (PoseSampleFromIdl).

}  // namespace
}  // namespace rover::msg
