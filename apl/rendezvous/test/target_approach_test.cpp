// The science-target approach in a kinematic world: the rover's wheels slip (its pose believes
// the commanded motion), and a fake vision sees the target's true position in the rover frame
// with noise. Checks the approach ends at the standoff facing the target with the target in R
// as seen (not as odometry has it), every goal error typed, bad commands named.
#include "rover/apl/rendezvous/target_approach.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "rover/base/units.hpp"
#include "rover/geometry/planar.hpp"

namespace rover::apl::rendezvous {
namespace {

using ::testing::HasSubstr;
using msg::RendezvousFault;
using msg::RendezvousPhase;

struct Rover2 {
  double x = 0.0, y = 0.0, heading = 0.0;
  Eigen::Isometry3d Pose() const {
    Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
    t.linear() = Eigen::AngleAxisd(heading, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    t.translation() = Eigen::Vector3d(x, y, 0.0);
    return t;
  }
};

struct ApproachWorld {
  Eigen::Vector3d target{10.0, 1.0, 0.12};
  Rover2 truth, odometry;
  double slip = 0.2;       // straights come out this much short
  double turn_error = 0.03;  // turns come out this much long
  double noise = 0.003;    // [m] the fake's measurement noise
  int lose_after = -1;     // the fake loses the target at this Track call (-1: never)
  bool designation_fails = false;
  std::mt19937 rng{3};

  void Straight(double s) {
    odometry.x += s * std::cos(odometry.heading);
    odometry.y += s * std::sin(odometry.heading);
    const double real = s * (1.0 - slip);
    truth.x += real * std::cos(truth.heading);
    truth.y += real * std::sin(truth.heading);
  }
  void Turn(double a) {
    odometry.heading = geometry::WrapAngle(odometry.heading + a);
    truth.heading = geometry::WrapAngle(truth.heading + a * (1.0 + turn_error));
  }
  Eigen::Vector3d TargetInRover() const { return truth.Pose().inverse() * target; }
};

class FakeTracker : public TargetVision {
 public:
  explicit FakeTracker(ApproachWorld* w) : w_(w) {}
  int tracks = 0;
  Result<TargetFix> Designate(const NavcamPair&, const Eigen::Isometry3d&,
                              const Eigen::Vector2d& pixel) override {
    if (w_->designation_fails) {
      return InvalidArgument("pixel (" + std::to_string(static_cast<int>(pixel.x())) + ", " +
                             std::to_string(static_cast<int>(pixel.y())) +
                             ") has no stereo range: no texture");
    }
    return Fix();
  }
  Result<TargetFix> Track(const NavcamPair&, const Eigen::Isometry3d&) override {
    if (tracks++ == w_->lose_after) {
      TargetFix f;
      f.loss = TargetLoss::kTooFewFeatures;
      f.why = "2 of 30 features found again";
      return f;
    }
    return Fix();
  }

 private:
  TargetFix Fix() {
    std::normal_distribution<double> n(0.0, w_->noise);
    TargetFix f;
    f.tracked = true;
    f.target_measured = true;
    f.target_rover = w_->TargetInRover() + Eigen::Vector3d(n(w_->rng), n(w_->rng), 0.0);
    f.sigma = w_->noise;
    f.features = f.matched = f.inliers = 20;
    return f;
  }
  ApproachWorld* w_;
};

struct ApproachHarness {
  explicit ApproachHarness(const RendezvousOptions& o = {}) : exec(o, vision) {}
  ApproachWorld world;
  std::shared_ptr<FakeTracker> vision = std::make_shared<FakeTracker>(&world);
  TargetApproach exec;
  double t = 10.0;
  std::vector<msg::RendezvousStatus> statuses;
  std::vector<msg::MobilityCommand> drives;
  // A fake dl-arm: STOW -> STOWED; PLACE -> `place_reply` with the face 2 mm above the
  // target; AUTOFOCUS -> `focus_reply` (the arm is then out).
  std::vector<msg::ArmCommand> arm_commands;
  msg::ArmState place_reply = msg::ArmState::kPlaced;
  msg::ArmState focus_reply = msg::ArmState::kFocused;
  bool arm_stowed = true;
  // A forward-looking pinhole NAVCAM 1.5 m up (the by-point designation projects into it).
  geometry::CameraModel model = [] {
    geometry::PinholeRadial p;
    p.fx = p.fy = 1000.0;
    p.cx = p.cy = 511.5;
    p.width = p.height = 1024;
    p.pose.linear() << 0, 0, 1, -1, 0, 0, 0, -1, 0;
    p.pose.translation() = Eigen::Vector3d(0.0, 0.0, 1.5);
    return *geometry::CameraModel::Create(p);
  }();

  Time Now() const { return Time::FromSeconds(t); }
  msg::PoseSample Pose() const {
    msg::PoseSample p;
    p.stamp = Now();
    p.site_from_rover = world.odometry.Pose();
    return p;
  }
  void Execute(const msg::MobilityCommand& c) {
    if (c.mode == msg::MobilityMode::kDirected) {
      for (const auto& p : c.primitives) {
        if (p.kind == msg::DrivePrimitive::kTurnInPlace) world.Turn(p.angle);
        else world.Straight(p.distance);
      }
    } else {
      // A leg: face the goal (by odometry) and drive to it (by odometry).
      const Eigen::Vector2d d = c.goal.head<2>() - Eigen::Vector2d(world.odometry.x, world.odometry.y);
      world.Turn(geometry::WrapAngle(std::atan2(d.y(), d.x()) - world.odometry.heading));
      world.Straight(d.norm());
    }
    t += 30.0;
  }
  void Pump(ExecutorOutput out, int limit = 400) {
    for (int i = 0; i < limit; ++i) {
      for (const auto& s : out.statuses) statuses.push_back(s);
      ExecutorOutput next;
      auto add = [&next](ExecutorOutput o) {
        for (auto& x : o.mobility) next.mobility.push_back(x);
        for (auto& x : o.mast) next.mast.push_back(x);
        for (auto& x : o.camera) next.camera.push_back(x);
        for (auto& x : o.arm) next.arm.push_back(x);
        for (auto& x : o.statuses) next.statuses.push_back(x);
      };
      for (const auto& a : out.arm) {
        arm_commands.push_back(a);
        if (a.mode == msg::ArmMode::kStop) continue;
        msg::ArmStatus s;
        s.command_id = a.command_id;
        if (a.mode == msg::ArmMode::kStow) {
          arm_stowed = true;
          s.state = msg::ArmState::kStowed;
        } else if (a.mode == msg::ArmMode::kAutofocus) {
          arm_stowed = false;
          s.state = focus_reply;
          s.focus_height = 0.0605;
          s.focus_images = 11;
          s.focus_image_id = 77;
          s.message = focus_reply == msg::ArmState::kFocused ? "best focus" : "no focus peak";
        } else {
          arm_stowed = false;
          s.state = place_reply;
          s.tool_point = a.target + Eigen::Vector3d(0.0, 0.0, 0.002);
          s.message = place_reply == msg::ArmState::kPlaced ? "face 2 mm above the target"
                                                             : "no contact within 0.03 m below the target";
        }
        s.stowed = arm_stowed;
        t += 20.0;
        add(exec.OnArmStatus(s, Now()));
      }
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
        pair.request_id = r.request_id;
        pair.left_model = pair.right_model = &model;
        add(exec.OnStereoPair(pair, Now()));
      }
      for (const auto& c : out.mobility) {
        drives.push_back(c);
        if (c.mode == msg::MobilityMode::kStop) continue;
        Execute(c);
        exec.OnPose(Pose(), Now());
        msg::MobilityStatus s;
        s.command_id = c.command_id;
        s.state = msg::MobilityState::kSucceeded;
        add(exec.OnMobilityStatus(s, Now()));
      }
      t += 1.0;
      exec.OnPose(Pose(), Now());
      add(exec.Step(Now()));
      out = std::move(next);
      if (!exec.busy() && out.mobility.empty() && out.mast.empty() && out.camera.empty() &&
          out.arm.empty()) {
        for (const auto& s : out.statuses) statuses.push_back(s);
        return;
      }
    }
    FAIL() << "the approach did not end; last: " << exec.status().message;
  }
  msg::RendezvousCommand Command() const {
    msg::RendezvousCommand c;
    c.command_id = 9;
    c.target = msg::RendezvousTarget::kScience;
    c.image_id = 0x01000001;
    c.pixel_x = 500;
    c.pixel_y = 600;
    return c;
  }
  void Start(const msg::RendezvousCommand& c, bool with_pair = true) {
    exec.OnPose(Pose(), Now());
    NavcamPair pair;
    pair.request_id = c.image_id;
    Pump(exec.OnCommand(c, with_pair ? &pair : nullptr, world.odometry.Pose(), Now()));
  }
  bool Saw(RendezvousPhase p) const {
    for (const auto& s : statuses) if (s.phase == p) return true;
    return false;
  }
};

TEST(TargetApproachTest, ReachesTheStandoffFacingTheTargetDespiteSlip) {
  ApproachHarness h;
  h.Start(h.Command());
  const msg::RendezvousStatus& s = h.exec.status();
  ASSERT_EQ(s.phase, RendezvousPhase::kDone) << s.message;
  EXPECT_TRUE(h.Saw(RendezvousPhase::kAtTarget));
  EXPECT_TRUE(h.Saw(RendezvousPhase::kApproachTarget));
  // Truth: the rover stands the standoff from the target, facing it.
  const Eigen::Vector3d rel = h.world.TargetInRover();
  EXPECT_NEAR(rel.head<2>().norm(), 1.05, 0.04);
  EXPECT_LT(std::abs(std::atan2(rel.y(), rel.x())), 3.0 * kDegree);
  // What the arm gets is the target as seen, within the fake's noise of the truth...
  EXPECT_LT((s.target_in_rover - rel).head<2>().norm(), 0.015);
  // ... while odometry alone is off by decimetres after 20 % slip over ~9 m.
  const Eigen::Vector3d by_odometry = h.world.odometry.Pose().inverse() * h.world.target;
  EXPECT_GT((by_odometry - rel).head<2>().norm(), 0.5);
  // Autonav legs first, the last moves directed.
  EXPECT_EQ(h.drives.front().mode, msg::MobilityMode::kAutoNav);
  EXPECT_EQ(h.drives.back().mode, msg::MobilityMode::kDirected);
}

TEST(TargetApproachTest, ASitePointDesignatesInAPairTakenLookingAtIt) {
  ApproachHarness h;
  auto c = h.Command();
  c.image_id = 0;
  c.target_estimate = h.world.target + Eigen::Vector3d(0.3, -0.2, 0.0);  // roughly there
  h.Start(c, /*with_pair=*/false);
  EXPECT_EQ(h.exec.status().phase, RendezvousPhase::kDone) << h.exec.status().message;
  EXPECT_NEAR(h.world.TargetInRover().head<2>().norm(), 1.05, 0.04);
  // A point behind the rover never projects into the pair: BAD_COMMAND, nothing drives.
  ApproachHarness behind;
  c.target_estimate = Eigen::Vector3d(-5.0, 0.0, 0.0);
  behind.Start(c, false);
  EXPECT_EQ(behind.exec.status().fault, RendezvousFault::kBadCommand);
  EXPECT_THAT(behind.exec.status().message, HasSubstr("target_estimate is not in the NAVCAM image"));
  EXPECT_TRUE(behind.drives.empty());
  c.target_estimate.y() = std::nan("");
  ApproachHarness nan;
  nan.Start(c, false);
  EXPECT_THAT(nan.exec.status().message, HasSubstr("target_estimate.y = nan"));
}

TEST(TargetApproachTest, PlacesTheInstrumentWhereTheLastPairSawTheTarget) {
  ApproachHarness h;
  auto c = h.Command();
  c.place_instrument = true;
  h.Start(c);
  const msg::RendezvousStatus& s = h.exec.status();
  ASSERT_EQ(s.phase, RendezvousPhase::kDone) << s.message;
  EXPECT_TRUE(h.Saw(RendezvousPhase::kAtTarget));
  EXPECT_TRUE(h.Saw(RendezvousPhase::kPlacing));
  EXPECT_TRUE(h.Saw(RendezvousPhase::kPlaced));
  ASSERT_EQ(h.arm_commands.size(), 1u);
  const msg::ArmCommand& place = h.arm_commands[0];
  EXPECT_EQ(place.mode, msg::ArmMode::kPlace);
  EXPECT_EQ(place.target, s.target_in_rover);  // the target as the last pair measured it
  EXPECT_LT((place.target - h.world.TargetInRover()).head<2>().norm(), 0.015);
  // Without place_instrument the arm is left alone.
  ApproachHarness plain;
  plain.Start(plain.Command());
  EXPECT_TRUE(plain.arm_commands.empty());
  EXPECT_FALSE(plain.Saw(RendezvousPhase::kPlacing));
}

TEST(TargetApproachTest, AutofocusFollowsThePlacementAboutTheContactPoint) {
  ApproachHarness h;
  auto c = h.Command();
  c.place_instrument = true;
  c.autofocus = true;
  h.Start(c);
  const msg::RendezvousStatus& s = h.exec.status();
  ASSERT_EQ(s.phase, RendezvousPhase::kDone) << s.message;
  EXPECT_TRUE(h.Saw(RendezvousPhase::kPlaced));
  EXPECT_TRUE(h.Saw(RendezvousPhase::kFocusing));
  EXPECT_TRUE(h.Saw(RendezvousPhase::kFocused));
  ASSERT_EQ(h.arm_commands.size(), 2u);
  EXPECT_EQ(h.arm_commands[0].mode, msg::ArmMode::kPlace);
  EXPECT_EQ(h.arm_commands[1].mode, msg::ArmMode::kAutofocus);
  // About the face where it touched (the contact measured the surface), not the pair's point.
  EXPECT_EQ(h.arm_commands[1].target, h.arm_commands[0].target + Eigen::Vector3d(0.0, 0.0, 0.002));
  bool focused_said = false;
  for (const auto& st : h.statuses) {
    if (st.phase == RendezvousPhase::kFocused) {
      EXPECT_THAT(st.message, HasSubstr("60.5 mm above the target after 11 frames"));
      EXPECT_THAT(st.message, HasSubstr("ddl/mi_frame 77"));
      focused_said = true;
    }
  }
  EXPECT_TRUE(focused_said);
  // Without the placement: about the target the last pair measured.
  ApproachHarness only;
  auto f = only.Command();
  f.autofocus = true;
  only.Start(f);
  ASSERT_EQ(only.exec.status().phase, RendezvousPhase::kDone) << only.exec.status().message;
  ASSERT_EQ(only.arm_commands.size(), 1u);
  EXPECT_EQ(only.arm_commands[0].mode, msg::ArmMode::kAutofocus);
  EXPECT_EQ(only.arm_commands[0].target, only.exec.status().target_in_rover);
  EXPECT_FALSE(only.Saw(RendezvousPhase::kPlacing));
  // A sweep that ends in a fault: ARM, dl-arm's reason named.
  ApproachHarness bad;
  bad.focus_reply = msg::ArmState::kFault;
  bad.Start(c);
  EXPECT_EQ(bad.exec.status().phase, RendezvousPhase::kFailed);
  EXPECT_EQ(bad.exec.status().fault, RendezvousFault::kArm);
  EXPECT_THAT(bad.exec.status().message, HasSubstr("dl-arm FAULT: no focus peak"));
}

TEST(TargetApproachTest, ArmFaultsAreTypedAndAnArmLeftOutIsStowedBeforeDriving) {
  ApproachHarness h;
  h.place_reply = msg::ArmState::kFault;
  auto c = h.Command();
  c.place_instrument = true;
  h.Start(c);
  EXPECT_EQ(h.exec.status().phase, RendezvousPhase::kFailed);
  EXPECT_EQ(h.exec.status().fault, RendezvousFault::kArm);
  EXPECT_THAT(h.exec.status().message, HasSubstr("dl-arm FAULT: no contact"));
  // The next approach starts with the arm out (dl-arm said so): STOW before the first leg.
  const std::size_t drives_before = h.drives.size();
  h.world = ApproachWorld{};
  c.command_id = 10;
  c.place_instrument = false;
  h.Start(c);
  EXPECT_EQ(h.exec.status().phase, RendezvousPhase::kDone) << h.exec.status().message;
  ASSERT_GE(h.arm_commands.size(), 2u);
  EXPECT_EQ(h.arm_commands[1].mode, msg::ArmMode::kStow);
  EXPECT_GT(h.drives.size(), drives_before);
  // No answer from dl-arm: ARM after arm_timeout_s, and the arm is told to stop.
  RendezvousOptions quick;
  quick.arm_timeout_s = 10.0;
  ApproachWorld far;  // 10 m from the target again
  TargetApproach silent(quick, std::make_shared<FakeTracker>(&far));
  msg::PoseSample p;
  p.stamp = Time::FromSeconds(1.0);
  p.site_from_rover = far.odometry.Pose();
  silent.OnPose(p, p.stamp);
  msg::ArmStatus out_arm;
  out_arm.stowed = false;
  silent.OnArmStatus(out_arm, p.stamp);
  NavcamPair pair;
  pair.request_id = c.image_id;
  ExecutorOutput o = silent.OnCommand(c, &pair, far.odometry.Pose(), p.stamp);
  ASSERT_EQ(o.arm.size(), 1u) << msg::RendezvousPhaseName(silent.status().phase) << ": "
                              << silent.status().message;
  EXPECT_EQ(o.arm[0].mode, msg::ArmMode::kStow);
  EXPECT_TRUE(o.mobility.empty()) << "no leg before the arm is stowed";
  o = silent.Step(Time::FromSeconds(20.0));
  EXPECT_EQ(silent.status().fault, RendezvousFault::kArm);
  EXPECT_THAT(silent.status().message, HasSubstr("no STOWED from dl-arm"));
  ASSERT_EQ(o.arm.size(), 1u);
  EXPECT_EQ(o.arm[0].mode, msg::ArmMode::kStop);
}

TEST(TargetApproachTest, DirectedLegsWorkToo) {
  RendezvousOptions o;
  o.target_leg_mode = "directed";
  ApproachHarness h(o);
  h.Start(h.Command());
  EXPECT_EQ(h.exec.status().phase, RendezvousPhase::kDone) << h.exec.status().message;
  for (const auto& c : h.drives) EXPECT_EQ(c.mode, msg::MobilityMode::kDirected);
}

TEST(TargetApproachTest, ALostTargetIsATypedGoalErrorAndNothingDrivesOn) {
  ApproachHarness h;
  h.world.lose_after = 2;
  h.Start(h.Command());
  const msg::RendezvousStatus& s = h.exec.status();
  EXPECT_EQ(s.phase, RendezvousPhase::kFailed);
  EXPECT_EQ(s.fault, RendezvousFault::kTargetLost);
  EXPECT_THAT(s.message, HasSubstr("TOO_FEW_FEATURES"));
  EXPECT_THAT(s.message, HasSubstr("2 of 30 features"));
  EXPECT_EQ(h.drives.size(), 3u);  // the legs before the lost pair, none after
  EXPECT_FALSE(h.exec.busy());
}

TEST(TargetApproachTest, BadCommandsAreNamedAndNothingMoves) {
  {
    ApproachHarness h;
    auto c = h.Command();
    h.Start(c, /*with_pair=*/false);
    EXPECT_EQ(h.exec.status().fault, RendezvousFault::kBadCommand);
    EXPECT_THAT(h.exec.status().message, HasSubstr("image_id = 16777217"));
    EXPECT_TRUE(h.drives.empty());
  }
  {
    ApproachHarness h;
    auto c = h.Command();
    c.standoff = 0.2;
    h.Start(c);
    EXPECT_EQ(h.exec.status().fault, RendezvousFault::kBadCommand);
    EXPECT_THAT(h.exec.status().message, HasSubstr("standoff = 0.2 m"));
    EXPECT_TRUE(h.drives.empty());
  }
  {
    ApproachHarness h;
    h.world.designation_fails = true;
    h.Start(h.Command());
    EXPECT_EQ(h.exec.status().fault, RendezvousFault::kBadCommand);
    EXPECT_THAT(h.exec.status().message, HasSubstr("pixel (500, 600)"));
    EXPECT_TRUE(h.drives.empty());
  }
  {
    ApproachHarness h;
    h.world.target = Eigen::Vector3d(45.0, 0.0, 0.0);
    h.Start(h.Command());
    EXPECT_EQ(h.exec.status().fault, RendezvousFault::kBadCommand);
    EXPECT_THAT(h.exec.status().message, HasSubstr("beyond target_max_range"));
  }
}

TEST(TargetApproachTest, BusyWhileRunningAndStopEndsIt) {
  ApproachHarness h;
  h.exec.OnPose(h.Pose(), h.Now());
  NavcamPair pair;
  ExecutorOutput out = h.exec.OnCommand(h.Command(), &pair, h.world.odometry.Pose(), h.Now());
  ASSERT_TRUE(h.exec.busy());
  ASSERT_EQ(out.mobility.size(), 1u);
  auto c2 = h.Command();
  c2.command_id = 10;
  ExecutorOutput busy = h.exec.OnCommand(c2, &pair, h.world.odometry.Pose(), h.Now());
  ASSERT_GE(busy.statuses.size(), 1u);
  EXPECT_EQ(busy.statuses[0].command_id, 10u);
  EXPECT_EQ(busy.statuses[0].fault, RendezvousFault::kBusy);
  EXPECT_TRUE(h.exec.busy());
  ExecutorOutput stop;
  EXPECT_TRUE(h.exec.Stop(11, &stop));
  EXPECT_EQ(h.exec.status().fault, RendezvousFault::kStopped);
  ASSERT_EQ(stop.mobility.size(), 1u);  // the leg it started is stopped
  EXPECT_EQ(stop.mobility[0].mode, msg::MobilityMode::kStop);
  EXPECT_FALSE(h.exec.busy());
}

TEST(TargetApproachTest, NoPoseIsStalePose) {
  ApproachHarness h;
  NavcamPair pair;
  ExecutorOutput out = h.exec.OnCommand(h.Command(), &pair, h.world.odometry.Pose(), h.Now());
  EXPECT_EQ(h.exec.status().fault, RendezvousFault::kStalePose);
  EXPECT_TRUE(out.mobility.empty());
}

}  // namespace
}  // namespace rover::apl::rendezvous
