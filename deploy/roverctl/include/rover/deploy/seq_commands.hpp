#pragma once
/// @file
/// `roverctl seq run FILE [--set name=value ...]`: sends a sequence (apl/sequencer's text form)
/// to the apl-sequencer of a running set on apl/sequence_command, with the --set values as its
/// overrides (values replacing the text's TARGET / CONST definitions: one template file serves
/// many runs), and follows its apl/sequence_status to the end. roverctl does not parse the
/// language (it is the sequencer's, an APL library): a text or override the sequencer refuses
/// comes back as FAILED with the parser's message (line and column). docs/roverctl.md "seq".

#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

#include "rover/base/status.hpp"
#include "rover/msg/sequence.hpp"

namespace rover::deploy {

struct SeqRunArgs {
  std::string file;               ///< the sequence text file
  std::vector<std::string> sets;  ///< "name=value" overrides, e.g. "target=(5.2, 0.4, 0)"
  bool no_wait = false;           ///< return after the first status of the command
  double timeout_s = 0.0;         ///< [s] wall: give up waiting after this (0 = never)
  double discovery_s = 10.0;      ///< [s] wall: how long to wait for apl-sequencer to hear us
};

/// The apl/sequence_command of `args` with id `command_id`. Errors (InvalidArgument, naming
/// what is wrong): the file unreadable or longer than the message carries, a --set without
/// '=' or with a name that is not a word, overrides longer than the message carries.
Result<msg::SequenceCommand> BuildSequenceCommand(const SeqRunArgs& args, std::uint32_t command_id);

/// Sends the command to the set on `domain` and prints each status change ("RUNNING step 3:
/// ..."). Exit code: 0 on DONE, 1 on FAILED (refused text, failed step) or a timeout, 3 when no
/// apl-sequencer hears the command within discovery_s (nothing sent).
int RunSeqRun(int domain, const SeqRunArgs& args, std::ostream& out, std::ostream& err);

}  // namespace rover::deploy
