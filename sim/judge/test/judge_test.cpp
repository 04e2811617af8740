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

// A rock outline: the ellipse of semi-axes ax, ay about c, as 32 vertices.
std::vector<Eigen::Vector2d> Ellipse(const Eigen::Vector2d& c, double ax, double ay) {
  std::vector<Eigen::Vector2d> out;
  for (int k = 0; k < 32; ++k) {
    const double t = 2.0 * std::numbers::pi * k / 32;
    out.push_back(c + Eigen::Vector2d(ax * std::cos(t), ay * std::sin(t)));
  }
  return out;
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
  ASSERT_NE(v.Find("hazard_contacts"), nullptr);
  EXPECT_EQ(v.Find("hazard_contacts")->measured, 0);
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
  EXPECT_NE(v.FailureSummary().find("hazard_contacts: 1 count"), std::string::npos)
      << v.FailureSummary();
  EXPECT_NE(v.Find("hazard_contacts")->detail.find("rocks 7 (0.25 m, wheel_l"), std::string::npos)
      << v.Find("hazard_contacts")->detail;
  // Where, by which part and when, for the map.
  ASSERT_EQ(v.contacts.size(), 1u);
  EXPECT_EQ(v.contacts[0].rock_id, 7);
  EXPECT_EQ(v.contacts[0].xy, Eigen::Vector2d(2.0, 0.5));
  EXPECT_DOUBLE_EQ(v.contacts[0].height, 0.25);
  EXPECT_EQ(v.contacts[0].part.rfind("wheel_l", 0), 0u) << v.contacts[0].part;
  EXPECT_GT(v.contacts[0].t_s, 0.0);
}

TEST(Judge, BellyHitsOnlyAboveClearance) {
  JudgeCriteria c;
  auto j = Judge::Create(c, {{1, {2.0, 0.0}, 0.3, 0.25}, {2, {4.0, 0.0}, 0.3, 0.35}});
  ASSERT_TRUE(j.ok());
  DriveStraight(*j, 5.0);  // both pass between the wheel tracks, under the belly
  const Verdict v = j->Evaluate();
  // The belly is 0.35 m up; less the judge's 0.05 m margin, 0.25 m passes and 0.35 m does not.
  ASSERT_EQ(v.rocks_hit.size(), 1u);
  EXPECT_EQ(v.rocks_hit[0], 2);
  EXPECT_NE(v.Find("hazard_contacts")->detail.find("(0.35 m, body)"), std::string::npos);
}

TEST(Judge, SuspensionBandsBetweenTheWheelsTouchRocks) {
  // One pose at the origin; rocks of radius 0.1 m on the left wheel line, in the gaps between
  // the wheel discs (reach hypot(0.125, 0.08) = 0.148 m).
  const std::vector<JudgeRock> rocks = {
      {1, {-0.31, 0.5}, 0.2, 0.25},  // under the bogie: its links come down to the wheels
      {2, {0.31, 0.5}, 0.2, 0.25},   // under the rocker, whose link is 0.33 m up there
      {3, {0.31, -0.5}, 0.2, 0.30},  // the same on the right, above the rocker's 0.28 m
  };
  auto j = Judge::Create(JudgeCriteria{}, rocks);
  ASSERT_TRUE(j.ok());
  j->AddTruth(Time::FromSeconds(0), Pose(0, 0, 0));
  const Verdict v = j->Evaluate();
  EXPECT_EQ(v.rocks_hit, (std::vector<int>{1, 3}));
  const std::string& d = v.Find("hazard_contacts")->detail;
  EXPECT_NE(d.find("1 (0.25 m, bogie_l)"), std::string::npos) << d;
  EXPECT_NE(d.find("3 (0.30 m, rocker_r)"), std::string::npos) << d;
}

TEST(Judge, HazardContactsAreTouchesFootprintOverlapsAlsoCountStraddledRocks) {
  // Drive along x from 0 to 5 m. The ground footprint of the default rover reaches |y| <= 0.58 m
  // (wheel outer edges) and 0.75 m ahead of the centre; a wheel disc reaches 0.648 m out.
  const std::vector<JudgeRock> rocks = {
      {1, {2.0, 0.0}, 0.3, 0.25},   // between the wheels, under the belly: straddled
      {2, {3.0, 0.66}, 0.2, 0.30},  // its edge 0.56 m from the line: beside a wheel, touching
      {3, {3.0, -0.9}, 0.2, 0.30},  // 0.8 m off: clear
      {4, {4.0, 0.0}, 0.3, 0.10},   // under the rover but traversable
      {5, {5.85, 0.0}, 0.3, 0.40},  // 0.85 m ahead of the last pose: within the rectangle only
      // An ellipse 0.13 m along x, 0.30 m along y: its nominal disc (0.2 m) would end 0.66 m out,
      // clear of the wheels (0.648 m); its long side reaches 0.76 - 0.15 = 0.61 m.
      {6, {1.0, -0.76}, 0.2, 0.30, Ellipse({1.0, -0.76}, 0.0667, 0.15)},
  };
  JudgeCriteria judged;
  judged.max_hazard_contacts = 0;
  auto j = Judge::Create(judged, rocks);
  ASSERT_TRUE(j.ok());
  DriveStraight(*j, 5.0);
  const Verdict v = j->Evaluate();
  EXPECT_EQ(v.rocks_hit, (std::vector<int>{2, 6}));
  EXPECT_EQ(v.footprint_overlaps, (std::vector<int>{1, 2, 5}));
  const Criterion* h = v.Find("hazard_contacts");
  ASSERT_NE(h, nullptr);
  EXPECT_EQ(h->measured, 2);
  EXPECT_FALSE(h->pass);
  EXPECT_FALSE(v.pass);
  EXPECT_NE(h->detail.find("rocks 2 (0.30 m, wheel_lf), 6 (0.30 m, wheel_rf)"), std::string::npos)
      << h->detail;
  bool overlaps = false;
  for (const auto& fig : v.figures) {
    if (fig.name == "footprint_overlaps") {
      overlaps = fig.measured == 3 && fig.detail.find("rocks 1, 2, 5") != std::string::npos;
    }
  }
  EXPECT_TRUE(overlaps);

  // A limit above the count passes; a negative one is refused.
  JudgeCriteria lenient;
  lenient.max_hazard_contacts = 2;
  auto l = Judge::Create(lenient, rocks);
  ASSERT_TRUE(l.ok());
  DriveStraight(*l, 5.0);
  EXPECT_TRUE(l->Evaluate().Find("hazard_contacts")->pass);
  JudgeCriteria bad;
  bad.max_hazard_contacts = -1;
  EXPECT_FALSE(Judge::Create(bad, {}).ok());
  RoverFootprint no_parts;
  EXPECT_FALSE(Judge::Create(JudgeCriteria{}, {}, no_parts).ok());
}

TEST(Judge, RockTouchesUsesTheOutline) {
  hwconfig::ContactPart box;
  box.min = {-0.5, -0.35};
  box.max = {0.5, 0.35};
  const Eigen::Matrix2d rot = Eigen::Matrix2d::Identity();
  const Eigen::Vector2d t = Eigen::Vector2d::Zero();
  // A long thin rock beside the box, its tip 5 cm off the box's side; and one lying across the
  // box's corner with no vertex inside it (the corner pokes into its outline).
  const JudgeRock beside{1, {0.0, 0.6}, 0.1, 0.3, Ellipse({0.0, 0.6}, 0.4, 0.2)};
  EXPECT_FALSE(RockTouches(beside, rot, t, box));
  EXPECT_TRUE(RockTouches(beside, rot, t, box, 0.06));
  std::vector<Eigen::Vector2d> square = {{0.45, 0.2}, {0.7, 0.45}, {0.45, 0.7}, {0.2, 0.45}};
  const JudgeRock across{2, {0.45, 0.45}, 0.3, 0.3, square};
  EXPECT_TRUE(RockTouches(across, rot, t, box));
  // Turned by 90 degrees the rover's box reaches 0.5 m along site y: the first rock now touches.
  const Eigen::Matrix2d quarter = Eigen::Rotation2Dd(std::numbers::pi / 2).toRotationMatrix();
  EXPECT_TRUE(RockTouches(beside, quarter, t, box));
  EXPECT_NEAR(beside.Reach(), 0.4, 1e-12);
  EXPECT_NEAR((JudgeRock{3, {0, 0}, 0.3, 0.3, {}}).Reach(), 0.15, 1e-12);
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
  EXPECT_NEAR(v.Find("estimate_final_error_percent")->measured, 1.981, 0.01);
  EXPECT_FALSE(v.Find("estimate_final_error_percent")->pass);      // 1.98 % > 1 %
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
