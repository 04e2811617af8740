#pragma once
/// @file
/// Parameters of the simulated MER-like six-wheel rocker-bogie rover: geometry, masses, contact,
/// motors, integrator. Defaults follow MER (about 180 kg, wheel radius 0.125 m, wheelbase
/// 1.25 m, track 1 m); README.md has the table.
///
/// Chassis (rover) frame C: x forward, y left, z up; origin at nominal ground level below the
/// midpoint of the two rocker pivots, i.e. on flat ground with zero rocker/bogie angles and no
/// sinkage the origin touches the ground. All positions below are in C at zero joint angles.
///
/// Joint sign conventions (right-hand rule about the axis named):
///   wheel (drive)  about +y of its carrier: positive rolls the rover forward (both sides);
///   steering       about +z: positive turns the wheel's front to the left;
///   rocker, bogie  about +y of the chassis / rocker: positive pitches the part nose-down;
///                  the differential keeps rocker_left = -rocker_right (stiff coupling);
///   mast pan       about +z: positive looks left;   mast tilt about -y: positive looks up.

#include <Eigen/Core>
#include <array>

#include "rover/base/status.hpp"
#include "rover/sim/physics/motor_controller.hpp"
#include "rover/sim/physics/terrain_contact.hpp"

namespace rover::sim {

inline constexpr int kNumWheels = 6;
inline constexpr int kNumMotors = 12;

/// Wheel indices: 0..5 = LF LM LR RF RM RR (same as their drive motors).
enum WheelId : int { kWheelLF = 0, kWheelLM, kWheelLR, kWheelRF, kWheelRM, kWheelRR };

/// Motor indices (the order of hw/* motor topics).
enum MotorId : int {
  kDriveLF = 0,
  kDriveLM = 1,
  kDriveLR = 2,
  kDriveRF = 3,
  kDriveRM = 4,
  kDriveRR = 5,
  kSteerLF = 6,
  kSteerLR = 7,
  kSteerRF = 8,
  kSteerRR = 9,
  kMastPan = 10,
  kMastTilt = 11,
};
/// "drive_lf", ..., "mast_tilt"; "?" outside 0..11.
const char* MotorName(int motor);
/// Wheel steered by steering motor 6..9 (0, 2, 3, 5); -1 for other motors.
int SteeredWheel(int motor);

struct RoverGeometry {
  double wheel_radius = 0.125;   ///< [m]
  double wheel_width = 0.16;     ///< [m]
  double front_wheel_x = 0.625;  ///< [m] wheel centres along x
  double middle_wheel_x = 0.0;
  double rear_wheel_x = -0.625;
  double half_track = 0.5;      ///< [m] |y| of the wheel centres
  double rocker_pivot_x = 0.0;  ///< [m] differential (rocker) pivots at (x, +-y, z)
  double rocker_pivot_y = 0.42;
  double rocker_pivot_z = 0.45;
  double bogie_pivot_x = -0.3125;  ///< [m] bogie pivots at (x, +-half_track, z)
  double bogie_pivot_z = 0.30;
  double steer_height = 0.17;  ///< [m] steering joint above the wheel centre (vertical axis)
  Eigen::Vector3d chassis_box_size{1.0, 0.7, 0.30};    ///< [m] body box (belly contact, inertia)
  Eigen::Vector3d chassis_box_center{0.0, 0.0, 0.50};  ///< [m] = chassis CoM
  Eigen::Vector3d mast_base{0.35, 0.0, 0.65};  ///< [m] pan joint (vertical axis) on the deck
  double mast_height = 0.85;  ///< [m] tilt axis above the pan joint (head at ~1.5 m)
  Eigen::Vector3d hazcam_front{0.52, 0.0, 0.50};  ///< [m] front HAZCAM pair centre
  Eigen::Vector3d hazcam_rear{-0.52, 0.0, 0.50};  ///< [m] rear HAZCAM pair centre
  double hazcam_depression = 0.785398;            ///< [rad] boresight below horizontal (45 deg)
  Eigen::Vector3d imu_station{0.0, 0.0, 0.45};    ///< [m] IMU location (specific force point)
  double rocker_limit = 0.6;                      ///< [rad] hard stops at +-limit
  double bogie_limit = 0.8;                       ///< [rad]

  Status Validate() const;
};

struct RoverMasses {
  double chassis = 137.0;      ///< [kg] body, electronics, deck (box inertia)
  double rocker = 5.0;         ///< [kg] each
  double bogie = 3.0;          ///< [kg] each
  double steer_bracket = 1.5;  ///< [kg] each of four
  double wheel = 2.5;          ///< [kg] each of six (solid cylinder inertia)
  double mast_pan = 3.0;       ///< [kg] mast tube (rotates with pan)
  double mast_head = 3.0;      ///< [kg] camera bar (rotates with pan and tilt)

  double Total() const {
    return chassis + 2 * rocker + 2 * bogie + 4 * steer_bracket + 6 * wheel + mast_pan + mast_head;
  }
  Status Validate() const;
};

enum class IntegratorMethod {
  /// Simbody SemiExplicitEuler2: error-controlled (two half steps against one full step),
  /// steps end on every control tick and shrink when the accuracy demands it.
  kSemiExplicitEuler2 = 0,
  /// Simbody SemiExplicitEuler: one fixed step per control tick (1 ms), no error control;
  /// ~2.4x faster; on the benchmark runs it matched SEE2 to 3 digits of slip and 3 um of
  /// position after 60 s (README.md). Keep SEE2 when making contacts or gains stiffer.
  kSemiExplicitEulerFixed = 1,
};

struct IntegratorParams {
  IntegratorMethod method = IntegratorMethod::kSemiExplicitEulerFixed;  // 2.4x faster, same results
  double accuracy = 1e-3;           ///< SEE2 relative accuracy
  double control_rate_hz = 1000.0;  ///< motor controller rate
  double settle_time = 2.0;         ///< [s] settling after placing the rover (Reset)
  double max_advance = 3600.0;      ///< [s] longest single Advance()

  Status Validate() const;
};

/// Default motor parameters by kind (drive, steer, mast pan, mast tilt); README.md has the table.
MotorParams DefaultDriveMotorParams();
MotorParams DefaultSteerMotorParams();
MotorParams DefaultMastPanMotorParams();
MotorParams DefaultMastTiltMotorParams();

struct RoverModelParams {
  RoverGeometry geometry;
  RoverMasses masses;
  ContactParams contact;
  PointContactParams belly;
  std::array<MotorParams, kNumMotors> motors = DefaultMotors();
  IntegratorParams integrator;
  /// Rocker differential: torsional coupling tau = -k (q_l + q_r) - c (u_l + u_r) on each rocker.
  double differential_stiffness = 2e4;  ///< k [N m/rad]
  double differential_damping = 500.0;  ///< c [N m s/rad]
  double gravity = 3.711;               ///< [m/s^2] Mars
  double ambient_temperature_c = -40.0;

  static std::array<MotorParams, kNumMotors> DefaultMotors();
  Status Validate() const;
};

/// Where to put the rover: chassis origin (x, y) in the site frame and heading (yaw about site
/// z; 0 faces +x = north, +pi/2 faces +y = west). Height, roll, pitch and the suspension angles
/// follow from the terrain.
struct StartPose {
  double x = 0.0;
  double y = 0.0;
  double yaw = 0.0;
};

}  // namespace rover::sim
