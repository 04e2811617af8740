// The autonomous-driving judge figures on synthetic maps and tracks: each figure's arithmetic,
// and the cases that must count against the rover.
#include "rover/deploy/runner/autonav_judging.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

namespace rover::deploy::runner {
namespace {

// A 10 m x 10 m map of 0.2 m cells from (0, -5), all known and perfect.
GoodnessGrid ClearMap() {
  GoodnessGrid g;
  g.origin_x = 0;
  g.origin_y = -5;
  g.resolution = 0.2;
  g.width = 50;
  g.height = 50;
  g.goodness.assign(2500, 255);
  g.flags.assign(2500, 1);
  return g;
}

// Marks every cell within `r` of (x, y) as an obstacle.
void MarkDisc(GoodnessGrid* g, double x, double y, double r) {
  for (int j = 0; j < g->height; ++j) {
    for (int i = 0; i < g->width; ++i) {
      const double cx = g->origin_x + (i + 0.5) * g->resolution;
      const double cy = g->origin_y + (j + 0.5) * g->resolution;
      if (std::hypot(cx - x, cy - y) <= r) g->goodness[j * g->width + i] = 0;
    }
  }
}

// A straight drive along y = 0 from x = 0 to x = 10 at 0.1 m/s, points every 0.2 s.
Track StraightTrack(double speed = 0.1, double duration = 100) {
  Track t;
  const int n = static_cast<int>(std::lround(duration / 0.2));
  for (int k = 0; k <= n; ++k) t.push_back({0.2 * k, speed * 0.2 * k, 0.0});
  return t;
}

TEST(HazardMap, RecallCountsSeenHazardsMarkedAsObstacles) {
  GoodnessGrid map = ClearMap();
  const std::vector<sim::judge::JudgeRock> rocks = {
      {1, {5, 2}, 0.4, 0.3},    // hazard near the path, marked below
      {2, {7, -3}, 0.4, 0.3},   // hazard near the path, not marked
      {3, {6, 1}, 0.4, 0.1},    // too low: not a hazard
      {4, {5, 30}, 0.4, 0.5},   // far from the path
  };
  MarkDisc(&map, 5, 2, 1.3);
  const HazardMapQuality q = EvaluateHazardMap(map, rocks, 0.2, StraightTrack());
  EXPECT_EQ(q.hazards_near_path, 2);
  EXPECT_EQ(q.hazards_seen, 2);
  EXPECT_EQ(q.hazards_marked, 1);
  EXPECT_DOUBLE_EQ(q.Recall(), 0.5);
  // Every obstacle cell lies within the rover disc of rock 1: no false obstacle.
  EXPECT_GT(q.obstacle_cells, 100);
  EXPECT_EQ(q.false_obstacle_cells, 0);
  EXPECT_DOUBLE_EQ(q.FalseObstacleRate(), 0.0);
}

TEST(HazardMap, UnseenHazardsDoNotCountAndPhantomObstaclesDo) {
  GoodnessGrid map = ClearMap();
  const std::vector<sim::judge::JudgeRock> rocks = {{1, {5, 2}, 0.4, 0.3}};
  // The hazard's cell is unknown: the rover never saw it.
  const int k = map.CellAt(5, 2);
  ASSERT_GE(k, 0);
  map.flags[static_cast<std::size_t>(k)] = 0;
  // A phantom obstacle 3 m from any hazard.
  MarkDisc(&map, 5, -3, 0.25);
  const HazardMapQuality q = EvaluateHazardMap(map, rocks, 0.2, StraightTrack());
  EXPECT_EQ(q.hazards_near_path, 1);
  EXPECT_EQ(q.hazards_seen, 0);
  EXPECT_TRUE(std::isnan(q.Recall()));
  EXPECT_GT(q.obstacle_cells, 0);
  EXPECT_EQ(q.false_obstacle_cells, q.obstacle_cells);
  EXPECT_DOUBLE_EQ(q.FalseObstacleRate(), 1.0);
  // An empty map sees nothing and marks nothing.
  const HazardMapQuality none = EvaluateHazardMap(GoodnessGrid{}, rocks, 0.2, StraightTrack());
  EXPECT_EQ(none.hazards_seen, 0);
  EXPECT_EQ(none.obstacle_cells, 0);
}

TEST(HazardMap, AHazardOutsideTheMapWasNotSeen) {
  GoodnessGrid map = ClearMap();
  const std::vector<sim::judge::JudgeRock> rocks = {{1, {-2, 0}, 0.4, 0.3}};
  const HazardMapQuality q = EvaluateHazardMap(map, rocks, 0.2, StraightTrack());
  EXPECT_EQ(q.hazards_near_path, 1);
  EXPECT_EQ(q.hazards_seen, 0);
}

TEST(Motion, TraverseRateAndStandingStill) {
  // 50 s driving at 0.1 m/s, then 50 s standing still.
  Track t = StraightTrack(0.1, 50);
  for (int k = 251; k <= 500; ++k) t.push_back({0.2 * k, 5.0, 0.0});
  const MotionFigures m = EvaluateMotion(t, 0, 100);
  EXPECT_NEAR(m.distance, 5.0, 1e-9);
  EXPECT_NEAR(m.traverse_rate, 180.0, 1e-6);  // 5 m in 100 s
  EXPECT_NEAR(m.standing_still, 0.5, 0.01);
  // Only the command's window counts.
  const MotionFigures first = EvaluateMotion(t, 0, 50);
  EXPECT_NEAR(first.traverse_rate, 360.0, 1e-6);
  EXPECT_NEAR(first.standing_still, 0.0, 1e-9);
  // Creeping below 1 cm/s is standing still.
  const MotionFigures creep = EvaluateMotion(StraightTrack(0.005, 20), 0, 20);
  EXPECT_NEAR(creep.standing_still, 1.0, 1e-9);
  EXPECT_EQ(EvaluateMotion({}, 0, 0).traverse_rate, 0.0);
}

TEST(Motion, TurningInPlaceIsNotStandingStill) {
  // 20 s standing, then 20 s turning in place at 0.1 rad/s, then 20 s at 0.005 rad/s (below
  // the 0.01 rad/s threshold), 0.2 s apart.
  Track t;
  std::vector<double> yaw;
  double a = 0;
  for (int k = 0; k <= 300; ++k) {
    const double time = 0.2 * k;
    if (time > 20 && time <= 40) a += 0.1 * 0.2;
    if (time > 40) a += 0.005 * 0.2;
    t.push_back({time, 1.0, 2.0});
    yaw.push_back(std::remainder(a, 2.0 * std::numbers::pi));  // wraps past pi: still a turn
  }
  const MotionFigures with = EvaluateMotion(t, 0, 60, yaw);
  EXPECT_NEAR(with.standing_still, 40.0 / 60.0, 0.01);
  EXPECT_NEAR(with.turning_in_place, 20.0 / 60.0, 0.01);
  const MotionFigures without = EvaluateMotion(t, 0, 60);
  EXPECT_NEAR(without.standing_still, 1.0, 1e-9);
  EXPECT_EQ(without.turning_in_place, 0.0);
  // Yaws that do not match the track are ignored.
  yaw.pop_back();
  EXPECT_NEAR(EvaluateMotion(t, 0, 60, yaw).standing_still, 1.0, 1e-9);
}

TEST(KeepOut, EntriesCountTrackPointsWithTheFrontInAZone) {
  // A band x in [9, 11] across the line; the rover drives along y = 0 from x = 0.
  const std::vector<std::vector<Eigen::Vector2d>> band = {{{9, -8}, {11, -8}, {11, 8}, {9, 8}}};
  Track stops_short, enters;
  for (double x = 0; x <= 8.0 + 1e-9; x += 0.1) stops_short.push_back({x, x, 0});
  for (double x = 0; x <= 10.0 + 1e-9; x += 0.1) enters.push_back({x, x, 0});
  EXPECT_EQ(KeepOutEntries(stops_short, band, 0.75), 0);
  // Centre at 8.3 m: the front (0.75 m ahead) is in the zone from there on.
  EXPECT_EQ(KeepOutEntries(enters, band, 0.75), 18);
  // Clockwise winding is the same zone.
  const std::vector<std::vector<Eigen::Vector2d>> cw = {{{9, 8}, {11, 8}, {11, -8}, {9, -8}}};
  EXPECT_EQ(KeepOutEntries(enters, cw, 0.75), 18);
  EXPECT_EQ(KeepOutEntries(enters, {}, 0.75), 0);
}

TEST(AutonavFigures, ListedWithUnitsAndLeftOutWhenUnmeasured) {
  MobilityOutcome mob;
  mob.steps = 12;
  mob.images = 14;
  mob.sim_start_s = 0;
  mob.sim_end_s = 100;
  const std::vector<sim::judge::JudgeRock> rocks = {{1, {5, 2}, 0.4, 0.3}};
  auto names = [](const std::vector<sim::judge::Criterion>& f) {
    std::vector<std::string> n;
    for (const auto& c : f) n.push_back(c.name);
    return n;
  };
  const auto no_map = AutonavFigures(mob, StraightTrack(), rocks, 0.2);
  EXPECT_EQ(names(no_map), (std::vector<std::string>{"mobility_steps", "mobility_images",
                                                     "traverse_rate", "standing_still"}));
  EXPECT_NEAR(no_map[2].measured, 360.0, 1e-6);
  EXPECT_EQ(no_map[2].unit, "m/h");
  mob.last_map = ClearMap();
  MarkDisc(&*mob.last_map, 5, 2, 1.3);
  const auto with_map = AutonavFigures(mob, StraightTrack(), rocks, 0.2);
  ASSERT_EQ(with_map.size(), 6u);
  EXPECT_EQ(with_map[4].name, "hazard_map_recall");
  EXPECT_DOUBLE_EQ(with_map[4].measured, 100.0);
  EXPECT_EQ(with_map[5].name, "hazard_map_false_obstacle_rate");
  EXPECT_DOUBLE_EQ(with_map[5].measured, 0.0);
}

}  // namespace
}  // namespace rover::deploy::runner
