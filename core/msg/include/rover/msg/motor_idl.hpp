#pragma once
/// @file
/// ddl/motor_command and ddl/motor_status <-> their idlc C structs (conventions: see
/// rover/msg/camera_idl.hpp).

#include "rover/base/status.hpp"
#include "rover/idl/types.hpp"
#include "rover/msg/motor.hpp"

namespace rover::msg {

/// A command: the mode value is kept as it is (the motor driver rejects an unknown one as
/// kUnknownMode); numbers are copied as they are.
MotorCommand MotorCommandFromIdl(const rover_ddl_MotorCommand& in);
void MotorCommandToIdl(const MotorCommand& in, rover_ddl_MotorCommand* out);

/// Errors: a state or fault value no enumerator has.
Result<MotorStatus> MotorStatusFromIdl(const rover_ddl_MotorStatus& in);
/// The message is truncated to 127 characters.
void MotorStatusToIdl(const MotorStatus& in, rover_ddl_MotorStatus* out);

}  // namespace rover::msg
