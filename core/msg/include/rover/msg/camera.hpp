#pragma once
/// @file
/// The camera messages as plain values: the rover's stereo cameras (rover_common.idl CameraId),
/// the camera model that travels with every frame (rover_ddl.idl CameraModel), a camera request
/// (ddl/camera_request) and a raw stereo frame (ddl/stereo_frame). The camera driver fills them,
/// the stereo and visual-odometry services read them; rover/msg/camera_idl.hpp converts them.
///
/// Camera model. The message carries every model twice, as the camera driver fills it:
///   * JPL CAHVOR vectors C [m], A (unit), H, V [px], O (unit), R = (r0, r1, r2), in the frame of
///     the sample (the rover frame); a CAHV model has R = 0 (O is then ignored);
///   * the equivalent pinhole with Brown radial distortion, fx, fy, cx, cy [px], k1..k3, and the
///     camera frame (x right, y down, z forward) as a pose in the same frame.
/// Pixels: the centre of the top-left pixel is (0, 0) (core/geometry).
///
/// CameraModelFieldsFromModel fills both parts from a geometry::CameraModel:
///   * CAHV: C, A, H, V; O = A, R = 0 (exact). CAHVOR: as is (exact).
///   * PINHOLE_RADIAL: CAHVOR by geometry::ToCahvor (exact when k3 = 0).
///   * CAHVORE: the fitted pinhole's CAHVOR (the moving entrance pupil is dropped).
///   * Pinhole part: geometry::ToPinholeRadial (exact for CAHV and pinhole, a least-squares fit
///     otherwise); its orientation quaternion has w >= 0.
/// CameraModelFromFields prefers the CAHVOR part (exact for CAHV/CAHVOR cameras); it uses the
/// pinhole part only when the CAHVOR vectors are all zero. When both are present they must
/// describe the same camera: |C - pose.position| <= 1 mm and the angle between A and the pose's
/// z axis <= 1 mrad (what CameraModelFieldsFromModel guarantees), else the model is rejected as
/// corrupt. A model with neither part (all zeros: "missing"), non-finite values, a size of 0,
/// a non-unit quaternion, or one that geometry::CameraModel::Create rejects (H, V, A coplanar:
/// "singular", |A| or |O| not 1, 1 + r0 <= 0) is an error naming the field.

#include <array>
#include <cstdint>
#include <span>
#include <string>

#include "rover/base/status.hpp"
#include "rover/base/time.hpp"
#include "rover/geometry/camera_model.hpp"
#include "rover/msg/health.hpp"

namespace rover::msg {

/// The rover's stereo pairs; same ordinals as the IDL. A value read from a command may be any
/// integer (the enum is 32 bit): IsKnownCamera says whether it names a camera.
enum class CameraId : std::int32_t { kNavcam = 0, kFrontHazcam = 1, kRearHazcam = 2 };
inline constexpr int kNumCameras = 3;

constexpr bool IsKnownCamera(CameraId c) {
  return static_cast<std::int32_t>(c) >= 0 && static_cast<std::int32_t>(c) < kNumCameras;
}
/// "navcam", "front_hazcam", "rear_hazcam"; "unknown" for any other value.
const char* CameraName(CameraId c);
/// The camera a name (as CameraName gives it) stands for. InvalidArgument for any other text.
Result<CameraId> CameraFromName(const std::string& name);

/// One camera model of the ddl CameraModel message, field for field (see the file comment).
struct CameraModelFields {
  std::array<double, 3> c{};                      ///< C [m] camera centre
  std::array<double, 3> a{};                      ///< A unit optical axis
  std::array<double, 3> h{};                      ///< H [px]
  std::array<double, 3> v{};                      ///< V [px]
  std::array<double, 3> o{};                      ///< O unit axis of the radial distortion
  std::array<double, 3> r{};                      ///< R = (r0, r1, r2)
  double fx = 0.0, fy = 0.0, cx = 0.0, cy = 0.0;  ///< [px] pinhole intrinsics
  double k1 = 0.0, k2 = 0.0, k3 = 0.0;            ///< Brown radial distortion
  std::array<double, 3> position{};               ///< [m] camera-frame origin (pinhole pose)
  std::array<double, 4> orientation{1.0, 0.0, 0.0, 0.0};  ///< w, x, y, z (pinhole pose)
  int width = 0;                                          ///< [px]
  int height = 0;                                         ///< [px]

  /// True if any of A, H, V is non-zero.
  bool HasCahvor() const;
  /// True if fx or fy is non-zero.
  bool HasPinhole() const;

  friend bool operator==(const CameraModelFields&, const CameraModelFields&) = default;
};

/// How well the pinhole part reproduces the model it was fitted to (0 when exact).
struct PinholeFit {
  double rms_error_px = 0.0;
  double max_error_px = 0.0;
};

/// Both parts from a geometry model (see the file comment); `fit` (optional) receives the
/// quality of the pinhole part. Errors: those of the geometry conversions (e.g. a field of view
/// of 180 deg or more for the pinhole).
Result<CameraModelFields> CameraModelFieldsFromModel(const geometry::CameraModel& model,
                                                     PinholeFit* fit = nullptr);

/// The geometry model of message fields (see the file comment). Errors (InvalidArgument) name
/// the field and the value.
Result<geometry::CameraModel> CameraModelFromFields(const CameraModelFields& fields);

/// ddl/camera_request: take a stereo pair. Commands keep any camera value (the driver rejects an
/// unknown one by name).
struct StereoRequest {
  Time stamp;
  std::uint32_t request_id = 0;
  CameraId camera = CameraId::kNavcam;
  std::uint32_t exposure_us = 0;  ///< [us] 0 = auto
  int width = 0;                  ///< [px] output width after downsampling; 0 = full size
};

/// ddl/stereo_frame: a raw (unrectified) stereo pair, two 8-bit mono images of width x height,
/// row-major, with the camera models valid for them (in the rover frame at capture time). The
/// images are VIEWS: of the received sample (valid while it is, e.g. during a DDS callback) or
/// of the producer's buffers (valid until the sample is written).
struct StereoFrame {
  Time stamp;  ///< capture time on the run clock
  std::uint32_t request_id = 0;
  CameraId camera = CameraId::kNavcam;
  std::uint32_t exposure_us = 0;
  int width = 0;   ///< [px]
  int height = 0;  ///< [px]
  CameraModelFields left_model, right_model;
  std::span<const std::uint8_t> left, right;
  SensorHealth health = SensorHealth::kOk;
};

/// Checks width, height >= 1, a positive stamp, both images of width x height bytes and both
/// models sized width x height. Errors name the image or model and the sizes.
Status CheckStereoFrame(const StereoFrame& frame);

/// ddl/mi_request: take one microscopic-imager frame.
struct MiRequest {
  Time stamp;
  std::uint32_t request_id = 0;
  std::uint32_t exposure_us = 0;  ///< [us] 0 = auto
};

/// ddl/mi_frame: one 8-bit mono microscopic-imager frame, width x height, row-major. The image
/// is a VIEW (of the received sample or the producer's buffer), as StereoFrame's.
struct MiFrame {
  Time stamp;  ///< capture time on the run clock
  std::uint32_t request_id = 0;
  std::uint32_t exposure_us = 0;
  int width = 0;   ///< [px]
  int height = 0;  ///< [px]
  std::span<const std::uint8_t> image;
  SensorHealth health = SensorHealth::kOk;
};

/// Checks width, height >= 1, a positive stamp and an image of width x height bytes; errors
/// name the size and the byte count.
Status CheckMiFrame(const MiFrame& frame);

}  // namespace rover::msg
