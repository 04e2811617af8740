#pragma once
/// @file
/// The hw/ bus mirrors of rover/hwconfig/hw_bus.hpp <-> their idlc C structs (rover_hw.idl),
/// field by field; conventions as in rover/msg/camera_idl.hpp (stamp_ns <-> header.stamp_ns).
/// Raw counts are copied as they are; the receiving driver judges them. Enum fields are read as
/// raw integers (hw::CameraRequest/CameraFrame keep `int camera`); a motor goal's mode must be
/// a MotorMode.

#include "rover/base/status.hpp"
#include "rover/hwconfig/hw_bus.hpp"
#include "rover/idl/types.hpp"

namespace rover::msg {

hw::MotorTelemetry MotorTelemetryFromIdl(const rover_hw_MotorTelemetry& in);
void MotorTelemetryToIdl(const hw::MotorTelemetry& in, rover_hw_MotorTelemetry* out);

/// Errors: a goal whose mode is not a MotorMode (names the motor).
Result<hw::MotorGoals> MotorGoalsFromIdl(const rover_hw_MotorGoals& in);
void MotorGoalsToIdl(const hw::MotorGoals& in, rover_hw_MotorGoals* out);

hw::SuspensionPots SuspensionPotsFromIdl(const rover_hw_SuspensionPots& in);
void SuspensionPotsToIdl(const hw::SuspensionPots& in, rover_hw_SuspensionPots* out);
hw::ArmContact ArmContactFromIdl(const rover_hw_ArmContact& in);
void ArmContactToIdl(const hw::ArmContact& in, rover_hw_ArmContact* out);

hw::ImuRaw ImuRawFromIdl(const rover_hw_ImuRaw& in);
void ImuRawToIdl(const hw::ImuRaw& in, rover_hw_ImuRaw* out);

hw::SunSensorRaw SunSensorRawFromIdl(const rover_hw_SunSensorRaw& in);
void SunSensorRawToIdl(const hw::SunSensorRaw& in, rover_hw_SunSensorRaw* out);

hw::CameraRequest CameraRequestFromIdl(const rover_hw_CameraRequest& in);
void CameraRequestToIdl(const hw::CameraRequest& in, rover_hw_CameraRequest* out);

/// The images view `in`'s buffers (valid while `in` is); sizes are the receiver's to check.
hw::CameraFrame CameraFrameFromIdl(const rover_hw_CameraFrame& in);
/// `left`/`right` borrow the frame's views (they must outlive the write).
void CameraFrameToIdl(const hw::CameraFrame& in, rover_hw_CameraFrame* out);
hw::MiRequest MiRequestFromIdl(const rover_hw_MiRequest& in);
void MiRequestToIdl(const hw::MiRequest& in, rover_hw_MiRequest* out);
/// The image views `in`'s buffer (valid while `in` lives).
hw::MiFrame MiFrameFromIdl(const rover_hw_MiFrame& in);
/// Borrows in.image's bytes (keep them alive until the sample is written).
void MiFrameToIdl(const hw::MiFrame& in, rover_hw_MiFrame* out);

}  // namespace rover::msg
