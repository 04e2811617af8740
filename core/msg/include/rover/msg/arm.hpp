#pragma once
/// @file
/// The arm messages as plain values (idl/rover_dl.idl): dl/arm_command (APL -> dl-arm) and
/// dl/arm_status (dl-arm -> APL). rover/msg/arm_idl.hpp converts them.
///
/// Joint angles in radians in the order azimuth, shoulder, elbow, wrist, as ddl/joint_state's
/// arm_angle (core/hwconfig arm_description.hpp has the conventions). `target` and
/// `tool_point` are in the rover frame (x forward, y left, z up), metres. Enumerator values
/// equal the IDL ordinals; a command read from the wire keeps whatever mode value it carried
/// so that dl-arm rejects an unknown one naming it.

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <string>

#include "rover/base/time.hpp"

namespace rover::msg {

enum class ArmMode : std::int32_t {
  kJoints = 0,  ///< go to `joints`
  kPlace = 1,   ///< put the instrument's face on `target`: above it, then a guarded descent
  kStow = 2,    ///< fold into the stowed pose
  kStop = 3,    ///< brake where it is
  kAutofocus = 4,  ///< image `target` with the microscopic imager through best focus
};

enum class ArmState : std::int32_t {
  kIdle = 0, kMoving, kAtGoal, kPlaced, kStowed, kFault, kRejected, kFocused
};
inline constexpr int kNumArmStates = 8;

/// "JOINTS", "PLACE", "STOW", "STOP", "AUTOFOCUS"; "UNKNOWN" for a value no enumerator has.
const char* ArmModeName(ArmMode m);
/// "IDLE", "MOVING", "AT_GOAL", "PLACED", "STOWED", "FAULT", "REJECTED", "FOCUSED"; "UNKNOWN"
/// otherwise.
const char* ArmStateName(ArmState s);
bool IsKnownArmMode(ArmMode m);

/// dl/arm_command.
struct ArmCommand {
  Time stamp;
  std::uint32_t command_id = 0;
  ArmMode mode = ArmMode::kStow;
  std::array<double, 4> joints{};                    ///< [rad] kJoints
  /// [m] rover frame: kPlace the face centre wanted, kAutofocus the estimated surface point
  Eigen::Vector3d target = Eigen::Vector3d::Zero();
  double timeout_s = 0.0;                            ///< [s] run clock; 0 = the service's
  int focus_steps = 0;     ///< kAutofocus: images in the sweep; 0 = the service's
  double focus_span = 0.0; ///< [m] kAutofocus: length of the sweep; 0 = the service's
};

/// dl/arm_status: the latched status of the latest command.
struct ArmStatus {
  Time stamp;
  std::uint32_t command_id = 0;
  ArmState state = ArmState::kIdle;
  std::array<double, 4> joints{};       ///< [rad] measured
  std::array<double, 4> joint_goals{};  ///< [rad] the goal being driven to
  Eigen::Vector3d tool_point = Eigen::Vector3d::Zero();  ///< [m] rover frame, from `joints`
  bool contact = false;                                  ///< the contact switch
  bool stowed = false;  ///< every joint within tolerance of the stowed pose
  // kAutofocus results (kFocused; zero before):
  double focus_height = 0.0;      ///< [m] the face above the target at best focus
  bool focus_predicted = false;   ///< best focus placed from the contact point
  int focus_images = 0;           ///< microscopic-imager frames taken
  std::uint32_t focus_image_id = 0;  ///< request id of the final frame (ddl/mi_frame)
  double focus_measure = 0.0;     ///< focus measure of that frame
  std::string message;  ///< <= 127 characters on the wire
};

}  // namespace rover::msg
