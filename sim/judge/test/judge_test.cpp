#include "rover/sim/judge/judge.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace rover::sim::judge {
namespace {

Eigen::Isometry3d Pose(double x, double y, double yaw, double roll = 0) {
  Eigen::Isometry3d p = Eigen::Isometry3d::Identity();
  p.translation() = Eigen::Vector3d(x, y, 0);
  p.linear() = (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  return p;
}

// Drives straight along x from 0 to `to` in 1 cm steps at 10 cm/s.
void DriveStraight(Judge& j, double to, double y = 0, double roll = 0) {
  for (int i = 0; i <= static_cast<int>(to * 100); ++i) {
    j.AddTruth(Time::FromSeconds(i * 0.1), Pose(i * 0.01, y, 0, roll));
  }
}

TEST(Judge, PassingRunReportsEveryCriterion) {
  JudgeCriteria c;
  c.target_xy = Eigen::Vector2d(5, 0);
  c.target_heading = 0;
  c.min_distance = 4.0;
  auto j = Judge::Create(c, {{1, {3.0, 3.0}, 0.5, 0.4}});  // a tall rock well off the path
  ASSERT_TRUE(j.ok());
  DriveStraight(*j, 5.0);
  const Verdict v = j->Evaluate();
  EXPECT_TRUE(v.pass) << v.FailureSummary();
  EXPECT_NEAR(v.distance_driven, 5.0, 1e-9);
  ASSERT_NE(v.Find("final_position_error"), nullptr);
  EXPECT_NEAR(v.Find("final_position_error")->measured, 0.0, 1e-9);
  EXPECT_EQ(v.Find("rock_contacts")->measured, 0);
  EXPECT_TRUE(v.Find("distance_driven")->pass);
}

TEST(Judge, TallRockUnderAWheelFailsSmallOnesDoNot) {
  JudgeCriteria c;
  std::vector<JudgeRock> rocks = {
      {7, {2.0, 0.5}, 0.3, 0.25},   // under the left wheel track, taller than 20 cm
      {8, {3.0, -0.5}, 0.3, 0.15},  // under the right track but traversable
  };
  auto j = Judge::Create(c, rocks);
  ASSERT_TRUE(j.ok());
  DriveStraight(*j, 4.0);
  const Verdict v = j->Evaluate();
  EXPECT_FALSE(v.pass);
  ASSERT_EQ(v.rocks_hit.size(), 1u);
  EXPECT_EQ(v.rocks_hit[0], 7);
  EXPECT_NE(v.FailureSummary().find("rock_contacts: 1 count"), std::string::npos)
      << v.FailureSummary();
}

TEST(Judge, BellyHitsOnlyAboveClearance) {
  JudgeCriteria c;
  auto j = Judge::Create(c, {{1, {2.0, 0.0}, 0.3, 0.25}, {2, {4.0, 0.0}, 0.3, 0.35}});
  ASSERT_TRUE(j.ok());
  DriveStraight(*j, 5.0);  // both pass between the wheel tracks, under the belly
  const Verdict v = j->Evaluate();
  ASSERT_EQ(v.rocks_hit.size(), 1u);
  EXPECT_EQ(v.rocks_hit[0], 2);
}

TEST(Judge, HazardContactsCountRocksUnderAnyPartOfTheFootprint) {
  // Drive along x from 0 to 5 m. The ground footprint of the default rover reaches |y| <= 0.58 m
  // (wheel outer edges) and 0.75 m ahead of the centre.
  const std::vector<JudgeRock> rocks = {
      {1, {2.0, 0.0}, 0.3, 0.25},   // between the wheels, under the belly: a hazard contact only
      {2, {3.0, 0.66}, 0.2, 0.30},  // its edge 0.56 m from the line: beside a wheel, touching
      {3, {3.0, -0.9}, 0.2, 0.30},  // 0.8 m off: clear
      {4, {4.0, 0.0}, 0.3, 0.10},   // under the rover but traversable
      {5, {5.85, 0.0}, 0.3, 0.40},  // 0.85 m ahead of the last pose: its edge within 0.75 m
  };
  JudgeCriteria judged;
  judged.max_hazard_contacts = 0;
  auto j = Judge::Create(judged, rocks);
  ASSERT_TRUE(j.ok());
  DriveStraight(*j, 5.0);
  const Verdict v = j->Evaluate();
  EXPECT_EQ(v.hazards_hit, (std::vector<int>{1, 2, 5}));
  const Criterion* h = v.Find("hazard_contacts");
  ASSERT_NE(h, nullptr);
  EXPECT_EQ(h->measured, 3);
  EXPECT_FALSE(h->pass);
  EXPECT_FALSE(v.pass);
  EXPECT_NE(h->detail.find("rocks 1, 2, 5"), std::string::npos) << h->detail;
  // The wheel-and-belly check sees only rock 2 at a wheel: rock 1 passes under the belly and
  // rock 5 is ahead of the body, between the wheel tracks.
  EXPECT_EQ(v.rocks_hit, (std::vector<int>{2}));

  // Without the criterion it is a figure, and a rover that kept clear has none.
  auto f = Judge::Create(JudgeCriteria{}, {{3, {3.0, -0.9}, 0.2, 0.30}});
  ASSERT_TRUE(f.ok());
  DriveStraight(*f, 5.0);
  const Verdict clear = f->Evaluate();
  EXPECT_EQ(clear.Find("hazard_contacts"), nullptr);
  bool figure = false;
  for (const auto& fig : clear.figures) {
    if (fig.name == "hazard_contacts") figure = fig.measured == 0;
  }
  EXPECT_TRUE(figure);
  JudgeCriteria bad;
  bad.max_hazard_contacts = -1;
  EXPECT_FALSE(Judge::Create(bad, {}).ok());
}

TEST(Judge, TiltAndFinalErrorsAreMeasured) {
  JudgeCriteria c;
  c.target_xy = Eigen::Vector2d(2, 0);
  c.position_tolerance = 0.1;
  c.max_tilt = 20.0 * std::numbers::pi / 180;
  auto j = Judge::Create(c, {});
  ASSERT_TRUE(j.ok());
  DriveStraight(*j, 1.5, 0.0, 25.0 * std::numbers::pi / 180);
  const Verdict v = j->Evaluate();
  EXPECT_FALSE(v.pass);
  EXPECT_NEAR(v.Find("max_tilt")->measured, 25.0, 1e-6);
  EXPECT_FALSE(v.Find("max_tilt")->pass);
  EXPECT_NEAR(v.Find("final_position_error")->measured, 0.5, 1e-9);
  EXPECT_FALSE(v.Find("final_position_error")->pass);
}

TEST(Judge, EstimateErrorAgainstInterpolatedTruth) {
  JudgeCriteria c;
  c.max_estimate_error = 0.05;
  c.max_estimate_error_fraction = 0.01;
  auto j = Judge::Create(c, {});
  ASSERT_TRUE(j.ok());
  DriveStraight(*j, 10.0);
  // Estimates between truth samples, drifting 2 cm per metre sideways.
  for (int i = 0; i < 100; ++i) {
    const double t = i * 1.0 + 0.05;
    const double x = t * 0.1;
    j->AddEstimate(Time::FromSeconds(t), Pose(x, 0.02 * x, 0));
  }
  const Verdict v = j->Evaluate();
  ASSERT_EQ(v.estimate_error.size(), 100u);
  EXPECT_NEAR(v.estimate_error.back().position_error, 0.02 * 9.905, 1e-6);
  EXPECT_FALSE(v.Find("max_estimate_error")->pass);                // 0.198 m > 0.05 m
  EXPECT_NEAR(v.Find("final_estimate_error_percent")->measured, 1.981, 0.01);
  EXPECT_FALSE(v.Find("final_estimate_error_percent")->pass);      // 1.98 % > 1 %
}

TEST(Judge, OdometryOnlyBaselineAndHeadingAreFiguresBesideTheEstimate) {
  JudgeCriteria c;
  c.max_estimate_heading_error = 1.0 * std::numbers::pi / 180.0;
  auto j = Judge::Create(c, {});
  ASSERT_TRUE(j.ok());
  DriveStraight(*j, 10.0);
  for (int i = 0; i < 100; ++i) {
    const double t = i * 1.0 + 0.05;
    const double x = t * 0.1;
    // Fused estimate: 0.5 % short, heading 0.5 deg off; baseline: 10 % long (slip), 3 deg off.
    j->AddEstimate(Time::FromSeconds(t), Pose(0.995 * x, 0, 0.5 * std::numbers::pi / 180.0));
    j->AddOdometryOnlyEstimate(Time::FromSeconds(t), Pose(1.1 * x, 0, 3 * std::numbers::pi / 180.0));
  }
  const Verdict v = j->Evaluate();
  ASSERT_EQ(v.odometry_only_error.size(), 100u);
  auto figure = [&](const std::string& name) -> const Criterion* {
    for (const auto& f : v.figures) {
      if (f.name == name) return &f;
    }
    return nullptr;
  };
  ASSERT_NE(figure("estimate_final_error_percent"), nullptr);
  ASSERT_NE(figure("odometry_only_final_error_percent"), nullptr);
  EXPECT_NEAR(figure("estimate_final_error_percent")->measured, 0.5, 0.01);
  EXPECT_NEAR(figure("odometry_only_final_error_percent")->measured, 10.0, 0.1);
  EXPECT_NEAR(figure("odometry_only_max_heading_error")->measured, 3.0, 1e-6);
  EXPECT_NE(figure("odometry_only_final_error")->detail.find("dl/pose_odometry vs sim/truth"),
            std::string::npos);
  for (const auto& f : v.figures) EXPECT_TRUE(std::isnan(f.limit)) << f.name;
  ASSERT_NE(v.Find("max_estimate_heading_error"), nullptr);
  EXPECT_NEAR(v.Find("max_estimate_heading_error")->measured, 0.5, 1e-6);
  EXPECT_TRUE(v.Find("max_estimate_heading_error")->pass);
  // The baseline is never judged: its 3 deg does not fail the run.
  EXPECT_TRUE(v.pass) << v.FailureSummary();
}

TEST(Judge, RejectsBadCriteriaAndReportsMissingTruth) {
  JudgeCriteria c;
  c.max_tilt = 2.0;  // rad: over 90 deg
  EXPECT_FALSE(Judge::Create(c, {}).ok());
  c = JudgeCriteria();
  c.position_tolerance = -1;
  auto bad = Judge::Create(c, {});
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.status().message().find("criteria.position_tolerance"), std::string::npos);
  auto j = Judge::Create(JudgeCriteria(), {});
  ASSERT_TRUE(j.ok());
  const Verdict v = j->Evaluate();
  EXPECT_FALSE(v.pass);
  EXPECT_NE(v.Find("truth_received"), nullptr);
  j->AddTruth(Time::FromSeconds(1), Pose(0, 0, 0));
  j->AddTruth(Time::FromSeconds(0.5), Pose(0, 0, 0));
  EXPECT_EQ(j->out_of_order(), 1u);
}

}  // namespace
}  // namespace rover::sim::judge
