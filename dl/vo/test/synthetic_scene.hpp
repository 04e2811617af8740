#pragma once
// Test helper (header only) of dl/vo's unit tests: the shared textured scene
// (tests/support/fakes, rover/testing/fakes/textured_scene.hpp) rendered into the VO library's
// StereoFrame, and the test camera and motions these tests use. Not part of the library API.
//
// World frame = left camera frame of the first pair (x right, y down, z forward); the scene is
// the shared one: a textured ground plane y = ground_y and back wall z = wall_z.

#include <Eigen/Geometry>
#include <cstdint>
#include <opencv2/core.hpp>

#include "rover/dl/vo/stereo_camera.hpp"
#include "rover/dl/vo/visual_odometry.hpp"
#include "rover/testing/fakes/textured_scene.hpp"

namespace rover::dl::vo::testing {

inline StereoCamera TestCamera() {
  StereoCamera c;
  c.width = 640;
  c.height = 480;
  c.fx = c.fy = 500.0;
  c.cx = 319.5;
  c.cy = 239.5;
  c.baseline = 0.3;
  return c;
}

using ::rover::testing::SyntheticScene;
using ::rover::testing::Texture;

// Renders the left (right = false) or right image of a camera whose left camera has pose
// t_world_cam (the shared renderer, on the VO library's camera).
inline cv::Mat RenderView(const StereoCamera& cam, const SyntheticScene& s,
                          const Eigen::Isometry3d& t_world_cam, bool right,
                          std::uint64_t noise_seed) {
  const ::rover::testing::PinholeStereo pinhole{cam.width, cam.height, cam.fx,      cam.fy,
                                                cam.cx,    cam.cy,     cam.baseline};
  return ::rover::testing::RenderView(pinhole, s, t_world_cam, right, noise_seed);
}

inline StereoFrame RenderPair(const StereoCamera& cam, const SyntheticScene& s,
                              const Eigen::Isometry3d& t_world_cam, double stamp_s,
                              std::uint64_t noise_seed) {
  StereoFrame f;
  f.stamp = Time::FromSeconds(stamp_s);
  f.left = RenderView(cam, s, t_world_cam, false, noise_seed);
  f.right = RenderView(cam, s, t_world_cam, true, noise_seed + 1);
  return f;
}

// A rover-like step in the level world frame: forward (z), sideways and a little up, with a yaw
// (about y, down) and small pitch and roll.
inline Eigen::Isometry3d TestMotion() {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = (Eigen::AngleAxisd(0.05, Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(0.01, Eigen::Vector3d::UnitX()) *
                Eigen::AngleAxisd(-0.008, Eigen::Vector3d::UnitZ()))
                   .toRotationMatrix();
  t.translation() = Eigen::Vector3d(0.06, -0.01, 0.45);
  return t;
}

// The camera is pitched down by `pitch` [rad] on the rover, as MER pointed its NAVCAMs at the
// terrain for visual odometry. World pose of the left camera after the rover moved by
// `rover_motion` (level world frame): T_world_cam = rover_motion * mount.
inline Eigen::Isometry3d CameraPose(const Eigen::Isometry3d& rover_motion, double pitch = 0.44) {
  Eigen::Isometry3d mount = Eigen::Isometry3d::Identity();
  mount.linear() = Eigen::AngleAxisd(-pitch, Eigen::Vector3d::UnitX()).toRotationMatrix();
  return rover_motion * mount;
}

// The camera-frame motion T_from_to of one TestMotion() step of a pitched camera.
inline Eigen::Isometry3d TestCameraMotion(double pitch = 0.44) {
  return CameraPose(Eigen::Isometry3d::Identity(), pitch).inverse() *
         CameraPose(TestMotion(), pitch);
}

}  // namespace rover::dl::vo::testing
