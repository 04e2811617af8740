#include "rover/msg/rendezvous_idl.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "rover/idl/access.hpp"

namespace rover::msg {
namespace {

TEST(RendezvousIdl, CommandRoundTripKeepsAnUnknownTargetAndNaN) {
  RendezvousCommand c;
  c.stamp = Time{42};
  c.command_id = 9;
  c.target = RendezvousTarget::kLander;
  c.target_estimate = {30.0, std::nan(""), 0.0};
  c.standoff = 1.2;
  c.ramp = 1;
  c.climb = false;
  c.time_budget_s = 900;
  c.image_id = 0xC8000001u;
  c.pixel_x = 512.25;
  c.pixel_y = -3.5;
  c.place_instrument = true;
  c.autofocus = true;
  rover_apl_RendezvousCommand m{};
  RendezvousCommandToIdl(c, &m);
  EXPECT_EQ(m.target, rover_apl_TARGET_LANDER);
  const RendezvousCommand back = RendezvousCommandFromIdl(m);
  EXPECT_EQ(back.stamp, c.stamp);
  EXPECT_EQ(back.command_id, 9u);
  EXPECT_EQ(back.target_estimate.x(), 30.0);
  EXPECT_TRUE(std::isnan(back.target_estimate.y()));
  EXPECT_EQ(back.standoff, 1.2);
  EXPECT_EQ(back.ramp, 1);
  EXPECT_FALSE(back.climb);
  EXPECT_EQ(back.time_budget_s, 900);
  EXPECT_EQ(back.image_id, 0xC8000001u);
  EXPECT_EQ(back.pixel_x, 512.25);
  EXPECT_EQ(back.pixel_y, -3.5);
  EXPECT_TRUE(back.place_instrument);
  EXPECT_TRUE(back.autofocus);
  idl::SetRawEnum(&m.target, 7);
  EXPECT_EQ(static_cast<int>(RendezvousCommandFromIdl(m).target), 7);
  EXPECT_STREQ(RendezvousTargetName(RendezvousCommandFromIdl(m).target), "UNKNOWN");
}

TEST(RendezvousIdl, StatusRoundTripAndBadEnums) {
  RendezvousStatus s;
  s.stamp = Time{7};
  s.command_id = 3;
  s.phase = RendezvousPhase::kAtRampBase;
  s.fault = RendezvousFault::kTooFewStripes;
  s.target_position = {1, 2, 3};
  s.range = 4.5;
  s.bearing = -0.25;
  s.ramp = 0;
  s.images = 70000;
  s.features = std::string(100, 'f');
  s.message = "three stripes";
  s.target_in_rover = {1.05, -0.01, 0.12};
  rover_apl_RendezvousStatus m{};
  RendezvousStatusToIdl(s, &m);
  const Result<RendezvousStatus> back = RendezvousStatusFromIdl(m);
  ASSERT_TRUE(back.ok()) << back.status().message();
  EXPECT_EQ(back->phase, RendezvousPhase::kAtRampBase);
  EXPECT_EQ(back->fault, RendezvousFault::kTooFewStripes);
  EXPECT_EQ(back->target_position, s.target_position);
  EXPECT_EQ(back->bearing, -0.25);
  EXPECT_EQ(back->images, 65535);
  EXPECT_EQ(back->features.size(), 63u);
  EXPECT_EQ(back->message, "three stripes");
  EXPECT_EQ(back->target_in_rover, s.target_in_rover);
  EXPECT_STREQ(RendezvousPhaseName(back->phase), "AT_RAMP_BASE");
  EXPECT_STREQ(RendezvousFaultName(back->fault), "TOO_FEW_STRIPES");
  m.phase = rover_apl_PHASE_AT_TARGET;
  EXPECT_EQ(RendezvousStatusFromIdl(m)->phase, RendezvousPhase::kAtTarget);
  m.phase = rover_apl_PHASE_PLACED;
  EXPECT_EQ(RendezvousStatusFromIdl(m)->phase, RendezvousPhase::kPlaced);
  m.phase = rover_apl_PHASE_FOCUSED;
  EXPECT_STREQ(RendezvousPhaseName(RendezvousStatusFromIdl(m)->phase), "FOCUSED");
  idl::SetRawEnum(&m.phase, 14);
  EXPECT_THAT(RendezvousStatusFromIdl(m).status().message(),
              ::testing::HasSubstr("apl/rendezvous_status phase = 14 is not a RendezvousPhase"));
  m.phase = rover_apl_PHASE_DONE;
  idl::SetRawEnum(&m.fault, -1);
  EXPECT_THAT(RendezvousStatusFromIdl(m).status().message(),
              ::testing::HasSubstr("fault = -1"));
}

}  // namespace
}  // namespace rover::msg
