#pragma once
/// @file
/// dl/drive_command and dl/drive_status <-> their idlc C structs (conventions: see
/// rover/msg/camera_idl.hpp).

#include "rover/base/status.hpp"
#include "rover/idl/types.hpp"
#include "rover/msg/drive.hpp"

namespace rover::msg {

/// A command: the primitive value is kept as it is (locomotion rejects an unknown one
/// REJECTED_INVALID, naming it); numbers are copied as they are.
DriveCommand DriveCommandFromIdl(const rover_dl_DriveCommand& in);
void DriveCommandToIdl(const DriveCommand& in, rover_dl_DriveCommand* out);

/// The wire enum of a known primitive; an unknown value becomes PRIMITIVE_STOP.
rover_dl_DrivePrimitive DrivePrimitiveToIdl(DrivePrimitive p);

/// Errors: a primitive, state or termination value no enumerator has.
Result<DriveStatus> DriveStatusFromIdl(const rover_dl_DriveStatus& in);
/// An unknown primitive value (only possible in a rejection) is sent as PRIMITIVE_STOP, since
/// the wire enum cannot carry it (the rejection's message names it). The message is truncated to
/// 127 characters.
void DriveStatusToIdl(const DriveStatus& in, rover_dl_DriveStatus* out);

}  // namespace rover::msg
