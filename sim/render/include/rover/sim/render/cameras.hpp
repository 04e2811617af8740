#pragma once
/// @file
/// The simulated rover's stereo cameras: MER-like default definitions (the "calibration file"
/// that the simulator renders with and that the DDL camera driver attaches to its frames), the
/// pan/tilt mast kinematics, and CameraPairSpec, what Renderer::RenderStereoPair takes.
///
/// Frames and mounts are the rover description's (core/hwconfig rover_description.hpp): rover
/// frame x forward, y left, z up, origin on the ground below the rocker pivots; mast-head frame
/// with origin on the tilt axis, x = boresight, y left, z up, placed by
///   rover_from_head = Translation(pan_joint + (0, 0, head_height)) * Rz(pan) * Ry(-tilt)
/// (pan > 0 looks left, tilt > 0 looks up); each pair's optical centres and boresight from its
/// StereoMount. This file adds the lenses. Camera models follow core/geometry (camera frame x
/// right, y down, z forward; pixel centre convention (0, 0)).
///
/// Default cameras (DefaultStereoCameras(1024) on the default description; README.md has the
/// table):
///   navcam:       CAHVOR, 45.0 deg square field, f = 1236.1 px, mild barrel distortion
///                 (r1 = -0.01), 0.20 m baseline, 1024 x 1024, on the mast head 0.05 m in front
///                 of the tilt axis; head 1.50 m above the rover origin (the ground).
///   front_hazcam: CAHVOR, 120 deg across the width (about 137 deg over the diagonal),
///                 f = 304.75 px with r1 = -0.01, 0.10 m baseline, 1024 x 1024, 0.50 m above the
///                 ground at x = +0.52 m, boresight 45 deg below horizontal; rigid on the body.
///                 (MER's flight HAZCAM models were CAHVOR too; the DDS CameraModel carries
///                 CAHVOR, and these equal deploy/config/cameras.yaml, checked by a test.)
///   rear_hazcam:  the same looking backwards from x = -0.52 m.
/// These follow MER (Maki et al. 2003): NAVCAM 45 deg FOV, 20 cm baseline, 1024 x 1024 CCD on
/// a mast ~1.5 m high; HAZCAMs 124 deg FOV, 10 cm baseline, ~0.5 m high, 45 deg down.

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "rover/base/status.hpp"
#include "rover/geometry/camera_model.hpp"
#include "rover/hwconfig/rover_description.hpp"
#include "rover/sim/heightfield.hpp"

namespace rover::sim::render {

/// Where a stereo pair is mounted.
enum class CameraMount {
  kMastHead,  ///< models in the mast-head frame; moves with pan/tilt
  kBody,      ///< models in the rover frame (rigid on the body)
};

/// One stereo pair of the calibration: name, mount and the two models.
struct StereoCameraDefinition {
  std::string name;  ///< "navcam", "front_hazcam", "rear_hazcam"
  CameraMount mount = CameraMount::kBody;
  geometry::CameraModel left;   ///< in the mount frame (head frame or rover frame)
  geometry::CameraModel right;  ///< in the mount frame
};

/// Mast joint angles [rad].
struct MastState {
  double pan = 0.0;   ///< + looks left
  double tilt = 0.0;  ///< + looks up
};

/// rover_from_head for the given joint angles (see the file comment).
Eigen::Isometry3d MastHeadPose(const MastState& mast, const hwconfig::MastDescription& geometry = {});

/// A stereo pair ready to render: models in a head frame plus the head's pose in the rover
/// frame (identity if the models are already in the rover frame).
struct CameraPairSpec {
  geometry::CameraModel left;
  geometry::CameraModel right;
  Eigen::Isometry3d rover_from_head = Eigen::Isometry3d::Identity();
  /// The models in the rover frame (geometry::Transform by rover_from_head).
  geometry::CameraModel LeftInRover() const;
  geometry::CameraModel RightInRover() const;
};

/// The MER-like default cameras for a square image of `image_size` pixels (the models are
/// defined at 1024 and resampled with geometry::Scale, so 512 is the 2x2-binned camera),
/// mounted where `rover` says. Precondition: 16 <= image_size <= 4096.
std::vector<StereoCameraDefinition> DefaultStereoCameras(
    int image_size = 1024, const hwconfig::RoverDescription& rover = {});

/// The definition named `name` (NotFound naming the known names otherwise).
Result<StereoCameraDefinition> FindStereoCamera(const std::vector<StereoCameraDefinition>& cameras,
                                                const std::string& name);

/// Pair spec of a definition: mast-mounted pairs get MastHeadPose(mast, geometry), body pairs
/// the identity. Errors: non-finite mast angles, an invalid mast geometry.
Result<CameraPairSpec> MakeCameraPairSpec(const StereoCameraDefinition& camera,
                                          const MastState& mast = {},
                                          const hwconfig::MastDescription& geometry = {});

/// Rover pose in the site frame from (x, y, yaw): origin at height z, zero roll and pitch.
Eigen::Isometry3d RoverPoseFromXyYaw(double x, double y, double z, double yaw);

/// Rover pose resting on `ground` at (x, y) with heading `yaw` (a renderer has no physics; for
/// tools and tests): the rover plane is fitted to the ground heights under the six wheels of
/// `rover`, the origin sits on that plane below (x, y).
Eigen::Isometry3d RoverPoseOnGround(const terrain::HeightField& ground, double x, double y,
                                    double yaw, const hwconfig::RoverDescription& rover = {});

}  // namespace rover::sim::render
