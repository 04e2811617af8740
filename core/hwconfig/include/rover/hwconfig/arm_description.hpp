#pragma once
/// @file
/// The instrument arm: a 4-DOF arm (FIDO's) on the front of the body, its kinematics and the
/// volumes it must not sweep through. Read by the simulator (the kinematic arm, its contact
/// switch), dl/arm (placement, refusals) and the runner (the instrument's truth).
///
/// Joints (motors hw::kArmAzimuth .. hw::kArmWrist, arm angles q0..q3 in ddl/joint_state order):
///   q0 azimuth  about the vertical axis through `shoulder`; + turns the arm to the left;
///   q1 shoulder elevation of the upper arm above the rover's x-y plane; + raises it;
///   q2 elbow    of the forearm relative to the upper arm; + raises the forearm;
///   q3 wrist    of the instrument relative to the forearm; + raises the instrument.
/// All pitch joints turn about the same horizontal axis h = (-sin q0, cos q0, 0), so the arm
/// stays in the vertical plane through the azimuth axis with in-plane direction
/// u = (cos q0, sin q0, 0). With d(a) = cos(a) u + sin(a) z (rover frame R):
///   S (shoulder pivot) = shoulder
///   E (elbow)          = S + upper_arm d(q1)
///   W (wrist)          = E + forearm d(q1 + q2)
///   F (instrument face centre, the reach point) = W + tool_length d(q1 + q2 + q3)
/// and the instrument looks along d(q1 + q2 + q3): placements use q1 + q2 + q3 = -pi/2 (face
/// down). The links sit side by side at the elbow, so they never meet each other.
///
/// Inverse kinematics for a face-down placement at F: W = F + tool_length z; q0 = atan2 of W
/// about the azimuth axis; in the arm plane (r, z) = (horizontal distance from the axis,
/// height above S) the two-link solution with the elbow above the line S-W:
///   c2 = (r^2 + z^2 - upper^2 - fore^2) / (2 upper fore),  q2 = -acos(c2),
///   q1 = atan2(z, r) + atan2(fore sin|q2|, upper + fore cos q2),  q3 = -pi/2 - q1 - q2.
///
/// Swept volumes. Each link is a capsule of radius `link_radius` about its segment (S-E, E-W,
/// W-F). The rover's own volumes are axis-aligned boxes of R (ArmKeepOut()): the body, the
/// front HAZCAM mount, the mast column and the six wheels at zero suspension and steering
/// angles; and the ground plane z = 0 for the upper arm and forearm (the instrument may touch
/// the ground: that is its job). A pose is clear when every capsule stays `clearance` away
/// from every box; a move is clear when every pose on the straight joint-space line between
/// its ends is (ddl-motor's synchronised moves follow that line to within its profile shape),
/// checked at steps of at most `check_step` rad of the largest joint change.
///
/// Units: metres, radians. Compiles as C++17 (rover_description.hpp includes it).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <string>
#include <vector>

#include "rover/base/status.hpp"

namespace rover::hwconfig {

inline constexpr int kArmJoints = 4;
using ArmAngles = std::array<double, kArmJoints>;

/// "azimuth", "shoulder", "elbow", "wrist"; "?" outside 0..3.
const char* ArmJointName(int joint);

/// A box of the rover frame with sides along its axes [m].
struct KeepOutBox {
  std::string name;
  Eigen::Vector3d min = Eigen::Vector3d::Zero();
  Eigen::Vector3d max = Eigen::Vector3d::Zero();
  /// Distance from p to the box, 0 inside [m].
  double DistanceTo(const Eigen::Vector3d& p) const {
    return (p - p.cwiseMax(min).cwiseMin(max)).norm();
  }
};

/// The arm's four points for some joint angles (see the file comment).
struct ArmPoints {
  Eigen::Vector3d shoulder, elbow, wrist, face;
  Eigen::Vector3d look;  ///< unit direction the instrument looks along
};

/// The microscopic imager on the instrument face (FIDO's colour microscopic imager, here
/// monochrome): a pinhole camera at the face centre looking along ArmPoints::look, image +x
/// along the arm's horizontal direction u when face down, focused on the plane
/// `working_distance` ahead of the face. Defocus follows a thin lens with entrance pupil
/// `aperture`: a surface at distance d [m] along the look direction is blurred into a disc of
///   c(d) = focal_px * aperture * |d - s| / (d * s)   pixels,  s = working_distance,
/// so the depth of field (c <= max_sharp_blur_px) is about s +- DepthOfFieldHalf().
struct MicroscopeOptics {
  int image_size = 256;            ///< [px] square image
  double focal_px = 750.0;         ///< [px] 0.08 mm per pixel at the working distance
  double working_distance = 0.06;  ///< [m] face to the plane of best focus
  double aperture = 0.004;         ///< [m] entrance-pupil diameter
  double max_sharp_blur_px = 2.0;  ///< [px] blur disc still counted as in focus

  /// Blur-disc diameter [px] of a surface `distance` [m] from the lens (> 0).
  double BlurDiameterPx(double distance) const;
  /// [m] half the depth of field: the defocus nearer than the working distance at which the
  /// blur reaches max_sharp_blur_px (the farther side is slightly deeper).
  double DepthOfFieldHalf() const;
};

struct ArmDescription {
  Eigen::Vector3d shoulder{0.62, 0.0, 0.45};  ///< [m] shoulder pivot in R (on the azimuth axis)
  double upper_arm = 0.35;                    ///< [m] shoulder to elbow
  double forearm = 0.35;                      ///< [m] elbow to wrist
  double tool_length = 0.10;                  ///< [m] wrist to the instrument's face centre
  double link_radius = 0.035;                 ///< [m] capsule radius of every link
  /// [m] radius of the instrument face's contact ring: the contact switch closes when any
  /// point of the ring (or the centre) reaches a surface.
  double face_radius = 0.02;
  /// [m] the contact switch closes when the face's centre or a point of its ring comes within
  /// this of a surface (its travel): a face stopped on contact stands about this high above it.
  double contact_standoff = 0.003;
  MicroscopeOptics imager;
  double clearance = 0.01;                    ///< [m] extra distance a pose keeps from keep-outs
  double check_step = 0.02;                   ///< [rad] swept-volume sampling step
  /// Joint limits [rad], azimuth, shoulder, elbow, wrist.
  ArmAngles min_angle{-1.6, -1.0, -3.05, -3.1};
  ArmAngles max_angle{1.6, 1.65, 0.3, 3.1};
  /// Stowed pose: upper arm up, forearm folded down beside it, instrument up; inside the
  /// rover's ground footprint and above the belly, so driving with it stowed changes nothing.
  ArmAngles stow{0.0, 1.5, -3.0, 3.0};

  /// Positive lengths below 2 m, link_radius, face_radius and clearance in [0, 0.2] m,
  /// contact_standoff in [0, 0.02] m,
  /// check_step in (0, 0.2] rad, min < max, stow inside the limits; imager: image_size
  /// [16, 2048] px, focal_px (0, 1e5], working_distance (0, 0.5] m, aperture (0, 0.05] m,
  /// max_sharp_blur_px (0, 20]. Messages start with "arm." + the field.
  Status Validate() const;
  ArmPoints Forward(const ArmAngles& q) const;
  /// The microscopic imager's camera frame in R (columns x = image right, y = image down,
  /// z = the look direction; origin the face centre): x = h (the pitch axis, rover left when
  /// q0 = 0), y = look x h (away from the rover when face down). See MicroscopeOptics.
  Eigen::Isometry3d ImagerPose(const ArmAngles& q) const;
  /// Face-down placement of the instrument's face at `face` (R). Errors (kOutOfRange) name the
  /// point and why: out of reach (too far / too near), on the azimuth axis, or a joint beyond
  /// its limit (named, with the value).
  Result<ArmAngles> FaceDown(const Eigen::Vector3d& face) const;
  /// kOutOfRange naming the joint and value when any angle is outside its limits or not finite.
  Status CheckLimits(const ArmAngles& q) const;
};

}  // namespace rover::hwconfig
