#include "rover/deploy/runner/judging.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "rover/base/params.hpp"
#include "rover/testing/test_support.hpp"

namespace rover::deploy::runner {
namespace {
namespace fs = std::filesystem;

sim::world::World SmallWorld(const std::string& rocks) {
  ParamSet p("world");
  sim::world::DeclareWorldParams(p);
  const std::string text =
      "terrain: {size_x: 8, size_y: 8, resolution: 0.05, seed: 5, hills: {amplitude: 0}, "
      "craters: {count: 0}, rocks: {preset: " +
      rocks + "}}\n";
  EXPECT_TRUE(p.LoadYamlSections(text, "w.yaml", sim::world::WorldSections()).ok());
  EXPECT_TRUE(p.Validate().ok());
  auto w = sim::world::BuildWorld(p);
  EXPECT_TRUE(w.ok()) << w.status().message();
  return std::move(*w);
}

Eigen::Isometry3d At(double x) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translation() = Eigen::Vector3d(x, 0, 0);
  return t;
}

// A judge of a 2 m straight along x to the target (2, 0), after the drive, with the estimate
// 5 cm to the side.
sim::judge::Judge JudgedDrive(double max_estimate_error) {
  sim::judge::JudgeCriteria criteria;
  criteria.target_xy = Eigen::Vector2d(2, 0);
  criteria.max_estimate_error = max_estimate_error;
  auto j = sim::judge::Judge::Create(criteria, {});
  EXPECT_TRUE(j.ok()) << j.status().message();
  for (int i = 0; i <= 20; ++i) {
    const Time t = Time::FromSeconds(i);
    j->AddTruth(t, At(0.1 * i));
    Eigen::Isometry3d e = At(0.1 * i);
    e.translation().y() = 0.05;
    j->AddEstimate(t, e);
  }
  return std::move(*j);
}

TEST(Judging, TheJudgeKnowsTheWorldsRocks) {
  Scenario s;
  const sim::world::World world = SmallWorld("vl2");
  ASSERT_FALSE(world.terrain.rocks.empty());
  auto judge = MakeJudge(s, world);
  ASSERT_TRUE(judge.ok()) << judge.status().message();
  // Dragging the rover across the whole map must touch some tall rock of a vl2 field.
  for (int i = 0; i <= 80; ++i) {
    for (int k = -3; k <= 3; ++k) {
      Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
      t.translation() = Eigen::Vector3d(-4 + 0.1 * i, k, 0);
      judge->AddTruth(Time::FromSeconds(i * 7 + k + 3), t);
    }
  }
  const sim::judge::Criterion* contacts = judge->Evaluate().Find("hazard_contacts");
  ASSERT_NE(contacts, nullptr);
  EXPECT_GT(contacts->measured, 0);
}

TEST(Judging, ScoreFillsTheResultAndNamesTheFirstFailedCriterion) {
  const sim::judge::Judge judge = JudgedDrive(0.01);
  RunResult r;
  std::string failure;
  const sim::judge::Criterion extra{"estimator_rejected_measurements", 3, 0, "count", true, ""};
  ScoreRun(judge, {extra}, &r, &failure);
  EXPECT_NEAR(r.distance_driven, 2.0, 1e-9);
  EXPECT_FALSE(r.estimate_error.empty());
  ASSERT_FALSE(r.figures.empty());
  EXPECT_EQ(r.figures.back().name, "estimator_rejected_measurements");  // after the judge's
  EXPECT_GT(r.figures.size(), 1u);
  // The estimate is 5 cm off with a 1 cm limit: the failure is the judge's first failed line.
  const std::string summary = judge.Evaluate().FailureSummary();
  EXPECT_EQ(failure, summary.substr(0, summary.find('\n')));
  EXPECT_NE(failure.find("estimate"), std::string::npos) << failure;
  // An earlier failure (a crash, a step) is kept.
  std::string earlier = "service 'x' crashed (exit 1)";
  ScoreRun(judge, {}, &r, &earlier);
  EXPECT_EQ(earlier, "service 'x' crashed (exit 1)");
}

TEST(Judging, APassingRunHasNoFailure) {
  RunResult r;
  std::string failure;
  ScoreRun(JudgedDrive(0.1), {}, &r, &failure);
  EXPECT_EQ(failure, "");
  for (const auto& c : r.criteria) EXPECT_TRUE(c.pass) << c.name;
}

TEST(Judging, OutputsAreWrittenAndTheFirstFailureWins) {
  const std::string dir = rover::testing::MakeTempDir("judging");
  const sim::world::World world = SmallWorld("none");
  RunResult r;
  r.scenario = "tiny";
  r.seed = 2;
  r.run_dir = dir;
  r.truth_track = {{0, 0, 0}, {1, 1, 0}};
  r.estimate_track = {{0, 0, 0}, {1, 1, 0.1}};
  r.estimate_error.push_back({Time::FromSeconds(1), 0.1, 0.01});
  ASSERT_TRUE(
      WriteRunOutputs(&r, "step 1 (straight) ended failed (tilt)", world.terrain, {{0, 0}, {2, 0}})
          .ok());
  EXPECT_FALSE(r.pass);
  EXPECT_EQ(r.failure, "step 1 (straight) ended failed (tilt)");
  std::ifstream in(dir + "/result.json");
  auto back = RunResultFromJson(nlohmann::json::parse(in));
  ASSERT_TRUE(back.ok()) << back.status().message();
  EXPECT_EQ(back->failure, r.failure);
  EXPECT_EQ(back->truth_track.size(), 2u);
  EXPECT_TRUE(fs::exists(dir + "/map.png"));
  EXPECT_TRUE(fs::exists(dir + "/estimate_error.png"));
  // A result that already names its failure keeps it; one without any passes.
  ASSERT_TRUE(WriteRunOutputs(&r, "later", world.terrain, {}).ok());
  EXPECT_EQ(r.failure, "step 1 (straight) ended failed (tilt)");
  RunResult ok;
  ok.run_dir = dir;
  ASSERT_TRUE(WriteRunOutputs(&ok, "", world.terrain, {}).ok());
  EXPECT_TRUE(ok.pass);
  // An unwritable folder is an error (the run could not be recorded).
  RunResult lost;
  lost.run_dir = dir + "/no/such/folder";
  EXPECT_FALSE(WriteRunOutputs(&lost, "", world.terrain, {}).ok());
  std::error_code ec;
  fs::remove_all(dir, ec);
}

}  // namespace
}  // namespace rover::deploy::runner
