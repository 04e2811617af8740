#pragma once
/// @file
/// Parameters of the simulated MER-like six-wheel rocker-bogie rover: geometry, masses, contact,
/// motors, integrator. Defaults follow MER (about 180 kg, wheel radius 0.125 m, wheelbase
/// 1.25 m, track 1 m); README.md has the table.
///
/// The geometry is the stack's rover description (core/hwconfig rover_description.hpp): its
/// rover frame (x forward, y left, z up, origin on the ground plane below the midpoint of the
/// rocker pivots), its positions at zero joint angles, its indices and its joint conventions
/// (RoverSimulation reports joint angles in them). The simulator reads it from the same
/// `geometry.*` parameters as the stack, and tests/consistency compares the Simbody model built
/// from it with what the stack derives.

#include <Eigen/Core>
#include <array>

#include "rover/base/status.hpp"
#include "rover/hwconfig/hw_bus.hpp"
#include "rover/hwconfig/rover_description.hpp"
#include "rover/sim/physics/motor_controller.hpp"
#include "rover/sim/physics/terrain_contact.hpp"

namespace rover::sim::physics {

// Motor and wheel indices are core/hwconfig's (hw::MotorIndex, hwconfig::WheelIndex).
using hw::kNumMotors;
using hwconfig::kNumWheels;

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
/// Arm joint j (0 azimuth .. 3 wrist): the joint limits are the arm description's.
MotorParams DefaultArmMotorParams(int joint);

struct RoverModelParams {
  hwconfig::RoverDescription geometry;  ///< validated with "geometry." before the field names
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

}  // namespace rover::sim::physics
