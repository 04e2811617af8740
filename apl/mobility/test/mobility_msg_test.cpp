// Round trips of the IDL conversions (src/mobility_msg.cpp), no DDS traffic.
#include "mobility_msg.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "rover/runtime/dds.hpp"

namespace rover::apl::mobility::msg {
namespace {

TEST(MobilityMsg, CommandRoundTrip) {
  MobilityCommand c;
  c.command_id = 42;
  c.mode = Mode::kGuardedArc;
  c.goal = {1.5, -2.5, 0.25};
  c.tolerance = 0.3;
  c.time_budget_s = 600;
  c.primitives = {{PrimitiveKind::kTurnInPlace, 0.0, 0.0, 1.0},
                  {PrimitiveKind::kArc, 0.5, 2.0, 0.0}};
  c.keep_out = {{"crater", {{0, 0}, {1, 0}, {1, 1}}}, {"dune", {{5, 5}, {6, 5}, {6, 6}, {5, 6}}}};
  c.think = ThinkMode::kStopAndGo;
  c.max_tilt = 0.3;
  c.min_northerly_tilt = 0.05;
  c.lmst_end_h = 15.5;
  c.max_steps = 77;
  const CommandMessage m = CommandToIdl(c, 123);
  const CommandMessage copy = m;  // re-pointed at its own storage
  const MobilityCommand b = CommandFromIdl(copy.msg);
  EXPECT_EQ(b.command_id, 42u);
  EXPECT_EQ(b.mode, Mode::kGuardedArc);
  EXPECT_EQ(b.goal, c.goal);
  EXPECT_EQ(b.tolerance, 0.3);
  EXPECT_EQ(b.time_budget_s, 600);
  ASSERT_EQ(b.primitives.size(), 2u);
  EXPECT_EQ(b.primitives[1].kind, PrimitiveKind::kArc);
  EXPECT_EQ(b.primitives[1].curvature, 0.5);
  EXPECT_EQ(b.primitives[0].angle, 1.0);
  ASSERT_EQ(b.keep_out.size(), 2u);
  EXPECT_EQ(b.keep_out[1].name, "dune");
  EXPECT_EQ(b.keep_out[1].vertices, c.keep_out[1].vertices);
  EXPECT_EQ(b.think, ThinkMode::kStopAndGo);
  EXPECT_EQ(b.max_tilt, 0.3);
  EXPECT_EQ(b.min_northerly_tilt, 0.05);
  EXPECT_EQ(b.lmst_end_h, 15.5);
  EXPECT_EQ(b.max_steps, 77);
}

TEST(MobilityMsg, UnknownEnumValuesSurviveForTheManagerToReject) {
  rover_apl_MobilityCommand m{};
  m.mode = static_cast<rover_apl_MobilityMode>(42);
  EXPECT_EQ(static_cast<int>(CommandFromIdl(m).mode), 42);
}

TEST(MobilityMsg, StatusRoundTrip) {
  MobilityStatus s;
  s.stamp = Time{5};
  s.command_id = 3;
  s.mode = Mode::kAutoNav;
  s.state = State::kFailed;
  s.fault_class = FaultClass::kMotionError;
  s.fault = Fault::kImg;
  s.message = "no range image";
  s.distance_to_goal = 2.5;
  s.distance_driven = 7.0;
  s.steps = 9;
  s.images = 4;
  s.motion_error_latched = true;
  const MobilityStatus b = StatusFromIdl(StatusToIdl(s));
  EXPECT_EQ(b.stamp.ns, 5);
  EXPECT_EQ(b.state, State::kFailed);
  EXPECT_EQ(b.fault, Fault::kImg);
  EXPECT_EQ(b.fault_class, FaultClass::kMotionError);
  EXPECT_EQ(b.message, "no range image");
  EXPECT_EQ(b.distance_to_goal, 2.5);
  EXPECT_EQ(b.distance_driven, 7.0);
  EXPECT_EQ(b.steps, 9u);
  EXPECT_EQ(b.images, 4u);
  EXPECT_TRUE(b.motion_error_latched);
  // A message longer than the IDL's 127 characters is truncated, not overrun.
  s.message.assign(300, 'x');
  EXPECT_EQ(StatusFromIdl(StatusToIdl(s)).message.size(), 127u);
}

TEST(MobilityMsg, GoodnessMapRoundTripAndSizeCheck) {
  nav_core::GoodnessMap g;
  g.origin_x = -5;
  g.origin_y = 2;
  g.resolution = 0.2;
  g.width = 3;
  g.height = 2;
  g.goodness = {0, 10, 20, 30, 40, 255};
  g.certainty = {255, 255, 0, 0, 128, 1};
  g.flags = {1, 1, 0, 0, 3, 5};
  g.unknown_goodness = 11;
  g.stamp = Time{77};
  const GoodnessMapMessage m = GoodnessMapToIdl(g);
  auto b = GoodnessMapFromIdl(GoodnessMapMessage(m).msg);
  ASSERT_TRUE(b.ok()) << b.status().message();
  EXPECT_EQ(b->goodness, g.goodness);
  EXPECT_EQ(b->certainty, g.certainty);
  EXPECT_EQ(b->flags, g.flags);
  EXPECT_EQ(b->width, 3);
  EXPECT_EQ(b->origin_x, -5);
  EXPECT_EQ(b->unknown_goodness, 11);
  EXPECT_EQ(b->stamp.ns, 77);
  GoodnessMapMessage bad = m;
  bad.msg.width = 4;
  b = GoodnessMapFromIdl(bad.msg);
  ASSERT_FALSE(b.ok());
  EXPECT_NE(b.status().message().find("GoodnessMap.goodness: 6 cells for 8"), std::string::npos);
}

TEST(MobilityMsg, ArcVotes) {
  ArcVotesSnapshot s;
  s.command_id = 4;
  s.step = 2;
  s.evaluation.candidates = {{nav_core::MotionKind::kArc, 0.5, -1, 2.0, 0.0},
                             {nav_core::MotionKind::kPointTurn, 0.0, 1, 0.0, 1.5}};
  s.evaluation.hazard = {{200, 255}, {100, 255}};
  s.evaluation.waypoint = {{10, 192}, {300, 192}};
  s.evaluation.merged = {{10, 255}, {150, 255}};
  s.evaluation.chosen = 1;
  const ArcVotesMessage m = ArcVotesToIdl(s);
  ASSERT_EQ(m.msg.votes._length, 2u);
  EXPECT_EQ(m.msg.votes._buffer[0].kind, rover_apl_CANDIDATE_ARC);
  EXPECT_EQ(m.msg.votes._buffer[0].direction, -1);
  EXPECT_EQ(m.msg.votes._buffer[1].turn_angle, 1.5);
  EXPECT_EQ(m.msg.votes._buffer[1].waypoint, 255);  // clamped to a byte
  EXPECT_EQ(m.msg.chosen, 1);
  EXPECT_EQ(m.msg.step, 2u);
}

TEST(MobilityMsg, RangeImageToScan) {
  rover_dl_RangeImage m{};
  m.header.stamp_ns = 9;
  m.request_id = 5;
  m.camera = rover_CAMERA_REAR_HAZCAM;
  m.width = 2;
  m.height = 1;
  m.rover_pose.position = {1, 2, 3};
  m.rover_pose.orientation = {2, 0, 0, 0};  // not unit: normalised
  std::vector<float> xyz = {1, 2, 3, 4, 5, 6};
  std::vector<std::uint8_t> valid = {1, 0};
  dds::BorrowSequence(m.xyz, xyz);
  dds::BorrowSequence(m.valid, valid);
  auto s = RangeScanFromIdl(m);
  ASSERT_TRUE(s.ok());
  EXPECT_TRUE(s->Validate().ok());
  EXPECT_EQ(s->xyz, xyz);
  EXPECT_EQ(s->capture_time.ns, 9);
  EXPECT_EQ(s->camera, "rear_hazcam");
  EXPECT_TRUE(s->site_from_rover.linear().isIdentity(1e-12));
  EXPECT_EQ(s->site_from_rover.translation(), Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(CameraFromIdl(m.camera), Camera::kRearHazcam);
  m.width = 3;
  s = RangeScanFromIdl(m);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.status().message().find("RangeImage.xyz: 6 floats"), std::string::npos);
  m.width = 2;
  m.rover_pose.orientation = {0, 0, 0, 0};
  s = RangeScanFromIdl(m);
  ASSERT_TRUE(s.ok());
  EXPECT_FALSE(s->Validate().ok());  // a zero quaternion becomes a non-finite pose
}

TEST(MobilityMsg, DeviceLayerMessages) {
  DriveRequest d;
  d.command_id = 8;
  d.kind = PrimitiveKind::kArc;
  d.curvature = -0.5;
  d.distance = -1.0;
  d.speed = 0.05;
  d.timeout_s = 30;
  d.stamp = Time{3};
  const DriveRequest b = DriveCommandFromIdl(DriveCommandToIdl(d));
  EXPECT_EQ(b.command_id, 8u);
  EXPECT_EQ(b.kind, PrimitiveKind::kArc);
  EXPECT_EQ(b.curvature, -0.5);
  EXPECT_EQ(b.distance, -1.0);
  EXPECT_EQ(b.speed, 0.05);
  EXPECT_EQ(b.timeout_s, 30);
  EXPECT_EQ(DriveCommandToIdl(d).primitive, rover_dl_PRIMITIVE_ARC);

  rover_dl_DriveStatus st{};
  st.command_id = 8;
  st.state = rover_dl_DRIVE_FAILED;
  st.termination = rover_dl_TERMINATION_SUSPENSION;
  st.distance_done = 0.4;
  dds::CopyString(st.message, "bogie");
  const DriveReport r = DriveStatusFromIdl(st);
  EXPECT_EQ(r.state, DriveState::kFailed);
  EXPECT_EQ(r.termination, DriveTermination::kSuspension);
  EXPECT_EQ(r.message, "bogie");

  const rover_dl_RangeRequest rr = RangeRequestToIdl({7, Camera::kFrontHazcam, 256, Time{1}});
  EXPECT_EQ(rr.camera, rover_CAMERA_FRONT_HAZCAM);
  EXPECT_EQ(rr.width, 256);
  EXPECT_EQ(rr.request_id, 7u);

  MastRequest mr;
  mr.look_at = true;
  mr.target = {3, 4, 0};
  const rover_dl_MastCommand mc = MastCommandToIdl(mr);
  EXPECT_EQ(mc.pointing, rover_dl_MAST_POINT_LOOK_AT);
  EXPECT_EQ(mc.look_at.y, 4);
  rover_dl_MastStatus ms{};
  ms.command_id = 2;
  ms.state = rover_dl_MAST_AT_GOAL;
  EXPECT_EQ(MastStatusFromIdl(ms).state, MastState::kAtGoal);

  rover_dl_RelativePose rp{};
  rp.source = rover_dl_SOURCE_WHEEL_ODOMETRY;
  EXPECT_FALSE(VisOdomFromIdl(rp).has_value());
  rp.source = rover_dl_SOURCE_VISUAL_ODOMETRY;
  rp.status = rover_dl_RELPOSE_TOO_FEW_FEATURES;
  rp.t_to_ns = 11;
  ASSERT_TRUE(VisOdomFromIdl(rp).has_value());
  EXPECT_FALSE(VisOdomFromIdl(rp)->converged);
  EXPECT_EQ(VisOdomFromIdl(rp)->t_to.ns, 11);

  rover_dl_PoseEstimate pe{};
  pe.header.stamp_ns = 12;
  const Eigen::Isometry3d t =
      Eigen::Translation3d(1, 2, 0) * Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ());
  pe.pose = IsometryToIdl(t);
  const PoseSample p = PoseFromIdl(pe);
  EXPECT_EQ(p.stamp.ns, 12);
  EXPECT_TRUE(p.site_from_rover.isApprox(t, 1e-12));
}

}  // namespace
}  // namespace rover::apl::mobility::msg
