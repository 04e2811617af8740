#include "rover/sim/rover_sim/truth_idl.hpp"

#include <gtest/gtest.h>

namespace rover::sim::rover_sim {
namespace {

TEST(TruthIdlTest, RoundTripsEveryField) {
  TruthSample t;
  t.time_s = 12.25;
  t.pose = Eigen::Translation3d(1.0, -2.0, 0.5) *
           Eigen::AngleAxisd(0.3, Eigen::Vector3d(0.1, 0.2, 0.9).normalized());
  t.velocity_site = {0.04, -0.01, 0.002};
  t.angular_velocity_body = {0.001, -0.002, 0.1};
  for (std::size_t i = 0; i < t.wheels.size(); ++i) {
    t.wheels[i].slip_ratio = 0.1 * static_cast<double>(i);
    t.wheels[i].normal_force_n = 50.0 + static_cast<double>(i);
    t.wheels[i].in_contact = i % 2 == 0;
    t.wheels[i].sinkage_m = 0.001 * static_cast<double>(i);
  }
  t.rocker_angle[0] = 0.05;
  t.rocker_angle[1] = -0.05;
  t.bogie_angle[0] = 0.1;
  t.bogie_angle[1] = -0.2;
  t.odometer = 33.5;
  t.rock_contacts = 2;
  t.max_contact_rock_height = 0.18;

  rover_sim_Truth m{};
  TruthToIdl(t, &m);
  EXPECT_EQ(m.header.stamp_ns, 12250000000);
  const TruthSample back = TruthFromIdl(m);
  EXPECT_DOUBLE_EQ(back.time_s, t.time_s);
  EXPECT_TRUE(back.pose.isApprox(t.pose, 1e-12));
  EXPECT_EQ(back.velocity_site, t.velocity_site);
  EXPECT_EQ(back.angular_velocity_body, t.angular_velocity_body);
  for (std::size_t i = 0; i < t.wheels.size(); ++i) {
    EXPECT_EQ(back.wheels[i].slip_ratio, t.wheels[i].slip_ratio) << i;
    EXPECT_EQ(back.wheels[i].normal_force_n, t.wheels[i].normal_force_n) << i;
    EXPECT_EQ(back.wheels[i].in_contact, t.wheels[i].in_contact) << i;
    EXPECT_EQ(back.wheels[i].sinkage_m, t.wheels[i].sinkage_m) << i;
  }
  EXPECT_EQ(back.rocker_angle[1], -0.05);
  EXPECT_EQ(back.bogie_angle[1], -0.2);
  EXPECT_EQ(back.odometer, 33.5);
  EXPECT_EQ(back.rock_contacts, 2u);
  EXPECT_EQ(back.max_contact_rock_height, 0.18);
}

}  // namespace
}  // namespace rover::sim::rover_sim
