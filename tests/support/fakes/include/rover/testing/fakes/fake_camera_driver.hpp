#pragma once
/// @file
/// Fake DDL camera driver (header only; target rover_fake_camera), used by the dl-stereo and
/// dl-vo service tests: it answers ddl/camera_request with ddl/stereo_frame, a stereo pair of
/// the textured scene (textured_scene.hpp) rendered from the rover pose the test says, with the
/// two camera models (CAHVOR vectors + pinhole part, rover frame) the driver would send.
///
/// Frames. Site frame S (x north, y west, z up) = the rover frame at the start; the renderer's
/// world frame W is camera-like (x right, y down, z forward) with the ground at y = ground_y:
///   W x = -S y,  W y = -S z,  W z = S x,  S origin at W (0, ground_y, 0)
/// so the site ground plane is z = 0 and the scene's back wall is at site x = wall_z.

#include <Eigen/Geometry>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "rover/dl/stereo/camera_model_fields.hpp"
#include "rover/runtime/dds.hpp"
#include "rover/testing/fakes/textured_scene.hpp"

namespace rover::testing {

/// World (renderer) from site, for a scene with the ground at W y = ground_y.
inline Eigen::Isometry3d WorldFromSite(double ground_y) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear().col(0) = Eigen::Vector3d(0, 0, 1);   // site x -> W z
  t.linear().col(1) = Eigen::Vector3d(-1, 0, 0);  // site y -> W -x
  t.linear().col(2) = Eigen::Vector3d(0, -1, 0);  // site z -> W -y
  t.translation() = Eigen::Vector3d(0, ground_y, 0);
  return t;
}

/// Camera (x right, y down, z forward) at `position` in the rover frame, pitched down by `pitch`.
inline Eigen::Isometry3d CameraMount(double pitch, const Eigen::Vector3d& position) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  const Eigen::Vector3d z(std::cos(pitch), 0.0, -std::sin(pitch));
  const Eigen::Vector3d x(0.0, -1.0, 0.0);
  t.linear().col(0) = x;
  t.linear().col(1) = z.cross(x);
  t.linear().col(2) = z;
  t.translation() = position;
  return t;
}

/// A rover pose in the site frame: position (x, y) on the ground, heading yaw.
inline Eigen::Isometry3d RoverPose(double x, double y, double yaw) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  t.translation() = Eigen::Vector3d(x, y, 0.0);
  return t;
}

/// A rectified pinhole stereo rig fixed on the rover.
struct Rig {
  Eigen::Isometry3d rover_from_left = CameraMount(0.6, {0.5, 0.1, 1.0});
  double baseline = 0.2;        ///< [m] right camera along the left camera's +x
  double focal_at_256 = 200.0;  ///< [px] focal length of a 256 px wide image

  /// The renderer's camera for an image `width` wide (height 3/4 of it, centred).
  PinholeStereo Camera(int width) const {
    PinholeStereo c;
    c.width = width;
    c.height = width * 3 / 4;
    c.fx = c.fy = focal_at_256 * width / 256.0;
    c.cx = (c.width - 1) / 2.0;
    c.cy = (c.height - 1) / 2.0;
    c.baseline = baseline;
    return c;
  }
  /// The message fields of the left (right = false) or right camera model for `width`.
  dl::stereo::CameraModelFields Model(int width, bool right) const {
    const PinholeStereo c = Camera(width);
    geometry::PinholeRadial p;
    p.fx = c.fx;
    p.fy = c.fy;
    p.cx = c.cx;
    p.cy = c.cy;
    p.width = c.width;
    p.height = c.height;
    p.pose = rover_from_left;
    if (right) p.pose = rover_from_left * Eigen::Translation3d(baseline, 0.0, 0.0);
    auto cahv = geometry::ToCahv(p);
    auto model = geometry::CameraModel::Create(*cahv, c.width, c.height);
    auto fields = dl::stereo::FieldsFromCameraModel(*model);
    return *fields;
  }
};

/// Answers ddl/camera_request like the DDL camera driver would.
class FakeCameraDriver {
 public:
  FakeCameraDriver() = default;
  Status Create(const dds::Participant& p) {
    auto r = dds::Reader<rover_ddl_StereoRequest>::Create(p, "ddl/camera_request");
    if (!r.ok()) return r.status();
    requests_ = std::move(*r);
    auto w = dds::Writer<rover_ddl_StereoFrame>::Create(p, "ddl/stereo_frame");
    if (!w.ok()) return w.status();
    frames_ = std::move(*w);
    return Status::Ok();
  }
  bool Matched() const { return requests_.MatchedWriters() >= 1 && frames_.MatchedReaders() >= 1; }

  /// Takes the requests that arrived into the pending list; returns how many are pending.
  std::size_t Poll() {
    for (auto& s : requests_.Take()) {
      seen.push_back(s.data());
      pending_.push_back(s.data());
    }
    return pending_.size();
  }

  /// Answers every pending request (unless `answer` is false: then they are dropped) with a pair
  /// rendered at `site_from_rover`, stamped `now`, after `corrupt` (if set) edited the message.
  /// Returns the number of frames sent.
  int Serve(Time now, const Eigen::Isometry3d& site_from_rover) {
    Poll();
    int n = 0;
    for (const rover_ddl_StereoRequest& r : pending_) {
      if (!answer) continue;
      Answer(r, now, site_from_rover);
      ++n;
    }
    pending_.clear();
    return n;
  }

  void Answer(const rover_ddl_StereoRequest& req, Time now,
              const Eigen::Isometry3d& site_from_rover) {
    const int width = req.width != 0 ? req.width : 512;
    const PinholeStereo cam = rig.Camera(width);
    const Eigen::Isometry3d world_from_left =
        WorldFromSite(scene.ground_y) * site_from_rover * rig.rover_from_left;
    ++renders_;
    cv::Mat left = RenderView(cam, scene, world_from_left, false, 100 + 2 * renders_);
    cv::Mat right = RenderView(cam, scene, world_from_left, true, 101 + 2 * renders_);
    std::vector<std::uint8_t> l(left.datastart, left.dataend), r(right.datastart, right.dataend);
    rover_ddl_StereoFrame m{};
    m.header.stamp_ns = now.ns;
    dds::CopyString(m.header.frame_id, "rover");
    m.header.seq = static_cast<std::uint32_t>(renders_);
    m.request_id = req.request_id;
    m.camera = req.camera;
    m.exposure_us = req.exposure_us;
    m.width = static_cast<std::uint16_t>(cam.width);
    m.height = static_cast<std::uint16_t>(cam.height);
    dl::stereo::FieldsToMessage(rig.Model(width, false), &m.left_model);
    dl::stereo::FieldsToMessage(rig.Model(width, true), &m.right_model);
    m.health = rover_HEALTH_OK;
    dds::BorrowSequence(m.left, l);
    dds::BorrowSequence(m.right, r);
    if (corrupt) corrupt(m, l, r);
    const Status s = frames_.Write(m);
    (void)s;
  }

  SyntheticScene scene;
  Rig rig;
  bool answer = true;
  /// Edits a frame before it is sent (the image vectors are borrowed by the message: re-borrow
  /// after resizing them).
  std::function<void(rover_ddl_StereoFrame&, std::vector<std::uint8_t>&,
                     std::vector<std::uint8_t>&)>
      corrupt;
  std::vector<rover_ddl_StereoRequest> seen;

 private:
  dds::Reader<rover_ddl_StereoRequest> requests_;
  dds::Writer<rover_ddl_StereoFrame> frames_;
  std::vector<rover_ddl_StereoRequest> pending_;
  int renders_ = 0;
};

}  // namespace rover::testing
