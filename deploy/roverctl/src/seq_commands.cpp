#include "rover/deploy/seq_commands.hpp"

#include <chrono>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <thread>
#include <unistd.h>

#include "rover/base/clock.hpp"
#include "rover/base/format.hpp"
#include "rover/msg/sequence_idl.hpp"
#include "rover/runtime/dds.hpp"

namespace rover::deploy {

Result<msg::SequenceCommand> BuildSequenceCommand(const SeqRunArgs& args, std::uint32_t command_id) {
  std::ifstream in(args.file);
  if (!in) return InvalidArgument("seq run: cannot read '" + args.file + "'");
  std::stringstream text;
  text << in.rdbuf();
  msg::SequenceCommand c;
  c.command_id = command_id;
  c.text = text.str();
  if (c.text.size() > msg::kMaxSequenceTextBytes) {
    return InvalidArgument("seq run: '" + args.file + "' is " + std::to_string(c.text.size()) +
                           " bytes; apl/sequence_command carries at most " +
                           std::to_string(msg::kMaxSequenceTextBytes));
  }
  std::map<std::string, std::string> overrides;
  for (const std::string& s : args.sets) {
    const std::size_t eq = s.find('=');
    if (eq == std::string::npos) {
      return InvalidArgument("seq run: --set '" + s + "' is not name=value");
    }
    overrides[s.substr(0, eq)] = s.substr(eq + 1);
  }
  Result<std::string> o = msg::FormatSequenceOverrides(overrides);
  if (!o.ok()) return InvalidArgument("seq run: --set: " + o.status().message());
  if (o->size() > msg::kMaxSequenceOverridesBytes) {
    return InvalidArgument("seq run: the --set values take " + std::to_string(o->size()) +
                           " bytes; apl/sequence_command carries at most " +
                           std::to_string(msg::kMaxSequenceOverridesBytes));
  }
  c.overrides = *o;
  return c;
}

int RunSeqRun(int domain, const SeqRunArgs& args, std::ostream& out, std::ostream& err) {
  // An id no other sender is likely to use: this process and the wall clock.
  const std::uint32_t id = static_cast<std::uint32_t>(
      (static_cast<std::uint64_t>(::getpid()) << 16) ^
      static_cast<std::uint64_t>(WallNow().ns / 1000000)) | 0x40000000u;
  Result<msg::SequenceCommand> c = BuildSequenceCommand(args, id);
  if (!c.ok()) {
    err << "roverctl: " << c.status().message() << "\n";
    return 2;
  }
  auto participant = dds::Participant::Create(domain);
  if (!participant.ok()) {
    err << "roverctl: " << participant.status().message() << "\n";
    return 3;
  }
  auto writer = dds::Writer<rover_apl_SequenceCommand>::Create(*participant, "apl/sequence_command");
  auto reader = dds::Reader<rover_apl_SequenceStatus>::Create(*participant, "apl/sequence_status");
  if (!writer.ok() || !reader.ok()) {
    err << "roverctl: cannot create the DDS endpoints\n";
    return 3;
  }
  const Time found_by = MonotonicNow() + Seconds(args.discovery_s);
  while (writer->MatchedReaders() == 0 && MonotonicNow() < found_by) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  if (writer->MatchedReaders() == 0) {
    err << "roverctl: no apl-sequencer on domain " << domain << " heard apl/sequence_command within "
        << FormatNumber(args.discovery_s) << " s; nothing was sent\n";
    return 3;
  }
  rover_apl_SequenceCommand wire{};
  if (Status s = msg::SequenceCommandToIdl(*c, &wire); !s.ok()) {
    err << "roverctl: " << s.message() << "\n";
    return 2;
  }
  dds::CopyString(wire.header.frame_id, "site");
  if (!writer->Write(wire).ok()) {
    err << "roverctl: cannot write apl/sequence_command\n";
    return 3;
  }
  out << "sequence " << id << " sent (" << c->text.size() << " bytes"
      << (c->overrides.empty() ? "" : ", overrides: " + std::to_string(args.sets.size())) << ")\n";
  const Time give_up = args.timeout_s > 0 ? MonotonicNow() + Seconds(args.timeout_s) : Time{INT64_MAX};
  std::optional<msg::SequenceStatus> last;
  while (MonotonicNow() < give_up) {
    std::optional<msg::SequenceStatus> end;
    bool any = false;
    reader->TakeEach([&](const dds::Sample<rover_apl_SequenceStatus>& s) {
      auto st = msg::SequenceStatusFromIdl(s.data());
      if (!st.ok() || st->command_id != id) return;
      any = true;
      if (!last || last->state != st->state || last->step != st->step || last->message != st->message) {
        out << msg::SequenceStateName(st->state) << " step " << st->step
            << (st->message.empty() ? "" : ": " + st->message) << "\n";
      }
      last = *st;
      if (st->state == msg::SequenceState::kDone || st->state == msg::SequenceState::kFailed) end = *st;
    });
    if (end) return end->state == msg::SequenceState::kDone ? 0 : 1;
    if (any && args.no_wait) return 0;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  err << "roverctl: no end of sequence " << id << " within " << FormatNumber(args.timeout_s)
      << " s\n";
  return 1;
}

}  // namespace rover::deploy
