// Seed 003's conditional approach template (deploy/sequences/approach_template.seq) run against
// a simulated approach: a fake mobility service that moves the rover by the commanded distance
// less a seeded random slip, and reports the pose as visual odometry would (the true pose after a
// VISODOM command) or as wheel odometry would (the commanded motion, slip unseen).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "rover/apl/sequencer/interpreter.hpp"
#include "rover/apl/sequencer/parser.hpp"

namespace rover::apl::sequencer {
namespace {

const std::string kTemplate =
    std::string(ROVER_SOURCE_DIR) + "/deploy/sequences/approach_template.seq";

Sequence LoadTemplate(const Vec3& target) {
  ParseOptions o;
  o.overrides["target"] = "(" + std::to_string(target.x) + ", " + std::to_string(target.y) +
                          ", " + std::to_string(target.z) + ")";
  Result<Sequence> s = ParseSequenceFile(kTemplate, o);
  EXPECT_TRUE(s.ok()) << s.status().ToString();
  return s.ok() ? *s : Sequence{};
}

/// The rover on flat ground: true planar pose, what the estimator believes, and the run clock.
class FakeRover {
 public:
  FakeRover(std::uint32_t seed, double max_slip, bool visual_odometry)
      : rng_(seed), slip_(0.0, max_slip), visual_odometry_(visual_odometry) {}

  /// Executes a mobility command; returns its outcome stamped with its end time.
  Outcome Execute(const Command& c) {
    const auto& m = std::get<MobilityRequest>(c.request);
    double seconds = 1.0;
    if (m.primitive == msg::DrivePrimitive::kStraight) {
      const double slip = slip_(rng_);
      const double moved = m.distance * (1.0 - slip);
      // Slip on a cross-slope also pushes the rover sideways a little.
      const double side = 0.1 * slip * m.distance;
      truth_x_ += moved * std::cos(truth_yaw_) - side * std::sin(truth_yaw_);
      truth_y_ += moved * std::sin(truth_yaw_) + side * std::cos(truth_yaw_);
      odo_x_ += m.distance * std::cos(odo_yaw_);
      odo_y_ += m.distance * std::sin(odo_yaw_);
      seconds = std::abs(m.distance) / 0.05;
    } else if (m.primitive == msg::DrivePrimitive::kTurnInPlace) {
      truth_yaw_ += m.angle;
      odo_yaw_ += m.angle;
      seconds = std::abs(m.angle) / 0.1 + 1.0;
    }
    if (m.mode == msg::MobilityMode::kVisOdom && visual_odometry_) {
      odo_x_ = truth_x_;
      odo_y_ = truth_y_;
      odo_yaw_ = truth_yaw_;
      seconds += 20.0;  // one visual-odometry update
    }
    now_ += seconds;
    if (m.mode == msg::MobilityMode::kVisOdom || m.mode == msg::MobilityMode::kDirected) ++motions_;
    return Outcome::Nominal(Time::FromSeconds(now_));
  }

  PoseSample Pose() const {
    PoseSample p;
    p.stamp = Time::FromSeconds(now_ + 0.1);
    p.position = {odo_x_, odo_y_, 0.0};
    p.yaw = odo_yaw_;
    return p;
  }
  Time Now() const { return Time::FromSeconds(now_ + 0.2); }
  void Wait(double s) { now_ += s; }

  double TrueDistanceTo(const Vec3& p) const { return std::hypot(p.x - truth_x_, p.y - truth_y_); }
  /// Bearing of `p` from the rover's true heading [rad].
  double TrueBearingOf(const Vec3& p) const {
    return std::remainder(std::atan2(p.y - truth_y_, p.x - truth_x_) - truth_yaw_,
                          2.0 * std::numbers::pi);
  }
  int motions() const { return motions_; }

 private:
  std::mt19937 rng_;
  std::uniform_real_distribution<double> slip_;
  bool visual_odometry_;
  double truth_x_ = 0.0, truth_y_ = 0.0, truth_yaw_ = 0.0;
  double odo_x_ = 0.0, odo_y_ = 0.0, odo_yaw_ = 0.0;
  double now_ = 0.0;
  int motions_ = 0;
};

struct Approach {
  SequenceStatus status;
  std::vector<Command> commands;  // the mobility commands
  std::vector<Command> arm;       // the arm commands (answered NOMINAL by a fake dl-arm)
};

Approach RunApproach(const Vec3& target, FakeRover& rover) {
  Result<Interpreter> it = Interpreter::Create();
  EXPECT_TRUE(it.ok());
  Approach out;
  EXPECT_TRUE(it->Start(LoadTemplate(target), rover.Now()).ok());
  it->OnPose(rover.Pose());
  for (int guard = 0; guard < 500 && it->busy(); ++guard) {
    StepOutput o = it->Step(rover.Now());
    if (o.command && std::holds_alternative<ArmRequest>(o.command->request)) {
      out.arm.push_back(*o.command);
      rover.Wait(30.0);
      EXPECT_TRUE(it->OnCommandResult(o.command->id, Outcome::Nominal(rover.Now())).ok());
    } else if (o.command) {
      out.commands.push_back(*o.command);
      const Outcome result = rover.Execute(*o.command);
      it->OnPose(rover.Pose());  // the estimator publishes after the motion
      EXPECT_TRUE(it->OnCommandResult(o.command->id, result).ok());
    } else if (it->busy()) {
      rover.Wait(0.5);
      it->OnPose(rover.Pose());
    }
  }
  out.status = it->status();
  return out;
}

TEST(ApproachTemplate, ParsesWithItsDefaultTarget) {
  Result<Sequence> s = ParseSequenceFile(kTemplate);
  ASSERT_TRUE(s.ok()) << s.status().ToString();
  EXPECT_EQ(s->targets.at("target"), (Vec3{6.0, 0.0, 0.0}));
  EXPECT_DOUBLE_EQ(s->constants.at("coarse_step").value, 30.0);
  ASSERT_EQ(s->on_abort.size(), 1u);
  EXPECT_EQ(s->on_abort[0].command.kind, CommandKind::kStop);
  int whiles = 0;
  for (const Statement& st : s->statements) {
    if (st.kind == Statement::Kind::kWhile) {
      ++whiles;
      EXPECT_EQ(st.condition.compare.quantity, Quantity::kDistanceTo);
      EXPECT_EQ(st.body[0].command.kind, CommandKind::kVisodomStraight);
    }
  }
  EXPECT_EQ(whiles, 2);
}

TEST(ApproachTemplate, EndsWithinTheArmsSweetSpotDespiteSlip) {
  const Vec3 target{6.0, 0.0, 0.0};
  for (std::uint32_t seed = 1; seed <= 10; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    FakeRover rover(seed, /*max_slip=*/0.4, /*visual_odometry=*/true);
    const Approach a = RunApproach(target, rover);
    EXPECT_EQ(a.status.state, SequenceState::kDone) << a.status.message;
    const double d = rover.TrueDistanceTo(target);
    EXPECT_GE(d, 1.0);
    EXPECT_LE(d, 1.1);
    EXPECT_LT(std::abs(rover.TrueBearingOf(target)), 1e-9);  // facing it
    ASSERT_FALSE(a.commands.empty());
    EXPECT_EQ(a.commands.back().kind, CommandKind::kVisodomTurnTo);
    // Then the instrument on the target, where the rover believes it is.
    ASSERT_EQ(a.arm.size(), 1u);
    EXPECT_EQ(a.arm[0].kind, CommandKind::kArmPlace);
    EXPECT_EQ(std::get<ArmRequest>(a.arm[0].request).point, target);
    // 4.7 m of 30 cm steps at 0-40 % slip, then a few 10 cm steps.
    int coarse = 0, fine = 0;
    for (const Command& c : a.commands) {
      const auto& m = std::get<MobilityRequest>(c.request);
      EXPECT_EQ(m.mode, msg::MobilityMode::kVisOdom);
      if (m.primitive == msg::DrivePrimitive::kStraight) (std::abs(m.distance - 0.3) < 1e-12 ? coarse : fine)++;
    }
    EXPECT_GE(coarse, 16);
    EXPECT_LE(coarse, 27);
    EXPECT_LE(fine, 4);
  }
}

TEST(ApproachTemplate, FacesAnOffAxisTarget) {
  const Vec3 target{4.0, 3.0, -0.2};
  FakeRover rover(7, 0.3, true);
  const Approach a = RunApproach(target, rover);
  EXPECT_EQ(a.status.state, SequenceState::kDone) << a.status.message;
  EXPECT_GE(rover.TrueDistanceTo(target), 1.0);
  EXPECT_LE(rover.TrueDistanceTo(target), 1.1);
  EXPECT_LT(std::abs(rover.TrueBearingOf(target)), 1e-9);
  EXPECT_NEAR(std::get<MobilityRequest>(a.commands.front().request).angle,
              std::atan2(3.0, 4.0), 1e-9);
}

TEST(ApproachTemplate, WithoutVisualOdometrySlipLeavesTheRoverShort) {
  // The same template on wheel odometry alone: the rover believes it moved the commanded
  // distance, so the conditional steps stop early by the accumulated slip.
  const Vec3 target{6.0, 0.0, 0.0};
  FakeRover rover(3, 0.4, /*visual_odometry=*/false);
  const Approach a = RunApproach(target, rover);
  EXPECT_EQ(a.status.state, SequenceState::kDone);
  EXPECT_GT(rover.TrueDistanceTo(target), 1.5);
}

TEST(ApproachTemplate, ATargetAlreadyCloseNeedsOnlyTheFinalTurn) {
  const Vec3 target{1.05, 0.0, 0.0};
  FakeRover rover(1, 0.0, true);
  const Approach a = RunApproach(target, rover);
  EXPECT_EQ(a.status.state, SequenceState::kDone);
  ASSERT_EQ(a.commands.size(), 2u);  // face it, then the final turn
  EXPECT_EQ(a.commands[0].kind, CommandKind::kVisodomTurnTo);
  EXPECT_EQ(a.commands[1].kind, CommandKind::kVisodomTurnTo);
}

}  // namespace
}  // namespace rover::apl::sequencer
