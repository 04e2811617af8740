#pragma once
/// @file
/// dl/mast_command and dl/mast_status <-> their idlc C structs (conventions: see
/// rover/msg/camera_idl.hpp).

#include "rover/base/status.hpp"
#include "rover/idl/types.hpp"
#include "rover/msg/mast.hpp"

namespace rover::msg {

/// A command: the pointing value is kept as it is (dl-mast rejects an unknown one, naming it);
/// numbers are copied as they are.
MastCommand MastCommandFromIdl(const rover_dl_MastCommand& in);
void MastCommandToIdl(const MastCommand& in, rover_dl_MastCommand* out);

/// Errors: a state value no enumerator has.
Result<MastStatus> MastStatusFromIdl(const rover_dl_MastStatus& in);
/// The message is truncated to 127 characters.
void MastStatusToIdl(const MastStatus& in, rover_dl_MastStatus* out);

}  // namespace rover::msg
