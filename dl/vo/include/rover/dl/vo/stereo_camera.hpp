#pragma once
/// @file
/// The camera input of visual odometry: a rectified pinhole stereo pair.
///
/// Frames: both cameras use the camera frame (x right, y down, z forward, metres). The pair is
/// rectified, so both cameras share the orientation and the intrinsics, and the right camera's
/// centre is at (+baseline, 0, 0) in the left camera frame. All 3D quantities of the VO library
/// are in the left camera frame.
///
/// Pixels: (u, v) = (column, row); the centre of the top-left pixel is (0, 0) (OpenCV and KITTI
/// convention). Projection of X = (x, y, z), z > 0, into the left image:
///   u = fx x / z + cx,   v = fy y / z + cy;
/// into the right image the same with x - baseline. Disparity d = u_left - u_right = fx b / z.
///
/// This small struct is what the VO library needs; a CAHV/CAHVOR or pinhole model from
/// core/geometry maps onto it once it is rectified (linearised CAHV: hc, vc, hs, vs give cx, cy,
/// fx, fy; the baseline is the distance between the two C vectors).

#include <Eigen/Core>

#include "rover/base/status.hpp"

namespace rover::dl::vo {

struct StereoCamera {
  int width = 0;          ///< [px] image width of both cameras
  int height = 0;         ///< [px] image height of both cameras
  double fx = 0.0;        ///< [px] focal length along u
  double fy = 0.0;        ///< [px] focal length along v
  double cx = 0.0;        ///< [px] principal point u
  double cy = 0.0;        ///< [px] principal point v
  double baseline = 0.0;  ///< [m] right camera centre at (+baseline, 0, 0) in the left frame

  /// Checks sizes > 0, finite positive focal lengths and baseline, finite principal point.
  Status Validate() const;

  /// Builds the pair from the 3x4 projection matrices of a rectified pair (KITTI's P0 and P1,
  /// OpenCV stereoRectify's P1 and P2): P_left = K [I | 0], P_right = K [I | (-b, 0, 0)^T], so
  /// baseline b = -P_right(0,3) / P_right(0,0). Rejects matrices that are not a rectified pair
  /// (different intrinsics, skew, vertical offset, non-positive baseline).
  static Result<StereoCamera> FromProjectionMatrices(const Eigen::Matrix<double, 3, 4>& p_left,
                                                     const Eigen::Matrix<double, 3, 4>& p_right,
                                                     int width, int height);

  /// Direction (z = 1) of the viewing ray through pixel `px` of either camera, in that camera's
  /// frame (which has the left camera's orientation).
  Eigen::Vector3d Ray(const Eigen::Vector2d& px) const {
    return {(px.x() - cx) / fx, (px.y() - cy) / fy, 1.0};
  }
  /// Centre of the right camera in the left camera frame [m].
  Eigen::Vector3d RightCentre() const { return {baseline, 0.0, 0.0}; }

  /// Projection into the left image. Precondition: p.z() > 0.
  Eigen::Vector2d ProjectLeft(const Eigen::Vector3d& p) const {
    return {fx * p.x() / p.z() + cx, fy * p.y() / p.z() + cy};
  }
  /// Projection into the right image. Precondition: p.z() > 0.
  Eigen::Vector2d ProjectRight(const Eigen::Vector3d& p) const {
    return {fx * (p.x() - baseline) / p.z() + cx, fy * p.y() / p.z() + cy};
  }
  /// Jacobian d(ProjectLeft)/dp (2x3). Precondition: p.z() > 0.
  Eigen::Matrix<double, 2, 3> ProjectLeftJacobian(const Eigen::Vector3d& p) const;

  /// True if (u, v) lies at least `margin` pixels inside the image.
  bool Inside(const Eigen::Vector2d& px, double margin) const {
    return px.x() >= margin && px.y() >= margin && px.x() <= width - 1 - margin &&
           px.y() <= height - 1 - margin;
  }
};

}  // namespace rover::dl::vo
