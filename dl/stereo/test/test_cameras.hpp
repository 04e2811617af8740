#pragma once
// Camera models shared by the dl_stereo tests that need message fields.

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "rover/geometry/camera_model.hpp"
#include "rover/msg/camera.hpp"

namespace rover::dl::stereo::testing {

// Fields of a distortion-free 128x96 camera of focal length f [px] looking along rover +x from
// (0.5, y, 1.0) [m].
inline msg::CameraModelFields ForwardCamera(double y, double f = 100.0) {
  geometry::PinholeRadial p;
  p.fx = p.fy = f;
  p.cx = 63.5;
  p.cy = 47.5;
  p.width = 128;
  p.height = 96;
  p.pose.linear().col(0) = Eigen::Vector3d(0, -1, 0);
  p.pose.linear().col(1) = Eigen::Vector3d(0, 0, -1);
  p.pose.linear().col(2) = Eigen::Vector3d(1, 0, 0);
  p.pose.translation() = Eigen::Vector3d(0.5, y, 1.0);
  auto m = geometry::CameraModel::Create(p);
  EXPECT_TRUE(m.ok());
  auto fields = msg::CameraModelFieldsFromModel(*m);
  EXPECT_TRUE(fields.ok());
  return *fields;
}

}  // namespace rover::dl::stereo::testing
