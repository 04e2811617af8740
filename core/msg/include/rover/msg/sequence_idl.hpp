#pragma once
/// @file
/// apl/sequence_command and apl/sequence_status <-> their idlc C structs (conventions: see
/// rover/msg/camera_idl.hpp).

#include "rover/base/status.hpp"
#include "rover/idl/types.hpp"
#include "rover/msg/sequence.hpp"

namespace rover::msg {

/// A command: the text is copied as it is (the sequencer's parser judges it).
SequenceCommand SequenceCommandFromIdl(const rover_apl_SequenceCommand& in);
/// Errors: a text longer than kMaxSequenceTextBytes (cutting a sequence would change what it
/// does), naming its length; `out` is then untouched.
Status SequenceCommandToIdl(const SequenceCommand& in, rover_apl_SequenceCommand* out);

/// Errors: a state value no enumerator has.
Result<SequenceStatus> SequenceStatusFromIdl(const rover_apl_SequenceStatus& in);
/// The message is truncated to 127 characters.
void SequenceStatusToIdl(const SequenceStatus& in, rover_apl_SequenceStatus* out);

}  // namespace rover::msg
