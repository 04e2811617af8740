#pragma once
/// @file
/// Reads the camera model and coordinate-system states from a PDS3 label (attached or detached
/// `.LBL`, plain ODL text) of the MER/MSL camera products, e.g. the MSL NAVCAM EDRs.
///
/// Read from the label:
///  * GROUP = GEOMETRIC_CAMERA_MODEL_PARMS: MODEL_TYPE (CAHV, CAHVOR or CAHVORE) and
///    MODEL_COMPONENT_1..n = C, A, H, V [, O, R [, E, T, P]] (for CAHVORE component 8 is the type
///    T = 1 perspective, 2 fisheye, 3 general and component 9 the linearity parameter P), and
///    REFERENCE_COORD_SYSTEM_NAME / _INDEX: the frame the model is expressed in (for MSL
///    "ROVER_NAV_FRAME"). The model is valid for the image of this product.
///  * OBJECT = IMAGE: LINE_SAMPLES (width) and LINES (height) [px].
///  * Every GROUP or OBJECT that holds ORIGIN_OFFSET_VECTOR and ORIGIN_ROTATION_QUATERNION (MSL:
///    ROVER_COORD_SYSTEM_PARMS, SITE_COORD_SYSTEM_PARMS, RSM_COORD_SYSTEM_PARMS,
///    ARM_COORD_SYSTEM_PARMS, INITIAL_STATE_PARMS, ...), with its COORDINATE_SYSTEM_NAME and
///    REFERENCE_COORD_SYSTEM_NAME where present (empty otherwise, e.g. INITIAL_STATE_PARMS).
///
/// Conventions (PDS / MIPL): ORIGIN_OFFSET_VECTOR is the frame's origin in the reference frame
/// [m]; ORIGIN_ROTATION_QUATERNION = (s, v1, v2, v3), scalar first, rotates vectors of the frame
/// into the reference frame. So reference_from_frame = Translation(offset) * Rotation(q).
///
/// MSL frames are NOT the rover-stack convention: MSL's ROVER_NAV_FRAME is x forward, y right,
/// z down; the SITE_FRAME is x north, y east, z down. RoverFromMslNav() converts a model or pose
/// in ROVER_NAV_FRAME to the stack's rover frame (x forward, y left, z up):
///   CameraModel in_rover = Transform(label.model, RoverFromMslNav());
/// (the same rotation, diag(1, -1, -1), takes MSL's SITE_FRAME to the stack's site frame).
///
/// Errors name the file, the line and the key ("f.LBL:112: GEOMETRIC_CAMERA_MODEL_PARMS.
/// MODEL_COMPONENT_2: expected 3 numbers, got '(1,2)'"); a missing key names the group and the
/// line where the group starts.

#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "rover/base/status.hpp"
#include "rover/geometry/camera_model.hpp"

namespace rover::geometry {

/// One coordinate-system state of the label.
struct PdsCoordinateSystem {
  std::string group;           ///< GROUP/OBJECT name, e.g. "ROVER_COORD_SYSTEM_PARMS"
  std::string name;            ///< COORDINATE_SYSTEM_NAME, e.g. "ROVER_NAV_FRAME" ("" if absent)
  std::string reference_name;  ///< REFERENCE_COORD_SYSTEM_NAME, e.g. "SITE_FRAME" ("" if absent)
  Eigen::Vector3d origin_offset = Eigen::Vector3d::Zero();  ///< [m] in the reference frame
  Eigen::Quaterniond origin_rotation = Eigen::Quaterniond::Identity();  ///< frame -> reference
  int line = 0;  ///< line of the ORIGIN_OFFSET_VECTOR key

  /// reference_from_frame = Translation(origin_offset) * origin_rotation (normalised).
  Eigen::Isometry3d ReferenceFromFrame() const;
};

/// The camera-related content of a PDS3 label.
struct PdsCameraLabel {
  std::string source;                  ///< the file path (or the name given to ParsePdsCameraLabel)
  std::string model_type;              ///< "CAHV", "CAHVOR" or "CAHVORE"
  std::string model_frame;             ///< REFERENCE_COORD_SYSTEM_NAME of the model ("" if absent)
  std::vector<int> model_frame_index;  ///< REFERENCE_COORD_SYSTEM_INDEX of the model
  CameraModel model;                   ///< in `model_frame`, sized LINE_SAMPLES x LINES
  std::vector<PdsCoordinateSystem> coordinate_systems;  ///< in label order

  /// The first coordinate system with COORDINATE_SYSTEM_NAME == name, or nullptr.
  const PdsCoordinateSystem* FindByName(std::string_view name) const;
  /// The coordinate system of GROUP/OBJECT `group`, or nullptr.
  const PdsCoordinateSystem* FindByGroup(std::string_view group) const;
};

/// Parses label text; `source` names it in error messages.
Result<PdsCameraLabel> ParsePdsCameraLabel(std::string_view text, const std::string& source);

/// Reads and parses the file at `path` (NotFound if it cannot be read).
Result<PdsCameraLabel> ReadPdsCameraLabel(const std::string& path);

/// rover_from_msl_nav: rotation by pi about x, diag(1, -1, -1) (MSL x fwd, y right, z down ->
/// stack x fwd, y left, z up).
Eigen::Isometry3d RoverFromMslNav();

}  // namespace rover::geometry
