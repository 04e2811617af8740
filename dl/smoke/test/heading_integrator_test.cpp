#include "rover/dl/smoke/heading_integrator.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace rover::dl::smoke {
namespace {

TEST(HeadingIntegrator, IntegratesConstantRate) {
  HeadingIntegrator h;
  for (int i = 0; i <= 100; ++i) {
    ASSERT_TRUE(h.Add(Time::FromSeconds(0.01 * i), 0.5).ok());
  }
  EXPECT_NEAR(h.heading(), 0.5, 1e-9);
  EXPECT_EQ(h.samples(), 101);
}

TEST(HeadingIntegrator, WrapsToPlusMinusPi) {
  HeadingIntegrator h(std::chrono::seconds(10));
  ASSERT_TRUE(h.Add(Time::FromSeconds(0), 1.0).ok());
  ASSERT_TRUE(h.Add(Time::FromSeconds(4), 1.0).ok());
  EXPECT_NEAR(h.heading(), 4.0 - 2 * std::numbers::pi, 1e-9);
}

TEST(HeadingIntegrator, RejectsOutOfOrderAndNaN) {
  HeadingIntegrator h;
  ASSERT_TRUE(h.Add(Time::FromSeconds(1), 1.0).ok());
  EXPECT_EQ(h.Add(Time::FromSeconds(1), 1.0).code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(h.Add(Time::FromSeconds(0.5), 1.0).code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(h.Add(Time::FromSeconds(1.1), std::nan("")).code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(h.heading(), 0.0);
}

TEST(HeadingIntegrator, GapRestartsWithoutIntegrating) {
  HeadingIntegrator h(std::chrono::milliseconds(100));
  ASSERT_TRUE(h.Add(Time::FromSeconds(0), 1.0).ok());
  EXPECT_EQ(h.Add(Time::FromSeconds(5), 1.0).code(), StatusCode::kOutOfRange);
  EXPECT_EQ(h.heading(), 0.0);
  ASSERT_TRUE(h.Add(Time::FromSeconds(5.05), 1.0).ok());
  EXPECT_NEAR(h.heading(), 0.05, 1e-9);
}

}  // namespace
}  // namespace rover::dl::smoke
