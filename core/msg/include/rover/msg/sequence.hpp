#pragma once
/// @file
/// The sequencer's messages as plain values (idl/rover_apl.idl): apl/sequence_command (operator
/// or scenario runner -> apl-sequencer: a sequence in the text form of apl/sequencer/README.md)
/// and apl/sequence_status (apl-sequencer -> operators, runner; latched).
/// rover/msg/sequence_idl.hpp converts them. Enumerator values equal the IDL ordinals.

#include <cstddef>
#include <cstdint>
#include <string>

#include "rover/base/time.hpp"

namespace rover::msg {

/// The longest sequence text apl/sequence_command carries [bytes].
inline constexpr std::size_t kMaxSequenceTextBytes = 4095;

enum class SequenceState : std::int32_t {
  kIdle = 0,     ///< nothing has run yet
  kRunning = 1,  ///< running its statements or its ON_ABORT block
  kDone = 2,     ///< ran to its end
  kFailed = 3,   ///< refused (a parse error: nothing ran), a step failed, or it was stopped
};

/// "IDLE", "RUNNING", "DONE", "FAILED"; "UNKNOWN" for a value no enumerator has.
const char* SequenceStateName(SequenceState s);

/// apl/sequence_command: run this sequence text.
struct SequenceCommand {
  Time stamp;
  std::uint32_t command_id = 0;
  std::string text;  ///< <= kMaxSequenceTextBytes on the wire
};

/// apl/sequence_status: the latched status of the latest sequence.
struct SequenceStatus {
  Time stamp;
  std::uint32_t command_id = 0;  ///< the apl/sequence_command it reports on
  SequenceState state = SequenceState::kIdle;
  std::uint32_t step = 0;        ///< current or last step (1-based, writing order), 0 = none
  /// Why it failed (the first parse error with line and column, or the failed step with its
  /// line, text and reason); "" otherwise. <= 127 characters on the wire.
  std::string message;
};

}  // namespace rover::msg
