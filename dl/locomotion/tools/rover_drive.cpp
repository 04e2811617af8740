// rover-drive: operator tool. Sends one drive primitive on dl/drive_command and prints every
// dl/drive_status of that command until it is DONE, FAILED or REJECTED. Command line and exit
// codes: tools/drive_cli.hpp; usage: docs/howto/drive-the-rover.md.
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>

#include "rover/base/clock.hpp"
#include "rover/runtime/dds.hpp"
#include "tools/drive_cli.hpp"

namespace {

using rover::Duration;
using rover::Time;
namespace dds = rover::dds;
namespace tools = rover::dl::locomotion::tools;

volatile std::sig_atomic_t g_interrupted = 0;
void OnSignal(int) { g_interrupted = 1; }

std::string SecondsText(double s) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%g s", s);
  return buf;
}

int Fail(const std::string& message, int code) {
  std::fprintf(stderr, "rover-drive: error: %s\n", message.c_str());
  return code;
}

void Say(const std::string& line) {
  std::fprintf(stdout, "%s\n", line.c_str());
  std::fflush(stdout);
}

std::uint32_t ChooseCommandId() {
  const auto ms = static_cast<std::uint64_t>(rover::WallNow().ns / 1000000);
  const auto id =
      static_cast<std::uint32_t>((ms * 131u + static_cast<std::uint64_t>(getpid())) & 0x7fffffffu);
  return id == 0 ? 1 : id;
}

class Session {
 public:
  static std::optional<Session> Open(const tools::DriveCliOptions& o, std::string* error) {
    Session s;
    s.options_ = o;
    auto p = dds::Participant::Create(static_cast<dds_domainid_t>(o.domain));
    if (!p.ok()) {
      *error = p.status().message();
      return std::nullopt;
    }
    s.participant_ = std::move(*p);
    auto r = dds::Reader<rover_dl_DriveStatus>::Create(s.participant_, "dl/drive_status");
    auto w = dds::Writer<rover_dl_DriveCommand>::Create(s.participant_, "dl/drive_command");
    auto ws = dds::WaitSet::Create(s.participant_);
    if (!r.ok() || !w.ok() || !ws.ok()) {
      *error =
          !r.ok() ? r.status().message() : (!w.ok() ? w.status().message() : ws.status().message());
      return std::nullopt;
    }
    s.status_reader_ = std::move(*r);
    s.writer_ = std::move(*w);
    s.waitset_ = std::move(*ws);
    (void)s.waitset_.Attach(s.status_reader_.handle(), 1);
    if (o.clock == "sim") {
      auto c = dds::Reader<rover_sim_Clock>::Create(s.participant_, "sim/clock");
      if (!c.ok()) {
        *error = c.status().message();
        return std::nullopt;
      }
      s.clock_reader_.emplace(std::move(*c));
      (void)s.waitset_.Attach(s.clock_reader_->handle(), 2);
    }
    s.deadline_ = rover::MonotonicNow() + rover::Seconds(o.timeout_s);
    return s;
  }

  Duration Remaining() const { return deadline_ - rover::MonotonicNow(); }
  bool Expired() const { return Remaining().count() <= 0; }

  /// Waits up to 100 ms (never past the deadline) for data; keeps the latest sim time.
  void WaitSlice() {
    const Duration slice =
        std::clamp(Remaining(), Duration::zero(), Duration(std::chrono::milliseconds(100)));
    (void)waitset_.Wait(slice.count());
    if (clock_reader_.has_value()) {
      for (auto& c : clock_reader_->Take()) sim_now_ = c->sim_time_ns;
    }
  }

  bool Connected() const {
    return writer_.MatchedReaders() >= 1 && status_reader_.MatchedWriters() >= 1 &&
           (!clock_reader_.has_value() || sim_now_.has_value());
  }

  std::int64_t Stamp() const { return clock_reader_.has_value() ? *sim_now_ : rover::WallNow().ns; }

  rover::Status Send(const tools::DriveCliOptions& o, std::uint32_t id) {
    return writer_.Write(tools::MakeDriveCommand(o, id, Stamp()));
  }

  void SendStop(std::uint32_t id) {
    tools::DriveCliOptions stop = options_;
    stop.primitive = rover::msg::DrivePrimitive::kStop;
    if (Send(stop, id).ok()) Say("rover-drive: sent STOP #" + std::to_string(id));
  }

  dds::Reader<rover_dl_DriveStatus>& statuses() { return status_reader_; }

 private:
  tools::DriveCliOptions options_;
  dds::Participant participant_;
  dds::Reader<rover_dl_DriveStatus> status_reader_;
  dds::Writer<rover_dl_DriveCommand> writer_;
  std::optional<dds::Reader<rover_sim_Clock>> clock_reader_;
  dds::WaitSet waitset_;
  std::optional<std::int64_t> sim_now_;
  Time deadline_;
};

int Run(const tools::DriveCliOptions& o) {
  std::string error;
  std::optional<Session> session = Session::Open(o, &error);
  if (!session.has_value()) return Fail(error, tools::kExitNotDone);

  // Discovery: dl-locomotion's reader must match our writer (commands are volatile: one sent
  // before the match would be lost) and its latched status writer our reader.
  while (!session->Connected()) {
    if (g_interrupted != 0) return tools::kExitInterrupted;
    if (session->Expired()) {
      return Fail("no dl-locomotion answered on domain " + std::to_string(o.domain) + " within " +
                      SecondsText(o.timeout_s) + " (" +
                      (o.clock == "sim" ? "or no sim/clock; " : "") +
                      "is the rover running, and is the domain right?)",
                  tools::kExitTimeout);
    }
    session->WaitSlice();
  }
  (void)session->statuses().Take(256);  // latched statuses of earlier commands

  const std::uint32_t id = o.command_id != 0 ? o.command_id : ChooseCommandId();
  const rover::Status sent = session->Send(o, id);
  if (!sent.ok()) return Fail(sent.message(), tools::kExitNotDone);
  Say("rover-drive: sent " + std::string(rover::msg::DrivePrimitiveName(o.primitive)) + " #" +
      std::to_string(id) + " on domain " + std::to_string(o.domain));

  while (true) {
    for (auto& s : session->statuses().Take()) {
      if (s->command_id != id) continue;
      Say(tools::FormatDriveStatus(s.data()));
      if (tools::IsTerminal(s.data())) {
        return s->state == rover_dl_DRIVE_DONE ? tools::kExitDone : tools::kExitNotDone;
      }
    }
    if (g_interrupted != 0) {
      if (o.primitive != rover::msg::DrivePrimitive::kStop) session->SendStop(id + 1);
      return Fail("interrupted", tools::kExitInterrupted);
    }
    if (session->Expired()) {
      if (o.primitive != rover::msg::DrivePrimitive::kStop) session->SendStop(id + 1);
      return Fail("no terminal status for #" + std::to_string(id) + " within " +
                      SecondsText(o.timeout_s) + " (--timeout)",
                  tools::kExitTimeout);
    }
    session->WaitSlice();
  }
}

}  // namespace

int main(int argc, char** argv) {
  const tools::ParseOutcome parsed =
      tools::ParseDriveCli(argc, argv, std::getenv("ROVER_DOMAIN"), std::getenv("ROVER_CLOCK"));
  if (!parsed.options.has_value()) {
    std::fputs(parsed.output.c_str(), parsed.output_is_error ? stderr : stdout);
    return parsed.exit_code;
  }
  std::signal(SIGINT, OnSignal);
  std::signal(SIGTERM, OnSignal);
  return Run(*parsed.options);
}
