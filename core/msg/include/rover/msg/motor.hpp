#pragma once
/// @file
/// The motor-group messages as plain values (idl/rover_ddl.idl): ddl/motor_command (DL -> the
/// DDL motor driver, after MER's MOT) and ddl/motor_status. Arrays of 16 follow the hw motor
/// order (rover/hwconfig/hw_bus.hpp MotorIndex). rover/msg/motor_idl.hpp converts them.
///
/// Enumerator values equal the IDL ordinals. A command read from the wire keeps whatever mode
/// value it carried (the enums are 32 bit), so that the driver rejects an unknown one with its
/// typed reason instead of the value being lost in conversion.

#include <array>
#include <cstdint>
#include <string>

#include "rover/base/time.hpp"
#include "rover/hwconfig/hw_bus.hpp"

namespace rover::msg {

enum class GroupMode : std::int32_t { kPosition = 0, kVelocity = 1, kStop = 2 };
enum class GroupState : std::int32_t {
  kIdle = 0,
  kRunning = 1,
  kDone = 2,
  kFault = 3,
  kRejected = 4,
};
enum class MotorFault : std::int32_t {
  kNone = 0,
  kStall,
  kOverCurrent,
  kOverTemp,
  kTimeout,
  kNoTelemetry,
  kBadCommand,
  kStopped,
};

/// The IDL enumerator names without their prefix ("POSITION", "RUNNING", "STALL", ...);
/// "UNKNOWN" for a value no enumerator has.
const char* GroupModeName(GroupMode m);
const char* GroupStateName(GroupState s);
const char* MotorFaultName(MotorFault f);
bool IsKnownGroupMode(GroupMode m);

/// ddl/motor_command: one group of motors moved together.
struct MotorCommand {
  Time stamp;
  std::uint32_t command_id = 0;
  std::uint16_t motor_mask = 0;  ///< bit i selects motor i (hw order)
  GroupMode mode = GroupMode::kPosition;
  std::array<double, hw::kNumMotors> goal{};      ///< [rad] or [rad/s] per motor
  std::array<double, hw::kNumMotors> max_rate{};  ///< [rad/s] for position goals; 0 = default
  double timeout_s = 0.0;                         ///< [s] run clock; 0 = default
};

/// ddl/motor_status: the latched status of one group, with the motors' telemetry.
struct MotorStatus {
  Time stamp;
  std::uint32_t command_id = 0;
  GroupState state = GroupState::kIdle;
  MotorFault fault = MotorFault::kNone;
  std::int8_t fault_motor = -1;                      ///< motor (or mask bit) at fault, -1 if none
  std::string message;                               ///< <= 127 characters on the wire
  std::array<double, hw::kNumMotors> position{};     ///< [rad]
  std::array<double, hw::kNumMotors> velocity{};     ///< [rad/s]
  std::array<double, hw::kNumMotors> current{};      ///< [A]
  std::array<double, hw::kNumMotors> temperature{};  ///< [deg C]
};

}  // namespace rover::msg
