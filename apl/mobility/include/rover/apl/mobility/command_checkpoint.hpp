#pragma once
/// @file
/// What apl-mobility remembers across a crash: which command was running. A command cannot be
/// resumed safely after the mobility manager restarts (its map, votes and limit-cycle history are
/// gone, and the commander may have moved on), so a restarted apl-mobility ends the interrupted
/// command with the goal error RESTART on apl/mobility_status: the commander (the runner, the
/// sequencer, an operator) hears at once that the command is over, instead of waiting for its
/// time budget. The rover itself stops when the drive step in flight ends (dl-locomotion runs
/// one step at a time). Stored with core/base's CheckpointStore (one file per service set).

#include <cstdint>
#include <map>
#include <string>

#include "rover/apl/mobility/mobility_types.hpp"
#include "rover/base/status.hpp"
#include "rover/base/time.hpp"

namespace rover::apl::mobility {

struct CommandCheckpoint {
  bool running = false;         ///< a command was running when the checkpoint was written
  std::uint32_t command_id = 0;
  Mode mode = Mode::kDirected;

  friend bool operator==(const CommandCheckpoint&, const CommandCheckpoint&) = default;
};

/// The checkpoint's fields: `running` (0 / 1), `command_id`, `mode` (the core/msg name).
std::map<std::string, std::string> CommandCheckpointFields(const CommandCheckpoint& c);

/// Parses CommandCheckpointFields. Errors (InvalidArgument) name the field and value: a missing
/// field, `running` other than 0 / 1, a command id that is not a 32-bit unsigned number, an
/// unknown mode name.
Result<CommandCheckpoint> CommandCheckpointFromFields(const std::map<std::string, std::string>& f);

/// The checkpoint after `status` was published, from the one before: a RUNNING status starts
/// (or keeps) its command; a final status (SUCCEEDED, FAILED, REJECTED) of the running command
/// ends it; anything else (a BUSY rejection of another command id, IDLE) leaves it as it was.
CommandCheckpoint NextCommandCheckpoint(const CommandCheckpoint& before,
                                        const MobilityStatus& status);

/// The status that ends command `c` (running) interrupted by a restart: FAILED, fault RESTART
/// (a goal error), stamped `now`, with a message naming the command and its mode.
MobilityStatus InterruptedCommandStatus(const CommandCheckpoint& c, Time now);

}  // namespace rover::apl::mobility
