// TerrainMap end to end on synthetic HAZCAM scans of sim/terrain scenes (range_synth.hpp).
#include "rover/apl/gestalt/terrain_map.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "rover/testing/fakes/range_synth.hpp"
#include "rover/apl/gestalt/arc_evaluator.hpp"
#include "truth_check.hpp"

namespace rover::apl::gestalt {
namespace {

using nav_core::RangeScan;
using rover::testing::AddRock;
using rover::testing::FlatWorld;
using rover::testing::FrontHazcam;
using rover::testing::PinholeCamera;
using rover::testing::RoverPose;
using rover::testing::SynthesizeScan;

TerrainMap MakeMap(const GestaltOptions& o = {}) {
  auto m = TerrainMap::Create(o);
  EXPECT_TRUE(m.ok()) << m.status().message();
  return std::move(m).value();
}

RangeScan Look(const sim::terrain::Terrain& world, double x, double y, double yaw,
               std::uint64_t seed = 1) {
  PinholeCamera cam = FrontHazcam();
  cam.noise_at_1m = 0.002;
  cam.seed = seed;
  return SynthesizeScan(world.natural, cam, RoverPose(world.natural, x, y, yaw));
}

nav_core::CellValue At(const TerrainMap& m, double x, double y) { return m.GoodnessAt({x, y}); }

const CellAssessment& AssessmentAt(const TerrainMap& m, double x, double y) {
  int i = 0, j = 0;
  m.goodness_map().CellOf(x, y, &i, &j);
  return m.assessments().at(i, j);
}

TEST(TerrainMap, CreateValidatesOptions) {
  GestaltOptions o;
  o.min_coverage = 0.0;
  EXPECT_EQ(TerrainMap::Create(o).status().message(), "min_coverage = 0 is outside (0, 1]");
}

TEST(TerrainMap, MalformedScansAreRejectedAndChangeNothing) {
  const sim::terrain::Terrain world = FlatWorld(14.0);
  TerrainMap m = MakeMap();
  ASSERT_TRUE(m.Update(Look(world, 0, 0, 0)).ok());
  const std::uint64_t rev = m.goodness_map().revision;
  const std::vector<std::uint8_t> before = m.goodness_map().goodness;
  RangeScan bad = Look(world, 0, 0, 0);
  bad.valid.pop_back();
  bad.camera = "front_hazcam";
  auto r = m.Update(bad);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().message(),
            "RangeScan.valid: 65535 bytes for 65536 pixels (camera front_hazcam)");
  EXPECT_EQ(m.goodness_map().revision, rev);
  EXPECT_EQ(m.goodness_map().goodness, before);
  // Non-finite points marked valid are skipped, not fatal.
  RangeScan nan_points = Look(world, 0, 0, 0);
  for (std::size_t k = 0; k < 300; ++k) nan_points.xyz[3 * k + 20000] = std::nanf("");
  auto s = m.Update(nan_points);
  ASSERT_TRUE(s.ok());
  EXPECT_LT(s->points_used, s->points_total);
}

TEST(TerrainMap, FlatGroundIsPerfectAndTheRestUnknown) {
  const sim::terrain::Terrain world = FlatWorld(14.0);
  TerrainMap m = MakeMap();
  auto s = m.Update(Look(world, 0, 0, 0));
  ASSERT_TRUE(s.ok());
  EXPECT_GT(s->points_used, 30000);
  EXPECT_GT(s->cells_touched, 300);
  EXPECT_GT(s->cells_fov_edge, 50);
  EXPECT_EQ(s->cells_obstacle, 0);
  const nav_core::GoodnessMap& g = m.goodness_map();
  EXPECT_EQ(g.width, 50);
  EXPECT_DOUBLE_EQ(g.origin_x, -5.0);  // the rover's cell is the centre one
  EXPECT_DOUBLE_EQ(g.origin_y, -5.0);
  int known = 0;
  for (std::size_t k = 0; k < g.cell_count(); ++k) {
    if (!(g.flags[k] & nav_core::kCellKnown)) {
      EXPECT_EQ(g.goodness[k], 11);
      EXPECT_EQ(g.certainty[k], 0);
      continue;
    }
    ++known;
    if (g.flags[k] & nav_core::kCellBorder) {
      EXPECT_EQ(g.goodness[k], 250);
      EXPECT_EQ(g.certainty[k], 128);
    } else {
      EXPECT_EQ(g.goodness[k], 255);
      EXPECT_EQ(g.certainty[k], 255);
    }
  }
  EXPECT_GT(known, 300);
  EXPECT_TRUE(At(m, 2.5, 0.0).known());
  EXPECT_FALSE(At(m, -2.5, 0.0).known());  // behind the rover
  EXPECT_FALSE(At(m, 20.0, 0.0).known());  // off the map
}

// Flat ground with a 0.3 m rock 2.5 m ahead, seen once.
struct OneRock {
  sim::terrain::Terrain world = FlatWorld(14.0);
  TerrainMap map = MakeMap();
  OneRock() {
    AddRock(&world, 2.5, 0.0, 0.5, 0.3);
    EXPECT_TRUE(map.Update(Look(world, 0, 0, 0)).ok());
  }
};

TEST(TerrainMap, ARockIsAnObstacleBlobTheSizeOfTheRoverDisc) {
  OneRock scene;
  const TerrainMap& m = scene.map;
  EXPECT_EQ(At(m, 2.5, 0.0).goodness, 0);
  const CellAssessment& a = AssessmentAt(m, 2.5, 0.0);
  EXPECT_EQ(a.step_goodness, 0);
  EXPECT_GT(a.step, 0.25);
  // Configuration space: within the disc radius (1.3 m) of the rock's edge the rover would
  // have it under its body; a little farther out it would not.
  EXPECT_EQ(At(m, 2.5, 1.2).goodness, 0);
  EXPECT_EQ(At(m, 3.6, 0.0).goodness, 0);
  EXPECT_GT(At(m, 2.5, 1.9).goodness, 200);
  EXPECT_GT(At(m, 4.6, 0.0).goodness, 200);
}

TEST(TerrainMap, TallThinRocksAreFoundThroughTheCellSpread) {
  sim::terrain::Terrain world = FlatWorld(14.0);
  AddRock(&world, 2.2, 0.3, 0.09, 0.32, 0.05);  // a 9 cm wide, 32 cm tall flat-topped post
  GestaltOptions mean_only;
  mean_only.step_sigma_k = 0.0;
  TerrainMap blind = MakeMap(mean_only), seen = MakeMap();
  const RangeScan scan = Look(world, 0, 0, 0);
  ASSERT_TRUE(blind.Update(scan).ok());
  ASSERT_TRUE(seen.Update(scan).ok());
  EXPECT_GT(At(blind, 2.2, 0.3).goodness, 30);  // the mean barely rises: looks passable
  EXPECT_LT(At(seen, 2.2, 0.3).goodness, 10);   // mean + sigma: an obstacle
  EXPECT_LT(AssessmentAt(blind, 2.2, 0.3).step, AssessmentAt(seen, 2.2, 0.3).step - 0.08);
}

TEST(TerrainMap, StepEstimateTracksRockHeight) {
  // Round rocks twice as wide as tall, 2.5 m ahead. Cell means alone read a rock low (its cells
  // average its flanks with its top); mean + 1 sigma reads it within a few centimetres.
  for (double h : {0.10, 0.15, 0.20, 0.25, 0.30}) {
    sim::terrain::Terrain world = FlatWorld(14.0);
    AddRock(&world, 2.5, 0.0, 2.0 * h, h);
    GestaltOptions mean_only;
    mean_only.step_sigma_k = 0.0;
    TerrainMap a = MakeMap(), b = MakeMap(mean_only);
    const RangeScan scan = Look(world, 0, 0, 0);
    ASSERT_TRUE(a.Update(scan).ok());
    ASSERT_TRUE(b.Update(scan).ok());
    EXPECT_NEAR(AssessmentAt(a, 2.5, 0.0).step, h, 0.035) << h;
    EXPECT_LT(AssessmentAt(b, 2.5, 0.0).step, h - 0.02) << h;
  }
}

TEST(TerrainMap, FootprintCheckFlagsHazardAndTallCells) {
  // A 0.18 m and a 0.32 m rock, 2.5 m ahead: both hazards (>= 0.15 m), only the second tall
  // (>= 0.22 m, reaching the body and rocker links); no flags without the footprint check.
  sim::terrain::Terrain world = FlatWorld(14.0);
  AddRock(&world, 2.5, -0.8, 0.36, 0.18);
  AddRock(&world, 2.5, 0.8, 0.5, 0.32);
  GestaltOptions o;
  o.footprint_check = true;
  TerrainMap with = MakeMap(o), without = MakeMap();
  const RangeScan scan = Look(world, 0, 0, 0);
  ASSERT_TRUE(with.Update(scan).ok());
  ASSERT_TRUE(without.Update(scan).ok());
  const nav_core::CellValue low = At(with, 2.5, -0.8), tall = At(with, 2.5, 0.8);
  EXPECT_NE(low.flags & nav_core::kCellHazard, 0);
  EXPECT_EQ(low.flags & nav_core::kCellTall, 0);
  EXPECT_NE(tall.flags & nav_core::kCellHazard, 0);
  EXPECT_NE(tall.flags & nav_core::kCellTall, 0);
  EXPECT_EQ(At(with, 2.5, 0.0).flags & nav_core::kCellHazard, 0);  // the ground between
  EXPECT_EQ(At(without, 2.5, 0.8).flags & nav_core::kCellHazard, 0);
}

TEST(TerrainMap, PitchersMoundsCanBeClimbed) {
  // A hill rising at 13 deg from 2 m ahead of the rover, seen by the HAZCAM. Searching for steps
  // anywhere in the 2.6 m rover disc (MER's first flight software) finds the flat-to-hill bend
  // an obstacle in front of the hill; the belly-sized disc does not, so the rover can climb.
  sim::terrain::Terrain world = FlatWorld(14.0);
  const double s = std::tan(13.0 * kDegree);
  for (int j = 0; j < world.bare.ny(); ++j) {
    for (int i = 0; i < world.bare.nx(); ++i) {
      const double x = world.bare.min_x() + i * world.bare.resolution();
      world.bare.at(i, j) = static_cast<float>(s * std::clamp(x - 2.0, 0.0, 2.5));
    }
  }
  sim::terrain::RebuildHeights(&world);
  GestaltOptions whole;
  whole.step_disc_diameter = whole.rover_disc_diameter;
  TerrainMap old_way = MakeMap(whole), belly = MakeMap();
  const RangeScan scan = Look(world, 0, 0, 0);
  ASSERT_TRUE(old_way.Update(scan).ok());
  ASSERT_TRUE(belly.Update(scan).ok());
  int worst_old = 255, worst_belly = 255, known = 0;
  for (double x = 0.9; x <= 4.4; x += 0.2) {
    const nav_core::CellValue a = At(old_way, x, 0.0), b = At(belly, x, 0.0);
    if (!a.known() || !b.known()) continue;
    ++known;
    worst_old = std::min(worst_old, a.goodness);
    worst_belly = std::min(worst_belly, b.goodness);
  }
  EXPECT_GT(known, 10);
  EXPECT_LT(worst_old, 10);    // forbidden
  EXPECT_GT(worst_belly, 30);  // rough going, allowed
  auto evaluator = ArcEvaluator::Create(GestaltOptions{});
  ASSERT_TRUE(evaluator.ok());
  nav_core::ArcRequest up_the_hill;
  up_the_hill.site_from_rover = RoverPose(world.natural, 0, 0, 0);
  up_the_hill.goal = {4.0, 0.0};
  auto e_old = evaluator->Evaluate(old_way.goodness_map(), up_the_hill);
  auto e_belly = evaluator->Evaluate(belly.goodness_map(), up_the_hill);
  ASSERT_TRUE(e_old.ok() && e_belly.ok());
  EXPECT_EQ(e_old->hazard[11].goodness, 0);  // the straight arc
  EXPECT_GT(e_belly->hazard[11].goodness, 30);
}

TEST(TerrainMap, NewDataOverridesOld) {
  OneRock scene;
  sim::terrain::Terrain& world = scene.world;
  TerrainMap& m = scene.map;
  ASSERT_EQ(At(m, 2.5, 0.0).goodness, 0);
  // The "rock" was a stereo artefact (or a pose error): the next look shows flat ground.
  world.rocks.clear();
  sim::terrain::RebuildHeights(&world);
  ASSERT_TRUE(m.Update(Look(world, 0, 0, 0, 2)).ok());
  EXPECT_EQ(At(m, 2.5, 0.0).goodness, 255);
}

TEST(TerrainMap, UpdatesAreIncremental) {
  // After two overlapping scans, every cell's stored assessment equals a fresh assessment of the
  // final moment grid: the cells the second scan did not reach kept valid results.
  const sim::terrain::Terrain world = rover::testing::SeededRockField("vl1", 8, 20.0);
  GestaltOptions o;
  o.num_layers = 1;
  TerrainMap m = MakeMap(o);
  ASSERT_TRUE(m.Update(Look(world, 0, 0, 0, 1)).ok());
  auto s2 = m.Update(Look(world, 0.6, 0.2, 0.5, 2));
  ASSERT_TRUE(s2.ok());
  EXPECT_LT(s2->cells_assessed, 50 * 50);  // not the whole grid
  const DiscAssessor assessor(o);
  Grid<CellStats> stats(50, 50);
  Grid<int> covered(50, 50, 0);
  for (std::size_t k = 0; k < stats.size(); ++k) {
    stats[k] = StatsOf(m.moments()[k], o.min_cell_points);
    covered[k] = stats[k].covered;
  }
  RowPrefix<Moments> sums;
  sums.Build(m.moments());
  RowPrefix<int> counts;
  counts.Build(covered);
  int compared = 0;
  for (int j = 0; j < 50; ++j) {
    for (int i = 0; i < 50; ++i) {
      const CellAssessment& stored = m.assessments().at(i, j);
      if (!stored.known()) continue;
      const CellAssessment fresh =
          assessor.Assess(i, j, sums.DiscSum(i, j, assessor.rover_disc()),
                          counts.DiscSum(i, j, assessor.rover_disc()), stats);
      ASSERT_TRUE(fresh.known()) << i << "," << j;
      EXPECT_EQ(fresh.goodness, stored.goodness) << i << "," << j;
      ++compared;
    }
  }
  EXPECT_GT(compared, 400);
}

TEST(TerrainMap, FollowRecentresAndForgetsFarData) {
  const sim::terrain::Terrain world = FlatWorld(30.0);
  TerrainMap m = MakeMap();
  ASSERT_TRUE(m.Update(Look(world, 0, 0, 0)).ok());
  ASSERT_TRUE(At(m, 2.5, 0.0).known());
  m.Follow(RoverPose(world.natural, 4.0, 0.0, 0.0));
  EXPECT_DOUBLE_EQ(m.goodness_map().origin_x, -1.0);
  EXPECT_TRUE(At(m, 2.5, 0.0).known());  // 1.5 m from the rover now
  m.Follow(RoverPose(world.natural, 8.0, 0.0, 0.0));
  EXPECT_FALSE(At(m, 2.5, 0.0).known());  // 5.5 m away: forgotten
  m.Clear();
  EXPECT_FALSE(At(m, 8.5, 0.0).known());
}

TEST(TerrainMap, PartialViewsAtTheFovEdgeAreMergedConservatively) {
  // A small tall rock inside one cell, seen whole; then the rover turns right until the left
  // edge of the image cuts through that cell and only a sliver of the rock is in view.
  sim::terrain::Terrain world = FlatWorld(14.0);
  AddRock(&world, 2.1, 0.1, 0.18, 0.3, 0.3);
  const double yaw = -48.0 * kDegree;
  GestaltOptions overwrite;  // no FOV-edge handling: new data always replaces old
  overwrite.fov_edge_band_px = 0;
  overwrite.fov_edge_margin_cells = 0;
  overwrite.num_layers = 1;
  GestaltOptions careful;  // the FOV-edge handling alone (no layers)
  careful.num_layers = 1;
  TerrainMap a = MakeMap(overwrite), b = MakeMap(careful);
  for (TerrainMap* m : {&a, &b}) {
    ASSERT_TRUE(m->Update(Look(world, 0, 0, 0, 1)).ok());
    ASSERT_EQ(At(*m, 2.1, 0.1).goodness, 0);
  }
  int i = 0, j = 0;
  a.goodness_map().CellOf(2.1, 0.1, &i, &j);
  const double points_whole = a.moments().at(i, j).n;
  for (TerrainMap* m : {&a, &b}) ASSERT_TRUE(m->Update(Look(world, 0, 0, yaw, 2)).ok());
  ASSERT_NE(b.fov_edge_cells().at(i, j), 0);              // the cell is at the edge of the view
  ASSERT_LT(a.moments().at(i, j).n, 0.6 * points_whole);  // and only partly seen
  // Overwritten by the sliver, the cell (and every cell whose disc holds it) looks passable;
  // merged conservatively it stays an obstacle.
  EXPECT_GT(At(a, 2.1, 0.1).goodness, 100);
  EXPECT_EQ(At(b, 2.1, 0.1).goodness, 0);
  EXPECT_TRUE(At(b, 2.1, 0.1).flags & nav_core::kCellFovEdge);
  EXPECT_GE(b.moments().at(i, j).n, points_whole);  // the partial view added to the whole one
}

TEST(TerrainMap, LayersRememberAnObstacleThatLeftTheView) {
  // MER's per-image assessment (discs fitted to the latest scan only): after the rover turns
  // away, partial discs near the edge of the new view rate the rock's surroundings safe.
  sim::terrain::Terrain world = FlatWorld(14.0);
  AddRock(&world, 2.0, 0.8, 0.5, 0.3);
  GestaltOptions single;
  single.fit_from_scan_only = true;
  single.num_layers = 1;
  GestaltOptions layered = single;
  layered.num_layers = 7;
  TerrainMap a = MakeMap(single), b = MakeMap(layered);
  const RangeScan ahead = Look(world, 0, 0, 0, 1);
  const RangeScan right = Look(world, 0, 0, -40.0 * kDegree, 2);  // rock just out of view
  ASSERT_TRUE(a.Update(ahead).ok());
  ASSERT_TRUE(b.Update(ahead).ok());
  const nav_core::GoodnessMap before = a.goodness_map();
  ASSERT_TRUE(a.Update(right).ok());
  ASSERT_TRUE(b.Update(right).ok());
  // Cells of the rock's blob the second scan re-rated safe.
  int forgotten = 0, remembered = 0;
  for (std::size_t k = 0; k < before.cell_count(); ++k) {
    if (!(before.flags[k] & nav_core::kCellKnown) || before.goodness[k] > 0) continue;
    if (a.goodness_map().goodness[k] < 200) continue;
    ++forgotten;
    if (b.goodness_map().goodness[k] < 10) ++remembered;
  }
  EXPECT_GT(forgotten, 5);
  EXPECT_EQ(remembered, forgotten);
  // The rock itself is still an obstacle in both.
  EXPECT_EQ(At(b, 2.0, 0.8).goodness, 0);
  // With the default (discs fitted to the merged map) the old data fill the partial discs.
  TerrainMap c = MakeMap();
  ASSERT_TRUE(c.Update(ahead).ok());
  ASSERT_TRUE(c.Update(right).ok());
  for (std::size_t k = 0; k < before.cell_count(); ++k) {
    if (!(before.flags[k] & nav_core::kCellKnown) || before.goodness[k] > 0) continue;
    if (a.goodness_map().goodness[k] < 200) continue;
    EXPECT_LT(c.goodness_map().goodness[k], 10) << k;
  }
}

TEST(TerrainMap, SkipImagingOnceTheMapCoversEveryPath) {
  sim::terrain::Terrain world = FlatWorld(20.0);
  auto evaluator = ArcEvaluator::Create(GestaltOptions{});
  ASSERT_TRUE(evaluator.ok());
  auto request_at = [&](double x) {
    nav_core::ArcRequest r;
    r.site_from_rover = RoverPose(world.natural, x, 0.0, 0.0);
    r.goal = {x + 6.0, 0.0};
    r.goal_tolerance = 0.5;
    return r;
  };
  TerrainMap m = MakeMap();
  ASSERT_TRUE(m.Update(Look(world, 0, 0, 0)).ok());
  auto e0 = evaluator->Evaluate(m.goodness_map(), request_at(0.0));
  ASSERT_TRUE(e0.ok());
  EXPECT_FALSE(e0->all_paths_safe);  // the tight arcs reach ground not seen yet
  // A panorama (left, ahead, right), then one metre forward without imaging.
  ASSERT_TRUE(m.Update(Look(world, 0, 0, 55.0 * kDegree, 2)).ok());
  ASSERT_TRUE(m.Update(Look(world, 0, 0, -55.0 * kDegree, 3)).ok());
  m.Follow(RoverPose(world.natural, 1.0, 0.0, 0.0));
  auto e1 = evaluator->Evaluate(m.goodness_map(), request_at(1.0));
  ASSERT_TRUE(e1.ok());
  EXPECT_TRUE(e1->all_paths_safe);
  // The same with a rock on one of the paths: image again.
  AddRock(&world, 3.0, 1.2, 0.5, 0.3);
  TerrainMap r = MakeMap();
  for (double deg : {0.0, 55.0, -55.0})
    ASSERT_TRUE(r.Update(Look(world, 0, 0, deg * kDegree)).ok());
  r.Follow(RoverPose(world.natural, 1.0, 0.0, 0.0));
  auto e2 = evaluator->Evaluate(r.goodness_map(), request_at(1.0));
  ASSERT_TRUE(e2.ok());
  EXPECT_FALSE(e2->all_paths_safe);
  ASSERT_TRUE(e2->has_choice());
}

// Hazard-map quality against the truth rocks over short drives through seeded rock fields.
TEST(TerrainMap, MarksTheHazardsItSawAndFewCellsWithoutCause) {
  const GestaltOptions o;
  testing::HazardQuality total, total_strict;
  auto add = [](testing::HazardQuality* t, const testing::HazardQuality& q) {
    t->hazards_seen += q.hazards_seen;
    t->hazards_marked += q.hazards_marked;
    t->obstacle_cells += q.obstacle_cells;
    t->false_obstacles += q.false_obstacles;
  };
  for (const char* preset : {"vl1", "vl2"}) {
    for (std::uint64_t seed : {1u, 2u, 3u}) {
      const sim::terrain::Terrain world = rover::testing::SeededRockField(preset, seed, 24.0);
      TerrainMap m = MakeMap(o);
      // A hazard counts as seen when its own cell holds a few points (a rock glimpsed past the
      // edge of a view is not assessed yet; later views will). An obstacle cell is explained
      // by a rock within reach of at least 0.15 m (three quarters of max_step: a rock just under
      // the limit may read just over it), or, strictly, of at least max_step.
      testing::TruthCheckOptions lenient, strict;
      lenient.excuse_height = 0.15;
      lenient.seen = [&m](const sim::terrain::Rock& rock) {
        int i = 0, j = 0;
        m.goodness_map().CellOf(rock.position.x(), rock.position.y(), &i, &j);
        return m.moments().Contains(i, j) && m.moments().at(i, j).n >= 5.0;
      };
      strict.excuse_height = o.max_step;
      testing::HazardQuality field, field_strict;
      for (int step = 0; step < 5; ++step) {
        const double x = 0.8 * step, yaw = 0.2 * std::sin(1.3 * step);
        ASSERT_TRUE(m.Update(Look(world, x, 0.0, yaw, 10 + step)).ok());
        add(&field, testing::CompareWithTruth(m.goodness_map(), world, {x, 0.0}, o, lenient));
        add(&field_strict, testing::CompareWithTruth(m.goodness_map(), world, {x, 0.0}, o, strict));
      }
      std::printf(
          "%s seed %llu: hazards marked %d / %d; obstacle cells %d, unexplained by rocks "
          ">= 0.15 m %.3f, by rocks >= %.2f m %.3f\n",
          preset, static_cast<unsigned long long>(seed), field.hazards_marked, field.hazards_seen,
          field.obstacle_cells, field.false_rate(), o.max_step, field_strict.false_rate());
      add(&total, field);
      add(&total_strict, field_strict);
    }
  }
  std::printf(
      "all: recall %.3f (%d hazards), unexplained obstacle cells %.4f (of %d), strict %.3f\n",
      total.recall(), total.hazards_seen, total.false_rate(), total.obstacle_cells,
      total_strict.false_rate());
  EXPECT_GT(total.hazards_seen, 20);
  EXPECT_GE(total.recall(), 0.95);
  EXPECT_LE(total.false_rate(), 0.02);
}

}  // namespace
}  // namespace rover::apl::gestalt
