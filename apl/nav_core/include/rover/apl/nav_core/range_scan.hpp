#pragma once
/// @file
/// RangeScan: one range image as terrain assessment consumes it, free of DDS.
///
/// Frames: `xyz` is in the rover frame at capture time (x forward, y left, z up; origin at
/// nominal ground below the rocker pivots); `site_from_rover` is the rover's pose at capture in
/// the site frame (x north, y west, z up; gravity along -z), so p_site = site_from_rover * p_rover.
/// Units: metres, run-clock time.
///
/// The pixel grid is kept (rather than a bag of points) because assessors use it: GESTALT finds
/// the outline of the image footprint from it (cells at the edge of the field of view are merged
/// conservatively). RangeScanFromImage builds it from dl/range_image (core/msg's RangeImage):
/// width, height, xyz, valid and the pose carry over one to one.

#include <Eigen/Geometry>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "rover/base/format.hpp"
#include "rover/base/status.hpp"
#include "rover/base/time.hpp"
#include "rover/msg/range.hpp"

namespace rover::apl::nav_core {

/// Ok when every entry of the pose's matrix is finite; else "<name>(r, c) is nan (must be
/// finite)" for the first bad entry.
inline Status CheckPoseFinite(const std::string& name, const Eigen::Isometry3d& pose) {
  const Eigen::Matrix4d m = pose.matrix();
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) {
      if (!std::isfinite(m(r, c))) {
        return InvalidArgument(name + "(" + std::to_string(r) + ", " + std::to_string(c) + ") is " +
                               FormatNumber(m(r, c)) + " (must be finite)");
      }
    }
  }
  return Status::Ok();
}

struct RangeScan {
  int width = 0;   ///< [px] columns
  int height = 0;  ///< [px] rows
  /// [m] 3 floats (x, y, z) per pixel, row-major (index 3 * (v * width + u)), rover frame.
  std::vector<float> xyz;
  /// 1 byte per pixel, row-major; nonzero = the pixel has a range.
  std::vector<std::uint8_t> valid;
  Time capture_time;  ///< run clock at capture
  /// Pose of the rover at capture in the site frame (rotation must be orthonormal).
  Eigen::Isometry3d site_from_rover = Eigen::Isometry3d::Identity();
  std::string camera;  ///< which camera pair, e.g. "front_hazcam" (for messages only)

  std::size_t pixel_count() const {
    return static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  }
  bool is_valid(int u, int v) const { return valid[static_cast<std::size_t>(v) * width + u] != 0; }
  Eigen::Vector3d point(int u, int v) const {
    const std::size_t k = 3 * (static_cast<std::size_t>(v) * width + u);
    return {xyz[k], xyz[k + 1], xyz[k + 2]};
  }

  /// Checks the shape and the pose (not the points: a non-finite point marked valid is
  /// skipped by consumers). Messages name the field and value, e.g.
  /// "RangeScan.xyz: 300 floats for 10 x 10 pixels (need 300 = 3 per pixel)".
  Status Validate() const {
    if (width <= 0 || height <= 0) {
      return InvalidArgument("RangeScan.width x height = " + std::to_string(width) + " x " +
                             std::to_string(height) + " (both must be > 0)");
    }
    if (xyz.size() != 3 * pixel_count()) {
      return InvalidArgument("RangeScan.xyz: " + std::to_string(xyz.size()) + " floats for " +
                             std::to_string(width) + " x " + std::to_string(height) +
                             " pixels (need " + std::to_string(3 * pixel_count()) +
                             " = 3 per pixel)");
    }
    if (valid.size() != pixel_count()) {
      return InvalidArgument("RangeScan.valid: " + std::to_string(valid.size()) + " bytes for " +
                             std::to_string(pixel_count()) + " pixels");
    }
    ROVER_RETURN_IF_ERROR(CheckPoseFinite("RangeScan.site_from_rover", site_from_rover));
    const Eigen::Matrix3d rot = site_from_rover.linear();
    const double err = (rot.transpose() * rot - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
    if (err > 1e-6 || rot.determinant() < 0.0) {
      return InvalidArgument(
          "RangeScan.site_from_rover: rotation is not orthonormal (|R^T R - I| = " +
          FormatNumber(err) + ", det = " + FormatNumber(rot.determinant()) + ")");
    }
    return Status::Ok();
  }
};

/// The scan of a dl/range_image: width, height, xyz and valid copied, capture time = the image's
/// stamp, site_from_rover = its rover_pose, camera = msg::CameraName of its camera. The disparity
/// is not carried. Call Validate on the result: it is not checked here.
inline RangeScan RangeScanFromImage(const msg::RangeImage& image) {
  RangeScan s;
  s.width = image.width;
  s.height = image.height;
  s.xyz = image.xyz;
  s.valid = image.valid;
  s.capture_time = image.stamp;
  s.site_from_rover = image.rover_pose;
  s.camera = msg::CameraName(image.camera);
  return s;
}

}  // namespace rover::apl::nav_core
