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

const sim::judge::Criterion* FigureOf(const RunResult& r, const std::string& name) {
  for (const auto& f : r.figures) {
    if (f.name == name) return &f;
  }
  return nullptr;
}

// A mobility run with a target gets the field's passability from truth; a field without rocks
// taller than the traversable height gets none (nothing to pass), and a run that is not a
// mobility task none either.
TEST(Judging, MobilityRunsReportWhetherAContactFreePathExisted) {
  Scenario s;
  s.criteria.target_xy = Eigen::Vector2d(3.0, 0.0);
  s.criteria.position_tolerance = 0.5;
  RunResult r;
  r.mobility = MobilityOutcome{};
  r.distance_driven = 3.5;
  std::string failure;
  AddMobilityFigures(s, SmallWorld("vl2"), &r, &failure);
  EXPECT_TRUE(failure.empty()) << failure;
  const sim::judge::Criterion* passable = FigureOf(r, "passable");
  ASSERT_NE(passable, nullptr);
  if (passable->measured >= 1.0) {
    const sim::judge::Criterion* len = FigureOf(r, "contact_free_path");
    const sim::judge::Criterion* margin = FigureOf(r, "contact_free_margin");
    const sim::judge::Criterion* ratio = FigureOf(r, "path_length_ratio");
    ASSERT_NE(len, nullptr);
    ASSERT_NE(margin, nullptr);
    ASSERT_NE(ratio, nullptr);
    EXPECT_GE(len->measured, 2.4);  // 3 m to the target, less its 0.5 m tolerance and a cell
    EXPECT_NEAR(ratio->measured, 3.5 / len->measured, 1e-12);
    EXPECT_TRUE(margin->measured == 0.1 || margin->measured == 0.05 || margin->measured == 0.0);
  } else {
    EXPECT_EQ(FigureOf(r, "contact_free_path"), nullptr);
  }

  RunResult open;
  open.mobility = MobilityOutcome{};
  AddMobilityFigures(s, SmallWorld("none"), &open, &failure);
  EXPECT_EQ(FigureOf(open, "passable"), nullptr);
  RunResult drive;  // not a mobility task
  AddMobilityFigures(s, SmallWorld("vl2"), &drive, &failure);
  EXPECT_EQ(FigureOf(drive, "passable"), nullptr);
}

// The campaign summary counts the passable fields and the runs that passed on them.
TEST(Judging, TheSummaryGivesSuccessOverPassableFields) {
  std::vector<RunResult> runs(4);
  for (int i = 0; i < 4; ++i) {
    runs[static_cast<std::size_t>(i)].scenario = "autonav";
    runs[static_cast<std::size_t>(i)].pass = i != 1;
    runs[static_cast<std::size_t>(i)].figures.push_back(
        {"passable", i == 3 ? 0.0 : 1.0, 0, "count", true, ""});
  }
  const CampaignSummary sum = Summarize(runs, 10.0);
  EXPECT_EQ(sum.passed, 3);
  EXPECT_EQ(sum.passable, 3);
  EXPECT_EQ(sum.passed_passable, 2);
  EXPECT_NE(FormatSummaryTable(runs, sum).find("3/4 passed (75%); on passable fields 2/3"),
            std::string::npos)
      << FormatSummaryTable(runs, sum);
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
