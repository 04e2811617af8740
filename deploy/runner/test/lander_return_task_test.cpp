#include "rover/deploy/runner/tasks/lander_return_task.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "rover/base/units.hpp"
#include "rover/deploy/runner/rendezvous_judging.hpp"
#include "run_fixture.hpp"

namespace rover::deploy::runner {
namespace {

using ::testing::HasSubstr;
using testing::ScenarioWithTask;

TEST(LanderReturnTask, ParsesAndChecksItsSection) {
  EXPECT_TRUE(ValidateTask(ScenarioWithTask(
                  "task: {type: lander_return, estimate: {x: 30, y: 1}, ramp: 1, standoff: 1.2}\n"))
                  .ok());
  EXPECT_THAT(ValidateTask(ScenarioWithTask("task: {type: lander_return}\n")).message(),
              HasSubstr("missing 'estimate'"));
  EXPECT_THAT(ValidateTask(ScenarioWithTask(
                  "task: {type: lander_return, estimate: {x: 30, y: 1}, ramp: 2}\n"))
                  .message(),
              HasSubstr("task.ramp"));
  EXPECT_THAT(ValidateTask(ScenarioWithTask(
                  "task: {type: lander_return, estimate: {x: 30}}\n"))
                  .message(),
              HasSubstr("missing 'y'"));
  EXPECT_THAT(ValidateTask(ScenarioWithTask("task: {type: lander_return, estimate: {x: 30, y: "
                                            "1}, climb: false, expect: on_deck}\n"))
                  .message(),
              HasSubstr("'on_deck' needs climb: true"));
  EXPECT_THAT(ValidateTask(ScenarioWithTask(
                  "task: {type: lander_return, estimate: {x: 30, y: 1}, expect: landed}\n"))
                  .message(),
              HasSubstr("task.expect: 'landed' is not one of: on_deck, at_ramp_base, acquired, BAD_COMMAND"));
  auto t = TaskRegistry::Builtin().Make(ScenarioWithTask(
      "task: {type: lander_return, estimate: {x: 30, y: 1}, expect: NOT_FOUND}\n"));
  ASSERT_TRUE(t.ok()) << t.status().message();
  // core/msg's names; the hyphenated spelling of older scenarios is read as the same fault.
  auto hyphen = TaskRegistry::Builtin().Make(ScenarioWithTask(
      "task: {type: lander_return, estimate: {x: 30, y: 1}, expect: TOO-FEW-STRIPES}\n"));
  ASSERT_TRUE(hyphen.ok()) << hyphen.status().message();
  EXPECT_EQ(dynamic_cast<const LanderReturnTask&>(**hyphen).spec().expect, "TOO_FEW_STRIPES");
  EXPECT_EQ((*t)->PlannedPath(), (std::vector<Eigen::Vector2d>{{1, 2}, {30, 1}}));
}

// A lander at (30, 0) whose ramp 0 descends towards -x: its foot at x = 30 - 4.299.
sim::terrain::Lander TestLander() {
  sim::terrain::Lander l;
  l.params.x = 30.0;
  l.params.y = 0.0;
  l.params.yaw_deg = 180.0;
  const double a = 1.5 * std::cos(30.0 * kDegree);
  for (int m = 0; m < 6; ++m) {
    const double ang = kPi + (30.0 + 60.0 * m) * kDegree;
    l.deck_vertices[static_cast<std::size_t>(m)] =
        Eigen::Vector2d(30.0, 0.0) + 1.5 * Eigen::Vector2d(std::cos(ang), std::sin(ang));
  }
  l.ramps[0].direction = Eigen::Vector2d(-1.0, 0.0);
  l.ramps[0].bottom_center = Eigen::Vector3d(30.0 - a - 3.0, 0.0, 0.0);
  l.ramps[1].direction = Eigen::Vector2d(1.0, 0.0);
  l.ramps[1].bottom_center = Eigen::Vector3d(30.0 + a + 3.0, 0.0, 0.0);
  return l;
}

TEST(RendezvousJudging, RangeErrorsPlacementAndOnDeck) {
  const sim::terrain::Lander lander = TestLander();
  RunResult r;
  // Straight along y = 0.01 from x = 0 to the placement point, then onto the deck centre.
  const double foot = lander.ramps[0].bottom_center.x();
  for (int i = 0; i <= 100; ++i) {
    const double x = (foot - 1.0 + 0.003) * i / 100.0;
    r.truth_track.push_back({static_cast<double>(i), x, 0.01});
    r.truth_yaw.push_back(0.5 * kDegree);
  }
  r.truth_track.push_back({101.0, 30.0, 0.0});
  r.truth_yaw.push_back(0.0);
  RendezvousLog log;
  log.standoff = 1.0;
  log.ramp = 0;
  log.at_base_t = 100.0;
  // Sightings: at t = 0 the rover is 30 m out, at t = 50 17.65 m out (within 3 m of 15 m).
  log.samples.push_back({0.0, 2, 30.6, 0.5, true, ""});
  log.samples.push_back({50.0, 2, 13.0, 0.2, true, ""});
  log.samples.push_back({60.0, 2, 13.0, 0.2, false, ""});  // repeated: not judged
  const auto figures = RendezvousFigures(log, lander, {}, r);
  auto find = [&](const std::string& name) -> const sim::judge::Criterion* {
    for (const auto& f : figures) {
      if (f.name == name) return &f;
    }
    return nullptr;
  };
  ASSERT_NE(find("range_error_15m"), nullptr);
  const double true_d = 30.0 - (foot - 0.997) * 0.5;
  EXPECT_NEAR(find("range_error_15m")->measured, 100.0 * std::abs(13.0 - true_d) / true_d, 0.05);
  EXPECT_EQ(find("range_error_25m"), nullptr);  // nothing within 3 m of 25 m
  ASSERT_NE(find("placement_lateral"), nullptr);
  EXPECT_NEAR(find("placement_lateral")->measured, 1.0, 1e-6);       // 1 cm left
  EXPECT_NEAR(find("placement_longitudinal")->measured, 0.3, 1e-6);  // 3 mm past the goal
  EXPECT_NEAR(find("placement_heading")->measured, 0.5, 1e-6);
  ASSERT_NE(find("on_deck"), nullptr);
  EXPECT_EQ(find("on_deck")->measured, 1.0);
  ASSERT_NE(find("acquired_at_m"), nullptr);
  EXPECT_NEAR(find("acquired_at_m")->measured, 30.0, 0.05);
  ASSERT_NE(find("toward_distractor"), nullptr);
  EXPECT_EQ(find("toward_distractor")->measured, 0.0);
  r.truth_track.back() = {101.0, 20.0, 0.0};
  EXPECT_EQ(RendezvousFigures(log, lander, {}, r).back().measured, 0.0);
}

TEST(RendezvousJudging, AnEstimateOnALayeredOutcropIsADriveTowardADistractor) {
  const sim::terrain::Lander lander = TestLander();  // deck centre (30, 0)
  RunResult r;
  for (int i = 0; i <= 10; ++i) r.truth_track.push_back({static_cast<double>(i), 0.0, 0.0});
  sim::terrain::Rock outcrop;
  outcrop.position = Eigen::Vector3d(25.0, 8.0, 0.0);
  outcrop.diameter = 4.0;
  outcrop.elongation = 2.0;
  outcrop.layers = 3;
  sim::terrain::Rock boulder = outcrop;
  boulder.layers = 0;  // an ordinary rock there is not a distractor
  RendezvousLog log;
  log.samples.push_back({1.0, 1, 26.0, 4.0, true, "far", Eigen::Vector2d(29.0, 0.5)});
  log.samples.push_back({5.0, 1, 22.0, 4.0, true, "far", Eigen::Vector2d(25.5, 7.0)});
  auto toward = [&](const std::vector<sim::terrain::Rock>& rocks) {
    for (const auto& f : RendezvousFigures(log, lander, rocks, r)) {
      if (f.name == "toward_distractor") return f.measured;
    }
    return -1.0;
  };
  EXPECT_EQ(toward({outcrop}), 1.0);
  EXPECT_EQ(toward({boulder}), 0.0);
  EXPECT_EQ(toward({}), 0.0);
  // An estimate short of the lander on its bearing, beside the outcrop, is a range error.
  log.samples[1].target = Eigen::Vector2d(22.0, 0.3);
  outcrop.position = Eigen::Vector3d(22.0, 3.5, 0.0);
  EXPECT_EQ(toward({outcrop}), 0.0);
}

}  // namespace
}  // namespace rover::deploy::runner
