#pragma once
/// @file
/// Conversions between the IDL C structs of ddl-joints' topics and the ddl_encoders library's
/// plain structs: hw/motor_telemetry and hw/suspension_pots in, ddl/joint_state out. Field by
/// field; headers are the caller's.

#include "rover/ddl/encoders/joint_reader.hpp"
#include "rover/hwconfig/hw_bus.hpp"
#include "rover/idl/types.hpp"

namespace rover::ddl {

/// hw/motor_telemetry (stamp from the header).
hw::MotorTelemetry JointTelemetryFromIdl(const rover_hw_MotorTelemetry& in);
/// hw/suspension_pots (stamp from the header).
hw::SuspensionPots SuspensionPotsFromIdl(const rover_hw_SuspensionPots& in);
/// ddl/joint_state, except the header.
void JointStateToIdl(const JointState& in, rover_ddl_JointState* out);
/// rover::SensorHealth -> the IDL enum (same order).
rover_SensorHealth JointHealthToIdl(SensorHealth h);

}  // namespace rover::ddl
