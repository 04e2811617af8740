#include "rover/apl/enav/clearance.hpp"

#include <gtest/gtest.h>

#include "scene.hpp"

namespace rover::apl::enav {
namespace {

using testing::Block;
using testing::Blocks;
using testing::ScanOf;
using testing::TerrainOf;
using testing::TestOptions;


TEST(ClearanceChecker, DiscsCoverEveryContactPart) {
  const HeightTerrain t = TerrainOf(Blocks({}));
  const ClearanceChecker c(t);
  // Every point of every part lies in a disc of that part.
  for (int p = 0; p < static_cast<int>(c.parts().size()); ++p) {
    const hwconfig::ContactPart& part = c.parts()[static_cast<std::size_t>(p)];
    const Eigen::Vector2d r = Eigen::Vector2d::Constant(part.radius);
    const Eigen::Vector2d lo = part.is_disc ? Eigen::Vector2d(part.centre - r) : part.min;
    const Eigen::Vector2d hi = part.is_disc ? Eigen::Vector2d(part.centre + r) : part.max;
    for (double x = lo.x(); x <= hi.x(); x += 0.02) {
      for (double y = lo.y(); y <= hi.y(); y += 0.02) {
        if (part.DistanceTo({x, y}) > 0.0) continue;
        bool covered = false;
        for (const PartDisc& d : c.discs()) {
          covered = covered || (d.part == p && (d.centre - Eigen::Vector2d(x, y)).norm() <=
                                                   d.radius + 1e-9);
        }
        EXPECT_TRUE(covered) << part.name << " at " << x << ", " << y;
      }
    }
  }
}

TEST(ClearanceChecker, FlatGroundPasses) {
  const HeightTerrain t = TerrainOf(Blocks({}));
  const PoseCheck r = ClearanceChecker(t).CheckPose({0.0, 0.0, 0.3}, true);
  EXPECT_TRUE(r.ok) << r.why;
  EXPECT_NEAR(r.tilt, 0.0, 1e-6);
  EXPECT_EQ(r.unknown_wheels, 0);
}

TEST(ClearanceChecker, RockUnderAWheelLineFailsNamingThePart) {
  // 0.25 m rock at the left wheel line (y = +0.5) beside the middle wheel.
  const HeightTerrain t = TerrainOf(Blocks({{0.3, 0.5, 0.1, 0.25}}));
  const PoseCheck r = ClearanceChecker(t).CheckPose({0.0, 0.0, 0.0}, true);
  EXPECT_FALSE(r.ok);
  EXPECT_TRUE(r.why.find("_l") != std::string::npos || r.why.find("wheel_l") != std::string::npos)
      << r.why;
  EXPECT_NE(r.why.find("wheel hazard"), std::string::npos) << r.why;
}

// Room agrees with the parts check: positive (and large) on open ground, negative where a part
// touches a hazard, and it falls as the rover moves toward a rock.
TEST(ClearanceChecker, RoomIsPositiveExactlyWhereThePartsCheckPasses) {
  const HeightTerrain t = TerrainOf(Blocks({{0.3, 0.5, 0.1, 0.25}}));
  const ClearanceChecker c(t);
  EXPECT_LT(c.Room({0.0, 0.0, 0.0}), 0.0);
  EXPECT_FALSE(c.CheckPose({0.0, 0.0, 0.0}, false).ok);
  double last = c.Room({0.0, -1.5, 0.0});
  EXPECT_GT(last, 0.3);
  for (double y = -1.4; y <= 0.0 + 1e-9; y += 0.1) {
    const double room = c.Room({0.0, y, 0.0});
    EXPECT_LE(room, last + 1e-9) << y;
    EXPECT_EQ(room > 0.0, c.CheckPose({0.0, y, 0.0}, false).ok) << y << " room " << room;
    last = room;
  }
  EXPECT_GT(ClearanceChecker(TerrainOf(Blocks({}))).Room({0.0, 0.0, 0.0}), 1.0);
}

TEST(ClearanceChecker, RockBetweenTheWheelsPassesUnderTheBelly) {
  // 0.25 m tall, 0.3 m wide, centred under the body: the rover straddles it.
  const HeightTerrain straddle = TerrainOf(Blocks({{0.0, 0.0, 0.15, 0.25}}));
  const PoseCheck ok = ClearanceChecker(straddle).CheckPose({0.0, 0.0, 0.0}, true);
  EXPECT_TRUE(ok.ok) << ok.why;
  // 0.5 m tall there: the body hits it.
  const HeightTerrain tall = TerrainOf(Blocks({{0.0, 0.0, 0.15, 0.5}}));
  const PoseCheck bad = ClearanceChecker(tall).CheckPose({0.0, 0.0, 0.0}, true);
  EXPECT_FALSE(bad.ok);
  EXPECT_NE(bad.why.find("body"), std::string::npos) << bad.why;
}

TEST(ClearanceChecker, SuspensionFollowsTheWheelsAndLimitsTilt) {
  // A 15 cm plateau under the left wheels only (wide, so no step inside the wheel patches
  // reaches the wheel limit... it does at its edge, so raise the wheel limit for this test).
  EnavOptions o = TestOptions();
  o.wheel_step = 0.3;
  o.clearance_margin = 0.0;
  const HeightTerrain t = TerrainOf([](double, double y) { return y > 0.25 ? 0.15 : 0.0; }, o);
  const PoseCheck r = ClearanceChecker(t).CheckPose({0.0, 0.0, 0.0}, true);
  EXPECT_TRUE(r.ok) << r.why;
  EXPECT_NEAR(r.tilt, std::atan2(0.15, 1.0), 0.02);  // roll over the 1 m track
  o.max_tilt = 5.0 * kDegree;
  const HeightTerrain steep = TerrainOf([](double, double y) { return y > 0.25 ? 0.15 : 0.0; }, o);
  const PoseCheck tilted = ClearanceChecker(steep).CheckPose({0.0, 0.0, 0.0}, true);
  EXPECT_FALSE(tilted.ok);
  EXPECT_NE(tilted.why.find("tilt"), std::string::npos) << tilted.why;
}

TEST(ClearanceChecker, TouchedHazardsCanBeExemptedOthersNot) {
  // A rock against the left front wheel and another 0.9 m behind the right rear wheel.
  const HeightTerrain t = TerrainOf(Blocks({{0.85, 0.5, 0.1, 0.25}, {-1.6, -0.5, 0.1, 0.25}}));
  const ClearanceChecker c(t);
  const geometry::Pose2 here{0.0, 0.0, 0.0};
  EXPECT_FALSE(c.CheckPose(here, false).ok);
  const Exempt touched = c.Touching(here, 0.0);
  EXPECT_FALSE(touched.empty());
  EXPECT_TRUE(c.CheckPose(here, false, &touched).ok);
  // Backing 0.5 m off the exempt rock is clear; 1 m puts the right rear wheel on the other.
  EXPECT_TRUE(c.CheckPose({-0.5, 0.0, 0.0}, false, &touched).ok);
  const PoseCheck back = c.CheckPose({-1.0, 0.0, 0.0}, false, &touched);
  EXPECT_FALSE(back.ok);
  EXPECT_NE(back.why.find("_rr"), std::string::npos) << back.why;
}

TEST(ClearanceChecker, AnExemptionHoldsOnlyForThePartThatTouches) {
  // A rock against the left middle wheel only. Turning in place 40 deg clockwise swings the left
  // rear wheel (0.8 m from the centre) through where the rock is: the middle wheel may leave
  // it, the rear wheel may not run onto it.
  const HeightTerrain t = TerrainOf(Blocks({{0.0, 0.72, 0.08, 0.25}}));
  const ClearanceChecker c(t);
  const geometry::Pose2 here{0.0, 0.0, 0.0};
  const Exempt touched = c.Touching(here, 0.0);
  ASSERT_FALSE(touched.empty());
  EXPECT_TRUE(c.CheckPose(here, false, &touched).ok);
  bool swept = false;
  for (int deg = 5; deg <= 60; deg += 5) {
    const PoseCheck turned = c.CheckPose({0.0, 0.0, -deg * kDegree}, false, &touched);
    if (!turned.ok) {
      swept = true;
      EXPECT_NE(turned.why.find("_l"), std::string::npos) << turned.why;
      EXPECT_EQ(turned.why.find("wheel_lm"), std::string::npos) << turned.why;
    }
  }
  EXPECT_TRUE(swept);
}

TEST(ClearanceChecker, UnseenWheelPatchesAreCounted) {
  auto t = HeightTerrain::Create(TestOptions());
  ASSERT_TRUE(t.ok());
  ASSERT_TRUE(t->Update(ScanOf(Blocks({}), -3, 0.3, -3, 3)).ok());  // nothing ahead of x = 0.3
  const PoseCheck r = ClearanceChecker(*t).CheckPose({0.0, 0.0, 0.0}, true);
  EXPECT_TRUE(r.ok) << r.why;
  EXPECT_EQ(r.unknown_wheels, 2);  // the front wheels at x = 0.625
}

}  // namespace
}  // namespace rover::apl::enav
