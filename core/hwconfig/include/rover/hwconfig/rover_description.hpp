#pragma once
/// @file
/// The rover description: the one definition of the rover's shape that the simulator (Simbody
/// model, camera mounts, renderer), the device layer (locomotion kinematics, wheel odometry) and
/// the application layer (terrain assessment, planning) all read. Defaults are the simulated
/// MER/FIDO-like rover; parameters `geometry.*` (RoverDescription::BindParams) override them.
///
/// Rover frame R: x forward, y left, z up. The ground plane is the plane the six wheels stand on
/// when the rover rests on flat ground with zero rocker and bogie angles and no sinkage; the
/// origin lies on it, below the midpoint of the two rocker (differential) pivots. Every wheel
/// centre is then at z = wheel_radius. For the default rover the origin is also the centre of the
/// wheel contact rectangle and lies on the middle axle.
///
/// Units: metres, radians, seconds (parameter keys ending in _deg are degrees). The rover is
/// mirror-symmetric about its x-z plane: quantities with a y are given for the left side (y > 0)
/// and the right side is their mirror image (y -> -y).
///
/// Indices (rover_hw.idl): wheels 0 LF, 1 LM, 2 LR, 3 RF, 4 RM, 5 RR (drive motor i turns wheel
/// i); steered wheels j = 0 LF, 1 LR, 2 RF, 3 RR (steer motor 6 + j); motors 10 mast pan and
/// 11 mast tilt (hw_bus.hpp has the motor enum); sides 0 left, 1 right.
///
/// Joint conventions (encoder counts, ddl/joint_state and the simulator's joints agree on them):
///   drive      + rolls the rover forward, on both sides;
///   steer      about the vertical axis through the wheel centre; + turns the wheel's front left;
///   rocker     about the rocker pivot's y axis; + raises the front of the rocker (front wheel up,
///              bogie pivot down); the differential holds rocker_left = -rocker_right;
///   bogie      about the bogie pivot's y axis, relative to the rocker; + raises the front of the
///              bogie (middle wheel up, rear wheel down);
///   mast pan   about +z through mast.pan_joint; + looks left;
///   mast tilt  about the head's -y axis at the tilt axis; + looks up.
///
/// Footprint and turn circle (what terrain assessment and planning need):
///   GroundFootprint()   the smallest rectangle of R's x-y plane, sides along x and y, that holds
///                       the vertical projection of the rover standing with zero suspension
///                       angles and straight wheels: each wheel (2 wheel_radius long, wheel_width
///                       wide, about its centre), the body box, the mast and camera mounts.
///   TurnInPlaceCircle() the disc of R's x-y plane about the turn-in-place centre (x of the
///                       unsteered middle axle, y = 0) that holds the rover at every moment of a
///                       turn in place, including the corner wheels being steered: each corner
///                       wheel counts as the disc of radius hypot(wheel_radius, wheel_width / 2)
///                       about its centre (any steering angle), the middle wheels and the body as
///                       their rectangles. MER's terrain assessment modelled its rover by such a
///                       disc (2.6 m across, solar arrays included); this rover's is 1.90 m.
///   ContactParts()      the parts that can touch a rock standing on the ground, as plan-view
///                       shapes of R's x-y plane, each with the height above the ground plane
///                       below which a rock passes under it (its clearance):
///                         wheel_<i>  six discs of radius hypot(wheel_radius, wheel_width / 2)
///                                    about the wheel centres (any steering angle), clearance 0;
///                         bogie_<s>  the band between the rear and middle wheel centres,
///                                    wheel_width wide on the wheel line, clearance 0 (its links
///                                    come down to the wheel centres);
///                         rocker_<s> the band between the middle and front wheel centres,
///                                    clearance = the rocker link's height where it leaves the
///                                    front wheel's disc (pivot to steering joint, a straight
///                                    line);
///                         body       the body box's outline, clearance BellyClearance().
///                       The mast and camera mounts stand above the body and are left out.
///                       Heights are at zero suspension angles; a user that needs a margin for
///                       articulation subtracts its own.
///
/// Camera mounts. A stereo pair's frame P has x along the boresight, y left, z up, its origin
/// midway between the two optical centres; the left camera sits at +baseline/2 along P's y:
///   parent_from_pair = Translation(position) * Rz(yaw) * Ry(depression)
/// with yaw about the parent's z (0 = the parent's x, pi = backwards) and depression the
/// boresight's angle below the parent's x-y plane. The HAZCAM pairs' parent is R; the NAVCAM
/// pair's is the mast-head frame H (origin on the tilt axis, x boresight, y left, z up; at
/// pan = tilt = 0 it is R moved to the tilt axis):
///   rover_from_head = Translation(mast.pan_joint + (0, 0, mast.head_height)) * Rz(pan) * Ry(-tilt)
/// Lens models (focal length, distortion, image size) are calibration, not description: they
/// live in deploy/config/cameras.yaml and sim/render.
///
/// This header compiles as C++17 too (the simulator's Simbody translation unit includes it).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "rover/base/status.hpp"
#include "rover/base/units.hpp"
#include "rover/hwconfig/arm_description.hpp"
#include "rover/hwconfig/hw_bus.hpp"

namespace rover {
template <class Options>
class ParamBinder;
}  // namespace rover

namespace rover::hwconfig {

/// One degree [rad] (the scale of the *_deg parameter keys).
inline constexpr int kNumWheels = 6;
/// Steered (corner) wheels; the middle wheels LM and RM are fixed.
inline constexpr int kNumSteered = 4;

/// Wheel indices; wheel i is turned by drive motor hw::kDriveLF + i.
enum WheelIndex : int { kWheelLF = 0, kWheelLM, kWheelLR, kWheelRF, kWheelRM, kWheelRR };
/// Sides of the suspension (rocker, bogie) and of the wheels.
enum Side : int { kLeft = 0, kRight = 1 };

/// Wheel of steer actuator j (steer motor hw::kSteerLF + j): LF, LR, RF, RR.
inline constexpr std::array<int, kNumSteered> kSteeredWheel = {kWheelLF, kWheelLR, kWheelRF,
                                                               kWheelRR};
/// Motor index of steer actuator j (0..3).
constexpr int SteerMotor(int j) { return hw::kSteerLF + j; }
/// Wheel steered by motor `motor` (kSteerLF..kSteerRR); -1 for every other motor.
constexpr int SteeredWheelOfMotor(int motor) {
  return motor >= hw::kSteerLF && motor <= hw::kSteerRR ? kSteeredWheel[motor - hw::kSteerLF] : -1;
}
/// Side of a wheel: kLeft for 0..2, kRight for 3..5.
constexpr int SideOfWheel(int wheel) { return wheel < 3 ? kLeft : kRight; }
/// Bit masks over motor indices: the six drive motors, the four steer motors, both.
inline constexpr std::uint16_t kDriveMotorMask = 0x003F;
inline constexpr std::uint16_t kSteerMotorMask = 0x03C0;
inline constexpr std::uint16_t kMobilityMotorMask = kDriveMotorMask | kSteerMotorMask;
/// "LF", "LM", "LR", "RF", "RM", "RR"; "?" outside 0..5.
const char* WheelName(int wheel);

/// A rectangle of the rover frame's x-y plane with sides along x and y [m].
struct Footprint {
  double min_x = 0.0, max_x = 0.0;
  double min_y = 0.0, max_y = 0.0;

  double Length() const { return max_x - min_x; }
  double Width() const { return max_y - min_y; }
  /// True if (x, y) lies inside or on the border.
  bool Contains(double x, double y) const {
    return x >= min_x && x <= max_x && y >= min_y && y <= max_y;
  }
};

/// A disc of the rover frame's x-y plane [m].
struct TurnCircle {
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  double radius = 0.0;

  double Diameter() const { return 2.0 * radius; }
};

/// A part of the rover that can touch a rock (ContactParts(); see the file comment): a disc or an
/// axis-aligned box of the rover frame's x-y plane [m], and its clearance above the ground [m].
struct ContactPart {
  std::string name;
  bool is_disc = false;
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();  ///< disc centre
  double radius = 0.0;                               ///< disc radius
  Eigen::Vector2d min = Eigen::Vector2d::Zero();     ///< box corner (x, y smallest)
  Eigen::Vector2d max = Eigen::Vector2d::Zero();     ///< box corner (x, y largest)
  double clearance = 0.0;  ///< a rock lower than this passes under the part

  /// Distance from `p` to the part's outline, 0 inside [m].
  double DistanceTo(const Eigen::Vector2d& p) const {
    if (is_disc) {
      const double d = (p - centre).norm() - radius;
      return d > 0.0 ? d : 0.0;
    }
    return (p - p.cwiseMax(min).cwiseMin(max)).norm();
  }
};

/// A stereo pair's mount in its parent frame (see the file comment).
struct StereoMount {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< [m] pair-frame origin
  double yaw = 0.0;         ///< [rad] boresight azimuth about the parent's z
  double depression = 0.0;  ///< [rad] boresight below the parent's x-y plane (+ looks down)
  double baseline = 0.1;    ///< [m] distance between the two optical centres

  /// parent_from_pair = Translation(position) * Rz(yaw) * Ry(depression).
  Eigen::Isometry3d Pose() const;
  /// Optical centre of the left (kLeft, +y of the pair) or right camera in the parent frame.
  Eigen::Vector3d CameraCentre(int side) const;
  /// Finite position within 10 m, |yaw| <= 360 deg, |depression| <= 90 deg, baseline in
  /// (0, 5] m; messages start with `name` + "." + the field.
  Status Validate(const std::string& name) const;
};

/// The pan/tilt mast (see the file comment for the head pose).
struct MastDescription {
  Eigen::Vector3d pan_joint{0.35, 0.0, 0.65};  ///< [m] in R; the pan axis is vertical through it
  double head_height = 0.85;  ///< [m] tilt axis (head frame origin) above the pan joint

  /// rover_from_head for mast angles `pan`, `tilt` [rad].
  Eigen::Isometry3d HeadPose(double pan, double tilt) const;
  /// pan_joint finite within 10 m, head_height in [0, 10] m ("mast.pan_joint[1] is nan ...").
  Status Validate() const;
};

/// The rover: wheels, suspension, body, mast, camera mounts and driving limits. All positions are
/// in the rover frame at zero suspension angles, left side (see the file comment).
struct RoverDescription {
  // Wheels.
  double wheel_radius = 0.125;   ///< [m]
  double wheel_width = 0.16;     ///< [m]
  double front_wheel_x = 0.625;  ///< [m] wheel centres along x (wheelbase 1.25 m)
  double middle_wheel_x = 0.0;   ///< [m] the unsteered middle axle (holds every turn centre)
  double rear_wheel_x = -0.625;  ///< [m]
  double half_track = 0.5;       ///< [m] |y| of every wheel centre (track 1.0 m)
  double steer_height = 0.17;    ///< [m] steering joint above the wheel centre, on its axis

  // Suspension: rocker pivot on the body (x, |y|, z); bogie pivot on the rocker, in the wheel
  // plane y = +-half_track (x, z). Mechanical stops at +-limit.
  double rocker_pivot_x = 0.0;     ///< [m] (the front wheel : bogie pivot lever is 2 : 1)
  double rocker_pivot_y = 0.42;    ///< [m]
  double rocker_pivot_z = 0.45;    ///< [m]
  double bogie_pivot_x = -0.3125;  ///< [m] midway between middle and rear wheels
  double bogie_pivot_z = 0.30;     ///< [m]
  double rocker_limit = 0.6;       ///< [rad]
  double bogie_limit = 0.8;        ///< [rad]

  // Body (the warm electronics box): a box with sides along the rover axes.
  Eigen::Vector3d body_size{1.0, 0.7, 0.30};     ///< [m] x, y, z extents
  Eigen::Vector3d body_centre{0.0, 0.0, 0.50};   ///< [m] (also the body's centre of mass)
  Eigen::Vector3d imu_position{0.0, 0.0, 0.45};  ///< [m] the IMU's reference point

  // Mast and cameras (MER-like: NAVCAM 20 cm baseline on a 1.5 m mast, HAZCAMs 10 cm at 0.5 m
  // looking 45 deg down).
  MastDescription mast;
  StereoMount navcam = {Eigen::Vector3d(0.05, 0.0, 0.0), 0.0, 0.0, 0.20};  ///< in the head frame
  StereoMount front_hazcam = {Eigen::Vector3d(0.52, 0.0, 0.50), 0.0, 45.0 * kDegree, 0.10};
  StereoMount rear_hazcam = {Eigen::Vector3d(-0.52, 0.0, 0.50), 180.0 * kDegree, 45.0 * kDegree,
                             0.10};
  /// The instrument arm (arm_description.hpp).
  ArmDescription arm;

  // Driving limits (locomotion enforces them; planners choose within them).
  double max_steer_angle = 70.0 * kDegree;  ///< [rad] corner-wheel steering limit for driving
  double min_turn_radius = 1.0;             ///< [m] tightest arc (of the middle-axle centre point)
  double max_wheel_speed = 0.1;             ///< [m/s] fastest rim speed a drive motor is asked for

  /// Ranges, the wheel and pivot layout (front > middle > rear; bogie pivot between rear and
  /// middle wheels, rocker pivot between bogie pivot and front wheel; pivots above the wheel
  /// centres; the body above the ground), min_turn_radius > half_track, and that max_steer_angle
  /// covers both the inner corner wheel on the tightest arc and turning in place. Messages start
  /// with the field (= parameter key, without _deg) they concern.
  Status Validate() const;
  /// Parameters (keys = field names, angles in degrees as *_deg; nested ones as mast.pan_joint,
  /// front_hazcam.depression_deg): DeclareParams<RoverDescription>(params, "geometry.").
  static void BindParams(ParamBinder<RoverDescription>& b);

  /// Wheel centre at zero suspension angles (x_i, +-half_track, wheel_radius).
  /// Precondition: 0 <= wheel < kNumWheels.
  Eigen::Vector3d WheelCentre(int wheel) const;
  /// Rocker pivot of a side (rocker_pivot_x, +-rocker_pivot_y, rocker_pivot_z).
  Eigen::Vector3d RockerPivot(int side) const;
  /// Bogie pivot of a side at zero suspension angles (bogie_pivot_x, +-half_track, bogie_pivot_z).
  Eigen::Vector3d BogiePivot(int side) const;
  /// front_wheel_x - rear_wheel_x [m].
  double Wheelbase() const { return front_wheel_x - rear_wheel_x; }
  /// 2 half_track [m] (between wheel centres).
  double Track() const { return 2.0 * half_track; }
  /// Height of the body's underside above the ground plane [m] (MER: 0.29 m).
  double BellyClearance() const { return body_centre.z() - 0.5 * body_size.z(); }
  /// [1/m] 1 / min_turn_radius.
  double MaxCurvature() const { return 1.0 / min_turn_radius; }
  /// The turn-in-place centre (middle_wheel_x, 0) [m].
  Eigen::Vector2d TurnCentre() const { return Eigen::Vector2d(middle_wheel_x, 0.0); }
  /// See the file comment.
  Footprint GroundFootprint() const;
  /// See the file comment.
  TurnCircle TurnInPlaceCircle() const;
  /// See the file comment: 6 wheels, 2 bogies, 2 rockers, the body, in that order.
  std::vector<ContactPart> ContactParts() const;
  /// rover_from_pair of the NAVCAM pair at mast angles `pan`, `tilt` [rad].
  Eigen::Isometry3d NavcamPose(double pan, double tilt) const;

  /// The boxes the arm must keep out of (arm_description.hpp): "body", "front_hazcam", "mast",
  /// "wheel_LF" .. "wheel_RR".
  std::vector<KeepOutBox> ArmKeepOut() const;
  /// OK when every link of the arm at `q` keeps arm.link_radius + arm.clearance from every
  /// keep-out box (and the upper arm and forearm from the ground plane); otherwise
  /// kFailedPrecondition naming the link, the part and the distance. Limits are not checked here.
  Status CheckArmPose(const ArmAngles& q) const;
  /// CheckArmPose along the straight joint-space line from `from` to `to` (both ends included,
  /// steps of at most arm.check_step); the message says where along the move it fails.
  Status CheckArmMove(const ArmAngles& from, const ArmAngles& to) const;
};

}  // namespace rover::hwconfig
