#pragma once
/// @file
/// dl/arm_command and dl/arm_status <-> their idlc C structs (conventions: see
/// rover/msg/camera_idl.hpp).

#include "rover/base/status.hpp"
#include "rover/idl/types.hpp"
#include "rover/msg/arm.hpp"

namespace rover::msg {

/// A command: the mode value is kept as it is (dl-arm rejects an unknown one, naming it);
/// numbers are copied as they are.
ArmCommand ArmCommandFromIdl(const rover_dl_ArmCommand& in);
void ArmCommandToIdl(const ArmCommand& in, rover_dl_ArmCommand* out);

/// Errors: a state value no enumerator has.
Result<ArmStatus> ArmStatusFromIdl(const rover_dl_ArmStatus& in);
/// The message is truncated to 127 characters.
void ArmStatusToIdl(const ArmStatus& in, rover_dl_ArmStatus* out);

}  // namespace rover::msg
