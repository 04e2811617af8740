#include "rover/apl/mobility/command_checkpoint.hpp"

#include <charconv>
#include <limits>

namespace rover::apl::mobility {
namespace {

Result<std::string> Field(const std::map<std::string, std::string>& f, const std::string& key) {
  const auto it = f.find(key);
  if (it == f.end()) return InvalidArgument("mobility checkpoint: field '" + key + "' is missing");
  return it->second;
}

Status BadValue(const std::string& key, const std::string& value, const std::string& what) {
  return InvalidArgument("mobility checkpoint: " + key + " '" + value + "' " + what);
}

}  // namespace

std::map<std::string, std::string> CommandCheckpointFields(const CommandCheckpoint& c) {
  return {{"running", c.running ? "1" : "0"},
          {"command_id", std::to_string(c.command_id)},
          {"mode", msg::MobilityModeName(c.mode)}};
}

Result<CommandCheckpoint> CommandCheckpointFromFields(const std::map<std::string, std::string>& f) {
  CommandCheckpoint c;
  ROVER_ASSIGN_OR_RETURN(const std::string running, Field(f, "running"));
  if (running != "0" && running != "1") return BadValue("running", running, "is not 0 or 1");
  c.running = running == "1";
  ROVER_ASSIGN_OR_RETURN(const std::string id, Field(f, "command_id"));
  std::uint64_t v = 0;
  const auto [end, ec] = std::from_chars(id.data(), id.data() + id.size(), v);
  if (id.empty() || ec != std::errc() || end != id.data() + id.size() ||
      v > std::numeric_limits<std::uint32_t>::max()) {
    return BadValue("command_id", id, "is not a 32-bit unsigned number");
  }
  c.command_id = static_cast<std::uint32_t>(v);
  ROVER_ASSIGN_OR_RETURN(const std::string mode, Field(f, "mode"));
  bool found = false;
  for (int m = 0; m < msg::kMobilityModeCount && !found; ++m) {
    if (msg::MobilityModeName(static_cast<Mode>(m)) == mode) {
      c.mode = static_cast<Mode>(m);
      found = true;
    }
  }
  if (!found) return BadValue("mode", mode, "is not a mobility mode");
  return c;
}

CommandCheckpoint NextCommandCheckpoint(const CommandCheckpoint& before,
                                        const MobilityStatus& status) {
  if (status.state == State::kRunning) return {true, status.command_id, status.mode};
  const bool final = status.state == State::kSucceeded || status.state == State::kFailed ||
                     status.state == State::kRejected;
  if (final && before.running && status.command_id == before.command_id) {
    CommandCheckpoint after = before;
    after.running = false;
    return after;
  }
  return before;
}

MobilityStatus InterruptedCommandStatus(const CommandCheckpoint& c, Time now) {
  MobilityStatus s;
  s.stamp = now;
  s.command_id = c.command_id;
  s.mode = c.mode;
  s.state = State::kFailed;
  s.fault = Fault::kRestart;
  s.fault_class = FaultClassOf(Fault::kRestart);
  s.message = "apl-mobility restarted while command " + std::to_string(c.command_id) + " (" +
              msg::MobilityModeName(c.mode) + ") ran: the command is abandoned";
  return s;
}

}  // namespace rover::apl::mobility
