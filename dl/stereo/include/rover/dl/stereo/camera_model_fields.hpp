#pragma once
/// @file
/// The camera models that arrive with every ddl/stereo_frame (IDL `rover::ddl::CameraModel`,
/// idl/rover_ddl.idl) as plain fields, and their conversion to and from core/geometry's
/// CameraModel. No DDS here: the templates at the end copy between the fields and any struct
/// with the IDL's member names (the idlc-generated C struct in the services).
///
/// The message carries every model twice, as the camera driver fills it:
///   * JPL CAHVOR vectors C [m], A (unit), H, V [px], O (unit), R = (r0, r1, r2), in the frame of
///     the sample (the rover frame); a CAHV model has R = 0 (O is then ignored);
///   * the equivalent pinhole with Brown radial distortion, fx, fy, cx, cy [px], k1..k3, and the
///     camera frame (x right, y down, z forward) as a pose in the same frame.
/// Pixels: the centre of the top-left pixel is (0, 0) (core/geometry).
///
/// CameraModelFromFields prefers the CAHVOR part (exact for CAHV/CAHVOR cameras); it uses the
/// pinhole part only when the CAHVOR vectors are all zero. When both are present they must
/// describe the same camera: |C - pose.position| <= 1 mm and the angle between A and the pose's
/// z axis <= 1 mrad (what the driver's conversions guarantee), else the model is rejected as
/// corrupt. A model with neither part (all zeros: "missing"), non-finite values, a size of 0,
/// a non-unit quaternion, or one that geometry::CameraModel::Create rejects (H, V, A coplanar:
/// "singular", |A| or |O| not 1, 1 + r0 <= 0) is an error naming the field.

#include <Eigen/Geometry>
#include <array>
#include <cstddef>
#include <cstdint>

#include "rover/base/status.hpp"
#include "rover/geometry/camera_model.hpp"

namespace rover::dl::stereo {

/// One camera model of the ddl CameraModel message, field for field.
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

/// The geometry model of a message model (see the file comment for the rules). Errors
/// (InvalidArgument) name the field and the value.
Result<geometry::CameraModel> CameraModelFromFields(const CameraModelFields& fields);

/// Both parts of the message from a geometry model, as the camera driver fills them: CAHV ->
/// O = A, R = 0; CAHVOR as is; PINHOLE_RADIAL -> geometry::ToCahvor; CAHVORE -> the fitted
/// pinhole's CAHVOR. Pinhole part from geometry::ToPinholeRadial. Errors: those conversions'.
Result<CameraModelFields> FieldsFromCameraModel(const geometry::CameraModel& model);

/// Copies a message struct (members c, a, h, v, o, r [3], fx ... k3, pose {position {x, y, z},
/// orientation {w, x, y, z}}, width, height) into fields.
template <class Msg>
CameraModelFields FieldsFromMessage(const Msg& m) {
  CameraModelFields f;
  for (std::size_t i = 0; i < 3; ++i) {
    f.c[i] = m.c[i];
    f.a[i] = m.a[i];
    f.h[i] = m.h[i];
    f.v[i] = m.v[i];
    f.o[i] = m.o[i];
    f.r[i] = m.r[i];
  }
  f.fx = m.fx;
  f.fy = m.fy;
  f.cx = m.cx;
  f.cy = m.cy;
  f.k1 = m.k1;
  f.k2 = m.k2;
  f.k3 = m.k3;
  f.position = {m.pose.position.x, m.pose.position.y, m.pose.position.z};
  f.orientation = {m.pose.orientation.w, m.pose.orientation.x, m.pose.orientation.y,
                   m.pose.orientation.z};
  f.width = static_cast<int>(m.width);
  f.height = static_cast<int>(m.height);
  return f;
}

/// Copies fields into a message struct (see FieldsFromMessage). Sizes are clamped to the
/// message's integer type.
template <class Msg>
void FieldsToMessage(const CameraModelFields& f, Msg* m) {
  for (std::size_t i = 0; i < 3; ++i) {
    m->c[i] = f.c[i];
    m->a[i] = f.a[i];
    m->h[i] = f.h[i];
    m->v[i] = f.v[i];
    m->o[i] = f.o[i];
    m->r[i] = f.r[i];
  }
  m->fx = f.fx;
  m->fy = f.fy;
  m->cx = f.cx;
  m->cy = f.cy;
  m->k1 = f.k1;
  m->k2 = f.k2;
  m->k3 = f.k3;
  m->pose.position.x = f.position[0];
  m->pose.position.y = f.position[1];
  m->pose.position.z = f.position[2];
  m->pose.orientation.w = f.orientation[0];
  m->pose.orientation.x = f.orientation[1];
  m->pose.orientation.y = f.orientation[2];
  m->pose.orientation.z = f.orientation[3];
  using Size = decltype(m->width);
  auto clamp = [](int v) { return static_cast<Size>(v < 0 ? 0 : (v > 65535 ? 65535 : v)); };
  m->width = clamp(f.width);
  m->height = clamp(f.height);
}

}  // namespace rover::dl::stereo
