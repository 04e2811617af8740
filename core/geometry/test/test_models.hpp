#pragma once
// Synthetic camera models shared by the geometry tests.

#include <cstdlib>
#include <random>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "rover/geometry/camera_model.hpp"
#include "rover/geometry/transforms.hpp"

namespace rover::geometry::testing {

// reference_from_camera for a camera at `c` looking along the rover's x axis (rover frame x fwd,
// y left, z up; camera x right, y down, z fwd), then turned by yaw (left), tilted by pitch
// (positive = down) and rolled about its axis.
inline Eigen::Isometry3d CameraPose(const Eigen::Vector3d& c, double yaw, double pitch,
                                    double roll) {
  Eigen::Matrix3d rover_from_cam0;
  rover_from_cam0 << 0, 0, 1,  //
      -1, 0, 0,                //
      0, -1, 0;
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = RotationFromRpy(0.0, pitch, yaw) * rover_from_cam0 *
               Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  t.translation() = c;
  return t;
}

inline Cahv MakeCahv(const Eigen::Isometry3d& pose, double fx, double fy, double cx, double cy) {
  const Eigen::Matrix3d r = pose.linear();
  Cahv m;
  m.c = pose.translation();
  m.a = r.col(2);
  m.h = fx * r.col(0) + cx * m.a;
  m.v = fy * r.col(1) + cy * m.a;
  return m;
}

// A NAVCAM-like CAHV, 1024 x 768, 45 deg horizontal FOV, tilted down 25 deg.
inline Cahv TestCahv() {
  return MakeCahv(CameraPose({0.8, 0.3, 1.9}, 0.2, 0.44, 0.01), 1236.0, 1234.5, 515.3, 380.7);
}

// CAHVOR with O 0.5 deg off A and barrel-ish distortion (about 3 px at the corners).
inline Cahvor TestCahvor() {
  const Cahv l = TestCahv();
  Cahvor m{l.c, l.a, l.h, l.v, l.a, Eigen::Vector3d(0.0, -0.02, 0.015)};
  m.o = Eigen::AngleAxisd(0.5 * 3.14159265358979 / 180.0,
                          Eigen::Vector3d(0.3, 1.0, 0.2).normalized()) *
        l.a;
  return m;
}

// Hazcam-like fisheye CAHVORE, 1024 x 1024, ~180 deg diagonal FOV, with a moving pupil.
inline Cahvore TestCahvore(CahvoreType type = CahvoreType::kFisheye, double parameter = 0.0) {
  const Cahv l =
      MakeCahv(CameraPose({1.0, -0.1, 0.7}, -0.1, 0.7, -0.02), 330.0, 331.0, 511.0, 513.5);
  Cahvore m;
  m.c = l.c;
  m.a = l.a;
  m.h = l.h;
  m.v = l.v;
  m.o = Eigen::AngleAxisd(0.01, Eigen::Vector3d(1.0, 0.5, 0.0).normalized()) * l.a;
  m.r = Eigen::Vector3d(0.0, -0.01, 0.002);
  m.e = Eigen::Vector3d(0.012, 0.006, -0.002);
  m.type = type;
  m.parameter = parameter;
  return m;
}

inline PinholeRadial TestPinholeRadial() {
  PinholeRadial p;
  p.fx = 700.0;
  p.fy = 702.0;
  p.cx = 321.0;
  p.cy = 236.5;
  p.k1 = -0.25;
  p.k2 = 0.08;
  p.k3 = -0.01;
  p.pose = CameraPose({0.2, 0.1, 1.2}, 0.05, 0.3, 0.0);
  p.width = 640;
  p.height = 480;
  return p;
}

inline CameraModel Must(Result<CameraModel> r) {
  if (!r.ok()) std::abort();
  return std::move(r).value();
}

// All test models with their sizes.
inline std::vector<CameraModel> AllTestModels() {
  return {Must(CameraModel::Create(TestCahv(), 1024, 768)),
          Must(CameraModel::Create(TestCahvor(), 1024, 768)),
          Must(CameraModel::Create(TestCahvore(), 1024, 1024)),
          Must(CameraModel::Create(TestCahvore(CahvoreType::kGeneral, 0.4), 1024, 1024)),
          Must(CameraModel::Create(TestCahvore(CahvoreType::kPerspective), 1024, 1024)),
          Must(CameraModel::Create(TestPinholeRadial()))};
}

// Random points in front of a model: unprojected random in-image pixels at random ranges.
inline std::vector<Eigen::Vector3d> PointsInView(const CameraModel& m, int n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> ux(0.0, m.width() - 1.0);
  std::uniform_real_distribution<double> uy(0.0, m.height() - 1.0);
  std::uniform_real_distribution<double> range(0.3, 60.0);
  std::vector<Eigen::Vector3d> points;
  while (static_cast<int>(points.size()) < n) {
    const auto ray = m.Unproject({ux(rng), uy(rng)});
    if (ray) points.push_back(ray->origin + range(rng) * ray->direction);
  }
  return points;
}

}  // namespace rover::geometry::testing
