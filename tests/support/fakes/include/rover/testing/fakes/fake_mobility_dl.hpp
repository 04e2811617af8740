#pragma once
/// @file
/// Fake dl-locomotion and dl-stereo for application-layer service tests (header only; target
/// rover_fake_mobility_dl). Deterministic: what they publish depends only on what they read and
/// on the run-clock times the test passes.
///
///   FakeLocomotion: takes dl/drive_command; integrates the running primitive into a planar
///     pose at `speed` [m/s] or `turn_rate` [rad/s] on each Advance(now); publishes dl/drive_status
///     (DRIVING on acceptance and on every Advance while it runs, as dl-locomotion reports each
///     cycle, unless `report_progress` is off; DONE at the end, REJECTED_BUSY for a second
///     primitive, FAILED / STOP_COMMAND for a STOP while one runs) and the pose on dl/pose
///     (unless `publish_pose` is off).
///   FakeStereo: takes dl/range_request; answers each with dl/range_image, a RockField capture
///     (rock_field.hpp) from the locomotion's pose at the time of the request, `camera` and
///     `rover_pose` filled in as dl-stereo does.
///
///   testing::FakeLocomotion loco;   testing::FakeStereo stereo(&field, &loco);
///   ASSERT_TRUE(loco.Create(h.peer()).ok() && stereo.Create(h.peer()).ok());
///   loco.Advance(h.now()); stereo.Serve(h.now());   // after every AdvanceTo

#include <Eigen/Geometry>
#include <cmath>
#include <optional>
#include <vector>

#include "rover/base/time.hpp"
#include "rover/runtime/dds.hpp"
#include "rover/testing/fakes/fake_pose.hpp"
#include "rover/testing/fakes/rock_field.hpp"

namespace rover::testing {

class FakeLocomotion {
 public:
  Status Create(const dds::Participant& p) {
    auto c = dds::Reader<rover_dl_DriveCommand>::Create(p, "dl/drive_command");
    if (!c.ok()) return c.status();
    commands_ = std::move(*c);
    auto s = dds::Writer<rover_dl_DriveStatus>::Create(p, "dl/drive_status");
    if (!s.ok()) return s.status();
    status_ = std::move(*s);
    return pose_.Create(p);
  }
  bool Matched() const {
    return pose_.Matched() && status_.MatchedReaders() >= 1 && commands_.MatchedWriters() >= 1;
  }

  /// Takes new commands, moves the rover to `now`, publishes statuses and dl/pose.
  void Advance(Time now) {
    for (auto& s : commands_.Take()) Accept(s.data(), now);
    if (running_ && last_.ns > 0) {
      const bool turn = running_->primitive == rover_dl_PRIMITIVE_TURN_IN_PLACE;
      const double goal = turn ? std::abs(running_->angle) : std::abs(running_->distance);
      const double inc =
          std::min(goal - done_, (turn ? turn_rate : speed) * ToSeconds(now - last_));
      if (turn) {
        heading += std::copysign(inc, running_->angle);
      } else {
        const double s = std::copysign(inc, running_->distance);
        const double k = running_->primitive == rover_dl_PRIMITIVE_ARC ? running_->curvature : 0.0;
        const double dx = std::abs(k) > 1e-9 ? std::sin(k * s) / k : s;
        const double dy = std::abs(k) > 1e-9 ? (1.0 - std::cos(k * s)) / k : 0.0;
        x += std::cos(heading) * dx - std::sin(heading) * dy;
        y += std::sin(heading) * dx + std::cos(heading) * dy;
        heading += k * s;
      }
      done_ += inc;
      if (done_ >= goal - 1e-9) {
        Publish(running_->command_id, running_->primitive, rover_dl_DRIVE_DONE,
                rover_dl_TERMINATION_NOMINAL, now);
        running_.reset();
      } else if (report_progress) {
        Publish(running_->command_id, running_->primitive,
                turn ? rover_dl_DRIVE_TURNING : rover_dl_DRIVE_DRIVING, rover_dl_TERMINATION_NONE,
                now);
      }
    }
    last_ = now;
    pose_.state.SetPose(Pose());
    if (publish_pose) (void)pose_.Publish(now);
  }

  Eigen::Isometry3d Pose() const {
    Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
    t.linear() = Eigen::AngleAxisd(heading, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    t.translation() = Eigen::Vector3d(x, y, 0.0);
    return t;
  }
  bool busy() const { return running_.has_value(); }
  int accepted() const { return accepted_; }

  double x = 0.0, y = 0.0, heading = 0.0;  ///< [m, m, rad] planar pose
  double speed = 0.25;                     ///< [m/s]
  double turn_rate = 0.5;                  ///< [rad/s]
  bool report_progress = true;             ///< DRIVING / TURNING on every Advance while running
  bool publish_pose = true;                ///< dl/pose on every Advance
  /// The pose writer (a test may publish its own samples, e.g. corrupted ones).
  FakePose& pose_publisher() { return pose_; }

 private:
  void Accept(const rover_dl_DriveCommand& c, Time now) {
    if (c.primitive == rover_dl_PRIMITIVE_STOP) {
      if (running_) {
        Publish(running_->command_id, running_->primitive, rover_dl_DRIVE_FAILED,
                rover_dl_TERMINATION_STOP_COMMAND, now);
        running_.reset();
      }
      Publish(c.command_id, c.primitive, rover_dl_DRIVE_DONE, rover_dl_TERMINATION_NOMINAL, now);
      return;
    }
    if (running_) {
      Publish(c.command_id, c.primitive, rover_dl_DRIVE_REJECTED,
              rover_dl_TERMINATION_REJECTED_BUSY, now);
      return;
    }
    running_ = c;
    done_ = 0.0;
    ++accepted_;
    Publish(c.command_id, c.primitive, rover_dl_DRIVE_DRIVING, rover_dl_TERMINATION_NONE, now);
  }
  void Publish(std::uint32_t id, rover_dl_DrivePrimitive p, rover_dl_DriveState st,
               rover_dl_DriveTermination term, Time now) {
    rover_dl_DriveStatus m{};
    m.header.stamp_ns = now.ns;
    m.command_id = id;
    m.primitive = p;
    m.state = st;
    m.termination = term;
    m.distance_done = running_ && running_->command_id == id ? done_ : 0.0;
    (void)status_.Write(m);
  }

  dds::Reader<rover_dl_DriveCommand> commands_;
  dds::Writer<rover_dl_DriveStatus> status_;
  FakePose pose_;
  std::optional<rover_dl_DriveCommand> running_;
  double done_ = 0.0;
  Time last_;
  int accepted_ = 0;
};

class FakeStereo {
 public:
  FakeStereo(const RockField* field, const FakeLocomotion* rover) : field_(field), rover_(rover) {}
  Status Create(const dds::Participant& p) {
    auto r = dds::Reader<rover_dl_RangeRequest>::Create(p, "dl/range_request");
    if (!r.ok()) return r.status();
    requests_ = std::move(*r);
    auto w = dds::Writer<rover_dl_RangeImage>::Create(p, "dl/range_image");
    if (!w.ok()) return w.status();
    images_ = std::move(*w);
    return Status::Ok();
  }
  bool Matched() const { return images_.MatchedReaders() >= 1 && requests_.MatchedWriters() >= 1; }

  /// Answers every request that arrived, captured at `now` from the rover's current pose.
  void Serve(Time now) {
    for (auto& s : requests_.Take()) {
      const rover_dl_RangeRequest& req = s.data();
      const bool rear = req.camera == rover_CAMERA_REAR_HAZCAM;
      SyntheticScan img = field_->Capture(rover_->x, rover_->y, rover_->heading, rear, spec);
      rover_dl_RangeImage m{};
      m.header.stamp_ns = now.ns;
      dds::CopyString(m.header.frame_id, "rover");
      m.request_id = req.request_id;
      m.camera = answer_camera ? *answer_camera : req.camera;
      m.width = static_cast<std::uint16_t>(img.width);
      m.height = static_cast<std::uint16_t>(img.height);
      const Eigen::Isometry3d pose = rover_->Pose();
      const Eigen::Quaterniond q(pose.linear());
      m.rover_pose.position = {pose.translation().x(), pose.translation().y(), 0.0};
      m.rover_pose.orientation = {q.w(), q.x(), q.y(), q.z()};
      std::vector<float> disparity(img.valid.size(), -1.0f);
      dds::BorrowSequence(m.xyz, img.xyz);
      dds::BorrowSequence(m.valid, img.valid);
      dds::BorrowSequence(m.disparity, disparity);
      (void)images_.Write(m);
      ++served_;
    }
  }
  int served() const { return served_; }

  HazcamSpec spec;
  /// Set: every image claims this camera (tests of the wrong-camera check).
  std::optional<rover_CameraId> answer_camera;

 private:
  const RockField* field_;
  const FakeLocomotion* rover_;
  dds::Reader<rover_dl_RangeRequest> requests_;
  dds::Writer<rover_dl_RangeImage> images_;
  int served_ = 0;
};

}  // namespace rover::testing
