#include "rover/deploy/run_report.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace rover::deploy {
namespace {

RunResult MakeRun(std::uint32_t seed, bool pass, double err) {
  RunResult r;
  r.scenario = "drive-flat";
  r.seed = seed;
  r.pass = pass;
  r.failure = pass ? "" : "final_position_error: 0.8 m (limit 0.5) <&>";
  r.criteria.push_back({"final_position_error", err, 0.5, "m", err <= 0.5, "ended at (1, 2)"});
  r.distance_driven = 20;
  r.sim_time_s = 400;
  r.wall_time_s = 40;
  r.startup_s = 3;
  r.teardown_s = 1;
  r.estimate_error.push_back({Time::FromSeconds(1.5), 0.1, 0.01});
  r.steps.push_back({"straight", 1, "done", "nominal", "", 0, 390});
  r.truth_track.push_back({0, 0, 0});
  return r;
}

TEST(RunReport, JsonRoundTrip) {
  const RunResult r = MakeRun(3, false, 0.8);
  auto back = RunResultFromJson(ToJson(r));
  ASSERT_TRUE(back.ok()) << back.status().message();
  EXPECT_EQ(back->seed, 3u);
  EXPECT_FALSE(back->pass);
  ASSERT_EQ(back->criteria.size(), 1u);
  EXPECT_EQ(back->criteria[0].measured, 0.8);
  EXPECT_EQ(back->steps[0].termination, "nominal");
  EXPECT_EQ(back->estimate_error[0].t.seconds(), 1.5);
  EXPECT_FALSE(RunResultFromJson(nlohmann::json{{"seed", 1}}).ok());
}

TEST(RunReport, TimingsRoundTripAndSummarizeWhereTheTimeWent) {
  RunResult r = MakeRun(5, true, 0.1);
  r.lockstep = "strict";
  r.late_samples = 2;
  r.recording_mb = 12.5;
  r.service_timing.push_back({"rover-sim", 20.0, {{"physics", 12.0, 40000}, {"render", 4.0, 10}}});
  r.service_timing.push_back({"scenario-runner", 1.0, {}});
  // Through text, as roverctl report reads it.
  auto back = RunResultFromJson(nlohmann::json::parse(ToJson(r).dump()));
  ASSERT_TRUE(back.ok()) << back.status().message();
  EXPECT_EQ(back->lockstep, "strict");
  EXPECT_EQ(back->late_samples, 2u);
  EXPECT_EQ(back->recording_mb, 12.5);
  ASSERT_EQ(back->service_timing.size(), 2u);
  EXPECT_EQ(back->service_timing[0].service, "rover-sim");
  ASSERT_EQ(back->service_timing[0].activities.size(), 2u);
  EXPECT_EQ(back->service_timing[0].activities[0].name, "physics");
  EXPECT_EQ(back->service_timing[0].activities[0].count, 40000u);
  EXPECT_TRUE(back->service_timing[1].activities.empty());

  RunResult other = MakeRun(6, true, 0.1);  // wall 40 s like the first
  other.recording_mb = 7.5;
  other.service_timing.push_back({"rover-sim", 10.0, {{"physics", 8.0, 40000}}});
  const CampaignSummary s = Summarize({r, other}, 80.0);
  EXPECT_DOUBLE_EQ(s.recording_mb_mean, 10.0);
  auto find = [&](const std::string& name) {
    for (const auto& t : s.time_shares) {
      if (t.name == name) return t;
    }
    ADD_FAILURE() << name;
    return CampaignSummary::TimeShare{};
  };
  EXPECT_DOUBLE_EQ(find("rover-sim cpu").mean_s, 15.0);
  EXPECT_DOUBLE_EQ(find("physics (rover-sim)").mean_s, 10.0);
  EXPECT_DOUBLE_EQ(find("physics (rover-sim)").share, 0.25);  // of the mean run wall, 40 s
  EXPECT_DOUBLE_EQ(find("render (rover-sim)").mean_s, 2.0);   // absent in one run: counts 0
  const std::string table = FormatSummaryTable({r, other}, s);
  EXPECT_NE(table.find("where the time went"), std::string::npos) << table;
  EXPECT_NE(table.find("10.0 MB recorded per run"), std::string::npos) << table;
}

TEST(RunReport, NotANumberSurvivesTheRoundTrip) {
  // A figure or criterion nobody could measure is NaN, which JSON writes as null; reading the
  // folder back (roverctl report, a fault campaign's table) must not fail on it.
  RunResult r = MakeRun(4, false, std::numeric_limits<double>::quiet_NaN());
  r.figures.push_back({"max_tilt", std::numeric_limits<double>::quiet_NaN(),
                       std::numeric_limits<double>::quiet_NaN(), "deg", true, ""});
  const nlohmann::json j = nlohmann::json::parse(ToJson(r).dump());
  auto back = RunResultFromJson(j);
  ASSERT_TRUE(back.ok()) << back.status().message();
  EXPECT_TRUE(std::isnan(back->criteria[0].measured));
  ASSERT_EQ(back->figures.size(), r.figures.size());
  EXPECT_TRUE(std::isnan(back->figures.back().measured));
}

TEST(RunReport, MobilityOutcomeRoundTripsAndIsPrinted) {
  std::vector<RunResult> runs;
  for (std::uint32_t seed = 1; seed <= 3; ++seed) {
    RunResult r = MakeRun(seed, seed != 2, 0.1);
    MobilityOutcome m;
    m.task = "autonav";
    m.mode = "autonav";
    m.expect = "reached";
    m.outcome = seed == 2 ? "NOPATH" : "reached";
    m.state = seed == 2 ? "failed" : "succeeded";
    m.fault = seed == 2 ? "NOPATH" : "NONE";
    m.fault_class = seed == 2 ? "goal error" : "none";
    m.steps = 12;
    m.images = 13;
    m.distance_to_goal = 0.4;
    m.sim_start_s = 1;
    m.sim_end_s = 300;
    m.arcs.push_back({1, 2, 0.5, false, 0.25, -1, 0});
    m.last_map = GoodnessGrid{};  // not written
    r.mobility = m;
    runs.push_back(r);
  }
  auto back = RunResultFromJson(ToJson(runs[1]));
  ASSERT_TRUE(back.ok()) << back.status().message();
  ASSERT_TRUE(back->mobility.has_value());
  EXPECT_EQ(back->mobility->outcome, "NOPATH");
  EXPECT_EQ(back->mobility->fault_class, "goal error");
  EXPECT_EQ(back->mobility->steps, 12u);
  EXPECT_EQ(back->mobility->sim_end_s, 300);
  ASSERT_EQ(back->mobility->arcs.size(), 1u);
  EXPECT_EQ(back->mobility->arcs[0].direction, -1);
  EXPECT_DOUBLE_EQ(back->mobility->arcs[0].curvature, 0.25);
  EXPECT_FALSE(back->mobility->last_map.has_value());
  // A run without a mobility task has none.
  EXPECT_FALSE(RunResultFromJson(ToJson(MakeRun(1, true, 0.1)))->mobility.has_value());
  const std::string table = FormatSummaryTable(runs, Summarize(runs, 10));
  EXPECT_NE(table.find("autonav: NOPATH (goal error), expected reached"), std::string::npos)
      << table;
  EXPECT_NE(table.find("outcomes: NOPATH (goal error) x1; reached x2;"), std::string::npos)
      << table;
}

TEST(RunReport, InjectedFaultsRoundTripAndArePrinted) {
  RunResult r = MakeRun(2, true, 0.1);
  InjectedFault f;
  f.id = 3;
  f.name = "half the poses";
  f.kind = "drop";
  f.topic = "dl/pose";
  f.service = "*";
  f.side = "writer";
  f.description = "fault 3: drop 50% of dl/pose ...";
  f.start_s = 20;
  f.end_s = 30;
  f.samples_seen = 100;
  f.samples_hit = 48;
  f.services = {"dl-pose"};
  r.faults.push_back(f);
  InjectedFault never = f;
  never.id = 4;
  never.name.clear();
  never.start_s = -1;
  never.end_s = -1;
  never.samples_seen = never.samples_hit = 0;
  never.services.clear();
  r.faults.push_back(never);
  auto back = RunResultFromJson(ToJson(r));
  ASSERT_TRUE(back.ok()) << back.status().message();
  ASSERT_EQ(back->faults.size(), 2u);
  EXPECT_EQ(back->faults[0].id, 3u);
  EXPECT_EQ(back->faults[0].name, "half the poses");
  EXPECT_EQ(back->faults[0].side, "writer");
  EXPECT_EQ(back->faults[0].start_s, 20);
  EXPECT_EQ(back->faults[0].end_s, 30);
  EXPECT_EQ(back->faults[0].samples_hit, 48u);
  EXPECT_EQ(back->faults[0].services, std::vector<std::string>{"dl-pose"});
  EXPECT_EQ(DescribeInjected(back->faults[0]),
            "fault 3 'half the poses' drop dl/pose (writer of *): 20.0 s to 30.0 s, 48 of 100 "
            "samples hit in dl-pose");
  EXPECT_EQ(DescribeInjected(back->faults[1]),
            "fault 4 drop dl/pose (writer of *): never started, 0 of 0 samples hit");
  const std::string table = FormatSummaryTable({*back}, Summarize({*back}, 40));
  EXPECT_NE(table.find("         fault 3 'half the poses' drop dl/pose"), std::string::npos) << table;
  // Older result.json files have no faults.
  nlohmann::json old = ToJson(MakeRun(1, true, 0.1));
  old.erase("faults");
  ASSERT_TRUE(RunResultFromJson(old).ok());
}

TEST(RunReport, GoodnessGridCells) {
  GoodnessGrid g;
  g.origin_x = -1;
  g.origin_y = 2;
  g.resolution = 0.5;
  g.width = 4;
  g.height = 2;
  g.flags = {0, 1, 0, 0, 0, 0, 0, 1};
  EXPECT_EQ(g.CellAt(-1, 2), 0);
  EXPECT_EQ(g.CellAt(0.99, 2.99), 7);
  EXPECT_EQ(g.CellAt(1.0, 2.5), -1);
  EXPECT_EQ(g.CellAt(0, 1.9), -1);
  EXPECT_TRUE(g.Known(1, 0));
  EXPECT_TRUE(g.Known(3, 1));
  EXPECT_FALSE(g.Known(0, 0));
  EXPECT_FALSE(g.Known(4, 0));
  EXPECT_FALSE(g.Known(-1, 0));
}

TEST(RunReport, SummaryStatistics) {
  std::vector<RunResult> runs;
  for (int i = 0; i < 20; ++i) runs.push_back(MakeRun(i, i != 7, 0.01 * (i + 1)));
  const CampaignSummary s = Summarize(runs, 100.0);
  EXPECT_EQ(s.runs, 20);
  EXPECT_EQ(s.passed, 19);
  EXPECT_NEAR(s.pass_rate, 0.95, 1e-12);
  const FigureStats& f = s.figures[0];
  EXPECT_EQ(f.name, "final_position_error");
  EXPECT_NEAR(f.mean, 0.105, 1e-12);
  EXPECT_NEAR(f.p95, 0.19, 1e-12);  // nearest rank 19 of 20
  EXPECT_NEAR(f.worst, 0.20, 1e-12);
  EXPECT_NEAR(s.sim_seconds_per_wall_second, 80.0, 1e-9);
  EXPECT_NEAR(s.runs_per_hour, 720.0, 1e-9);
  const std::string table = FormatSummaryTable(runs, s);
  EXPECT_NE(table.find("drive-flat: 19/20 passed (95%)"), std::string::npos) << table;
}

// The summary gives the criteria apart, each with its limit and the runs it held in; a figure
// that is also a criterion is listed once; count-only activities stay out of the time table.
TEST(RunReport, SummarySeparatesCriteriaWithTheirLimitsFromFigures) {
  std::vector<RunResult> runs;
  for (int i = 0; i < 4; ++i) {
    RunResult r = MakeRun(i, i != 2, i == 2 ? 0.8 : 0.1);
    r.figures.push_back({"max_tilt", 3.0 + i, 0, "deg", true, ""});
    // The same quantity as a figure: not printed twice.
    r.figures.push_back({"final_position_error", r.criteria[0].measured, 0, "m", true, ""});
    r.service_timing.push_back(
        {"dl-pose", 2.0, {{"ticks_served", 0.0, 40000}, {"update", 0.5, 40000}}});
    runs.push_back(r);
  }
  const CampaignSummary s = Summarize(runs, 100.0);
  ASSERT_GE(s.figures.size(), 2u);
  EXPECT_EQ(s.figures[0].name, "final_position_error");
  EXPECT_TRUE(s.figures[0].criterion);
  EXPECT_DOUBLE_EQ(s.figures[0].limit, 0.5);
  EXPECT_EQ(s.figures[0].passing, 3);
  EXPECT_EQ(s.figures[0].count, 4);  // the criterion's values, not also the figure's
  EXPECT_EQ(s.figures[1].name, "max_tilt");
  EXPECT_FALSE(s.figures[1].criterion);
  const std::string table = FormatSummaryTable(runs, s);
  EXPECT_NE(table.find("criterion"), std::string::npos) << table;
  EXPECT_NE(table.find("held"), std::string::npos) << table;
  EXPECT_NE(table.find("3/4"), std::string::npos) << table;
  const auto criteria_at = table.find("\ncriterion ");
  ASSERT_NE(criteria_at, std::string::npos) << table;
  const auto first = table.find("final_position_error", criteria_at);
  ASSERT_NE(first, std::string::npos);
  EXPECT_EQ(table.find("final_position_error", first + 1), std::string::npos) << table;
  EXPECT_EQ(table.find("ticks_served"), std::string::npos) << table;
  EXPECT_NE(table.find("update (dl-pose)"), std::string::npos) << table;
  const nlohmann::json j = ToJson(s);
  EXPECT_TRUE(j["figures"][0]["criterion"].get<bool>());
  EXPECT_DOUBLE_EQ(j["figures"][0]["limit"].get<double>(), 0.5);
  EXPECT_EQ(j["figures"][0]["passing"].get<int>(), 3);
  EXPECT_FALSE(j["figures"][1].contains("criterion"));
}

// A run cut off by stopping roverctl says nothing about the stack: counted apart, kept out of
// the pass rate and the figures (before, its partial figures were averaged in).
TEST(RunReport, InterruptedRunsAreCountedApartAndKeptOutOfTheFigures) {
  std::vector<RunResult> runs = {MakeRun(1, true, 0.1), MakeRun(2, false, 0.8)};
  RunResult cut = MakeRun(3, false, 25.0);
  cut.failure = "interrupted: roverctl was stopped (Ctrl-C or a termination signal) at 12.0 "
                "simulated s";
  runs.push_back(cut);
  EXPECT_TRUE(Interrupted(cut));
  EXPECT_FALSE(Interrupted(runs[1]));
  const CampaignSummary s = Summarize(runs, 100.0);
  EXPECT_EQ(s.runs, 3);
  EXPECT_EQ(s.interrupted, 1);
  EXPECT_EQ(s.passed, 1);
  EXPECT_DOUBLE_EQ(s.pass_rate, 0.5);
  ASSERT_FALSE(s.figures.empty());
  EXPECT_EQ(s.figures[0].name, "final_position_error");
  EXPECT_EQ(s.figures[0].count, 2);
  EXPECT_DOUBLE_EQ(s.figures[0].worst, 0.8);  // not the cut-off run's 25 m
  const std::string table = FormatSummaryTable(runs, s);
  EXPECT_NE(table.find("drive-flat: 1/2 passed (50%); 1 run interrupted (not in the rate or the "
                       "figures)"),
            std::string::npos)
      << table;
  EXPECT_NE(table.find("INTR"), std::string::npos) << table;
  EXPECT_EQ(ToJson(s)["interrupted_runs"].get<int>(), 1);
}

// The JUnit file must be well-formed XML with one test case per run; checked with xmllint
// (libxml2-utils, installed by scripts/setup.sh).
TEST(RunReport, JunitIsValidXmlWithOneCasePerRun) {
  std::vector<RunResult> runs = {MakeRun(1, true, 0.1), MakeRun(2, false, 0.8), MakeRun(3, true, 0.2)};
  const std::string xml = ToJunitXml(runs, "drive-flat");
  const std::string path = ::testing::TempDir() + "/junit_test.xml";
  std::ofstream(path) << xml;
  ASSERT_EQ(std::system(("xmllint --noout " + path).c_str()), 0) << xml;
  std::size_t cases = 0, pos = 0;
  while ((pos = xml.find("<testcase ", pos)) != std::string::npos) {
    ++cases;
    ++pos;
  }
  EXPECT_EQ(cases, 3u);
  EXPECT_NE(xml.find("failures=\"1\""), std::string::npos);
  EXPECT_NE(xml.find("&lt;&amp;&gt;"), std::string::npos);  // escaped
  std::remove(path.c_str());
}

TEST(RunReport, RunFolderDetection) {
  const std::string dir = ::testing::TempDir() + "/runfolder_test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir + "/drive-flat-seed1");
  EXPECT_FALSE(IsRunFolder(dir));
  EXPECT_FALSE(LoadRunFolder(dir).ok());
  std::ofstream(dir + "/campaign.json") << "{}";
  std::ofstream(dir + "/drive-flat-seed1/result.json") << ToJson(MakeRun(1, true, 0.1)).dump();
  auto runs = LoadRunFolder(dir);
  ASSERT_TRUE(runs.ok()) << runs.status().message();
  EXPECT_EQ(runs->size(), 1u);
  std::filesystem::remove_all(dir);
}

// `roverctl report`: the table re-printed from the files, with the campaign's wall time.
TEST(RunReport, CampaignReportReprintsTheTable) {
  const std::string dir = ::testing::TempDir() + "/report_test";
  std::filesystem::remove_all(dir);
  EXPECT_EQ(LoadCampaignReport(dir).status().code(), StatusCode::kNotFound);
  std::vector<RunResult> runs = {MakeRun(1, true, 0.1), MakeRun(2, false, 0.8),
                                 MakeRun(3, true, 0.2)};
  std::filesystem::create_directories(dir);
  std::ofstream(dir + "/campaign.json") << "{}";
  for (const auto& r : runs) {
    const std::string run_dir = dir + "/drive-flat-seed" + std::to_string(r.seed);
    std::filesystem::create_directories(run_dir);
    std::ofstream(run_dir + "/result.json") << ToJson(r).dump(2);
  }
  std::ofstream(dir + "/summary.json") << nlohmann::json{{"wall_time_s", 120.0}}.dump();
  auto report = LoadCampaignReport(dir);
  ASSERT_TRUE(report.ok()) << report.status().message();
  EXPECT_EQ(report->runs.size(), 3u);
  EXPECT_EQ(report->summary.wall_time_s, 120.0);
  EXPECT_EQ(report->table, FormatSummaryTable(runs, Summarize(runs, 120.0)));
  EXPECT_FALSE(report->all_passed);
  // Without summary.json the wall time is unknown (0); one failed run still fails the report.
  std::filesystem::remove(dir + "/summary.json");
  std::filesystem::remove_all(dir + "/drive-flat-seed2");
  report = LoadCampaignReport(dir);
  ASSERT_TRUE(report.ok());
  EXPECT_EQ(report->summary.wall_time_s, 0.0);
  EXPECT_TRUE(report->all_passed);
  // A folder of a campaign that was interrupted: its cut-off run wrote NaN (null) figures and
  // says why it ended; the report reads it and counts it apart.
  RunResult cut = MakeRun(4, false, std::numeric_limits<double>::quiet_NaN());
  cut.failure = "interrupted: roverctl was stopped (Ctrl-C or a termination signal) at 3.0 "
                "simulated s";
  std::filesystem::create_directories(dir + "/drive-flat-seed4");
  std::ofstream(dir + "/drive-flat-seed4/result.json") << ToJson(cut).dump(2);
  report = LoadCampaignReport(dir);
  ASSERT_TRUE(report.ok()) << report.status().message();
  EXPECT_EQ(report->runs.size(), 3u);
  EXPECT_EQ(report->summary.interrupted, 1);
  EXPECT_NE(report->table.find("1 run interrupted"), std::string::npos) << report->table;
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace rover::deploy
