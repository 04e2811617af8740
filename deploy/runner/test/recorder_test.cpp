#include "rover/deploy/runner/recorder.hpp"

#include <gtest/gtest.h>

#include "run_fixture.hpp"

namespace rover::deploy::runner {
namespace {
using testing::RunFixture;

rover_sim_Truth TruthAt(double t, double x) {
  rover_sim_Truth s{};
  s.header.stamp_ns = Time::FromSeconds(t).ns;
  s.pose.position.x = x;
  s.pose.orientation.w = 1;
  return s;
}

rover_dl_PoseEstimate EstimateAt(double t, double x, std::uint32_t rejected) {
  rover_dl_PoseEstimate s{};
  s.header.stamp_ns = Time::FromSeconds(t).ns;
  s.pose.position.x = x;
  s.pose.orientation.w = 1;
  s.rejected_measurements = rejected;
  return s;
}

// Pumps until `done` or a generous number of passes (DDS delivery is asynchronous).
bool PumpUntil(Recorder& r, const std::function<bool()>& done) {
  return rover::testing::WaitFor([&] {
    r.Pump();
    return done();
  });
}

TEST(Recorder, TracksAreDownsampledAndTheJudgeGetsEverySample) {
  auto lease = rover::testing::IsolatedDomain();
  auto p = dds::Participant::Create(lease.domain());
  ASSERT_TRUE(p.ok());
  auto judge = sim::judge::Judge::Create({}, {});
  ASSERT_TRUE(judge.ok());
  RunResult result;
  auto rec = Recorder::Create(*p, &*judge, &result);
  ASSERT_TRUE(rec.ok()) << rec.status().message();
  auto truth = dds::Writer<rover_sim_Truth>::Create(*p, "sim/truth");
  auto pose = dds::Writer<rover_dl_PoseEstimate>::Create(*p, "dl/pose");
  auto odo = dds::Writer<rover_dl_PoseEstimate>::Create(*p, "dl/pose_odometry");
  ASSERT_TRUE(truth.ok() && pose.ok() && odo.ok());
  ASSERT_TRUE(rover::testing::WaitFor([&] {
    return truth->MatchedReaders() > 0 && pose->MatchedReaders() > 0 && odo->MatchedReaders() > 0;
  }));
  EXPECT_FALSE((*rec)->has_estimate());
  // 2 s at 20 Hz, driving 0.1 m/s along x.
  for (int i = 0; i <= 40; ++i) {
    const double t = 0.05 * i;
    ASSERT_TRUE(truth->Write(TruthAt(t, 0.1 * t)).ok());
    ASSERT_TRUE(
        pose->Write(EstimateAt(t, 0.1 * t + 0.01, static_cast<std::uint32_t>(i / 10))).ok());
    ASSERT_TRUE(odo->Write(EstimateAt(t, 0.1 * t + 0.02, 0)).ok());
    (*rec)->Pump();  // as the run loop does while samples arrive
  }
  // Until the last samples are in (the last dl/pose sample says 4 rejected measurements).
  ASSERT_TRUE(PumpUntil(**rec, [&] {
    const auto f = (*rec)->Figures();
    return !f.empty() && f[0].measured == 4 && !result.truth_track.empty() &&
           result.truth_track.back()[0] >= 1.75 && !result.odometry_only_track.empty() &&
           result.odometry_only_track.back()[0] >= 1.75;
  }));
  EXPECT_TRUE((*rec)->has_estimate());
  for (const auto* track :
       {&result.truth_track, &result.estimate_track, &result.odometry_only_track}) {
    ASSERT_GE(track->size(), 9u);
    EXPECT_EQ((*track)[0][0], 0.0);
    for (std::size_t i = 1; i < track->size(); ++i) {
      EXPECT_GE((*track)[i][0] - (*track)[i - 1][0], 0.2 - 1e-9);  // one point per 0.2 s
      EXPECT_LE((*track)[i][0] - (*track)[i - 1][0], 0.25 + 1e-9);
    }
  }
  for (const auto& pt : result.truth_track) EXPECT_NEAR(pt[1], 0.1 * pt[0], 1e-9);
  EXPECT_EQ(result.truth_publishers, 1);
  EXPECT_EQ((*rec)->CrossTalk(lease.domain()), "");
  // The judge saw truth and estimates at full rate: up to 0.2 m driven, a 1 cm estimate error.
  const sim::judge::Verdict v = judge->Evaluate();
  EXPECT_GE(v.distance_driven, 0.175);
  EXPECT_LE(v.distance_driven, 0.2 + 1e-9);
  ASSERT_FALSE(v.estimate_error.empty());
  EXPECT_NEAR(v.estimate_error.back().position_error, 0.01, 1e-9);
  EXPECT_FALSE(v.odometry_only_error.empty());
  // dl/pose's last rejected-measurement count is a figure.
  const auto figures = (*rec)->Figures();
  ASSERT_EQ(figures.size(), 1u);
  EXPECT_EQ(figures[0].name, "estimator_rejected_measurements");
  EXPECT_EQ(figures[0].measured, 4);
}

TEST(Recorder, TwoSimulatorsOnOneDomainAreCrossTalk) {
  RunFixture run;
  auto other = dds::Participant::Create(run.domain());
  ASSERT_TRUE(other.ok());
  auto a = dds::Writer<rover_sim_Truth>::Create(run.participant(), "sim/truth");
  auto b = dds::Writer<rover_sim_Truth>::Create(*other, "sim/truth");
  ASSERT_TRUE(a.ok() && b.ok());
  ASSERT_TRUE(
      rover::testing::WaitFor([&] { return a->MatchedReaders() > 0 && b->MatchedReaders() > 0; }));
  ASSERT_TRUE(PumpUntil(run.recorder(), [&] {
    (void)a->Write(TruthAt(1, 0));
    (void)b->Write(TruthAt(1, 5));
    return run.result().truth_publishers == 2;
  }));
  EXPECT_EQ(run.recorder().CrossTalk(run.domain()),
            "cross-talk: 2 simulators heard on domain " + std::to_string(run.domain()));
  // The run loop fails on it once the runner adds the check.
  run.loop().AddCheck([&] { return run.recorder().CrossTalk(run.domain()); });
  EXPECT_NE(run.loop().WaitUntil([] { return false; }).find("cross-talk"), std::string::npos);
}

TEST(Recorder, ATaskRecordsOtherTopicsAndAddsFigures) {
  RunFixture run;
  std::vector<std::uint32_t> heard;
  ASSERT_TRUE(run.recorder()
                  .Record<rover_dl_DriveStatus>("dl/drive_status",
                                                [&](const dds::Sample<rover_dl_DriveStatus>& s) {
                                                  heard.push_back(s->command_id);
                                                })
                  .ok());
  auto w = dds::Writer<rover_dl_DriveStatus>::Create(run.participant(), "dl/drive_status");
  ASSERT_TRUE(w.ok());
  ASSERT_TRUE(rover::testing::WaitFor([&] { return w->MatchedReaders() > 0; }));
  rover_dl_DriveStatus s{};
  s.command_id = 7;
  ASSERT_TRUE(w->Write(s).ok());
  ASSERT_TRUE(PumpUntil(run.recorder(), [&] { return !heard.empty(); }));
  EXPECT_EQ(heard, std::vector<std::uint32_t>{7});
  // No dl/pose heard: only the task's own figure.
  run.recorder().AddFigure({"goal_distance", 0.4, 0, "m", true, "from the task"});
  const auto figures = run.recorder().Figures();
  ASSERT_EQ(figures.size(), 1u);
  EXPECT_EQ(figures[0].name, "goal_distance");
}

}  // namespace
}  // namespace rover::deploy::runner
