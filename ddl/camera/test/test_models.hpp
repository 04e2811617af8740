#pragma once
// Camera models shared by the ddl/camera tests.

#include "rover/geometry/camera_model.hpp"

namespace rover::ddl::camera::test {

// A NAVCAM-like CAHVOR (1024 x 768, 45 deg, mild barrel distortion) looking along +z, with the
// optical axis O slightly off A.
inline geometry::CameraModel NavcamCahvor(double baseline_x = 0.0) {
  geometry::Cahvor m;
  m.c = Eigen::Vector3d(baseline_x, 0.0, 0.0);
  m.a = Eigen::Vector3d::UnitZ();
  const double f = 1236.0, cx = 511.5 + 3.2, cy = 383.5 - 2.1;
  m.h = f * Eigen::Vector3d::UnitX() + cx * m.a;
  m.v = f * Eigen::Vector3d::UnitY() + cy * m.a;
  m.o = Eigen::Vector3d(0.002, -0.001, 1.0).normalized();
  m.r = Eigen::Vector3d(0.0, -0.02, 0.004);
  return *geometry::CameraModel::Create(m, 1024, 768);
}

}  // namespace rover::ddl::camera::test
