#pragma once
/// @file
/// The stereo cameras' calibration as the camera driver attaches it to every frame: one
/// left/right pair of JPL camera models (CAHV, CAHVOR or CAHVORE) per camera, where each pair is
/// mounted, and the pan/tilt mast kinematics that move the mast-head pair.
///
/// Cameras follow rover_common.idl's CameraId: 0 navcam, 1 front_hazcam, 2 rear_hazcam.
///
/// Frames (core/geometry conventions). Body-mounted pairs ("body") are given in the rover frame
/// (x forward, y left, z up). Mast-head pairs ("mast_head") are given in the mast-head frame:
/// origin on the tilt axis, x = boresight, y left, z up; at pan = tilt = 0 it is the rover frame
/// moved to the tilt axis. The head's pose in the rover frame is
///   rover_from_head = Translation(pan_joint + (0, 0, head_height)) * Rz(pan) * Ry(-tilt)
/// with pan > 0 looking left and tilt > 0 looking up (ddl/joint_state's conventions; the same
/// kinematics as the simulator's mast). The models of a mast-head pair in the rover frame are
/// geometry::Transform(model, rover_from_head).
///
/// File format (YAML, read through rover::ParamSet, so errors name file:line: key):
///   mast: {pan_joint: [x, y, z], head_height: h}          # [m], rover frame
///   navcam:                                               # also front_hazcam, rear_hazcam
///     mount: mast_head | body
///     model: CAHV | CAHVOR | CAHVORE                     # default CAHVOR
///     width: 1024                                         # [px] size the models are valid for
///     height: 1024
///     cahvore_type: perspective | fisheye | general       # CAHVORE only (default perspective)
///     cahvore_linearity: 1.0                              # CAHVORE general only
///     left:  {c: [..], a: [..], h: [..], v: [..], o: [..], r: [..], e: [..]}
///     right: {...}
/// C [m], A and O unit, H and V [px]; O and R are required for CAHVOR and CAHVORE, E for CAHVORE.
/// deploy/config/cameras.yaml is the documented default.

#include <Eigen/Geometry>
#include <string>
#include <utility>
#include <vector>

#include "rover/base/params.hpp"
#include "rover/base/status.hpp"
#include "rover/geometry/camera_model.hpp"
#include "rover/hwconfig/rover_description.hpp"
#include "rover/msg/camera.hpp"

namespace rover::ddl::camera {

/// The stereo cameras and their names (rover_common.idl CameraId): rover/msg/camera.hpp.
using msg::kNumCameras;

enum class CameraMount { kMastHead, kBody };

/// Pan/tilt mast geometry: the rover description's (defaults: pan joint (0.35, 0, 0.65) m, tilt
/// axis 0.85 m above it, i.e. 1.5 m above the rover origin on the ground).
using MastGeometry = hwconfig::MastDescription;

/// rover_from_head for mast angles pan, tilt [rad] (see the file comment).
Eigen::Isometry3d MastHeadPose(double pan, double tilt, const MastGeometry& mast);

/// One stereo pair.
struct StereoCameraCalibration {
  std::string name;  ///< msg::CameraName(index)
  CameraMount mount;
  geometry::CameraModel left;   ///< in the mount frame (head or rover)
  geometry::CameraModel right;  ///< in the mount frame

  /// Both models in the rover frame: transformed by MastHeadPose(pan, tilt, mast) for a
  /// mast-head pair, unchanged for a body pair.
  std::pair<geometry::CameraModel, geometry::CameraModel> InRover(double pan, double tilt,
                                                                  const MastGeometry& mast) const;
};

struct CameraCalibration {
  MastGeometry mast;
  std::vector<StereoCameraCalibration> cameras;  ///< index = CameraId (kNumCameras entries)
};

/// Declares every key of the file format above (no prefix).
void DeclareCameraCalibrationParams(ParamSet& params);

/// Builds the calibration from declared and loaded parameters. Errors (InvalidArgument, naming
/// file:line and key): missing O/R/E for the model kind, invalid models (geometry::CameraModel::
/// Create), and pairs whose models cannot be sent as ddl CameraModel fields
/// (msg::CameraModelFieldsFromModel, e.g. a field of view of 180 deg or more).
Result<CameraCalibration> CameraCalibrationFromParams(const ParamSet& params);

/// Declare, load `path`, build.
Result<CameraCalibration> LoadCameraCalibration(const std::string& path);

}  // namespace rover::ddl::camera
