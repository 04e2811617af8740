#include "rover/dl/arm/arm_executor.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace rover::dl::arm {
namespace {

using Eigen::Vector3d;
using hwconfig::RoverDescription;
using ::testing::HasSubstr;

Time ArmT(double s) { return Time::FromSeconds(s); }

constexpr double kArmTick = 0.02;  // [s] 50 Hz joint state, as ddl-joints

// A kinematic arm standing in for ddl-motor and ddl-joints: a position command moves the four
// joints along the straight joint-space line to its goal in max_travel / max_rate seconds (the
// synchronised move of ddl-motor, without the acceleration ramps), then reports the group
// DONE; a stop brakes. The contact switch closes when the face centre of Forward(q) is at or
// below `surface`. `jammed` stops the joints (a stall the test reports itself).
class KinematicArm {
 public:
  KinematicArm(const hwconfig::ArmDescription& arm, const ArmAngles& q) : arm_(arm), q_(q) {}

  void Apply(const msg::MotorCommand& m) {
    if ((m.motor_mask & kArmMotorMask) == 0) return;
    ++commands_;
    if (m.mode != msg::GroupMode::kPosition) {
      moving_ = false;
      return;
    }
    start_ = q_;
    double travel = 0.0;
    for (int j = 0; j < hwconfig::kArmJoints; ++j) {
      const auto k = static_cast<std::size_t>(j);
      goal_[k] = m.goal[static_cast<std::size_t>(hw::kArmAzimuth + j)];
      travel = std::max(travel, std::abs(goal_[k] - start_[k]));
    }
    const double rate = m.max_rate[hw::kArmAzimuth];
    duration_ = travel / rate;
    elapsed_ = 0.0;
    group_ = m.command_id;
    moving_ = true;
  }

  void Step(double dt) {
    if (!moving_ || jammed) return;
    elapsed_ += dt;
    const double s = duration_ > 0.0 ? std::min(1.0, elapsed_ / duration_) : 1.0;
    for (std::size_t k = 0; k < q_.size(); ++k) q_[k] = start_[k] + s * (goal_[k] - start_[k]);
    if (s >= 1.0) {
      moving_ = false;
      done_ = group_;
    }
  }

  msg::JointState Sample(Time t) const {
    msg::JointState j;
    j.stamp = t;
    j.arm_angle = q_;
    j.arm_contact = surface.has_value() && Face().z() <= *surface + standoff;
    j.wheel_rate[2] = wheel_rate;
    return j;
  }

  std::optional<std::uint32_t> TakeDone() {
    const auto d = done_;
    done_.reset();
    return d;
  }

  Vector3d Face() const { return arm_.Forward(q_).face; }
  const ArmAngles& q() const { return q_; }
  int commands() const { return commands_; }

  std::optional<double> surface;  ///< [m] height of a horizontal surface under the face
  double standoff = 0.0;          ///< [m] the switch closes this far above the surface
  double wheel_rate = 0.0;        ///< [rad/s] of wheel LR (the rover driving)
  bool jammed = false;

 private:
  hwconfig::ArmDescription arm_;
  ArmAngles q_{}, start_{}, goal_{};
  double duration_ = 0.0, elapsed_ = 0.0;
  bool moving_ = false;
  std::uint32_t group_ = 0;
  std::optional<std::uint32_t> done_;
  int commands_ = 0;
};

ArmCommand JointsCommand(std::uint32_t id, const ArmAngles& q) {
  ArmCommand c;
  c.command_id = id;
  c.mode = ArmMode::kJoints;
  c.joints = q;
  return c;
}

ArmCommand PlaceCommand(std::uint32_t id, const Vector3d& target) {
  ArmCommand c;
  c.command_id = id;
  c.mode = ArmMode::kPlace;
  c.target = target;
  return c;
}

ArmCommand ModeCommand(std::uint32_t id, ArmMode mode) {
  ArmCommand c;
  c.command_id = id;
  c.mode = mode;
  return c;
}

bool Contains(const std::string& text, const std::string& needle) {
  return text.find(needle) != std::string::npos;
}

class ArmExecutorTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto e = ArmExecutor::Create(rover_, ArmOptions{});
    ASSERT_TRUE(e.ok()) << e.status().message();
    exec_.emplace(std::move(*e));
    arm_.emplace(rover_.arm, rover_.arm.stow);
  }

  double now() const { return static_cast<double>(tick_) * kArmTick; }

  // Publishes what the executor said: motor commands go to the kinematic arm.
  void Take(const ArmOutput& out) {
    for (const msg::MotorCommand& m : out.motor_commands) {
      arm_->Apply(m);
      motor_commands_.push_back(m);
    }
    for (const msg::MiRequest& r : out.mi_requests) mi_requests_.push_back(r);
    statuses_.insert(statuses_.end(), out.statuses.begin(), out.statuses.end());
  }

  // Runs the loop for up to `seconds`: the arm moves, joints at 50 Hz, the arm's DONE, the
  // executor's step at check_rate_hz. Returns true as soon as `until` holds.
  bool Run(double seconds, const std::function<bool()>& until = nullptr) {
    const auto steps = static_cast<int>(std::lround(seconds / kArmTick));
    for (int i = 0; i < steps; ++i) {
      ++tick_;
      const Time t = ArmT(now());
      arm_->Step(kArmTick);
      if (publish_joints_) Take(exec_->OnJoints(arm_->Sample(t)));
      if (const auto done = arm_->TakeDone()) {
        msg::MotorStatus r;
        r.command_id = *done;
        r.state = msg::GroupState::kDone;
        Take(exec_->OnMotorStatus(r, t));
      }
      if (now() >= next_step_ - 1e-9) {
        next_step_ += 1.0 / exec_->options().check_rate_hz;
        Take(exec_->Step(t));
      }
      AnswerFrames(t);
      if (until && until()) return true;
    }
    return false;
  }

  bool Last(ArmState state) const { return !statuses_.empty() && statuses_.back().state == state; }

  ArmOutput Submit(const ArmCommand& c) {
    const ArmOutput out = exec_->Submit(c, ArmT(now()));
    Take(out);
    return out;
  }

  // Places the instrument on a surface at `target` (the test's standard placement).
  void PlaceOn(const Vector3d& target) {
    arm_->surface = target.z();
    Run(0.1);
    ASSERT_EQ(Submit(PlaceCommand(1, target)).statuses.at(0).state, ArmState::kMoving);
    ASSERT_TRUE(Run(120.0, [&] { return !exec_->moving(); }));
    ASSERT_EQ(exec_->status().state, ArmState::kPlaced) << exec_->status().message;
  }

  // The microscopic imager: a fixed texture blurred by the thin lens's disc for the face's
  // height above the surface (MicroscopeOptics::BlurDiameterPx, sigma = disc / 4), answered
  // 0.2 s after the request; `texture_contrast` 0 gives a featureless image.
  void AnswerFrames(Time t) {
    if (!answer_frames_) return;
    while (!mi_requests_.empty() && ToSeconds(t - mi_requests_.front().stamp) >= 0.2) {
      const msg::MiRequest r = mi_requests_.front();
      mi_requests_.erase(mi_requests_.begin());
      if (texture_.empty()) {
        cv::Mat noise(64, 64, CV_32FC1);
        cv::RNG rng(7);
        rng.fill(noise, cv::RNG::NORMAL, 0.0, 1.0);
        cv::resize(noise, texture_, cv::Size(256, 256), 0, 0, cv::INTER_CUBIC);
      }
      const double d = arm_->surface ? arm_->Face().z() - *arm_->surface : 1.0;
      const double sigma =
          std::min(24.0, rover_.arm.imager.BlurDiameterPx(std::max(d, 1e-3)) / 4.0);
      cv::Mat blurred = texture_.clone();
      if (sigma > 0.05) cv::GaussianBlur(texture_, blurred, cv::Size(0, 0), sigma);
      cv::Mat image;
      blurred.convertTo(image, CV_8U, 40.0 * texture_contrast, 120.0);
      frames_.push_back(image);
      msg::MiFrame f;
      f.stamp = t;
      f.request_id = r.request_id;
      f.width = image.cols;
      f.height = image.rows;
      f.image = {image.ptr<std::uint8_t>(), image.total()};
      Take(exec_->OnMiFrame(f, t));
    }
  }

  ArmCommand AutofocusCommand(std::uint32_t id, const Vector3d& target) {
    ArmCommand c;
    c.command_id = id;
    c.mode = ArmMode::kAutofocus;
    c.target = target;
    return c;
  }

  const RoverDescription rover_;
  std::vector<msg::MiRequest> mi_requests_;
  std::vector<cv::Mat> frames_;
  cv::Mat texture_;
  double texture_contrast = 1.0;
  bool answer_frames_ = true;
  std::optional<ArmExecutor> exec_;
  std::optional<KinematicArm> arm_;
  std::vector<msg::MotorCommand> motor_commands_;
  std::vector<ArmStatus> statuses_;
  std::int64_t tick_ = 0;
  double next_step_ = 0.0;
  bool publish_joints_ = true;
};

// A target on the ground in front of the rover, slightly to the left.
const Vector3d kTarget(1.0, 0.1, 0.05);

TEST_F(ArmExecutorTest, JointsCommandMovesTheFourArmMotorsAndArrives) {
  EXPECT_EQ(exec_->status().state, ArmState::kIdle);
  Run(0.1);
  EXPECT_TRUE(exec_->status().stowed);  // the arm starts stowed
  const Result<ArmAngles> goal = rover_.arm.FaceDown(Vector3d(1.0, 0.0, 0.2));
  ASSERT_TRUE(goal.ok()) << goal.status().message();
  const ArmOutput out = Submit(JointsCommand(5, *goal));
  ASSERT_EQ(out.motor_commands.size(), 1u);
  const msg::MotorCommand& m = out.motor_commands[0];
  EXPECT_EQ(m.mode, msg::GroupMode::kPosition);
  EXPECT_EQ(m.motor_mask, 0xF000);
  EXPECT_EQ(m.command_id, kMotorIdBase);
  EXPECT_DOUBLE_EQ(m.timeout_s, 0.0);
  for (int j = 0; j < hwconfig::kArmJoints; ++j) {
    const auto motor = static_cast<std::size_t>(12 + j);
    EXPECT_DOUBLE_EQ(m.goal[motor], (*goal)[static_cast<std::size_t>(j)]);
    EXPECT_DOUBLE_EQ(m.max_rate[motor], ArmOptions{}.speed);
  }
  EXPECT_DOUBLE_EQ(m.goal[hw::kMastPan], 0.0);  // nothing for other motors
  EXPECT_DOUBLE_EQ(m.max_rate[hw::kMastPan], 0.0);
  ASSERT_EQ(out.statuses.size(), 1u);
  EXPECT_EQ(out.statuses[0].state, ArmState::kMoving);
  EXPECT_EQ(out.statuses[0].command_id, 5u);
  EXPECT_EQ(out.statuses[0].joint_goals, *goal);
  EXPECT_TRUE(Contains(out.statuses[0].message, "moving to joints [")) << out.statuses[0].message;

  const double start = now();
  ASSERT_TRUE(Run(60.0, [&] { return Last(ArmState::kAtGoal); }));
  const ArmStatus& done = statuses_.back();
  EXPECT_EQ(done.command_id, 5u);
  for (std::size_t k = 0; k < 4; ++k) EXPECT_NEAR(done.joints[k], (*goal)[k], 1e-9);
  EXPECT_LT((done.tool_point - Vector3d(1.0, 0.0, 0.2)).norm(), 1e-9);
  EXPECT_FALSE(done.stowed);
  EXPECT_FALSE(done.contact);
  // The fastest joint ran at `speed`: the move took its travel / speed.
  double travel = 0.0;
  for (std::size_t k = 0; k < 4; ++k)
    travel = std::max(travel, std::abs((*goal)[k] - rover_.arm.stow[k]));
  EXPECT_NEAR(now() - start, travel / 0.25, 0.2);
  // Periodic MOVING statuses at 2 Hz in between.
  int periodic = 0;
  for (std::size_t i = 1; i + 1 < statuses_.size(); ++i) {
    periodic += statuses_[i].state == ArmState::kMoving;
  }
  EXPECT_NEAR(periodic, 2.0 * travel / 0.25, 2.0);
  const std::size_t statuses = statuses_.size();
  Run(1.0);
  EXPECT_EQ(statuses_.size(), statuses);  // quiet once there
}

TEST_F(ArmExecutorTest, PlaceHoversThenDescendsAndStopsOnContact) {
  arm_->surface = kTarget.z();
  Run(0.1);
  const ArmOutput first = Submit(PlaceCommand(3, kTarget));
  ASSERT_EQ(first.motor_commands.size(), 1u);
  const Result<ArmAngles> hover = rover_.arm.FaceDown(kTarget + Vector3d(0.0, 0.0, 0.06));
  const Result<ArmAngles> end = rover_.arm.FaceDown(kTarget - Vector3d(0.0, 0.0, 0.03));
  ASSERT_TRUE(hover.ok() && end.ok());
  EXPECT_DOUBLE_EQ(first.motor_commands[0].goal[hw::kArmShoulder], (*hover)[1]);
  EXPECT_DOUBLE_EQ(first.motor_commands[0].max_rate[hw::kArmShoulder], 0.25);
  EXPECT_TRUE(
      Contains(first.statuses.at(0).message, "moving 0.06 m above the target (1, 0.1, 0.05) m"))
      << first.statuses.at(0).message;

  // Stage 1 ends face down 6 cm above the target; the descent starts.
  ASSERT_TRUE(Run(60.0, [&] { return Contains(exec_->status().message, "descending"); }));
  const double descent_start = now();
  EXPECT_LT((arm_->Face() - (kTarget + Vector3d(0.0, 0.0, 0.06))).norm(), 1e-9);
  ASSERT_EQ(motor_commands_.size(), 2u);
  const msg::MotorCommand& descent = motor_commands_[1];
  EXPECT_EQ(descent.mode, msg::GroupMode::kPosition);
  EXPECT_EQ(exec_->status().joint_goals, *end);
  // The rate that moves the face 9 cm (hover + overdrive) in 9 s at 1 cm/s.
  double travel = 0.0;
  for (std::size_t k = 0; k < 4; ++k) travel = std::max(travel, std::abs((*end)[k] - (*hover)[k]));
  const double distance = (rover_.arm.Forward(*end).face - rover_.arm.Forward(*hover).face).norm();
  EXPECT_NEAR(distance, 0.09, 1e-9);
  for (int j = 0; j < 4; ++j) {
    EXPECT_NEAR(descent.max_rate[static_cast<std::size_t>(12 + j)], travel * 0.01 / 0.09, 1e-12);
    EXPECT_DOUBLE_EQ(descent.goal[static_cast<std::size_t>(12 + j)],
                     (*end)[static_cast<std::size_t>(j)]);
  }

  ASSERT_TRUE(Run(20.0, [&] { return !exec_->moving(); }));
  const ArmStatus& placed = exec_->status();
  ASSERT_EQ(placed.state, ArmState::kPlaced) << placed.message;
  EXPECT_EQ(placed.command_id, 3u);
  EXPECT_EQ(motor_commands_.back().mode, msg::GroupMode::kStop);
  EXPECT_EQ(motor_commands_.back().motor_mask, 0xF000);
  EXPECT_NEAR(arm_->Face().z(), kTarget.z(), 0.002);
  // The joint-space line bends the face's path: about 2.5 mm off the vertical at contact.
  EXPECT_LT((arm_->Face().head<2>() - kTarget.head<2>()).norm(), 0.004);
  EXPECT_TRUE(placed.contact);
  EXPECT_NEAR(placed.tool_point.z(), kTarget.z(), 0.002);
  EXPECT_TRUE(Contains(placed.message, "placed: face at (1.00")) << placed.message;
  EXPECT_TRUE(Contains(placed.message, "mm below the target")) << placed.message;
  // 6 cm at about 1 cm/s (the joint-space line bends the face's path a little).
  EXPECT_NEAR(now() - descent_start, 6.0, 0.6);
  // The arm stays put afterwards: no more commands, no more statuses.
  const std::size_t commands = motor_commands_.size(), statuses = statuses_.size();
  Run(2.0);
  EXPECT_EQ(motor_commands_.size(), commands);
  EXPECT_EQ(statuses_.size(), statuses);
}

TEST_F(ArmExecutorTest, PlaceWithoutASurfaceFaultsWithNoContact) {
  Run(0.1);
  Submit(PlaceCommand(4, kTarget));
  ASSERT_TRUE(Run(60.0, [&] { return !exec_->moving(); }));
  const ArmStatus& s = exec_->status();
  ASSERT_EQ(s.state, ArmState::kFault);
  EXPECT_TRUE(Contains(s.message, "no contact within 0.03 m below the target")) << s.message;
  EXPECT_NEAR(arm_->Face().z(), kTarget.z() - 0.03, 1e-9);
  EXPECT_FALSE(s.contact);
}

TEST_F(ArmExecutorTest, ContactOnTheWayAboveTheTargetFaults) {
  arm_->surface = kTarget.z() + 0.1;  // something 4 cm above the hover point
  Run(0.1);
  Submit(PlaceCommand(6, kTarget));
  ASSERT_TRUE(Run(60.0, [&] { return !exec_->moving(); }));
  const ArmStatus& s = exec_->status();
  ASSERT_EQ(s.state, ArmState::kFault);
  EXPECT_TRUE(Contains(s.message, "unexpected contact on the way above the target")) << s.message;
  EXPECT_EQ(motor_commands_.size(), 2u);  // the move above the target, then the stop
  EXPECT_EQ(motor_commands_.back().mode, msg::GroupMode::kStop);
  EXPECT_NEAR(arm_->Face().z(), kTarget.z() + 0.1, 0.01);

  // A switch that is closed before the descent would start (stuck, or the hover point touches
  // something) is no placement either.
  arm_->surface = 10.0;  // closed everywhere
  Run(0.1);
  const Result<ArmAngles> hover = rover_.arm.FaceDown(kTarget + Vector3d(0.0, 0.0, 0.06));
  ASSERT_TRUE(hover.ok());
  Submit(PlaceCommand(7, kTarget));
  ASSERT_TRUE(Run(60.0, [&] { return !exec_->moving(); }));
  EXPECT_EQ(exec_->status().state, ArmState::kFault);
  EXPECT_TRUE(Contains(exec_->status().message, "contact switch closed 0.06 m above the target"))
      << exec_->status().message;
}

TEST_F(ArmExecutorTest, StowFromAPlacementLiftsStraightUpFirst) {
  PlaceOn(kTarget);
  const Vector3d placed_face = arm_->Face();
  const std::size_t before = motor_commands_.size();
  const ArmOutput out = Submit(ModeCommand(8, ArmMode::kStow));
  ASSERT_EQ(out.motor_commands.size(), 1u);
  const Result<ArmAngles> lift = rover_.arm.FaceDown(placed_face + Vector3d(0.0, 0.0, 0.06));
  ASSERT_TRUE(lift.ok());
  for (int j = 0; j < 4; ++j) {
    EXPECT_NEAR(out.motor_commands[0].goal[static_cast<std::size_t>(12 + j)],
                (*lift)[static_cast<std::size_t>(j)], 1e-12);
  }
  EXPECT_EQ(out.statuses.at(0).message, "lifting the instrument 0.06 m before stowing");
  ASSERT_TRUE(Run(30.0, [&] { return exec_->status().message == "stowing"; }));
  EXPECT_LT((arm_->Face() - (placed_face + Vector3d(0.0, 0.0, 0.06))).norm(), 1e-9);
  EXPECT_FALSE(exec_->status().contact);
  ASSERT_EQ(motor_commands_.size(), before + 2);
  EXPECT_DOUBLE_EQ(motor_commands_.back().goal[hw::kArmWrist], rover_.arm.stow[3]);
  ASSERT_TRUE(Run(60.0, [&] { return !exec_->moving(); }));
  const ArmStatus& s = exec_->status();
  ASSERT_EQ(s.state, ArmState::kStowed) << s.message;
  EXPECT_EQ(s.command_id, 8u);
  EXPECT_TRUE(s.stowed);
  EXPECT_EQ(s.joint_goals, rover_.arm.stow);

  // Stowing from a pose that is not face down goes straight to stow.
  const Result<ArmAngles> up = rover_.arm.FaceDown(Vector3d(1.0, 0.0, 0.2));
  ASSERT_TRUE(up.ok());
  ArmAngles sideways = *up;
  sideways[3] += 1.0;  // the instrument looks forward and down, not straight down
  Submit(JointsCommand(9, sideways));
  ASSERT_TRUE(Run(60.0, [&] { return !exec_->moving(); }));
  ASSERT_EQ(exec_->status().state, ArmState::kAtGoal);
  EXPECT_EQ(Submit(ModeCommand(10, ArmMode::kStow)).statuses.at(0).message, "stowing");
  ASSERT_TRUE(Run(60.0, [&] { return !exec_->moving(); }));
  EXPECT_EQ(exec_->status().state, ArmState::kStowed);
}

TEST_F(ArmExecutorTest, RejectsBadCommandsNamingFieldAndValue) {
  const auto reject = [&](const ArmCommand& c, const std::string& needle) {
    const ArmOutput out = exec_->Submit(c, ArmT(now()));
    EXPECT_TRUE(out.motor_commands.empty()) << needle;
    ASSERT_EQ(out.statuses.size(), 1u);
    EXPECT_EQ(out.statuses[0].state, ArmState::kRejected);
    EXPECT_EQ(out.statuses[0].command_id, c.command_id);
    EXPECT_TRUE(Contains(out.statuses[0].message, needle)) << out.statuses[0].message;
    EXPECT_EQ(out.statuses[0].message.rfind("rejected: ", 0), 0u);
  };
  const ArmAngles stow = rover_.arm.stow;
  reject(JointsCommand(1, stow), "no ddl/joint_state received yet");
  tick_ = 50;  // 1 s
  exec_->OnJoints(arm_->Sample(ArmT(0.0)));
  reject(JointsCommand(2, stow),
         "ddl/joint_state is stale (latest 1 s old, joint_stale_s = 0.5 s)");
  exec_->OnJoints(arm_->Sample(ArmT(now())));

  reject(ModeCommand(3, static_cast<ArmMode>(7)),
         "mode = 7 is not an ArmMode value (0 JOINTS, 1 PLACE, 2 STOW, 3 STOP, 4 AUTOFOCUS)");
  ArmAngles bad = stow;
  bad[2] = std::nan("");
  reject(JointsCommand(4, bad), "joints[2] is nan");
  reject(PlaceCommand(5, Vector3d(INFINITY, 0.0, 0.0)), "target[0] is inf");
  ArmCommand c = ModeCommand(6, ArmMode::kStow);
  c.timeout_s = std::nan("");
  reject(c, "timeout_s is nan");
  c.timeout_s = -1.0;
  reject(c, "timeout_s = -1 s is outside [0, 600]");
  c.timeout_s = 601.0;
  reject(c, "timeout_s = 601 s is outside [0, 600]");
  bad = stow;
  bad[2] = 0.5;
  reject(JointsCommand(7, bad), "elbow angle = 0.5 rad is outside [-3.05, 0.3]");
  // Out of reach, on the azimuth axis, beyond a joint limit.
  reject(PlaceCommand(8, Vector3d(2.0, 0.0, 0.0)),
         "hover point 0.06 m above the target: arm target (2, 0, 0.06) [m] is out of reach");
  reject(PlaceCommand(9, Vector3d(0.62, 0.0, 0.1)), "lies on the arm's azimuth axis");
  reject(PlaceCommand(10, Vector3d(1.2, 0.2, 0.0)),
         "descent end 0.03 m below the target: arm target (1.2, 0.2, -0.03) [m] is out of reach");
  reject(PlaceCommand(11, Vector3d(0.55, 0.5, 0.3)),
         "needs azimuth angle = 1.70989 rad is outside");
  // Moves into the rover: the message names the part.
  const Vector3d wheel_top =
      rover_.WheelCentre(hwconfig::kWheelLF) + Vector3d(0.0, 0.0, rover_.wheel_radius + 0.02);
  const Result<ArmAngles> on_wheel = rover_.arm.FaceDown(wheel_top);
  ASSERT_TRUE(on_wheel.ok()) << on_wheel.status().message();
  reject(JointsCommand(12, *on_wheel), "from the rover's wheel_LF");
  reject(PlaceCommand(13, wheel_top), "from the rover's wheel_LF");
  reject(PlaceCommand(13, wheel_top), "(descent to 0.03 m below the target)");
  reject(JointsCommand(14, ArmAngles{0.0, -1.0, 0.0, 0.0}),
         "the arm's forearm would be 0.0439412 m above the ground plane");
  EXPECT_EQ(exec_->status().state, ArmState::kRejected);
  EXPECT_EQ(arm_->commands(), 0);
  EXPECT_TRUE(motor_commands_.empty());
}

TEST_F(ArmExecutorTest, ARejectedCommandLeavesTheRunningMoveAlone) {
  Run(0.1);
  const Result<ArmAngles> goal = rover_.arm.FaceDown(Vector3d(1.0, 0.0, 0.2));
  ASSERT_TRUE(goal.ok());
  Submit(JointsCommand(1, *goal));
  Run(1.0);
  const ArmOutput out = Submit(PlaceCommand(2, Vector3d(3.0, 0.0, 0.0)));
  ASSERT_EQ(out.statuses.size(), 1u);
  EXPECT_EQ(out.statuses[0].state, ArmState::kRejected);
  EXPECT_TRUE(out.motor_commands.empty());
  EXPECT_EQ(exec_->status().state, ArmState::kMoving);
  EXPECT_EQ(exec_->status().command_id, 1u);
  ASSERT_TRUE(Run(60.0, [&] { return !exec_->moving(); }));
  EXPECT_EQ(exec_->status().state, ArmState::kAtGoal);
  EXPECT_EQ(exec_->status().command_id, 1u);

  // A newer good command supersedes a running one.
  Submit(ModeCommand(3, ArmMode::kStow));
  Run(1.0);
  const ArmOutput newer = Submit(JointsCommand(4, *goal));
  EXPECT_TRUE(Contains(newer.statuses.at(0).message, "(supersedes command 3)"))
      << newer.statuses.at(0).message;
  ASSERT_TRUE(Run(60.0, [&] { return !exec_->moving(); }));
  EXPECT_EQ(exec_->status().state, ArmState::kAtGoal);
  EXPECT_EQ(exec_->status().command_id, 4u);
}

TEST_F(ArmExecutorTest, MotorDriverFaultNamesTheMotor) {
  Run(0.1);
  const std::uint32_t id = Submit(PlaceCommand(1, kTarget)).motor_commands.at(0).command_id;
  Run(0.5);
  msg::MotorStatus r;
  r.command_id = id + 100;  // not the arm's group: ignored
  r.state = msg::GroupState::kFault;
  EXPECT_TRUE(exec_->OnMotorStatus(r, ArmT(now())).statuses.empty());
  r.command_id = id;
  r.fault = msg::MotorFault::kStall;
  r.fault_motor = hw::kArmElbow;
  r.message = "no progress";
  const ArmOutput out = exec_->OnMotorStatus(r, ArmT(now()));
  ASSERT_EQ(out.statuses.size(), 1u);
  EXPECT_EQ(out.statuses[0].state, ArmState::kFault);
  EXPECT_EQ(out.statuses[0].message, "motor driver FAULT STALL on arm_elbow: no progress");
  EXPECT_TRUE(out.motor_commands.empty());  // the driver braked the group already
  EXPECT_TRUE(exec_->Stop("why", ArmT(now())).statuses.empty());  // not moving any more

  Submit(ModeCommand(2, ArmMode::kStow));
  r.command_id = motor_commands_.back().command_id;
  r.state = msg::GroupState::kRejected;
  r.fault = msg::MotorFault::kBadCommand;
  r.fault_motor = -1;
  r.message = "rate above the limit";
  EXPECT_EQ(exec_->OnMotorStatus(r, ArmT(now())).statuses.at(0).message,
            "motor driver REJECTED BAD_COMMAND: rate above the limit");
}

TEST_F(ArmExecutorTest, StaleJointsTimeoutAndStuckJointsFaultTheMove) {
  Run(0.1);
  const Result<ArmAngles> goal = rover_.arm.FaceDown(Vector3d(1.0, 0.0, 0.2));
  ASSERT_TRUE(goal.ok());
  Submit(JointsCommand(1, *goal));
  publish_joints_ = false;
  ASSERT_TRUE(Run(2.0, [&] { return !exec_->moving(); }));
  EXPECT_EQ(exec_->status().state, ArmState::kFault);
  EXPECT_TRUE(Contains(exec_->status().message, "ddl/joint_state went stale during the move"))
      << exec_->status().message;
  EXPECT_EQ(motor_commands_.back().mode, msg::GroupMode::kStop);
  EXPECT_EQ(motor_commands_.back().motor_mask, 0xF000);

  publish_joints_ = true;
  Run(0.1);
  arm_->jammed = true;
  ArmCommand c = JointsCommand(2, *goal);
  c.timeout_s = 2.0;
  Submit(c);
  ASSERT_TRUE(Run(5.0, [&] { return !exec_->moving(); }));
  EXPECT_EQ(exec_->status().state, ArmState::kFault);
  EXPECT_TRUE(Contains(exec_->status().message, "s (timeout_s = 2) in the move to the joint goal"))
      << exec_->status().message;
  EXPECT_EQ(motor_commands_.back().mode, msg::GroupMode::kStop);

  // DONE from the driver but the joints stay off the goal: FAULT after 1 s.
  Submit(JointsCommand(3, *goal));
  msg::MotorStatus r;
  r.command_id = motor_commands_.back().command_id;
  r.state = msg::GroupState::kDone;
  Take(exec_->OnMotorStatus(r, ArmT(now())));
  EXPECT_TRUE(exec_->moving());
  ASSERT_TRUE(Run(2.0, [&] { return !exec_->moving(); }));
  EXPECT_TRUE(Contains(exec_->status().message, "motors done but the ")) << exec_->status().message;
  EXPECT_TRUE(Contains(exec_->status().message, "rad from its goal (tolerance 0.01 rad)"));
}

TEST_F(ArmExecutorTest, StopCommandBrakesTheArm) {
  Run(0.1);
  Submit(PlaceCommand(1, kTarget));
  Run(1.0);
  const ArmOutput out = Submit(ModeCommand(9, ArmMode::kStop));
  ASSERT_EQ(out.motor_commands.size(), 1u);
  EXPECT_EQ(out.motor_commands[0].mode, msg::GroupMode::kStop);
  EXPECT_EQ(out.motor_commands[0].motor_mask, 0xF000);
  ASSERT_EQ(out.statuses.size(), 1u);
  EXPECT_EQ(out.statuses[0].state, ArmState::kFault);
  EXPECT_EQ(out.statuses[0].command_id, 9u);
  EXPECT_EQ(out.statuses[0].message, "stopped by command 9");
  const ArmAngles held = arm_->q();
  Run(1.0);
  EXPECT_EQ(arm_->q(), held);
  // A STOP is never refused: not even with stale joints and a bad timeout.
  publish_joints_ = false;
  Run(1.0);
  ArmCommand stop = ModeCommand(10, ArmMode::kStop);
  stop.timeout_s = -5.0;
  EXPECT_EQ(Submit(stop).statuses.at(0).message, "stopped by command 10");
  // Stop() (deactivation) only acts on a running command.
  EXPECT_TRUE(exec_->Stop("service deactivated", ArmT(now())).statuses.empty());
}

TEST_F(ArmExecutorTest, TheArmDoesNotMoveOutWhileTheRoverDrives) {
  arm_->wheel_rate = -0.8;
  Run(0.1);
  const ArmOutput refused = Submit(PlaceCommand(1, kTarget));
  ASSERT_EQ(refused.statuses.size(), 1u);
  EXPECT_EQ(refused.statuses[0].state, ArmState::kRejected);
  EXPECT_THAT(refused.statuses[0].message,
              HasSubstr("the rover is driving (wheel LR turning at 0.8 rad/s, max_wheel_rate "
                        "0.05 rad/s)"));
  EXPECT_TRUE(refused.motor_commands.empty());
  EXPECT_EQ(Submit(AutofocusCommand(2, kTarget)).statuses.at(0).state, ArmState::kRejected);
  EXPECT_EQ(Submit(JointsCommand(3, rover_.arm.stow)).statuses.at(0).state, ArmState::kRejected);
  // Creeping below the threshold is standing still: the placement starts ...
  arm_->wheel_rate = 0.04;
  Run(0.1);
  ASSERT_EQ(Submit(PlaceCommand(4, kTarget)).statuses.at(0).state, ArmState::kMoving);
  Run(1.0);
  // ... and faults, braking the arm, when the rover starts to drive.
  arm_->wheel_rate = 0.5;
  motor_commands_.clear();
  Run(0.1);
  EXPECT_EQ(exec_->status().state, ArmState::kFault);
  EXPECT_THAT(exec_->status().message, HasSubstr("the rover started driving during the move"));
  ASSERT_FALSE(motor_commands_.empty());
  EXPECT_EQ(motor_commands_.back().mode, msg::GroupMode::kStop);
  // A stow runs while it drives.
  ASSERT_EQ(Submit(ModeCommand(5, ArmMode::kStow)).statuses.at(0).state, ArmState::kMoving);
  ASSERT_TRUE(Run(60.0, [&] { return !exec_->moving(); }));
  EXPECT_EQ(exec_->status().state, ArmState::kStowed) << exec_->status().message;
}

TEST_F(ArmExecutorTest, IgnoresBadJointSamples) {
  exec_->OnJoints(arm_->Sample(ArmT(1.0)));
  msg::JointState j = arm_->Sample(ArmT(1.1));
  j.arm_angle[1] = std::nan("");
  exec_->OnJoints(j);
  j = arm_->Sample(ArmT(1.1));
  j.arm_angle = {0.1, 0.2, -0.3, 0.4};
  j.health = msg::SensorHealth::kStale;
  exec_->OnJoints(j);
  j.health = msg::SensorHealth::kFailed;
  exec_->OnJoints(j);
  j.health = msg::SensorHealth::kOk;
  j.stamp = ArmT(0.9);  // older
  exec_->OnJoints(j);
  EXPECT_EQ(exec_->status().joints, rover_.arm.stow);
  EXPECT_TRUE(exec_->status().stowed);
  EXPECT_FALSE(exec_->JointsFresh(ArmT(1.6)));
  EXPECT_TRUE(exec_->JointsFresh(ArmT(1.5)));
  EXPECT_STREQ(ArmStateName(ArmState::kPlaced), "PLACED");
  // A degraded sample is still a measurement.
  j.stamp = ArmT(1.2);
  j.health = msg::SensorHealth::kDegraded;
  exec_->OnJoints(j);
  EXPECT_DOUBLE_EQ(exec_->status().joints[0], 0.1);
  EXPECT_FALSE(exec_->status().stowed);
}

TEST(ArmExecutor, CreateRefusesInvalidOptionsAndDescriptions) {
  ArmOptions o;
  o.descent_speed = -1.0;
  auto e = ArmExecutor::Create(RoverDescription{}, o);
  ASSERT_FALSE(e.ok());
  EXPECT_EQ(e.status().message().rfind("descent_speed", 0), 0u) << e.status().message();
  RoverDescription rover;
  rover.arm.upper_arm = -0.1;
  e = ArmExecutor::Create(rover, ArmOptions{});
  ASSERT_FALSE(e.ok());
  EXPECT_EQ(e.status().message().rfind("arm.upper_arm", 0), 0u) << e.status().message();
}


// ---- auto-focus ----------------------------------------------------------------------------

TEST_F(ArmExecutorTest, AutofocusSweepsTenFramesAndSettlesAtBestFocus) {
  arm_->surface = kTarget.z();
  Run(0.1);
  const ArmOutput first = Submit(AutofocusCommand(7, kTarget));
  ASSERT_EQ(first.statuses.at(0).state, ArmState::kMoving) << first.statuses.at(0).message;
  EXPECT_TRUE(Contains(first.statuses.at(0).message, "10 frames from 90 mm above it"))
      << first.statuses.at(0).message;
  ASSERT_TRUE(Run(200.0, [&] { return !exec_->moving(); })) << exec_->status().message;
  const ArmStatus& s = exec_->status();
  ASSERT_EQ(s.state, ArmState::kFocused) << s.message;
  const double wd = rover_.arm.imager.working_distance;
  EXPECT_NEAR(s.focus_height, wd, 0.0025) << s.message;
  EXPECT_FALSE(s.focus_predicted);
  EXPECT_EQ(s.focus_images, 11);  // ten in the sweep and the final one
  EXPECT_EQ(s.focus_image_id, kMiRequestIdBase + 10);
  ASSERT_EQ(exec_->focus_samples().size(), 11u);
  // The sweep: 90 mm down to 30 mm above the target in 6.7 mm steps.
  EXPECT_NEAR(exec_->focus_samples().front().height, 0.09, 0.002);
  EXPECT_NEAR(exec_->focus_samples()[9].height, 0.03, 0.002);
  for (const FocusSample& f : exec_->focus_samples()) EXPECT_LE(f.measure, s.focus_measure * 1.001);
  EXPECT_NEAR(arm_->Face().z() - kTarget.z(), wd, 0.0025);
}

TEST_F(ArmExecutorTest, AutofocusPredictsBestFocusFromTheContactWhenTheSurfaceIsHigher) {
  // The surface is 4.5 cm above the designated point: the face touches it in the sweep.
  arm_->surface = kTarget.z() + 0.045;
  arm_->standoff = rover_.arm.contact_standoff;  // as the real switch: it closes 3 mm above
  Run(0.1);
  Submit(AutofocusCommand(8, kTarget));
  ASSERT_TRUE(Run(200.0, [&] { return !exec_->moving(); })) << exec_->status().message;
  const ArmStatus& s = exec_->status();
  ASSERT_EQ(s.state, ArmState::kFocused) << s.message;
  EXPECT_TRUE(s.focus_predicted);
  EXPECT_TRUE(Contains(s.message, "predicted from the contact")) << s.message;
  EXPECT_NEAR(arm_->Face().z() - *arm_->surface, rover_.arm.imager.working_distance, 0.0025);
  EXPECT_LT(s.focus_images, 10);
}

TEST_F(ArmExecutorTest, AutofocusStepsBeyondTheSweepWhenTheSurfaceIsLower) {
  // 4 cm below the designated point: the sharpest frame is the lowest of the sweep, so it
  // steps on until best focus is bracketed.
  arm_->surface = kTarget.z() - 0.04;
  Run(0.1);
  Submit(AutofocusCommand(9, kTarget));
  ASSERT_TRUE(Run(300.0, [&] { return !exec_->moving(); })) << exec_->status().message;
  const ArmStatus& s = exec_->status();
  ASSERT_EQ(s.state, ArmState::kFocused) << s.message;
  EXPECT_FALSE(s.focus_predicted);
  EXPECT_GT(s.focus_images, 11);
  EXPECT_NEAR(arm_->Face().z() - *arm_->surface, rover_.arm.imager.working_distance, 0.0025);
}

TEST_F(ArmExecutorTest, AutofocusWithoutTextureOrFramesFaults) {
  arm_->surface = kTarget.z();
  texture_contrast = 0.0;  // a featureless image: no focus signal
  Run(0.1);
  Submit(AutofocusCommand(10, kTarget));
  ASSERT_TRUE(Run(200.0, [&] { return !exec_->moving(); }));
  EXPECT_EQ(exec_->status().state, ArmState::kFault);
  EXPECT_TRUE(Contains(exec_->status().message, "no focus signal")) << exec_->status().message;

  texture_contrast = 1.0;
  answer_frames_ = false;  // the imager never answers
  Submit(AutofocusCommand(11, kTarget));
  ASSERT_TRUE(Run(200.0, [&] { return !exec_->moving(); }));
  EXPECT_EQ(exec_->status().state, ArmState::kFault);
  EXPECT_TRUE(Contains(exec_->status().message, "not received within 15 s"))
      << exec_->status().message;
}

TEST_F(ArmExecutorTest, AutofocusBadInputIsRejectedByName) {
  Run(0.1);
  ArmCommand c = AutofocusCommand(12, kTarget);
  c.focus_steps = 2;
  ArmOutput out = Submit(c);
  ASSERT_EQ(out.statuses.at(0).state, ArmState::kRejected);
  EXPECT_TRUE(Contains(out.statuses[0].message, "focus_steps")) << out.statuses[0].message;
  c = AutofocusCommand(13, Vector3d(1.0, 0.1, std::nan("")));
  out = Submit(c);
  ASSERT_EQ(out.statuses.at(0).state, ArmState::kRejected);
  EXPECT_TRUE(Contains(out.statuses[0].message, "target")) << out.statuses[0].message;
  c = AutofocusCommand(14, kTarget);
  c.focus_span = 0.5;
  out = Submit(c);
  EXPECT_TRUE(Contains(out.statuses.at(0).message, "focus_span")) << out.statuses[0].message;
  // Out of reach: 3 m ahead.
  out = Submit(AutofocusCommand(15, Vector3d(3.0, 0.0, 0.0)));
  ASSERT_EQ(out.statuses.at(0).state, ArmState::kRejected);
  EXPECT_TRUE(Contains(out.statuses[0].message, "focus frame 1 of 10")) << out.statuses[0].message;
  EXPECT_TRUE(out.motor_commands.empty());
}

}  // namespace
}  // namespace rover::dl::arm
