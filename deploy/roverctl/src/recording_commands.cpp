#include "recording_commands.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <set>
#include <thread>

#include "rover/base/clock.hpp"
#include "rover/base/format.hpp"
#include "rover/mcap/info.hpp"
#include "rover/mcap/reader.hpp"
#include "rover/recording/bus_replayer.hpp"
#include "rover/recording/replay_plan.hpp"
#include "rover/runtime/discovery.hpp"
#include "rover/runtime/domain.hpp"

namespace rover::deploy {
namespace {

namespace fs = std::filesystem;

int Error(std::ostream& err, const std::string& message, int code) {
  err << "roverctl: error: " << message << "\n";
  return code;
}

std::string Megabytes(std::uint64_t bytes) {
  const double b = static_cast<double>(bytes);
  if (b < 1e3) return std::to_string(bytes) + " B";
  if (b < 1e6) return FormatNumber(b / 1e3, 3) + " kB";
  return FormatNumber(b / 1e6, 3) + " MB";
}

// The other participants' writers of `topics` on the domain: "sim/clock (pid 12 (rover-sim) ...)".
std::vector<std::string> Conflicts(const std::vector<dds::RemoteWriter>& writers,
                                   const std::set<std::string>& topics) {
  std::vector<std::string> out;
  for (const auto& w : writers) {
    if (topics.count(w.topic) != 0) out.push_back(w.topic + " (published by " + w.participant + ")");
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

}  // namespace

std::string DescribeReport(const recording::RecordingReport& report) {
  const auto& st = report.stats;
  std::size_t with_messages = 0;
  for (const auto& t : st.topics) with_messages += t.messages > 0 ? 1 : 0;
  std::string out = "recorded " + std::to_string(st.messages) + " messages on " +
                    std::to_string(with_messages) + " topics to " + report.path + " (" +
                    Megabytes(st.file_bytes);
  if (st.last_log_time_ns >= 0) {
    out += ", " + FormatNumber(static_cast<double>(st.last_log_time_ns - st.first_log_time_ns) * 1e-9, 4) +
           " s of run clock";
  }
  out += ")\n";
  if (st.capped) {
    out += "size cap reached: " + std::to_string(st.dropped) +
           " later messages were not recorded (the file says it was cut)\n";
  }
  if (st.lost > 0) {
    out += "samples lost in transport before the recorder got them: " + std::to_string(st.lost) + "\n";
    for (const auto& t : st.topics) {
      if (t.lost > 0) out += "  " + t.topic + ": " + std::to_string(t.lost) + "\n";
    }
  }
  return out;
}

// ---- record ----------------------------------------------------------------------------------

int RunRecord(const RecordArgs& args, std::ostream& out, std::ostream& err) {
  if (args.record.path.empty()) return Error(err, "record: give the file with -o FILE", 2);
  if (const Status s = args.record.Validate(); !s.ok()) return Error(err, "record: " + s.message(), 2);
  if (args.duration_s < 0) return Error(err, "record: --duration must be >= 0", 2);
  auto participant = dds::Participant::Create(args.target.domain);
  if (!participant.ok()) return Error(err, participant.status().message(), 1);

  recording::BusRecorderOptions o;
  o.record = args.record;
  o.qos_overrides = args.target.qos;
  std::string clock = args.clock;
  if (clock == "auto") clock = args.target.clock;
  if (clock.empty() || clock == "auto") {
    // A bare domain: sim time if a simulator publishes sim/clock there.
    auto writers = dds::DiscoverRemoteWriters(*participant, std::chrono::milliseconds(1500));
    clock = "wall";
    if (writers.ok()) {
      for (const auto& w : *writers) {
        if (w.topic == recording::kClockTopic) clock = "sim";
      }
      if (writers->empty()) {
        out << "roverctl: nothing publishes on DDS domain " << args.target.domain
            << " yet; recording what comes\n";
      }
    }
  }
  if (clock != "sim" && clock != "wall") {
    return Error(err, "record: --clock '" + clock + "' is not one of: auto, sim, wall", 2);
  }
  o.clock = clock == "sim" ? recording::LogClock::Mode::kSim : recording::LogClock::Mode::kWall;
  o.metadata = {{"domain", std::to_string(args.target.domain)}, {"recorder", "roverctl record"}};
  if (!args.target.project.empty()) o.metadata["project"] = args.target.project;

  auto recorder = recording::BusRecorder::Create(*participant, o);
  if (!recorder.ok()) {
    const int code = recorder.status().code() == StatusCode::kInvalidArgument ? 2 : 1;
    return Error(err, recorder.status().message(), code);
  }
  if (const Status s = (*recorder)->Start(); !s.ok()) return Error(err, s.message(), 1);
  out << "roverctl: recording " << (*recorder)->topics().size() << " topics ("
      << args.record.topics.Describe() << ") of DDS domain " << args.target.domain
      << (args.target.project.empty() ? "" : " ('" + args.target.project + "')") << " to "
      << args.record.path << ", log time on the " << clock << " clock; "
      << (args.duration_s > 0 ? "for " + FormatNumber(args.duration_s) + " s of run clock or " : "")
      << "Ctrl-C to stop\n"
      << std::flush;

  std::optional<std::int64_t> base;
  std::string why_stopped;
  while (true) {
    if (args.stop != nullptr && args.stop->load()) break;
    if (!(*recorder)->health().ok()) break;
    if (args.target.alive && !args.target.alive()) {
      why_stopped = "the set '" + args.target.project + "' went down";
      break;
    }
    if (args.duration_s > 0 && (*recorder)->clock_valid()) {
      const std::int64_t now = (*recorder)->RunClockNs();
      if (!base) base = now;
      if (static_cast<double>(now - *base) * 1e-9 >= args.duration_s) break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  const recording::RecordingReport report = (*recorder)->Stop();
  if (!report.status.ok()) {
    return Error(err, "the recording failed: " + report.status.message() + "; " + report.path +
                          " is incomplete (no footer: readers refuse it)",
                 1);
  }
  if (!why_stopped.empty()) out << "roverctl: " << why_stopped << "\n";
  out << "roverctl: " << DescribeReport(report) << std::flush;
  return 0;
}

// ---- replay ----------------------------------------------------------------------------------

int RunReplay(const ReplayArgs& args, std::ostream& out, std::ostream& err) {
  if (!(args.rate >= 0) || !std::isfinite(args.rate)) {
    return Error(err, "replay: --rate must be a number >= 0 (1 = real time, 0 = as fast as possible)", 2);
  }
  // The whole file is checked (every CRC, every chunk) before anything is published.
  mcap::ReaderOptions ro;
  ro.verification = mcap::Verification::kFull;
  auto reader = mcap::Reader::Open(args.file, ro);
  if (!reader.ok()) return Error(err, reader.status().message() + "; nothing was published", 2);
  recording::ReplaySelection sel;
  sel.topics = args.topics;
  sel.clock = args.clock;
  sel.accept_schema_changes = args.accept_schema_changes;
  auto plan = recording::PlanReplay(**reader, sel, recording::CatalogTopics());
  if (!plan.ok()) return Error(err, plan.status().message() + "; nothing was published", 2);

  std::set<std::string> topics;
  for (const auto& t : plan->topics) topics.insert(t.name);
  if (plan->synthesize_clock) topics.insert(recording::kClockTopic);

  // A bare domain is leased like a set's, so that no `roverctl up` or run lands on it meanwhile.
  dds::DomainLease lease;
  if (args.target.project.empty()) {
    auto l = dds::DomainLease::Acquire(args.target.domain);
    if (l.ok()) {
      lease = std::move(*l);
    } else if (!args.force) {
      return Error(err, "DDS domain " + std::to_string(args.target.domain) +
                            " is leased by another roverctl (a set, a run or a replay): give "
                            "--project to replay into a running set, or --force",
                   1);
    }
  }
  auto participant = dds::Participant::Create(args.target.domain);
  if (!participant.ok()) return Error(err, participant.status().message(), 1);
  auto writers = dds::DiscoverRemoteWriters(
      *participant, std::chrono::milliseconds(static_cast<std::int64_t>(args.discovery_s * 1000)));
  if (!writers.ok()) return Error(err, writers.status().message(), 1);
  const auto conflicts = Conflicts(*writers, topics);
  if (!conflicts.empty()) {
    std::string list;
    for (const auto& c : conflicts) list += "\n  " + c;
    if (!args.force) {
      return Error(err, "DDS domain " + std::to_string(args.target.domain) +
                            " is in use: others already publish topics this replay would "
                            "publish:" + list +
                            "\nleave them out with --topics/--exclude (or --no-clock), replay "
                            "onto a fresh domain, or --force",
                   1);
    }
    out << "roverctl: warning: replaying beside other publishers of:" << list << "\n";
  }

  const double span_s = static_cast<double>(plan->end_time - plan->start_time) * 1e-9;
  out << "roverctl: replaying " << plan->messages << " messages of " << plan->topics.size()
      << " topics (" << FormatNumber(span_s, 4) << " s of run clock) from " << args.file
      << " onto DDS domain " << args.target.domain
      << (args.target.project.empty() ? "" : " ('" + args.target.project + "')") << " at rate "
      << FormatNumber(args.rate) << (args.rate == 0 ? " (as fast as possible)" : "")
      << (plan->synthesize_clock ? "; sim/clock made up from the log times" : "") << "\n"
      << std::flush;
  recording::BusReplayOptions o;
  o.rate = args.rate;
  o.settle_s = 0.5;
  o.qos_overrides = args.target.qos;
  o.abort = args.stop;
  auto report = recording::ReplayOnBus(*participant, **reader, *plan, o);
  if (!report.ok()) return Error(err, report.status().message(), 1);
  out << "roverctl: published " << report->messages << " messages";
  if (report->clock_ticks > 0) out << " and " << report->clock_ticks << " sim/clock ticks";
  out << " in " << FormatNumber(report->wall_s, 4) << " s"
      << (report->interrupted ? " (interrupted)" : "") << "\n";
  for (const auto& [topic, n] : report->published) out << "  " << topic << "  " << n << "\n";
  out << std::flush;
  return report->interrupted ? 1 : 0;
}

// ---- info ------------------------------------------------------------------------------------

int RunInfo(const std::string& file, std::ostream& out, std::ostream& err) {
  auto info = mcap::SummarizeFile(file);
  if (!info.ok()) return Error(err, info.status().message(), 2);
  out << mcap::FormatRecordingInfo(*info) << std::flush;
  return 0;
}

// ---- a set's recording -------------------------------------------------------------------------

Result<std::unique_ptr<SetRecording>> SetRecording::Start(const ComposeProject& project,
                                                          int domain,
                                                          const std::string& state_dir) {
  if (!project.rover.record || !project.rover.record->enabled) return std::unique_ptr<SetRecording>();
  std::unique_ptr<SetRecording> r(new SetRecording());
  recording::BusRecorderOptions o;
  o.record = *project.rover.record;
  if (o.record.path.empty()) o.record.path = state_dir + "/recording.mcap";
  std::error_code ec;
  fs::create_directories(fs::path(o.record.path).parent_path(), ec);
  o.clock = project.rover.clock == "sim" ? recording::LogClock::Mode::kSim
                                         : recording::LogClock::Mode::kWall;
  o.qos_overrides = project.rover.qos;
  o.metadata = {{"domain", std::to_string(domain)},
                {"project", project.rover.project},
                {"compose_file", project.file},
                {"recorder", "roverctl up (x-rover.record)"}};
  ROVER_ASSIGN_OR_RETURN(r->participant_, dds::Participant::Create(domain));
  ROVER_ASSIGN_OR_RETURN(r->recorder_, recording::BusRecorder::Create(r->participant_, o));
  ROVER_RETURN_IF_ERROR(r->recorder_->Start());
  return r;
}

}  // namespace rover::deploy
