#pragma once
/// @file
/// The sequencer's messages as plain values (idl/rover_apl.idl): apl/sequence_command (operator
/// or scenario runner -> apl-sequencer: a sequence in the text form of apl/sequencer/README.md)
/// and apl/sequence_status (apl-sequencer -> operators, runner; latched).
/// rover/msg/sequence_idl.hpp converts them. Enumerator values equal the IDL ordinals.

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>

#include "rover/base/status.hpp"
#include "rover/base/time.hpp"

namespace rover::msg {

/// The longest sequence text apl/sequence_command carries [bytes].
inline constexpr std::size_t kMaxSequenceTextBytes = 4095;
/// The longest overrides text apl/sequence_command carries [bytes].
inline constexpr std::size_t kMaxSequenceOverridesBytes = 1023;

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
  /// "name = value" lines (FormatSequenceOverrides): values replacing the text's TARGET and
  /// CONST definitions; <= kMaxSequenceOverridesBytes on the wire.
  std::string overrides;
};

/// "name = value" lines of `overrides` (in name order), for SequenceCommand::overrides.
/// Errors: a name that is not a word (letters, digits, '_'), a value with a line break.
Result<std::string> FormatSequenceOverrides(const std::map<std::string, std::string>& overrides);
/// The map of SequenceCommand::overrides; blank lines are skipped. Errors name the line:
/// "overrides line 2: 'step 10 cm' has no '='", a name that is not a word, a name given twice.
Result<std::map<std::string, std::string>> ParseSequenceOverrides(const std::string& text);

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
