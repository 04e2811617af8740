#include "rover/msg/navigation_idl.hpp"

#include <gtest/gtest.h>

#include <string>

#include "rover/idl/access.hpp"

namespace rover::msg {
namespace {

GoodnessMap SmallMap() {
  GoodnessMap g;
  g.stamp = Time{77};
  g.origin_x = -5;
  g.origin_y = 2;
  g.resolution = 0.2;
  g.width = 3;
  g.height = 2;
  g.unknown_goodness = 11;
  g.goodness = {0, 10, 20, 30, 40, 255};
  g.certainty = {255, 255, 0, 0, 128, 1};
  g.flags = {1, 1, 0, 0, 3, 5};
  return g;
}

TEST(NavigationIdl, GoodnessMapRoundTrip) {
  const GoodnessMap g = SmallMap();
  rover_apl_GoodnessMap m{};
  ASSERT_TRUE(GoodnessMapToIdl(g, &m).ok());
  EXPECT_EQ(m.goodness._buffer, g.goodness.data());  // borrowed, not copied
  const auto b = GoodnessMapFromIdl(m);
  ASSERT_TRUE(b.ok()) << b.status().message();
  EXPECT_EQ(b->stamp.ns, 77);
  EXPECT_EQ(b->origin_x, -5);
  EXPECT_EQ(b->origin_y, 2);
  EXPECT_EQ(b->resolution, 0.2);
  EXPECT_EQ(b->width, 3);
  EXPECT_EQ(b->height, 2);
  EXPECT_EQ(b->unknown_goodness, 11);
  EXPECT_EQ(b->goodness, g.goodness);
  EXPECT_EQ(b->certainty, g.certainty);
  EXPECT_EQ(b->flags, g.flags);
}

TEST(NavigationIdl, GoodnessMapSizeErrorsNameTheArray) {
  GoodnessMap g = SmallMap();
  rover_apl_GoodnessMap m{};
  ASSERT_TRUE(GoodnessMapToIdl(g, &m).ok());
  m.width = 4;
  auto b = GoodnessMapFromIdl(m);
  ASSERT_FALSE(b.ok());
  EXPECT_EQ(b.status().message(), "apl/goodness_map goodness: 6 cells for 8 = 4 x 2");
  g.flags.pop_back();
  rover_apl_GoodnessMap untouched{};
  const Status s = GoodnessMapToIdl(g, &untouched);
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.message(), "apl/goodness_map flags: 5 cells for 6 = 3 x 2");
  EXPECT_EQ(untouched.width, 0);
  g = SmallMap();
  g.unknown_goodness = 300;
  ASSERT_TRUE(GoodnessMapToIdl(g, &m).ok());
  EXPECT_EQ(m.unknown_goodness, 255);  // clamped to a byte
}

ArcVotes TwoVotes() {
  ArcVotes a;
  a.stamp = Time{8};
  a.command_id = 4;
  a.step = 2;
  a.rover_pose = Eigen::Translation3d(1, 2, 0) * Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ());
  a.votes = {{CandidateKind::kArc, 0.5, -1, 0.0, 200, 10, 10},
             {CandidateKind::kPointTurn, 0.0, 1, 1.5, 100, 255, 150}};
  a.chosen = 1;
  return a;
}

TEST(NavigationIdl, ArcVotesRoundTripThroughACopiedHolder) {
  const ArcVotes a = TwoVotes();
  ArcVotesMessage m;
  ArcVotesToIdl(a, &m);
  const ArcVotesMessage copy = m;
  m = ArcVotesMessage{};
  ASSERT_EQ(copy.msg.votes._length, 2u);
  EXPECT_EQ(copy.msg.votes._buffer[0].kind, rover_apl_CANDIDATE_ARC);
  EXPECT_EQ(copy.msg.votes._buffer[1].kind, rover_apl_CANDIDATE_POINT_TURN);
  const auto b = ArcVotesFromIdl(copy.msg);
  ASSERT_TRUE(b.ok()) << b.status().message();
  EXPECT_EQ(b->stamp.ns, 8);
  EXPECT_EQ(b->command_id, 4u);
  EXPECT_EQ(b->step, 2u);
  EXPECT_TRUE(b->rover_pose.isApprox(a.rover_pose, 1e-12));
  ASSERT_EQ(b->votes.size(), 2u);
  EXPECT_EQ(b->votes[0].kind, CandidateKind::kArc);
  EXPECT_EQ(b->votes[0].curvature, 0.5);
  EXPECT_EQ(b->votes[0].direction, -1);
  EXPECT_EQ(b->votes[0].hazard, 200);
  EXPECT_EQ(b->votes[1].kind, CandidateKind::kPointTurn);
  EXPECT_EQ(b->votes[1].turn_angle, 1.5);
  EXPECT_EQ(b->votes[1].waypoint, 255);
  EXPECT_EQ(b->votes[1].merged, 150);
  EXPECT_EQ(b->chosen, 1);
}

TEST(NavigationIdl, ArcVotesCarryAtMostTheIdlBound) {
  ArcVotes a = TwoVotes();
  a.votes.assign(kMaxArcVotes + 5, ArcVote{});
  a.votes[3].direction = -7;
  a.chosen = static_cast<int>(kMaxArcVotes) + 2;  // not carried: none chosen
  ArcVotesMessage m;
  ArcVotesToIdl(a, &m);
  EXPECT_EQ(m.msg.votes._length, kMaxArcVotes);
  EXPECT_EQ(m.msg.votes._buffer[3].direction, -1);  // the sign
  EXPECT_EQ(m.msg.chosen, -1);
  a.chosen = 5;
  ArcVotesToIdl(a, &m);
  EXPECT_EQ(m.msg.chosen, 5);
}

TEST(NavigationIdl, ArcVotesErrorsNameTheField) {
  ArcVotesMessage m;
  ArcVotesToIdl(TwoVotes(), &m);
  idl::SetRawEnum(&m.votes[1].kind, 4);
  auto b = ArcVotesFromIdl(m.msg);
  ASSERT_FALSE(b.ok());
  EXPECT_EQ(b.status().message(), "apl/arc_votes votes[1].kind = 4 is not a CandidateKind (0..1)");
  ArcVotesToIdl(TwoVotes(), &m);
  m.msg.chosen = 2;
  b = ArcVotesFromIdl(m.msg);
  ASSERT_FALSE(b.ok());
  EXPECT_EQ(b.status().message(), "apl/arc_votes chosen = 2 is outside -1..1");
  m.msg.chosen = -1;
  m.msg.rover_pose.orientation = {0, 0, 0, 0};
  b = ArcVotesFromIdl(m.msg);
  ASSERT_FALSE(b.ok());
  EXPECT_NE(b.status().message().find("apl/arc_votes rover_pose orientation"), std::string::npos)
      << b.status().message();
}

}  // namespace
}  // namespace rover::msg
