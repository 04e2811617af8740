#pragma once
/// @file
/// The ddl CameraModel message (idl/rover_ddl.idl) carries every model twice: as JPL CAHVOR
/// vectors and as the equivalent pinhole with Brown radial distortion. ToCameraModelFields fills
/// both from a geometry::CameraModel:
///  * CAHV: C, A, H, V; O = A, R = 0 (exact). CAHVOR: as is (exact).
///  * PINHOLE_RADIAL: CAHVOR by geometry::ToCahvor (exact when k3 = 0).
///  * CAHVORE: the fitted pinhole, then its CAHVOR (the moving entrance pupil is dropped).
///  * Pinhole part: geometry::ToPinholeRadial (exact for CAHV and pinhole, a least-squares fit
///    otherwise; the fit's RMS and max pixel error are reported).

#include <Eigen/Geometry>
#include <array>
#include <cstdint>

#include "rover/base/status.hpp"
#include "rover/geometry/camera_model.hpp"

namespace rover::ddl {

struct CameraModelFields {
  std::array<double, 3> c{}, a{}, h{}, v{}, o{}, r{};  ///< CAHVOR, in the model's frame
  double fx = 0.0, fy = 0.0, cx = 0.0, cy = 0.0;       ///< [px] pinhole intrinsics
  double k1 = 0.0, k2 = 0.0, k3 = 0.0;                 ///< radial distortion
  /// Camera frame (x right, y down, z forward) in the model's reference frame.
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  std::uint16_t width = 0, height = 0;
  double pinhole_rms_error_px = 0.0;  ///< fit quality of the pinhole part (0 if exact)
  double pinhole_max_error_px = 0.0;
};

/// Errors: the conversions' errors (e.g. a field of view of 180 deg or more for the pinhole).
Result<CameraModelFields> ToCameraModelFields(const geometry::CameraModel& model);

}  // namespace rover::ddl
