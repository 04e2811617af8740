#pragma once
/// @file
/// Conversions between the IDL C structs of the motor driver's topics (rover_ddl.idl,
/// rover_hw.idl) and the plain structs of the ddl_motor library. Field by field; enums are read
/// as raw integers so that an out-of-range value on the wire reaches the library's command check
/// (typed rejection) instead of being undefined behaviour. Header stamps and frames are the
/// caller's (ServiceContext::Stamp).

#include "rover/ddl/motor/motor_types.hpp"
#include "rover/hwconfig/hw_bus.hpp"
#include "rover/idl/types.hpp"

namespace rover::ddl {

/// ddl/motor_command. An unknown mode value is kept as is (GroupMode has an int underlying type)
/// and rejected by MotorGroupManager::Check as CommandError::kUnknownMode.
MotorCommand MotorCommandFromIdl(const rover_ddl_MotorCommand& in);

/// hw/motor_telemetry (stamp from the header).
hw::MotorTelemetry MotorTelemetryFromIdl(const rover_hw_MotorTelemetry& in);

/// hw/motor_goals, except the header.
void MotorGoalsToIdl(const hw::MotorGoals& in, rover_hw_MotorGoals* out);

/// ddl/motor_status, except the header (message truncated to 127 characters).
void MotorStatusToIdl(const MotorStatus& in, rover_ddl_MotorStatus* out);

/// rover::SensorHealth -> the IDL enum (same order).
rover_SensorHealth HealthToIdl(SensorHealth h);

}  // namespace rover::ddl
