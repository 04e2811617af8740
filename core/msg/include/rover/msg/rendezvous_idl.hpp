#pragma once
/// @file
/// apl/rendezvous_command and apl/rendezvous_status <-> their idlc C structs (conventions: see
/// rover/msg/camera_idl.hpp).

#include "rover/base/status.hpp"
#include "rover/idl/types.hpp"
#include "rover/msg/rendezvous.hpp"

namespace rover::msg {

/// A command: the target value and the numbers are kept as they are (apl-rendezvous checks them,
/// naming the field).
RendezvousCommand RendezvousCommandFromIdl(const rover_apl_RendezvousCommand& in);
void RendezvousCommandToIdl(const RendezvousCommand& in, rover_apl_RendezvousCommand* out);

/// Errors: a phase or fault value no enumerator has.
Result<RendezvousStatus> RendezvousStatusFromIdl(const rover_apl_RendezvousStatus& in);
/// features and message are truncated to 63 and 127 characters.
void RendezvousStatusToIdl(const RendezvousStatus& in, rover_apl_RendezvousStatus* out);

}  // namespace rover::msg
