#pragma once
/// @file
/// The ranging messages as plain values (idl/rover_dl.idl): dl/range_request (APL -> DL stereo:
/// take an image pair and range it) and dl/range_image (DL stereo -> APL). rover/msg/range_idl.hpp
/// converts them.

#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "rover/base/time.hpp"
#include "rover/msg/camera.hpp"

namespace rover::msg {

/// dl/range_request. Keeps any camera value read from the wire (stereo rejects unknown ones).
struct RangeRequest {
  Time stamp;
  std::uint32_t request_id = 0;
  CameraId camera = CameraId::kNavcam;
  int width = 0;  ///< [px] processing width; 0 = the service's default
};

/// dl/range_image: XYZ in the rover frame at capture.
struct RangeImage {
  Time stamp;  ///< capture time
  std::uint32_t request_id = 0;
  CameraId camera = CameraId::kNavcam;
  int width = 0;   ///< [px]
  int height = 0;  ///< [px]
  /// dl/pose estimate at capture time (site frame); identity when the pose was unknown.
  Eigen::Isometry3d rover_pose = Eigen::Isometry3d::Identity();
  std::vector<float> xyz;           ///< [m] 3 per pixel, row-major; NaN where invalid
  std::vector<std::uint8_t> valid;  ///< 1 per pixel: 1 = valid range
  std::vector<float> disparity;     ///< [px] per pixel, -1 where invalid

  /// Ok when xyz has 3 width x height values and valid and disparity width x height. Errors
  /// name the array and both sizes.
  Status CheckSizes() const;
};

}  // namespace rover::msg
