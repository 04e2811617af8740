#include "rover/dl/locomotion/drive_executor.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "rover/base/units.hpp"

namespace rover::dl::locomotion {
namespace {

constexpr auto kTick = std::chrono::milliseconds(25);  // 40 Hz plant and sensors
constexpr double kTickS = 0.025;

// A kinematic rover: steer motors slew to their goals, drive motors follow position or velocity
// goals, and the body moves as the wheels dictate (Ackermann arcs, or turns in place whose yaw
// is scaled by `yaw_slip` to mimic skid).
class Plant {
 public:
  explicit Plant(const RoverGeometry& g) : g_(g) {}

  double yaw_slip = 1.0;
  bool wheels_blocked = false;
  double roll = 0.0, pitch = 0.0, x = 0.0, y = 0.0, yaw = 0.0;
  std::array<double, 2> rocker{}, bogie{};
  std::array<double, 6> wheel{};
  std::array<double, 4> steer{};

  void Apply(const msg::MotorCommand& c) {
    if (c.mode == GroupMode::kStop) {
      drive_mode_ = GroupMode::kStop;
      steer_goal_ = steer;
      return;
    }
    if ((c.motor_mask & kSteerMotorMask) != 0) {
      for (std::size_t j = 0; j < 4; ++j) {
        steer_goal_[j] = c.goal[6 + j];
        steer_rate_[j] = c.max_rate[6 + j];
      }
    }
    if ((c.motor_mask & kDriveMotorMask) != 0) {
      drive_mode_ = c.mode;
      for (std::size_t i = 0; i < 6; ++i) {
        drive_goal_[i] = c.goal[i];
        drive_rate_[i] = c.max_rate[i];
      }
    }
  }

  void Advance(double dt) {
    for (std::size_t j = 0; j < 4; ++j) {
      const double step =
          std::clamp(steer_goal_[j] - steer[j], -steer_rate_[j] * dt, steer_rate_[j] * dt);
      steer[j] += step;
    }
    std::array<double, 6> d{};
    if (!wheels_blocked) {
      for (std::size_t i = 0; i < 6; ++i) {
        if (drive_mode_ == GroupMode::kPosition) {
          d[i] = std::clamp(drive_goal_[i] - wheel[i], -drive_rate_[i] * dt, drive_rate_[i] * dt);
        } else if (drive_mode_ == GroupMode::kVelocity) {
          d[i] = drive_goal_[i] * dt;
        }
        wheel[i] += d[i];
      }
    }
    const auto tip = TurnInPlaceSteerAngles(g_);
    bool in_place = true;
    for (std::size_t j = 0; j < 4; ++j) in_place = in_place && std::abs(steer[j] - tip[j]) < 0.1;
    if (in_place) {
      const auto q = TurnInPlaceRadii(g_);
      double dyaw = 0.0;
      for (std::size_t i = 0; i < 6; ++i) dyaw += d[i] * g_.wheel_radius / q[i] / 6.0;
      yaw += yaw_slip * dyaw;
    } else {
      // Curvature from the LF steer angle: tan(d) = k dx / (1 - k y).
      const double t = std::tan(steer[0]);
      const Eigen::Vector3d& p = g_.wheel_centre[0];
      const double k = t / (p.x() + p.y() * t);
      const auto ratio = ArcPathRatios(g_, k);
      double ds = 0.0;
      for (std::size_t i = 0; i < 6; ++i) ds += d[i] * g_.wheel_radius / ratio[i] / 6.0;
      x += ds * std::cos(yaw + 0.5 * k * ds);
      y += ds * std::sin(yaw + 0.5 * k * ds);
      yaw += k * ds;
    }
  }

  msg::JointState Joint(Time t) const {
    msg::JointState s;
    s.stamp = t;
    s.wheel_angle = wheel;
    s.steer_angle = steer;
    s.rocker_angle = rocker;
    s.bogie_angle = bogie;
    s.arm_angle = arm;
    return s;
  }
  std::array<double, 4> arm = hwconfig::RoverDescription{}.arm.stow;  // stowed unless a test moves it
  msg::AttitudeSample Attitude(Time t) const {
    msg::AttitudeSample a;
    a.stamp = t;
    a.roll = roll;
    a.pitch = pitch;
    a.yaw = std::remainder(yaw, 2 * std::numbers::pi);  // wrapped, as a pose estimate reports it
    return a;
  }

 private:
  RoverGeometry g_;
  GroupMode drive_mode_ = GroupMode::kStop;
  std::array<double, 6> drive_goal_{}, drive_rate_{};
  std::array<double, 4> steer_goal_{}, steer_rate_{};
};

class DriveExecutorTest : public ::testing::Test {
 protected:
  DriveExecutorTest() : plant_(RoverGeometry()) {}

  void SetUp() override { Build(DriveOptions()); }

  void Build(const DriveOptions& o) {
    Result<DriveExecutor> ex = DriveExecutor::Create(RoverGeometry(), o);
    ASSERT_TRUE(ex.ok()) << ex.status().ToString();
    ex_.emplace(std::move(ex).value());
    for (int n = 0; n < 4; ++n) Tick();  // fresh sensors
  }

  void Absorb(const DriveOutput& out) {
    for (const msg::MotorCommand& c : out.motor_commands) {
      plant_.Apply(c);
      commands_.push_back(c);
    }
    for (const DriveStatus& s : out.statuses) {
      // Invariants of every published status.
      if (s.state == DriveState::kDone) {
        EXPECT_EQ(s.termination, DriveTermination::kNominal);
      }
      if (s.state == DriveState::kFailed) {
        EXPECT_NE(s.termination, DriveTermination::kNominal);
        EXPECT_NE(s.termination, DriveTermination::kNone);
      }
      statuses_.push_back(s);
    }
  }

  void Tick() {
    now_ = now_ + kTick;
    plant_.Advance(kTickS);
    if (feed_joint_) {
      ASSERT_TRUE(ex_->OnJointState(plant_.Joint(now_)).ok());
    }
    if (feed_attitude_) ex_->OnAttitude(plant_.Attitude(now_));
    Absorb(ex_->Step(now_));
  }

  void Submit(DriveCommand c) {
    c.stamp = now_;
    c.command_id = ++next_id_;
    Absorb(ex_->Submit(c, now_));
  }

  // Runs until the executor is idle (or `limit_s` passes); returns the final status.
  DriveStatus RunUntilIdle(double limit_s = 200.0) {
    const Time end = now_ + Seconds(limit_s);
    while (ex_->busy() && now_ < end) Tick();
    EXPECT_FALSE(ex_->busy()) << "still running";
    return ex_->status();
  }
  void RunFor(double s) {
    const Time end = now_ + Seconds(s);
    while (now_ < end) Tick();
  }

  static DriveCommand Arc(double k, double s) {
    DriveCommand c;
    c.primitive = DrivePrimitive::kArc;
    c.curvature = k;
    c.distance = s;
    return c;
  }
  static DriveCommand Turn(double a) {
    DriveCommand c;
    c.primitive = DrivePrimitive::kTurnInPlace;
    c.angle = a;
    return c;
  }
  static DriveCommand Stop() { return DriveCommand(); }

  Plant plant_;
  std::optional<DriveExecutor> ex_;
  Time now_{0};
  std::uint32_t next_id_ = 100;
  bool feed_joint_ = true;
  bool feed_attitude_ = true;
  std::vector<msg::MotorCommand> commands_;
  std::vector<DriveStatus> statuses_;
};

TEST_F(DriveExecutorTest, ArcSteersFirstThenDrivesAndEndsNominally) {
  Submit(Arc(0.5, 1.0));
  ASSERT_FALSE(statuses_.empty());
  EXPECT_EQ(statuses_.back().state, DriveState::kSteering);
  const DriveStatus end = RunUntilIdle();
  EXPECT_EQ(end.state, DriveState::kDone);
  EXPECT_EQ(end.termination, DriveTermination::kNominal);
  EXPECT_EQ(end.command_id, next_id_);
  EXPECT_NEAR(end.distance_done, 1.0, 0.01);
  EXPECT_NEAR(end.heading_change, 0.5, 0.01);
  // Steer group, then drive group, then stop.
  ASSERT_EQ(commands_.size(), 3u);
  EXPECT_EQ(commands_[0].motor_mask, kSteerMotorMask);
  EXPECT_EQ(commands_[0].mode, GroupMode::kPosition);
  EXPECT_NEAR(commands_[0].goal[6], ArcSteerAngle(RoverGeometry(), 0, 0.5), 1e-12);
  EXPECT_EQ(commands_[1].motor_mask, kDriveMotorMask);
  EXPECT_EQ(commands_[1].mode, GroupMode::kPosition);
  EXPECT_NEAR(commands_[1].goal[4], ArcPathRatio(RoverGeometry(), 4, 0.5) / 0.125, 1e-9);
  EXPECT_GT(commands_[1].max_rate[4], commands_[1].max_rate[1]);  // outside wheel faster
  EXPECT_EQ(commands_[2].mode, GroupMode::kStop);
  EXPECT_EQ(commands_[2].motor_mask, kMobilityMotorMask);
  EXPECT_LT(commands_[0].command_id, commands_[1].command_id);
  // The plant drove the arc.
  EXPECT_NEAR(plant_.x, std::sin(0.5) / 0.5, 0.01);
  EXPECT_NEAR(plant_.y, (1 - std::cos(0.5)) / 0.5, 0.01);
  // Statuses while running.
  bool saw_driving = false;
  for (const auto& s : statuses_) saw_driving = saw_driving || s.state == DriveState::kDriving;
  EXPECT_TRUE(saw_driving);
}

TEST_F(DriveExecutorTest, StraightBackwards) {
  DriveCommand c;
  c.primitive = DrivePrimitive::kStraight;
  c.distance = -0.4;
  c.curvature = 0.7;  // ignored by STRAIGHT
  Submit(c);
  const DriveStatus end = RunUntilIdle();
  EXPECT_EQ(end.termination, DriveTermination::kNominal);
  EXPECT_NEAR(end.distance_done, -0.4, 0.01);
  EXPECT_NEAR(plant_.x, -0.4, 0.01);
  EXPECT_NEAR(plant_.y, 0.0, 1e-9);
}

TEST_F(DriveExecutorTest, TheRoverDoesNotDriveWithItsArmOut) {
  plant_.arm[1] -= 0.3;  // shoulder lowered from the stow
  for (int n = 0; n < 4; ++n) Tick();
  DriveCommand c;
  c.primitive = DrivePrimitive::kStraight;
  c.distance = 0.5;
  Submit(c);
  ASSERT_FALSE(statuses_.empty());
  EXPECT_EQ(statuses_.back().termination, DriveTermination::kRejectedInvalid);
  EXPECT_NE(statuses_.back().message.find("the arm is not stowed (shoulder -0.3 rad"), std::string::npos)
      << statuses_.back().message;
  EXPECT_FALSE(ex_->busy());
  EXPECT_NEAR(plant_.x, 0.0, 1e-12);
  // Stowed again (within the tolerance), it drives.
  plant_.arm[1] += 0.29;
  for (int n = 0; n < 4; ++n) Tick();
  Submit(c);
  EXPECT_EQ(RunUntilIdle().termination, DriveTermination::kNominal);
  EXPECT_NEAR(plant_.x, 0.5, 0.01);
  // An operator may switch the interlock off.
  DriveOptions o;
  o.require_arm_stowed = false;
  Build(o);
  plant_.arm[0] = 1.0;
  for (int n = 0; n < 4; ++n) Tick();
  c.distance = 0.2;
  Submit(c);
  EXPECT_EQ(RunUntilIdle().termination, DriveTermination::kNominal);
}

TEST_F(DriveExecutorTest, SteerOnlySteers) {
  DriveCommand c;
  c.primitive = DrivePrimitive::kSteer;
  c.curvature = -0.8;
  Submit(c);
  const DriveStatus end = RunUntilIdle();
  EXPECT_EQ(end.termination, DriveTermination::kNominal);
  for (std::size_t j = 0; j < 4; ++j) {
    EXPECT_NEAR(plant_.steer[j], ArcSteerAngle(RoverGeometry(), static_cast<int>(j), -0.8),
                DriveOptions().steer_tolerance);
  }
  for (const auto& m : commands_) {
    if (m.mode != GroupMode::kStop) {
      EXPECT_EQ(m.motor_mask & kDriveMotorMask, 0) << "drove";
    }
  }
  EXPECT_EQ(plant_.x, 0.0);
}

class TurnInPlaceTest : public DriveExecutorTest,
                        public ::testing::WithParamInterface<std::pair<double, double>> {};

TEST_P(TurnInPlaceTest, EndsAtTheCommandedHeadingWithinOneDegree) {
  const auto [angle_deg, slip] = GetParam();
  plant_.yaw_slip = slip;
  const double yaw0 = plant_.yaw;
  Submit(Turn(angle_deg * kDegree));
  const DriveStatus end = RunUntilIdle();
  EXPECT_EQ(end.state, DriveState::kDone);
  EXPECT_EQ(end.termination, DriveTermination::kNominal) << end.message;
  EXPECT_NEAR(plant_.yaw - yaw0, angle_deg * kDegree, 1.0 * kDegree);
  EXPECT_NEAR(end.heading_change, angle_deg * kDegree, 1.0 * kDegree);
  EXPECT_NEAR(plant_.x, 0.0, 1e-9);
  // Velocity goals on the drive motors, left side backwards for a left turn.
  bool saw_velocity = false;
  for (const auto& m : commands_) {
    if (m.mode == GroupMode::kVelocity) {
      saw_velocity = true;
      EXPECT_EQ(m.motor_mask, kDriveMotorMask);
    }
  }
  // A turn within the heading tolerance ends after steering without driving.
  EXPECT_EQ(saw_velocity, std::abs(angle_deg) > 1.0);
}

INSTANTIATE_TEST_SUITE_P(AnglesAndSlip, TurnInPlaceTest,
                         ::testing::Values(std::make_pair(90.0, 1.0), std::make_pair(90.0, 0.8),
                                           std::make_pair(-45.0, 0.6),
                                           std::make_pair(200.0, 0.9),  // through +-180
                                           std::make_pair(-270.0, 1.0), std::make_pair(0.5, 1.0)));

TEST_F(DriveExecutorTest, TiltOverTheLimitForNCyclesTerminates) {
  Submit(Arc(0.0, 1.0));
  RunFor(3.0);
  ASSERT_TRUE(ex_->busy());
  // A transient spike of two cycles is tolerated (tilt_cycles = 3).
  plant_.roll = 35 * kDegree;
  RunFor(2 * 0.125);
  plant_.roll = 0.0;
  RunFor(0.5);
  ASSERT_TRUE(ex_->busy());
  plant_.pitch = -32 * kDegree;
  const Time set = now_;
  const DriveStatus end = RunUntilIdle();
  EXPECT_EQ(end.state, DriveState::kFailed);
  EXPECT_EQ(end.termination, DriveTermination::kTilt);
  const double delay = ToSeconds(now_ - set);
  EXPECT_GE(delay, 2 * 0.125);
  EXPECT_LE(delay, 3 * 0.125 + 1e-9);
  EXPECT_EQ(commands_.back().mode, GroupMode::kStop);
  EXPECT_NE(end.message.find("tilt"), std::string::npos);
}

TEST_F(DriveExecutorTest, SuspensionOutOfRangeTerminates) {
  Submit(Arc(-0.3, 1.0));
  RunFor(4.0);
  plant_.bogie[1] = -40 * kDegree;
  const DriveStatus end = RunUntilIdle();
  EXPECT_EQ(end.termination, DriveTermination::kSuspension);
  EXPECT_NE(end.message.find("right bogie"), std::string::npos) << end.message;
  EXPECT_EQ(commands_.back().mode, GroupMode::kStop);
}

TEST_F(DriveExecutorTest, MotorGroupFaultsStopTheDrive) {
  struct Case {
    GroupState state;
    MotorFault fault;
    DriveTermination expected;
  };
  const Case cases[] = {
      {GroupState::kFault, MotorFault::kStall, DriveTermination::kMotorStall},
      {GroupState::kFault, MotorFault::kOverCurrent, DriveTermination::kMotorCurrent},
      {GroupState::kFault, MotorFault::kOverTemp, DriveTermination::kMotorFault},
      {GroupState::kFault, MotorFault::kNoTelemetry, DriveTermination::kMotorFault},
      {GroupState::kRejected, MotorFault::kBadCommand, DriveTermination::kMotorFault},
  };
  for (const Case& c : cases) {
    Submit(Arc(0.2, 1.0));
    RunFor(3.0);
    ASSERT_TRUE(ex_->busy());
    const std::uint32_t drive_group = commands_.back().command_id;
    ASSERT_EQ(commands_.back().motor_mask, kDriveMotorMask);
    msg::MotorStatus m;
    m.stamp = now_;
    m.command_id = drive_group;
    m.state = c.state;
    m.fault = c.fault;
    m.fault_motor = 2;
    m.message = "LR";
    ex_->OnMotorStatus(m);
    const std::size_t before = commands_.size();
    const DriveStatus end = RunUntilIdle(0.2);
    EXPECT_EQ(end.termination, c.expected) << MotorFaultName(c.fault);
    EXPECT_EQ(end.state, DriveState::kFailed);
    ASSERT_EQ(commands_.size(), before + 1);
    EXPECT_EQ(commands_.back().mode, GroupMode::kStop);
    EXPECT_NE(end.message.find("motor 2"), std::string::npos) << end.message;
  }
}

TEST_F(DriveExecutorTest, FaultOfAnEarlierGroupIsIgnored) {
  Submit(Arc(0.0, 0.3));
  RunUntilIdle();
  const std::uint32_t old_group = commands_.front().command_id;
  Submit(Arc(0.0, 0.3));
  msg::MotorStatus m;
  m.command_id = old_group;
  m.state = GroupState::kFault;
  m.fault = MotorFault::kStall;
  ex_->OnMotorStatus(m);
  EXPECT_EQ(RunUntilIdle().termination, DriveTermination::kNominal);
}

TEST_F(DriveExecutorTest, TimeoutOnTheRunClock) {
  plant_.wheels_blocked = true;
  DriveCommand c = Arc(0.0, 0.2);  // 4 s at 0.05 m/s -> 2 * 4 + 10 = 18 s derived
  const Time start = now_;
  Submit(c);
  DriveStatus end = RunUntilIdle();
  EXPECT_EQ(end.termination, DriveTermination::kTimeout);
  EXPECT_NEAR(ToSeconds(now_ - start), 18.0, 0.126);

  c.timeout_s = 3.0;
  const Time start2 = now_;
  Submit(c);
  end = RunUntilIdle();
  EXPECT_EQ(end.termination, DriveTermination::kTimeout);
  EXPECT_NEAR(ToSeconds(now_ - start2), 3.0, 0.126);
  EXPECT_EQ(commands_.back().mode, GroupMode::kStop);
}

TEST_F(DriveExecutorTest, StopCommandEndsTheRunningPrimitive) {
  Submit(Arc(0.1, 2.0));
  const std::uint32_t drive_id = next_id_;
  RunFor(5.0);
  const double x_at_stop = plant_.x;
  statuses_.clear();
  Submit(Stop());
  ASSERT_EQ(statuses_.size(), 2u);
  EXPECT_EQ(statuses_[0].command_id, drive_id);
  EXPECT_EQ(statuses_[0].state, DriveState::kFailed);
  EXPECT_EQ(statuses_[0].termination, DriveTermination::kStopCommand);
  EXPECT_GT(statuses_[0].distance_done, 0.05);
  EXPECT_EQ(statuses_[1].command_id, next_id_);
  EXPECT_EQ(statuses_[1].state, DriveState::kDone);
  EXPECT_EQ(commands_.back().mode, GroupMode::kStop);
  EXPECT_FALSE(ex_->busy());
  RunFor(1.0);
  EXPECT_NEAR(plant_.x, x_at_stop, 1e-12);  // stopped
  // STOP when idle just brakes.
  commands_.clear();
  Submit(Stop());
  ASSERT_EQ(commands_.size(), 1u);
  EXPECT_EQ(commands_[0].mode, GroupMode::kStop);
  EXPECT_EQ(ex_->status().state, DriveState::kDone);
}

TEST_F(DriveExecutorTest, NewPrimitiveWhileBusyIsRejectedAndTheRunningOneContinues) {
  Submit(Arc(0.0, 0.5));
  const std::uint32_t running = next_id_;
  RunFor(2.0);
  const std::size_t n_commands = commands_.size();
  statuses_.clear();
  Submit(Turn(1.0));
  ASSERT_EQ(statuses_.size(), 1u);
  EXPECT_EQ(statuses_[0].command_id, next_id_);
  EXPECT_EQ(statuses_[0].state, DriveState::kRejected);
  EXPECT_EQ(statuses_[0].termination, DriveTermination::kRejectedBusy);
  EXPECT_EQ(commands_.size(), n_commands);  // nothing sent
  EXPECT_TRUE(ex_->busy());
  const DriveStatus end = RunUntilIdle();
  EXPECT_EQ(end.command_id, running);
  EXPECT_EQ(end.termination, DriveTermination::kNominal);
}

TEST_F(DriveExecutorTest, InvalidCommandsAreRejectedWithATypedReason) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  struct Case {
    DriveCommand c;
    InvalidReason reason;
    const char* field;
  };
  DriveCommand unknown;
  unknown.primitive = static_cast<DrivePrimitive>(9);
  DriveCommand slow = Arc(0.1, 1.0);
  slow.speed = -0.01;
  DriveCommand fast = Arc(0.1, 1.0);
  fast.speed = 3.0;
  DriveCommand neg_timeout = Turn(0.3);
  neg_timeout.timeout_s = -1.0;
  DriveCommand steer_nan;
  steer_nan.primitive = DrivePrimitive::kSteer;
  steer_nan.curvature = nan;
  DriveCommand straight_inf;
  straight_inf.primitive = DrivePrimitive::kStraight;
  straight_inf.distance = std::numeric_limits<double>::infinity();
  const Case cases[] = {
      {Arc(nan, 1.0), InvalidReason::kNonFinite, "curvature"},
      {Arc(0.1, nan), InvalidReason::kNonFinite, "distance"},
      {straight_inf, InvalidReason::kNonFinite, "distance"},
      {steer_nan, InvalidReason::kNonFinite, "curvature"},
      {Arc(1.2, 1.0), InvalidReason::kCurvatureOutOfRange, "curvature"},
      {Arc(-1.0001, 1.0), InvalidReason::kCurvatureOutOfRange, "curvature"},
      {Arc(0.1, 1e6), InvalidReason::kDistanceOutOfRange, "distance"},
      {Arc(0.1, -51.0), InvalidReason::kDistanceOutOfRange, "distance"},
      {Turn(7.0), InvalidReason::kAngleOutOfRange, "angle"},
      {Turn(nan), InvalidReason::kNonFinite, "angle"},
      {slow, InvalidReason::kSpeedOutOfRange, "speed"},
      {fast, InvalidReason::kSpeedOutOfRange, "speed"},
      {neg_timeout, InvalidReason::kTimeoutOutOfRange, "timeout_s"},
      {unknown, InvalidReason::kUnknownPrimitive, "primitive"},
  };
  for (const Case& c : cases) {
    commands_.clear();
    statuses_.clear();
    Submit(c.c);
    ASSERT_EQ(statuses_.size(), 1u);
    const DriveStatus& s = statuses_[0];
    EXPECT_EQ(s.state, DriveState::kRejected);
    EXPECT_EQ(s.termination, DriveTermination::kRejectedInvalid);
    EXPECT_EQ(s.invalid_reason, c.reason) << s.message;
    EXPECT_NE(s.message.find(c.field), std::string::npos) << s.message;
    // Stays stopped: the only motor command is a brake.
    ASSERT_EQ(commands_.size(), 1u);
    EXPECT_EQ(commands_[0].mode, GroupMode::kStop);
    EXPECT_FALSE(ex_->busy());
    RunFor(0.5);
    EXPECT_EQ(plant_.x, 0.0);
    EXPECT_EQ(plant_.yaw, 0.0);
  }
  // While busy, an invalid command is rejected without stopping the running primitive.
  Submit(Arc(0.0, 0.3));
  RunFor(1.0);
  const std::size_t n = commands_.size();
  Submit(Arc(5.0, 1.0));
  EXPECT_EQ(statuses_.back().termination, DriveTermination::kRejectedInvalid);
  EXPECT_EQ(commands_.size(), n);
  EXPECT_EQ(RunUntilIdle().termination, DriveTermination::kNominal);
}

TEST_F(DriveExecutorTest, StaleSensorsRejectOrStop) {
  // Joint state stops while driving.
  Submit(Arc(0.0, 1.0));
  RunFor(3.0);
  feed_joint_ = false;
  const Time cut = now_;
  DriveStatus end = RunUntilIdle();
  EXPECT_EQ(end.termination, DriveTermination::kStaleSensor);
  EXPECT_NE(end.message.find("joint state"), std::string::npos);
  EXPECT_GT(ToSeconds(now_ - cut), 0.5);
  EXPECT_LE(ToSeconds(now_ - cut), 0.5 + 0.125 + 1e-9);
  EXPECT_EQ(commands_.back().mode, GroupMode::kStop);
  // Submitting with stale inputs is rejected.
  statuses_.clear();
  Submit(Arc(0.0, 1.0));
  ASSERT_EQ(statuses_.size(), 1u);
  EXPECT_EQ(statuses_[0].state, DriveState::kRejected);
  EXPECT_EQ(statuses_[0].termination, DriveTermination::kStaleSensor);
  EXPECT_EQ(commands_.back().mode, GroupMode::kStop);
  // Attitude stops.
  feed_joint_ = true;
  RunFor(0.1);
  Submit(Turn(1.0));
  RunFor(2.0);
  feed_attitude_ = false;
  end = RunUntilIdle();
  EXPECT_EQ(end.termination, DriveTermination::kStaleSensor);
  EXPECT_NE(end.message.find("attitude"), std::string::npos);
}

TEST_F(DriveExecutorTest, UnhealthyAndNonFiniteSamplesDoNotCountAsFresh) {
  Submit(Arc(0.0, 1.0));
  RunFor(2.0);
  feed_joint_ = false;
  const Time cut = now_;
  while (ex_->busy() && ToSeconds(now_ - cut) < 5.0) {
    msg::JointState bad = plant_.Joint(now_ + kTick);
    bad.wheel_angle[0] = std::numeric_limits<double>::quiet_NaN();
    EXPECT_TRUE(ex_->OnJointState(bad).ok());  // ignored, not refused
    msg::JointState sick = plant_.Joint(now_ + kTick);
    sick.health = msg::SensorHealth::kFailed;
    EXPECT_TRUE(ex_->OnJointState(sick).ok());
    Tick();
  }
  EXPECT_EQ(ex_->status().termination, DriveTermination::kStaleSensor);
}

TEST_F(DriveExecutorTest, RefusesAnEncoderJumpAndDrivesOnTheLastGoodSample) {
  Submit(Arc(0.0, 1.0));
  RunFor(2.0);
  msg::JointState flipped = plant_.Joint(now_ + kTick);
  flipped.wheel_angle[3] += 1e6;  // a flipped exponent bit
  const Status s = ex_->OnJointState(flipped);
  EXPECT_EQ(s.code(), StatusCode::kOutOfRange);
  EXPECT_NE(s.message().find("wheel 3 angle jumped"), std::string::npos) << s.message();
  // The good samples that follow are accepted and the drive ends normally.
  const DriveStatus end = RunUntilIdle();
  EXPECT_EQ(end.termination, DriveTermination::kNominal);
  EXPECT_NEAR(plant_.x, 1.0, 0.05);
}

TEST_F(DriveExecutorTest, ChecksRunAtEightHertzWhateverTheStepRate) {
  Submit(Arc(0.0, 1.0));
  RunFor(1.0);
  statuses_.clear();
  RunFor(4.0);  // Step() is called at 40 Hz
  EXPECT_EQ(statuses_.size(), 32u);
  // Called at exactly 8 Hz, every call is a cycle.
  statuses_.clear();
  for (int n = 0; n < 8; ++n) {
    now_ = now_ + std::chrono::milliseconds(125);
    ASSERT_TRUE(ex_->OnJointState(plant_.Joint(now_)).ok());
    ex_->OnAttitude(plant_.Attitude(now_));
    Absorb(ex_->Step(now_));
  }
  EXPECT_EQ(statuses_.size(), 8u);
}

TEST_F(DriveExecutorTest, ZeroDistanceArcEndsAfterSteering) {
  Submit(Arc(0.4, 0.0));
  const DriveStatus end = RunUntilIdle();
  EXPECT_EQ(end.termination, DriveTermination::kNominal);
  EXPECT_EQ(plant_.x, 0.0);
}

TEST(DriveOptions, ValidateAndParams) {
  DriveOptions o;
  EXPECT_TRUE(o.Validate().ok());
  o.rocker_min = 0.5;
  EXPECT_NE(o.Validate().message().find("rocker_min"), std::string::npos);
  o = DriveOptions();
  o.default_speed = 0.2;
  EXPECT_FALSE(o.Validate().ok());
  o = DriveOptions();
  o.tilt_cycles = 0;
  EXPECT_FALSE(o.Validate().ok());
  EXPECT_FALSE(DriveExecutor::Create(RoverGeometry(), o).ok());

  ParamSet p("locomotion");
  DeclareDriveParams(p);
  Result<DriveOptions> d = DriveOptionsFromParams(p);
  ASSERT_TRUE(d.ok()) << d.status().ToString();
  EXPECT_NEAR(d->max_tilt, DriveOptions().max_tilt, 1e-4);
  EXPECT_NEAR(d->heading_tolerance, DriveOptions().heading_tolerance, 1e-5);
  EXPECT_EQ(d->tilt_cycles, 3);

  ParamSet q("locomotion");
  DeclareDriveParams(q);
  ASSERT_TRUE(q.LoadYamlString("drive:\n  max_tilt_deg: 25\n  rocker_range_deg: [20, -20]\n",
                               "params/drive.yaml")
                  .ok());
  d = DriveOptionsFromParams(q);
  ASSERT_FALSE(d.ok());
  EXPECT_EQ(d.status().message().rfind("params/drive.yaml:3: key 'drive.rocker_range_deg'", 0), 0u)
      << d.status().message();
  ParamSet r("locomotion");
  DeclareDriveParams(r);
  ASSERT_TRUE(r.LoadYamlString("drive:\n  max_tilt_deg: 95\n", "d.yaml").ok());
  EXPECT_EQ(DriveOptionsFromParams(r).status().message(),
            "d.yaml:2: key 'drive.max_tilt_deg': 95 is out of range [1, 89]");
}

}  // namespace
}  // namespace rover::dl::locomotion
