#pragma once
/// @file
/// Mobility geometry of the six-wheel rocker-bogie rover as the locomotion library computes with
/// it (after MER's DRIVE module, Biesiadecki & Maimone 2006). The numbers come from the rover
/// description (core/hwconfig rover_description.hpp, parameters `geometry.*`), which the
/// simulator reads too; this struct holds them per wheel so that the kinematics are written,
/// and tested, for any layout.
///
/// Frames and units: the description's rover frame (x forward, y left, z up, origin on the
/// ground plane below the midpoint of the rocker pivots); metres and radians.
///
/// Layout: wheels LF LM LR RF RM RR (0..5); the four corner wheels LF LR RF RR are steered about
/// vertical axes through their wheel centres; the middle wheels LM, RM are not steered, so their
/// common axle line x = x_m (MiddleAxleX()) holds the turn centre of every arc. The reference
/// point of a drive arc is (x_m, 0) (the rover origin with the default geometry, x_m = 0).
///
/// Suspension (per side s = left, right): the rocker turns about a pivot fixed to the body at
/// (rocker_pivot.x, y_wheel, rocker_pivot.z); it carries the front wheel and the bogie pivot. The
/// bogie turns about the bogie pivot and carries the middle and rear wheels. A positive angle
/// raises the front of its link, i.e. a point q relative to the pivot moves to R(a) q with
///   R(a) = [cos a, 0, -sin a;  0, 1, 0;  sin a, 0, cos a]    (a rotation by -a about +y),
/// and the bogie angle is measured relative to the rocker. `wheel_centre` holds the centres at
/// zero rocker and bogie angles. The link pitch of a wheel (front: rocker; middle and rear:
/// rocker + bogie) is the slope of the terrain under it relative to the body, which wheel
/// odometry uses for the contact geometry.

#include <Eigen/Core>
#include <array>
#include <string>

#include "rover/base/params.hpp"
#include "rover/base/status.hpp"
#include "rover/dl/locomotion/drive_types.hpp"
#include "rover/hwconfig/rover_description.hpp"

namespace rover::dl::locomotion {

/// Rocker and bogie angles [rad]; index 0 left, 1 right.
struct SuspensionAngles {
  std::array<double, 2> rocker{};
  std::array<double, 2> bogie{};
};

struct RoverGeometry {
  /// The default rover description's geometry (wheelbase 1.25 m, track 1.0 m, middle axle at
  /// x = 0, 70 deg steering, 1 m tightest arc, 0.1 m/s rim speed).
  RoverGeometry();
  /// The geometry of `rover`: its wheel centres, pivots (x, z) and driving limits.
  explicit RoverGeometry(const hwconfig::RoverDescription& rover);

  double wheel_radius = 0.0;  ///< [m]
  /// [m] wheel centres at zero rocker/bogie angles, order LF LM LR RF RM RR.
  std::array<Eigen::Vector3d, kNumWheels> wheel_centre;
  Eigen::Vector2d rocker_pivot;  ///< [m] (x, z) on the body, both sides
  Eigen::Vector2d bogie_pivot;   ///< [m] (x, z) at zero angles, both sides
  double max_steer_angle = 0.0;  ///< [rad] |steer| limit of the corner wheels
  double min_turn_radius = 0.0;  ///< [m] smallest arc radius (of the reference point)
  double max_wheel_speed = 0.0;  ///< [m/s] fastest rim speed a drive motor may be asked for
  /// [rad] the instrument arm's stowed joint angles (azimuth, shoulder, elbow, wrist)
  std::array<double, 4> arm_stow{};

  /// Checks finiteness, the wheel layout (left y > 0, right y < 0, front > middle > rear per side,
  /// LM and RM on one axle), pivot placement, min_turn_radius > every |y_i| (so no wheel is
  /// inside the turn centre) and that both the Ackermann angles at the minimum radius and the
  /// turn-in-place angles are within max_steer_angle. Messages start with the field name.
  Status Validate() const;

  /// [1/m] 1 / min_turn_radius.
  double MaxCurvature() const { return 1.0 / min_turn_radius; }
  /// [m] x of the unsteered middle axle (holds every turn centre).
  double MiddleAxleX() const { return wheel_centre[1].x(); }
  /// 0 for the left wheels (0..2), 1 for the right ones.
  static int Side(int wheel) { return wheel < 3 ? 0 : 1; }
  /// Wheel centre [m] in the rover frame for the given suspension angles.
  /// Precondition: 0 <= wheel < 6.
  Eigen::Vector3d WheelCentre(int wheel, const SuspensionAngles& s) const;
  /// Pitch [rad] of the link carrying `wheel` relative to the body (front up positive).
  static double LinkPitch(int wheel, const SuspensionAngles& s);
};

/// Field-level validation result: the struct member, the rover description's parameter key
/// (without prefix) closest to it, and the problem. Empty `field` means valid.
struct GeometryIssue {
  std::string field;
  std::string key;
  std::string message;
};
GeometryIssue CheckRoverGeometry(const RoverGeometry& g);

/// Declares the rover description's parameters under `prefix` (e.g. "geometry."):
/// DeclareParams<hwconfig::RoverDescription> (keys in core/hwconfig/README.md: wheel_radius,
/// front_wheel_x, half_track, rocker_pivot_x, ..., max_steer_angle_deg, min_turn_radius,
/// max_wheel_speed, mast.*, navcam.*, front_hazcam.*, rear_hazcam.*).
void DeclareRoverGeometryParams(ParamSet& params, const std::string& prefix = "geometry.");

/// Reads and validates the rover description and builds its geometry. Errors name the origin of
/// the offending key, e.g.
///   "drive.yaml:7: key 'geometry.min_turn_radius': min_turn_radius = 0.4 m must exceed the
///    largest wheel |y|, half_track (0.5)".
Result<RoverGeometry> RoverGeometryFromParams(const ParamSet& params,
                                              const std::string& prefix = "geometry.");

}  // namespace rover::dl::locomotion
