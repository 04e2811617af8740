#include "rover/apl/rendezvous/rendezvous_executor.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "rover/base/units.hpp"
#include "rover/geometry/transforms.hpp"

namespace rover::apl::rendezvous {
namespace {

using ::testing::HasSubstr;
using msg::RendezvousFault;
using msg::RendezvousPhase;

// A kinematic world: a level site, the lander at `center` with ramp 0 descending along `yaw`,
// a rover that executes drives with a proportional error, and a fake vision that sees the truth
// (with noise) when the geometry allows it.
struct World {
  hwconfig::LanderDescription lander;
  Eigen::Vector2d center{30.0, 0.0};
  double yaw = 0.0;  // ramp 0 descends along this
  double x = 0.0, y = 0.0, heading = 0.0, z = 0.0;
  double drive_error = 0.02;   // straights and turns come out this much long
  double fix_noise = 0.01;     // relative range noise of the mid-range fix
  double lateral_drift = 0.0;  // straights drift sideways this much per metre (to the left)
  bool lander_visible = true;
  double sight_limit = 60.0;  // [m] the fake detector sees the lander within this range
  double blind_within = 0.0;  // [m] ... and not nearer than this (a view it misses)
  double far_from = 35.0;     // [m] beyond this the long-range detector looks
  int biased_fixes = 0;       // the first this many fixes report the range times range_scale
  double range_scale = 1.0;
  std::optional<Eigen::Vector2d> decoy;  // reported instead of the lander while set
  std::optional<Eigen::Vector2d> rock;  // apl-mobility refuses (NOPATH) goals within 1.5 m of it
  int stripes = 6;
  int stripes_near = 6;  // stripes seen within 3 m of the ramp base
  std::mt19937 rng{7};

  Eigen::Vector2d Down(int r) const {
    const double a = yaw + (r == 0 ? 0.0 : kPi);
    return {std::cos(a), std::sin(a)};
  }
  double Reach() const { return lander.Apothem() + lander.ramp_length; }
  Eigen::Vector2d Base(int r) const { return center + Reach() * Down(r); }
  Eigen::Isometry3d SiteFromRover() const {
    Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
    t.linear() = Eigen::AngleAxisd(heading, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    t.translation() = Eigen::Vector3d(x, y, z);
    return t;
  }
  Eigen::Isometry3d SiteFromRamp(int r) const {
    const Eigen::Vector2d d = Down(r);
    const Eigen::Vector2d mid = center + (lander.Apothem() + 0.5 * lander.ramp_length) * d;
    const Eigen::Vector3d u =
        Eigen::Vector3d(-d.x() * lander.ramp_length, -d.y() * lander.ramp_length,
                        lander.deck_height)
            .normalized();
    const Eigen::Vector3d v(d.y(), -d.x(), 0.0);
    Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
    t.linear().col(0) = u;
    t.linear().col(1) = v;
    t.linear().col(2) = u.cross(v);
    t.translation() = Eigen::Vector3d(mid.x(), mid.y(), 0.5 * lander.deck_height);
    return t;
  }
  // Truth placement against ramp r: lateral (left of the axis), along (past the goal), heading.
  Eigen::Vector3d Placement(int r, double standoff) const {
    const Eigen::Vector2d a = -Down(r), n(-a.y(), a.x());
    const Eigen::Vector2d goal = Base(r) - standoff * a;
    const Eigen::Vector2d p(x, y);
    return {(p - goal).dot(n), (p - goal).dot(a),
            geometry::WrapAngle(heading - std::atan2(a.y(), a.x()))};
  }
};

class FakeVision : public RendezvousVision {
 public:
  int decoys_reported = 0;
  int fixes_reported = 0;
  explicit FakeVision(World* w) : w_(w) {}
  Result<LanderFix> SightLander(const NavcamPair&, const Eigen::Vector3d&) override {
    LanderFix f;
    const Eigen::Vector3d c(w_->center.x(), w_->center.y(), w_->lander.deck_height);
    const Eigen::Vector3d in_rover = w_->SiteFromRover().inverse() * c;
    const double range = in_rover.head<2>().norm();
    f.far = range > w_->far_from;  // the long-range detector looked
    if (w_->decoy) {
      f.found = true;
      f.center_rover = w_->SiteFromRover().inverse() *
                       Eigen::Vector3d(w_->decoy->x(), w_->decoy->y(), w_->lander.deck_height);
      f.covariance = Eigen::Matrix3d::Identity() * 0.25;
      ++decoys_reported;
      return f;
    }
    if (!w_->lander_visible || range > w_->sight_limit || range < w_->blind_within) {
      f.why = "nothing lander-like";
      return f;
    }
    std::normal_distribution<double> n(0.0, w_->fix_noise);
    f.found = true;
    f.center_rover = in_rover * (1.0 + n(w_->rng));
    if (fixes_reported++ < w_->biased_fixes) {
      f.center_rover.head<2>() *= w_->range_scale;
    }
    f.covariance = Eigen::Matrix3d::Identity() * std::pow(w_->fix_noise * range, 2);
    f.features = "fake";
    return f;
  }
  Result<RampFix> SightRamp(const NavcamPair&) override {
    RampFix f;
    for (int r = 0; r < 2; ++r) {
      const Eigen::Vector2d rel = Eigen::Vector2d(w_->x, w_->y) - w_->Base(r);
      const double ahead = rel.dot(w_->Down(r));
      if (ahead < 0.3 || rel.norm() > 9.0 || std::abs(rel.normalized().dot(w_->Down(r))) < 0.5) {
        continue;
      }
      f.found = true;
      f.ramp = r;
      f.stripes = rel.norm() < 3.0 ? w_->stripes_near : w_->stripes;
      f.rover_from_ramp = w_->SiteFromRover().inverse() * w_->SiteFromRamp(r);
      // 1 mm and 0.05 deg of measurement noise.
      std::normal_distribution<double> n(0.0, 1.0);
      f.rover_from_ramp.translation() += 0.001 * Eigen::Vector3d(n(w_->rng), n(w_->rng), 0.0);
      f.rover_from_ramp.linear() =
          Eigen::AngleAxisd(0.05 * kDegree * n(w_->rng), Eigen::Vector3d::UnitZ()) *
          f.rover_from_ramp.linear();
      f.base_sigma = 0.002;
      f.features = "stripes";
      return f;
    }
    f.why = "no stripes in view";
    return f;
  }

 private:
  World* w_;
};

struct Harness {
  explicit Harness(const RendezvousOptions& options = {})
      : exec(options, hwconfig::LanderDescription{}, vision) {}
  World world;
  std::shared_ptr<FakeVision> vision = std::make_shared<FakeVision>(&world);
  RendezvousExecutor exec;
  double t = 10.0;
  std::vector<msg::RendezvousStatus> statuses;
  std::vector<msg::MobilityCommand> drives;
  std::optional<Eigen::Vector3d> placement_at_base;
  int refused = 0;

  Time Now() const { return Time::FromSeconds(t); }
  msg::PoseSample Pose() const {
    msg::PoseSample p;
    p.stamp = Now();
    p.site_from_rover = world.SiteFromRover();
    return p;
  }
  void Execute(const msg::MobilityCommand& c) {
    World& w = world;
    if (c.mode == msg::MobilityMode::kAutoNav || c.mode == msg::MobilityMode::kGoToWaypoint) {
      const Eigen::Vector2d from(w.x, w.y), to = c.goal.head<2>();
      const Eigen::Vector2d d = to - from;
      if (d.norm() > 1e-6) w.heading = std::atan2(d.y(), d.x());
      // Arrive within half the tolerance, off to the side.
      const Eigen::Vector2d side(-std::sin(w.heading), std::cos(w.heading));
      const Eigen::Vector2d end = to + 0.4 * c.tolerance * side;
      w.x = end.x();
      w.y = end.y();
      t += d.norm() / 0.05;
    } else if (c.mode == msg::MobilityMode::kDirected) {
      for (const auto& p : c.primitives) {
        if (p.kind == msg::DrivePrimitive::kTurnInPlace) {
          w.heading = geometry::WrapAngle(w.heading + p.angle * (1.0 + w.drive_error));
        } else {
          const double s = p.distance * (1.0 + w.drive_error);
          const double side = w.lateral_drift * std::abs(s);
          w.x += s * std::cos(w.heading) - side * std::sin(w.heading);
          w.y += s * std::sin(w.heading) + side * std::cos(w.heading);
          if (s > 3.0) w.z += w.lander.deck_height;  // the climb
        }
      }
      t += 30.0;
    }
  }
  // Runs outputs to completion: mast at goal at once, pairs at once, drives executed.
  void Pump(ExecutorOutput out, int limit = 400) {
    for (int i = 0; i < limit; ++i) {
      for (const auto& s : out.statuses) {
        statuses.push_back(s);
        if (s.phase == RendezvousPhase::kAtRampBase && !placement_at_base) {
          placement_at_base = world.Placement(s.ramp, 1.0);
        }
      }
      ExecutorOutput next;
      auto add = [&next](ExecutorOutput o) {
        for (auto& x : o.mobility) next.mobility.push_back(x);
        for (auto& x : o.mast) next.mast.push_back(x);
        for (auto& x : o.camera) next.camera.push_back(x);
        for (auto& x : o.statuses) next.statuses.push_back(x);
      };
      for (const auto& m : out.mast) {
        msg::MastStatus s;
        s.command_id = m.command_id;
        s.state = msg::MastState::kAtGoal;
        add(exec.OnMastStatus(s, Now()));
      }
      for (const auto& r : out.camera) {
        t += 2.0;
        exec.OnPose(Pose(), Now());
        NavcamPair pair;
        pair.stamp = Now();
        pair.request_id = r.request_id;
        add(exec.OnStereoPair(pair, Now()));
      }
      for (const auto& c : out.mobility) {
        drives.push_back(c);
        if (c.mode == msg::MobilityMode::kStop) continue;
        msg::MobilityStatus s;
        s.command_id = c.command_id;
        if (world.rock && c.mode == msg::MobilityMode::kAutoNav &&
            (c.goal.head<2>() - *world.rock).norm() < 1.5) {
          s.state = msg::MobilityState::kFailed;
          s.fault = msg::MobilityFault::kNoPath;
          s.fault_class = msg::FaultClass::kGoalError;
          s.message = "the goal lies on a rock";
          ++refused;
          add(exec.OnMobilityStatus(s, Now()));
          continue;
        }
        Execute(c);
        exec.OnPose(Pose(), Now());
        s.state = msg::MobilityState::kSucceeded;
        add(exec.OnMobilityStatus(s, Now()));
      }
      t += 1.0;
      exec.OnPose(Pose(), Now());
      add(exec.Step(Now()));
      out = std::move(next);
      if (!exec.busy() && out.mobility.empty() && out.mast.empty() && out.camera.empty()) {
        for (const auto& s : out.statuses) statuses.push_back(s);
        return;
      }
    }
    FAIL() << "the rendezvous did not end; last: " << exec.status().message;
  }
  msg::RendezvousCommand Command(int ramp = -1) const {
    msg::RendezvousCommand c;
    c.command_id = 5;
    c.target_estimate = Eigen::Vector3d(world.center.x() + 1.5, world.center.y() - 1.0, 0.0);
    c.ramp = ramp;
    return c;
  }
  void Start(const msg::RendezvousCommand& c) {
    exec.OnPose(Pose(), Now());
    Pump(exec.OnCommand(c, Now()));
  }
  bool SawPhase(RendezvousPhase p) const {
    for (const auto& s : statuses) {
      if (s.phase == p) return true;
    }
    return false;
  }
};

void ExpectPlacedAndClimbed(const Harness& h) {
  const msg::RendezvousStatus& s = h.exec.status();
  EXPECT_EQ(s.phase, RendezvousPhase::kDone) << s.message;
  EXPECT_EQ(s.fault, RendezvousFault::kNone) << s.message;
  ASSERT_TRUE(h.placement_at_base.has_value());
  const Eigen::Vector3d p = *h.placement_at_base;
  EXPECT_LT(std::abs(p.x()), 0.01) << "lateral";
  EXPECT_LT(std::abs(p.y()), 0.015) << "along";
  EXPECT_LT(std::abs(p.z()), 1.0 * kDegree) << "heading";
  EXPECT_GT(h.world.z, 0.5);
}

TEST(RendezvousExecutorTest, ReturnsFromThirtyMetresToTheFacingRampAndClimbs) {
  Harness h;
  h.world.yaw = kPi;  // ramp 0 descends towards the rover
  h.Start(h.Command());
  ExpectPlacedAndClimbed(h);
  EXPECT_TRUE(h.SawPhase(RendezvousPhase::kMidRange));
  EXPECT_TRUE(h.SawPhase(RendezvousPhase::kCloseRange));
  EXPECT_TRUE(h.SawPhase(RendezvousPhase::kClimb));
  EXPECT_EQ(h.exec.status().ramp, 0);
  // Mid-range legs are at most reacquire_step long.
  for (const auto& c : h.drives) EXPECT_NE(c.mode, msg::MobilityMode::kLongTraverse);
}

TEST(RendezvousExecutorTest, GoesRoundWhenTheWrongRampFacesTheRover) {
  Harness h;
  h.world.yaw = 0.0;  // ramp 1 descends towards the rover; ramp 0 is on the far side
  h.Start(h.Command(/*ramp=*/0));
  ExpectPlacedAndClimbed(h);
  EXPECT_EQ(h.exec.status().ramp, 0);
  bool orbited = false;
  for (const auto& s : h.statuses) orbited |= s.message.find("orbiting") != std::string::npos;
  EXPECT_TRUE(orbited);
}

TEST(RendezvousExecutorTest, OrbitsWhenTheLanderIsSideOn) {
  Harness h;
  h.world.yaw = 0.5 * kPi;  // ramps point across the approach
  h.Start(h.Command());
  ExpectPlacedAndClimbed(h);
}

TEST(RendezvousExecutorTest, ARockOnTheApproachPointMovesItRoundTheLander) {
  Harness h;
  h.world.yaw = kPi;
  // A rock where the approach point falls (7.5 m short of the deck centre on the rover's side).
  h.world.rock = Eigen::Vector2d(22.5, 0.0);
  h.Start(h.Command());
  ExpectPlacedAndClimbed(h);
  EXPECT_GE(h.refused, 1);
}

TEST(RendezvousExecutorTest, AFixFarFromTheEstimateIsNeverDrivenTo) {
  Harness h;
  h.world.center = Eigen::Vector2d(20.0, 0.0);
  h.world.decoy = Eigen::Vector2d(14.0, 9.0);  // 11 m off the estimate (21.5, -1)
  h.Start(h.Command());
  EXPECT_EQ(h.exec.status().fault, RendezvousFault::kNotFound);
  EXPECT_GE(h.vision->decoys_reported, 1);
  EXPECT_TRUE(h.drives.empty());
  bool rejected = false;
  for (const auto& s : h.statuses) rejected |= s.message.find("was rejected (gate 8 m)") != std::string::npos;
  EXPECT_TRUE(rejected);
}

TEST(RendezvousExecutorTest, FarAwayAFixOffTheEstimatesBearingIsNeverDrivenTo) {
  Harness h;
  h.world.center = Eigen::Vector2d(100.0, 0.0);
  h.world.decoy = Eigen::Vector2d(95.0, 30.0);  // 18 deg off: outside the far search window
  h.Start(h.Command());
  EXPECT_EQ(h.exec.status().fault, RendezvousFault::kNotFound);
  EXPECT_GE(h.vision->decoys_reported, 1);
  EXPECT_TRUE(h.drives.empty());
  bool rejected = false;
  for (const auto& s : h.statuses) rejected |= s.message.find("deg from the estimate's bearing") != std::string::npos;
  EXPECT_TRUE(rejected);
}

TEST(RendezvousExecutorTest, AGoodEstimateLeadsWhenTheDetectorLosesTheLanderNearby) {
  Harness h;
  h.world.yaw = kPi;
  h.world.blind_within = 12.0;  // mid-range sightings stop 12 m from the deck centre
  h.Start(h.Command());
  ExpectPlacedAndClimbed(h);
  bool led = false;
  for (const auto& s : h.statuses) led |= s.message.find("leads the next leg") != std::string::npos;
  EXPECT_TRUE(led);
}

TEST(RendezvousExecutorTest, ADriftingDriveSettlesAfterOneBackUpInsteadOfRunningOutOfSteps) {
  Harness h;
  h.world.yaw = kPi;
  h.world.lateral_drift = 0.035;  // 1.4 cm sideways over the last 0.4 m
  h.Start(h.Command());
  const msg::RendezvousStatus& s = h.exec.status();
  EXPECT_EQ(s.phase, RendezvousPhase::kDone) << s.message;
  ASSERT_TRUE(h.placement_at_base.has_value());
  EXPECT_LT(std::abs(h.placement_at_base->x()), 0.03);
  EXPECT_LT(std::abs(h.placement_at_base->y()), 0.04);
}

TEST(RendezvousExecutorTest, BlindLegsWhenAsked) {
  RendezvousOptions o;
  o.leg_mode = "goto_waypoint";
  Harness h(o);
  h.world.yaw = kPi;
  h.Start(h.Command());
  ExpectPlacedAndClimbed(h);
  for (const auto& c : h.drives) EXPECT_NE(c.mode, msg::MobilityMode::kAutoNav);
}

TEST(RendezvousExecutorTest, StopsAtTheBaseWithoutClimbingWhenAsked) {
  Harness h;
  h.world.yaw = kPi;
  msg::RendezvousCommand c = h.Command();
  c.climb = false;
  h.Start(c);
  EXPECT_EQ(h.exec.status().phase, RendezvousPhase::kDone);
  EXPECT_FALSE(h.SawPhase(RendezvousPhase::kClimb));
  EXPECT_LT(h.world.z, 0.1);
}

TEST(RendezvousExecutorTest, FarAwayTheLanderIsAcquiredBeforeTheFirstLeg) {
  Harness h;
  h.world.center = Eigen::Vector2d(60.0, 0.0);
  h.world.yaw = kPi;
  h.Start(h.Command());
  ExpectPlacedAndClimbed(h);
  EXPECT_TRUE(h.SawPhase(RendezvousPhase::kLongRange));
  // Legs are at most reacquire_step long, each after a sighting.
  ASSERT_FALSE(h.drives.empty());
  EXPECT_LE(h.drives.front().goal.head<2>().norm(), 5.0 + 1e-9);
}

TEST(RendezvousExecutorTest, BeyondSightRangeAMidRangeMissLetsTheEstimateLead) {
  Harness h;
  h.world.center = Eigen::Vector2d(33.0, 0.0);  // inside the mid-range detector's reach
  h.world.yaw = kPi;
  h.world.sight_limit = 30.0;                   // ... which sees it only inside 30 m
  h.Start(h.Command());
  ExpectPlacedAndClimbed(h);
  ASSERT_FALSE(h.drives.empty());
  EXPECT_LE(h.drives.front().goal.head<2>().norm(), 5.0 + 1e-9);
}

TEST(RendezvousExecutorTest, FarAwayOneBiasedFixDoesNotLockTheEstimatesRange) {
  Harness h;
  h.world.center = Eigen::Vector2d(100.0, 0.0);
  h.world.yaw = kPi;
  h.world.sight_limit = 200.0;
  h.world.biased_fixes = 1;
  h.world.range_scale = 0.75;  // the first fix says 75 m
  h.Start(h.Command());
  ExpectPlacedAndClimbed(h);
  bool reset = false;
  for (const auto& s : h.statuses) reset |= s.message.find("range was reset") != std::string::npos;
  EXPECT_TRUE(reset);
}

TEST(RendezvousExecutorTest, FarAwayALanderNeverSeenIsNotFoundAndNeverDrives) {
  Harness h;
  h.world.center = Eigen::Vector2d(60.0, 0.0);
  h.world.lander_visible = false;
  h.Start(h.Command());
  EXPECT_EQ(h.exec.status().fault, RendezvousFault::kNotFound);
  EXPECT_THAT(h.exec.status().message, HasSubstr("not found in 7 pairs"));
  EXPECT_TRUE(h.drives.empty());
}

TEST(RendezvousExecutorTest, LanderNotFoundAfterTheSearchNeverDrives) {
  Harness h;
  h.world.center = Eigen::Vector2d(20.0, 0.0);  // within sight range: the look-around runs
  h.world.lander_visible = false;
  h.Start(h.Command());
  EXPECT_EQ(h.exec.status().fault, RendezvousFault::kNotFound);
  EXPECT_THAT(h.exec.status().message, HasSubstr("not found in 7 pairs"));
  EXPECT_TRUE(h.drives.empty());
}

TEST(RendezvousExecutorTest, TooFewStripesAtTheBaseIsATypedFault) {
  Harness h;
  h.world.yaw = kPi;
  h.world.stripes_near = 3;
  h.Start(h.Command());
  EXPECT_EQ(h.exec.status().fault, RendezvousFault::kTooFewStripes);
  EXPECT_THAT(h.exec.status().message, HasSubstr("3 stripes, need 4"));
  EXPECT_FALSE(h.SawPhase(RendezvousPhase::kAtRampBase));
}

TEST(RendezvousExecutorTest, NoUsableRampAroundTheLanderIsNotFound) {
  Harness h;
  h.world.yaw = kPi;
  h.world.stripes = 3;
  h.world.stripes_near = 3;
  h.Start(h.Command());
  EXPECT_EQ(h.exec.status().fault, RendezvousFault::kNotFound);
  EXPECT_THAT(h.exec.status().message, HasSubstr("legs around the lander"));
}

TEST(RendezvousExecutorTest, RejectsBadCommandsNamingTheField) {
  Harness h;
  h.exec.OnPose(h.Pose(), h.Now());
  msg::RendezvousCommand c = h.Command();
  c.target_estimate.y() = std::nan("");
  ExecutorOutput out = h.exec.OnCommand(c, h.Now());
  ASSERT_EQ(out.statuses.size(), 1u);
  EXPECT_EQ(out.statuses[0].fault, RendezvousFault::kBadCommand);
  EXPECT_THAT(out.statuses[0].message, HasSubstr("target_estimate.y = nan"));
  EXPECT_FALSE(h.exec.busy());

  c = h.Command();
  c.standoff = 9.0;
  EXPECT_THAT(h.exec.OnCommand(c, h.Now()).statuses[0].message, HasSubstr("standoff = 9 m"));
  c = h.Command();
  c.target_estimate.x() = 400.0;
  EXPECT_THAT(h.exec.OnCommand(c, h.Now()).statuses[0].message, HasSubstr("beyond max_target_range"));
  c = h.Command();
  c.ramp = 2;
  EXPECT_THAT(h.exec.OnCommand(c, h.Now()).statuses[0].message, HasSubstr("ramp = 2"));
  c = h.Command();
  c.target = msg::RendezvousTarget::kScience;
  EXPECT_THAT(h.exec.OnCommand(c, h.Now()).statuses[0].message, HasSubstr("only LANDER"));
  EXPECT_FALSE(h.exec.busy());
}

TEST(RendezvousExecutorTest, StalePoseAndBusyAndStop) {
  Harness h;
  msg::RendezvousCommand c = h.Command();
  ExecutorOutput out = h.exec.OnCommand(c, h.Now());  // no pose yet
  EXPECT_EQ(out.statuses[0].fault, RendezvousFault::kStalePose);
  h.exec.OnPose(h.Pose(), h.Now());
  out = h.exec.OnCommand(c, h.Now() + Seconds(5.0));
  EXPECT_THAT(out.statuses[0].message, HasSubstr("dl/pose is 5 s old"));

  h.exec.OnPose(h.Pose(), h.Now());
  out = h.exec.OnCommand(c, h.Now());
  ASSERT_TRUE(h.exec.busy());
  ASSERT_EQ(out.mast.size(), 1u);
  msg::RendezvousCommand second = c;
  second.command_id = 6;
  out = h.exec.OnCommand(second, h.Now());
  ASSERT_EQ(out.statuses.size(), 2u);
  EXPECT_EQ(out.statuses[0].command_id, 6u);
  EXPECT_EQ(out.statuses[0].fault, RendezvousFault::kBusy);
  EXPECT_EQ(out.statuses[1].command_id, 5u);
  EXPECT_TRUE(h.exec.busy());
  msg::RendezvousCommand stop;
  stop.command_id = 7;
  stop.target = msg::RendezvousTarget::kStop;
  out = h.exec.OnCommand(stop, h.Now());
  EXPECT_EQ(h.exec.status().fault, RendezvousFault::kStopped);
  EXPECT_FALSE(h.exec.busy());
}

TEST(RendezvousExecutorTest, TimeOutsAreTyped) {
  Harness h;
  h.exec.OnPose(h.Pose(), h.Now());
  ExecutorOutput out = h.exec.OnCommand(h.Command(), h.Now());
  ASSERT_EQ(out.mast.size(), 1u);
  out = h.exec.Step(h.Now() + Seconds(100.0));
  EXPECT_EQ(h.exec.status().fault, RendezvousFault::kMast);
  h.exec.OnPose(h.Pose(), h.Now());
  msg::RendezvousCommand c = h.Command();
  c.time_budget_s = 50.0;
  out = h.exec.OnCommand(c, h.Now());
  msg::MastStatus at;
  at.command_id = out.mast[0].command_id;
  at.state = msg::MastState::kAtGoal;
  h.exec.OnMastStatus(at, h.Now());
  out = h.exec.Step(h.Now() + Seconds(1.0));
  ASSERT_EQ(out.camera.size(), 1u);
  out = h.exec.Step(h.Now() + Seconds(40.0));
  EXPECT_EQ(h.exec.status().fault, RendezvousFault::kCamera);
}

TEST(RendezvousExecutorTest, ADriveWithoutATerminalStatusIsAMobilityFault) {
  Harness h;
  h.world.yaw = kPi;
  h.exec.OnPose(h.Pose(), h.Now());
  ExecutorOutput out = h.exec.OnCommand(h.Command(), h.Now());
  msg::MastStatus at;
  at.command_id = out.mast.at(0).command_id;
  at.state = msg::MastState::kAtGoal;
  h.exec.OnMastStatus(at, h.Now());
  out = h.exec.Step(h.Now() + Seconds(1.0));
  NavcamPair pair;
  pair.request_id = out.camera.at(0).request_id;
  out = h.exec.OnStereoPair(pair, h.Now() + Seconds(1.0));
  ASSERT_EQ(out.mobility.size(), 1u);  // the first mid-range leg
  h.exec.OnPose(h.Pose(), h.Now() + Seconds(700.0));
  out = h.exec.Step(h.Now() + Seconds(700.0));
  EXPECT_EQ(h.exec.status().fault, RendezvousFault::kMobility);
  EXPECT_THAT(h.exec.status().message, HasSubstr("no terminal apl/mobility_status"));
  ASSERT_EQ(out.mobility.size(), 1u);  // and the drive is stopped
  EXPECT_EQ(out.mobility[0].mode, msg::MobilityMode::kStop);
}

}  // namespace
}  // namespace rover::apl::rendezvous

namespace rover::apl::rendezvous {
namespace {

TEST(CommandIds, CountPerTopicInTheirHalfAndSkipZero) {
  CommandIds lander(0), science(kScienceIdHalf);
  EXPECT_EQ(lander.Mobility(), 0x52000001u);
  EXPECT_EQ(lander.Mobility(), 0x52000002u);
  EXPECT_EQ(lander.Mast(), 0x52000001u);
  EXPECT_EQ(lander.Camera(), 0x03000001u);
  EXPECT_EQ(science.Mobility(), 0x52800001u);
  EXPECT_EQ(science.Arm(), 0x52800001u);
  EXPECT_EQ(science.Camera(), 0x03800001u);
  // After 2^23 - 1 ids the count wraps past 0 and stays in its half.
  std::uint32_t id = 0;
  for (std::uint32_t i = 1; i < kScienceIdHalf; ++i) id = science.Mast();
  EXPECT_EQ(id, 0x52FFFFFFu);
  EXPECT_EQ(science.Mast(), 0x52800001u);
}

}  // namespace
}  // namespace rover::apl::rendezvous
