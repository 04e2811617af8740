// dl-locomotion in-process on an isolated DDS domain, driven by a sim clock and a fake rover
// (test/locomotion_rig.hpp): arc = steer then drive then DONE; rejections (NaN -> INVALID,
// busy -> BUSY, stale inputs -> STALE_SENSOR) as typed statuses with the rover braked; turn in
// place closed on the dl/pose heading; 8 Hz status while running.
#include "locomotion_service.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "rover/dl/locomotion/ackermann.hpp"
#include "rover/msg/drive_idl.hpp"
#include "test/locomotion_rig.hpp"

namespace rover::dl::locomotion {
namespace {

using testing_support::LocomotionRig;

bool IsStop(const rover_ddl_MotorCommand& c) {
  return c.mode == rover_ddl_GROUP_STOP && c.motor_mask == kMobilityMotorMask;
}

class LocomotionServiceTest : public ::testing::Test {
 protected:
  void SetUp() override { h_.Start(); }
  void TearDown() override { h_.Stop(); }
  LocomotionRig h_;
};

TEST_F(LocomotionServiceTest, ArcSteersThenDrivesAndReportsDoneWhenTheWheelsHaveTurned) {
  h_.Advance(1.0);  // inputs fresh
  ASSERT_TRUE(h_.motor_commands().empty());
  const double k = 0.5, s = 0.3;
  h_.Send(LocomotionRig::Command(11, rover_dl_PRIMITIVE_ARC, k, s, 0.0, 0.05));
  const Time accepted = h_.now();
  ASSERT_TRUE(h_.Advance(60.0, [&] { return h_.Terminal(11); })) << "no terminal status";

  // Motor commands: steer group to the Ackermann angles, then drive group, then brake.
  const RoverGeometry g;
  const auto& mc = h_.motor_commands();
  ASSERT_EQ(mc.size(), 3u);
  EXPECT_EQ(mc[0].motor_mask, kSteerMotorMask);
  EXPECT_EQ(mc[0].mode, rover_ddl_GROUP_POSITION);
  const auto steer = ArcSteerAngles(g, k);
  for (int j = 0; j < kNumSteered; ++j) {
    EXPECT_NEAR(mc[0].goal[SteerMotor(j)], steer[static_cast<std::size_t>(j)], 1e-12) << j;
  }
  EXPECT_GT(steer[0], 0.0);  // left turn: front wheels point left
  EXPECT_EQ(mc[1].motor_mask, kDriveMotorMask);
  EXPECT_EQ(mc[1].mode, rover_ddl_GROUP_POSITION);
  const auto ratio = ArcPathRatios(g, k);
  for (int i = 0; i < kNumWheels; ++i) {
    const auto w = static_cast<std::size_t>(i);
    EXPECT_NEAR(mc[1].goal[w], ratio[w] * s / g.wheel_radius, 1e-9) << i;  // wheels started at 0
  }
  EXPECT_GT(mc[1].goal[3], mc[1].goal[0]);  // outer (right) front wheel turns further
  EXPECT_TRUE(IsStop(mc[2]));

  // Statuses: STEERING ... DRIVING ... DONE / NOMINAL with the distance from the wheels.
  const auto st = h_.StatusesOf(11);
  ASSERT_GE(st.size(), 3u);
  EXPECT_EQ(st.front().state, rover_dl_DRIVE_STEERING);
  EXPECT_EQ(st.front().primitive, rover_dl_PRIMITIVE_ARC);
  bool saw_driving = false;
  for (const auto& x : st) saw_driving = saw_driving || x.state == rover_dl_DRIVE_DRIVING;
  EXPECT_TRUE(saw_driving);
  const auto& done = st.back();
  EXPECT_EQ(done.state, rover_dl_DRIVE_DONE) << done.message;
  EXPECT_EQ(done.termination, rover_dl_TERMINATION_NOMINAL);
  EXPECT_NEAR(done.distance_done, s, 0.02);
  for (int i = 0; i < kNumWheels; ++i) {
    EXPECT_NEAR(h_.rover().wheels()[static_cast<std::size_t>(i)],
                mc[1].goal[static_cast<std::size_t>(i)], 0.05);
  }
  // 8 Hz while running (run clock): one status per check cycle.
  const double run_s = ToSeconds(Time{done.header.stamp_ns} - accepted);
  EXPECT_GE(static_cast<double>(st.size()), 0.9 * 8.0 * run_s);
  EXPECT_LE(static_cast<double>(st.size()), 8.0 * run_s + 3.0);
  for (std::size_t i = 1; i < st.size(); ++i) {
    EXPECT_GE(st[i].header.stamp_ns, st[i - 1].header.stamp_ns);
  }
}

TEST_F(LocomotionServiceTest, NanCommandIsRejectedInvalidAndTheRoverStaysBraked) {
  h_.Advance(1.0);
  h_.Send(LocomotionRig::Command(21, rover_dl_PRIMITIVE_ARC,
                                 std::numeric_limits<double>::quiet_NaN(), 1.0));
  const auto st = h_.StatusesOf(21);
  ASSERT_EQ(st.size(), 1u);
  EXPECT_EQ(st[0].state, rover_dl_DRIVE_REJECTED);
  EXPECT_EQ(st[0].termination, rover_dl_TERMINATION_REJECTED_INVALID);
  EXPECT_NE(std::string(st[0].message).find("curvature"), std::string::npos) << st[0].message;
  h_.Advance(1.0);
  ASSERT_EQ(h_.motor_commands().size(), 1u);
  EXPECT_TRUE(IsStop(h_.motor_commands()[0]));
  for (double w : h_.rover().wheels()) EXPECT_EQ(w, 0.0);
  // Out-of-range values are INVALID too, naming the field.
  h_.Send(LocomotionRig::Command(22, rover_dl_PRIMITIVE_ARC, 3.0, 1.0));
  EXPECT_EQ(h_.StatusesOf(22).at(0).termination, rover_dl_TERMINATION_REJECTED_INVALID);
  EXPECT_NE(std::string(h_.StatusesOf(22)[0].message).find("curvature 3"), std::string::npos);
  // The service is still up and drives the next good command.
  h_.Send(LocomotionRig::Command(23, rover_dl_PRIMITIVE_STRAIGHT, 0.0, 0.1));
  ASSERT_TRUE(h_.Advance(60.0, [&] { return h_.Terminal(23); }));
  EXPECT_EQ(h_.StatusesOf(23).back().state, rover_dl_DRIVE_DONE);
}

TEST_F(LocomotionServiceTest, UnknownPrimitiveIsRejectedInvalid) {
  h_.Advance(0.5);
  // A value outside the IDL enum: Cyclone refuses to serialise it (write fails with "Bad
  // Parameter"), but another vendor's writer might send it; if it arrives, the service must
  // reject it INVALID. Either way nothing moves and the service keeps running.
  rover_dl_DriveCommand c = LocomotionRig::Command(31, rover_dl_PRIMITIVE_STEER, 0.2);
  c.primitive = static_cast<rover_dl_DrivePrimitive>(42);
  if (h_.command_writer().Write(c).ok()) {
    h_.Advance(0.5);
    const auto st = h_.StatusesOf(31);
    if (!st.empty()) {
      EXPECT_EQ(st[0].state, rover_dl_DRIVE_REJECTED);
      EXPECT_EQ(st[0].termination, rover_dl_TERMINATION_REJECTED_INVALID);
      EXPECT_NE(std::string(st[0].message).find("unknown primitive 42"), std::string::npos);
    }
  }
  // The conversion path the service uses, without DDS in between.
  const DriveCommand d = msg::DriveCommandFromIdl(c);
  EXPECT_FALSE(IsKnownPrimitive(d.primitive));
  const DriveExecutor* ex = h_.service().drive_executor();
  ASSERT_NE(ex, nullptr);
  std::string why;
  EXPECT_EQ(ex->CheckCommand(d, &why), InvalidReason::kUnknownPrimitive);
  DriveStatus s;
  s.command_id = 31;
  s.primitive = d.primitive;
  s.state = DriveState::kRejected;
  s.termination = DriveTermination::kRejectedInvalid;
  rover_dl_DriveStatus wire{};
  msg::DriveStatusToIdl(s, &wire);
  EXPECT_EQ(wire.primitive, rover_dl_PRIMITIVE_STOP);  // wire-safe
  for (double w : h_.rover().steers()) EXPECT_EQ(w, 0.0);
  // Still serving.
  h_.Send(LocomotionRig::Command(32, rover_dl_PRIMITIVE_STOP));
  EXPECT_EQ(h_.StatusesOf(32).back().state, rover_dl_DRIVE_DONE);
}

TEST_F(LocomotionServiceTest, SecondCommandWhileBusyIsRejectedBusyAndTheFirstGoesOn) {
  h_.Advance(1.0);
  h_.Send(LocomotionRig::Command(41, rover_dl_PRIMITIVE_STRAIGHT, 0.0, 1.0));
  h_.Advance(1.0);
  const std::size_t commands_before = h_.motor_commands().size();
  h_.Send(LocomotionRig::Command(42, rover_dl_PRIMITIVE_ARC, 0.5, 1.0));
  const auto busy = h_.StatusesOf(42);
  ASSERT_EQ(busy.size(), 1u);
  EXPECT_EQ(busy[0].state, rover_dl_DRIVE_REJECTED);
  EXPECT_EQ(busy[0].termination, rover_dl_TERMINATION_REJECTED_BUSY);
  EXPECT_NE(std::string(busy[0].message).find("busy with command 41"), std::string::npos);
  h_.Advance(1.0);
  // No brake for a BUSY rejection: the running primitive goes on.
  for (std::size_t i = commands_before; i < h_.motor_commands().size(); ++i) {
    EXPECT_FALSE(IsStop(h_.motor_commands()[i]));
  }
  EXPECT_FALSE(h_.Terminal(41));
  // STOP ends it: command 41 FAILED / STOP_COMMAND, then the STOP itself DONE. Both statuses are
  // written at once and dl/drive_status keeps only the latest sample (latched, keep-last 1), so
  // a reader that takes after both sees the STOP's; when 41's arrives it must be the failure.
  h_.Send(LocomotionRig::Command(43, rover_dl_PRIMITIVE_STOP));
  const auto last41 = h_.StatusesOf(41).back();
  if (last41.state != rover_dl_DRIVE_DRIVING) {
    EXPECT_EQ(last41.state, rover_dl_DRIVE_FAILED);
    EXPECT_EQ(last41.termination, rover_dl_TERMINATION_STOP_COMMAND);
  }
  EXPECT_EQ(h_.StatusesOf(43).back().state, rover_dl_DRIVE_DONE);
  EXPECT_FALSE(h_.service().drive_executor()->busy());
  EXPECT_TRUE(IsStop(h_.motor_commands().back()));
  const std::size_t after_stop = h_.statuses().size();
  h_.Advance(1.0);
  EXPECT_EQ(h_.statuses().size(), after_stop);  // idle: no more periodic statuses
}

TEST_F(LocomotionServiceTest, StaleInputsRejectTheCommandAndStopARunningOne) {
  h_.set_publish_joints(false);
  h_.Advance(1.0);
  h_.Send(LocomotionRig::Command(51, rover_dl_PRIMITIVE_STRAIGHT, 0.0, 0.5));
  EXPECT_EQ(h_.StatusesOf(51).at(0).termination, rover_dl_TERMINATION_STALE_SENSOR);
  EXPECT_NE(std::string(h_.StatusesOf(51)[0].message).find("joint state"), std::string::npos);
  // Joint states come back; a drive starts; then dl/pose stops: the drive fails STALE_SENSOR.
  h_.set_publish_joints(true);
  h_.Advance(0.5);
  h_.Send(LocomotionRig::Command(52, rover_dl_PRIMITIVE_STRAIGHT, 0.0, 2.0));
  h_.Advance(2.0);
  h_.set_publish_pose(false);
  ASSERT_TRUE(h_.Advance(5.0, [&] { return h_.Terminal(52); }));
  EXPECT_EQ(h_.StatusesOf(52).back().state, rover_dl_DRIVE_FAILED);
  EXPECT_EQ(h_.StatusesOf(52).back().termination, rover_dl_TERMINATION_STALE_SENSOR);
  EXPECT_TRUE(IsStop(h_.motor_commands().back()));
}

TEST_F(LocomotionServiceTest, TurnInPlaceClosesTheLoopOnTheDlPoseHeading) {
  h_.Advance(1.0);
  const double angle = 30.0 * std::numbers::pi / 180.0;
  h_.Send(LocomotionRig::Command(61, rover_dl_PRIMITIVE_TURN_IN_PLACE, 0.0, 0.0, angle));
  ASSERT_TRUE(h_.Advance(120.0, [&] { return h_.Terminal(61); }));
  const auto done = h_.StatusesOf(61).back();
  EXPECT_EQ(done.state, rover_dl_DRIVE_DONE) << done.message;
  // The heading the fake pose reported reached the goal within the executor's 1 deg tolerance.
  EXPECT_NEAR(done.heading_change, angle, 1.0 * std::numbers::pi / 180.0);
  EXPECT_NEAR(h_.rover().yaw(), angle, 2.0 * std::numbers::pi / 180.0);
  // Velocity goals on the drive motors: left wheels backwards, right forwards for a left turn.
  bool saw_velocity = false;
  for (const auto& c : h_.motor_commands()) {
    if (c.mode != rover_ddl_GROUP_VELOCITY) continue;
    saw_velocity = true;
    EXPECT_EQ(c.motor_mask, kDriveMotorMask);
    EXPECT_LT(c.goal[0], 0.0);
    EXPECT_GT(c.goal[3], 0.0);
  }
  EXPECT_TRUE(saw_velocity);
}

// The conversions (AttitudeSampleFromIdl, JointStateFromIdl) are tested in
// core/msg/test/pose_idl_test.cpp and sensors_idl_test.cpp.

}  // namespace
}  // namespace rover::dl::locomotion
