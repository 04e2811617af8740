#pragma once
/// @file
/// RoverSimulation: Simbody multibody model of a MER-like rocker-bogie rover driving on a
/// HeightField, with the motor controllers (PID at 1 kHz, DC motor, faults) of motor_controller.hpp
/// and the wheel-terrain model of terrain_contact.hpp. This header does not include Simbody, so
/// users need no special compile flags.
///
/// Model (README.md has dimensions and equations): chassis on a free joint; two rockers on
/// pins about chassis y, tied by a stiff differential coupling that keeps q_rocker_left =
/// -q_rocker_right; a bogie on a pin at the rear of each rocker; front wheels on the rockers and
/// middle/rear wheels on the bogies; the four corner wheels hang from steering brackets (pins
/// about z); a pan/tilt mast. Motor rotor inertia (reflected through the gearheads) is part of
/// the driven bodies. Gravity along -z of the site frame (Simbody Ground = site frame).
///
/// The instrument arm (motors hw::kArmAzimuth..kArmWrist, core/hwconfig arm_description.hpp) is
/// kinematic, outside Simbody: each joint is a rigid inertia J = J_motor N^2 + kArmLinkInertia
/// driven by its motor controller's torque (semi-implicit Euler at the control rate), with no
/// gravity load and no reaction on the chassis. Its instrument's face cannot enter the terrain:
/// a control tick that would put the face centre below the terrain height under it is undone
/// (the joints keep their angles, their rates go to zero), so a commanded push stalls the
/// motors as a real arm's would. The arm is not drawn by the renderer.
///
/// Time: Advance(dt) integrates with Simbody's error-controlled semi-explicit Euler
/// (SemiExplicitEuler2, accuracy IntegratorParams::accuracy; or a fixed 1 ms semi-explicit
/// Euler, IntegratorParams::method). At every control tick (t = k / control_rate_hz,
/// k = 0, 1, ...) each motor controller samples its joint and sets a torque held constant until
/// the next tick (zero-order hold, as an FPGA PWM loop). Results do not depend on how the
/// caller splits time into Advance() calls when each dt is a multiple of the control period.
///
/// Readings are ideal (truth): no noise, bias or quantisation. Frames: site frame S (x north,
/// y west, z up); chassis frame C = the rover frame of the rover description (rover_model.hpp).
/// Joint angles follow the description's conventions (rocker and bogie + raise the front). Camera mount frames have x along the
/// boresight, y left, z up (rover convention; the renderer converts to x right, y down, z fwd).
///
/// Errors: bad parameters, poses or goals return a Status; a numerical failure inside Simbody
/// returns kInternal from Advance() and the simulation refuses to advance until Reset().
/// Not thread-safe; one instance per thread.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "rover/base/status.hpp"
#include "rover/sim/heightfield.hpp"
#include "rover/sim/physics/motor_controller.hpp"
#include "rover/sim/physics/rover_model.hpp"

namespace rover::sim::physics {

/// Ideal state of one wheel's terrain contact.
struct WheelReading {
  bool in_contact = false;
  terrain::Soil soil = terrain::Soil::kFirmSoil;
  double normal_force_n = 0.0;
  double slip_ratio = 0.0;  ///< (V_w - v_x)/max(|V_w|, |v_x|): +1 spinning in place
  double sinkage_m = 0.0;
  double longitudinal_force_n = 0.0;  ///< traction minus motion resistance, along rolling dir
  double lateral_force_n = 0.0;
  Eigen::Vector3d contact_point_site = Eigen::Vector3d::Zero();
  Eigen::Vector3d center_site = Eigen::Vector3d::Zero();
};

/// Ideal chassis state.
struct ChassisReading {
  Eigen::Isometry3d pose_site = Eigen::Isometry3d::Identity();      ///< X_SC: C in S
  Eigen::Vector3d linear_velocity_site = Eigen::Vector3d::Zero();   ///< of the C origin [m/s]
  Eigen::Vector3d linear_velocity_body = Eigen::Vector3d::Zero();   ///< same, in C
  Eigen::Vector3d angular_velocity_body = Eigen::Vector3d::Zero();  ///< [rad/s] in C (gyro)
  /// [m/s^2] in C at the IMU station: a - g (reads +g up at rest; accelerometer truth).
  Eigen::Vector3d specific_force_body = Eigen::Vector3d::Zero();
};

/// Camera mount frames (x boresight, y left, z up), in the site frame and in the chassis frame.
struct CameraFrames {
  Eigen::Isometry3d mast_head_site = Eigen::Isometry3d::Identity();  ///< at the tilt axis
  Eigen::Isometry3d hazcam_front_site = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d hazcam_rear_site = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d mast_head_chassis = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d hazcam_front_chassis = Eigen::Isometry3d::Identity();  ///< fixed
  Eigen::Isometry3d hazcam_rear_chassis = Eigen::Isometry3d::Identity();   ///< fixed
};

/// Poses (in the site frame) of the rover's parts, for drawing the rover (e.g. its wheels in
/// HAZCAM images). Body frames coincide with the chassis frame's axes at zero joint angles;
/// wheel frames sit at the wheel centre with y along the axle.
struct BodyPoses {
  std::array<Eigen::Isometry3d, 2> rockers;                    ///< left, right; origin at the pivot
  std::array<Eigen::Isometry3d, 2> bogies;                     ///< left, right; origin at the pivot
  std::array<Eigen::Isometry3d, kNumWheels> wheels;            ///< LF LM LR RF RM RR
  Eigen::Isometry3d mast_pan = Eigen::Isometry3d::Identity();  ///< origin at the pan joint
};

/// Inertia of each arm link about its joint [kg m^2], added to the reflected motor inertia.
inline constexpr double kArmLinkInertia = 0.05;
/// The contact switch closes when the face centre is within this height of the terrain [m].

struct RoverReadings {
  double time_s = 0.0;
  std::array<MotorReading, kNumMotors> motors;  ///< counts, counts/s, A, deg C, faults
  std::array<WheelReading, kNumWheels> wheels;
  /// [rad] + raises the front of the link; left = -right (differential).
  double rocker_left_rad = 0.0, rocker_right_rad = 0.0;
  double bogie_left_rad = 0.0, bogie_right_rad = 0.0;  ///< [rad] relative to the rocker
  std::array<double, kNumMotors> joint_angle_rad{};  ///< joint angle of each motor's joint
  /// The instrument arm (kinematic: its joints follow their motors, it pushes on nothing but
  /// what its face touches). Centre of the instrument's face in S, and whether that face
  /// touches the terrain (the contact switch's truth; it closes within the description's arm.contact_standoff).
  Eigen::Vector3d tool_point = Eigen::Vector3d::Zero();
  bool tool_contact = false;
  ChassisReading chassis;
  CameraFrames cameras;
  BodyPoses bodies;
};

/// Joint angles to pose the model at (the rover description's conventions) [rad].
struct ModelJointAngles {
  std::array<double, 2> rocker{};  ///< left, right; + raises the front
  std::array<double, 2> bogie{};   ///< left, right; relative to the rocker, + raises the front
  std::array<double, hwconfig::kNumSteered> steer{};  ///< LF LR RF RR; + turns the front left
  double pan = 0.0;                                   ///< + looks left
  double tilt = 0.0;                                  ///< + looks up
};

/// The model as built, posed with the chassis frame at the site origin: every part's frame in
/// the chassis frame (for checking the Simbody model against the rover description).
struct ModelGeometry {
  BodyPoses bodies;  ///< rockers, bogies, wheels (no wheel spin), mast pan
  /// Steering brackets LF LR RF RR: origin at the steering joint, z along its axis.
  std::array<Eigen::Isometry3d, hwconfig::kNumSteered> steer_brackets;
  CameraFrames cameras;  ///< *_site equal *_chassis
  std::vector<Eigen::Vector3d> belly_points;  ///< the body's terrain contact points
  Eigen::Vector3d imu_station = Eigen::Vector3d::Zero();  ///< where specific force is taken
};

/// Work counters (for benchmarks).
struct SimulationStats {
  std::int64_t integrator_steps = 0;
  std::int64_t control_ticks = 0;
};

class RoverSimulation {
 public:
  /// Builds the model, places the rover at `start` on `terrain` and lets it settle for
  /// params.integrator.settle_time with all brakes engaged; afterwards time() == 0.
  /// Errors: params.Validate(), an empty terrain, a start outside the terrain.
  static Result<std::unique_ptr<RoverSimulation>> Create(
      const RoverModelParams& params, std::shared_ptr<const terrain::HeightField> terrain,
      const StartPose& start);
  ~RoverSimulation();
  RoverSimulation(const RoverSimulation&) = delete;
  RoverSimulation& operator=(const RoverSimulation&) = delete;

  /// Re-places and settles the rover as Create() does; motors reset (off, no faults, ambient
  /// temperature, wheel angles 0); time() restarts at 0.
  Status Reset(const StartPose& start);

  /// Sets a goal for motor 0..11 (MotorId). Goals are in encoder counts of the joint
  /// (MotorParams::CountsPerRad(); wheel counts accumulate from 0 at Reset, steering/mast counts
  /// are absolute with 0 = straight ahead / level). See MotorController::SetGoal.
  Status SetMotorGoal(int motor, MotorMode mode, double position_counts,
                      double velocity_counts_per_s, double current_limit_a);
  /// Clears the latched faults of one motor (it stays off until the next goal).
  Status ClearMotorFaults(int motor);
  /// Ambient temperature of the motors' thermal model [deg C] (e.g. a Mars day/night cycle).
  Status SetAmbientTemperature(double celsius);

  /// Advances the simulation by dt seconds of simulated time (0 < dt <= max_advance).
  Status Advance(double dt);

  double time() const;
  /// All readings at time(). After a failed Advance() only time and motors are filled.
  RoverReadings Readings() const;
  /// Motor-only readings (cheaper than Readings()). Precondition: 0 <= motor < kNumMotors.
  MotorReading Motor(int motor) const;
  const RoverModelParams& params() const;
  const terrain::HeightField& terrain() const;
  SimulationStats stats() const;
  /// The built model at joint angles `q` (wheel spin 0), independent of the simulated state.
  ModelGeometry PoseModel(const ModelJointAngles& q) const;

 private:
  struct Impl;
  explicit RoverSimulation(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace rover::sim::physics
