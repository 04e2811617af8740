// The fast code against the straightforward references on synthetic HAZCAM scans of seeded
// rock fields: moment sums + prefix sums give the same plane fits and goodness as fitting the
// raw points of every disc, and walking along each arc finds the same cells as testing every
// cell of the map.
#include "reference_gestalt.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "rover/testing/fakes/range_synth.hpp"
#include "rover/apl/gestalt/arc_evaluator.hpp"
#include "rover/apl/gestalt/terrain_map.hpp"

namespace rover::apl::gestalt::testing {
namespace {

using rover::testing::FrontHazcam;
using rover::testing::PinholeCamera;
using rover::testing::RoverPose;
using rover::testing::SeededRockField;
using rover::testing::SynthesizeScan;

struct Scene {
  const char* preset;
  std::uint64_t seed;
  double x, y, yaw;
};

class ReferenceAgreement : public ::testing::TestWithParam<Scene> {};

TEST_P(ReferenceAgreement, AssessmentAndVotesMatch) {
  const Scene sc = GetParam();
  const sim::terrain::Terrain world = SeededRockField(sc.preset, sc.seed, 20.0);
  PinholeCamera cam = FrontHazcam();
  cam.noise_at_1m = 0.003;
  cam.seed = sc.seed;
  const Eigen::Isometry3d pose = RoverPose(world.natural, sc.x, sc.y, sc.yaw);
  const nav_core::RangeScan scan = SynthesizeScan(world.natural, cam, pose);
  const GestaltOptions o;
  auto map = TerrainMap::Create(o);
  ASSERT_TRUE(map.ok());
  ASSERT_TRUE(map->Update(scan).ok());
  const ReferenceResult ref = ReferenceAssess(o, scan);

  const nav_core::GoodnessMap& fast = map->goodness_map();
  ASSERT_EQ(fast.width, ref.map.width);
  EXPECT_DOUBLE_EQ(fast.origin_x, ref.map.origin_x);
  EXPECT_DOUBLE_EQ(fast.origin_y, ref.map.origin_y);
  int known = 0, off_by_one = 0;
  for (std::size_t k = 0; k < fast.cell_count(); ++k) {
    ASSERT_EQ(fast.flags[k] & nav_core::kCellKnown, ref.map.flags[k] & nav_core::kCellKnown) << k;
    EXPECT_EQ(fast.flags[k] & nav_core::kCellBorder, ref.map.flags[k] & nav_core::kCellBorder) << k;
    EXPECT_EQ(fast.certainty[k], ref.map.certainty[k]) << k;
    if (!(fast.flags[k] & nav_core::kCellKnown)) continue;
    ++known;
    const int d = std::abs(fast.goodness[k] - ref.map.goodness[k]);
    EXPECT_LE(d, 1) << "cell " << k;  // rounding at a ramp's half-way point may differ
    off_by_one += d;
    const CellAssessment& a = map->assessments()[k];
    const CellAssessment& b = ref.assessments[k];
    EXPECT_NEAR(a.tilt, b.tilt, 1e-5) << k;
    EXPECT_NEAR(a.roughness, b.roughness, 1e-5) << k;
    EXPECT_NEAR(a.step, b.step, 1e-5) << k;
  }
  EXPECT_GT(known, 300);
  EXPECT_LE(off_by_one, known / 100);

  // Votes toward a goal ahead and one behind, over the fast map.
  auto evaluator = ArcEvaluator::Create(o);
  ASSERT_TRUE(evaluator.ok());
  for (const Eigen::Vector2d& goal_rover :
       {Eigen::Vector2d(6.0, 1.0), Eigen::Vector2d(-2.0, -3.0)}) {
    nav_core::ArcRequest req;
    req.site_from_rover = pose;
    req.goal = (pose * Eigen::Vector3d(goal_rover.x(), goal_rover.y(), 0.0)).head<2>();
    req.goal_tolerance = 0.5;
    auto e = evaluator->Evaluate(fast, req);
    ASSERT_TRUE(e.ok());
    const nav_core::ArcEvaluation r = ReferenceEvaluate(o, fast, req);
    ASSERT_EQ(e->candidates.size(), r.candidates.size());
    for (std::size_t k = 0; k < r.candidates.size(); ++k) {
      EXPECT_EQ(e->hazard[k].goodness, r.hazard[k].goodness) << k;
      EXPECT_EQ(e->hazard[k].certainty, r.hazard[k].certainty) << k;
      EXPECT_EQ(e->waypoint[k].goodness, r.waypoint[k].goodness) << k;
      EXPECT_EQ(e->merged[k].goodness, r.merged[k].goodness) << k;
    }
    EXPECT_EQ(e->chosen, r.chosen);
    EXPECT_EQ(e->mode, r.mode);
  }
}

INSTANTIATE_TEST_SUITE_P(RockFields, ReferenceAgreement,
                         ::testing::Values(Scene{"vl1", 5, 0.0, 0.0, 0.0},
                                           Scene{"vl2", 6, 0.7, -0.4, 0.6}));

}  // namespace
}  // namespace rover::apl::gestalt::testing
