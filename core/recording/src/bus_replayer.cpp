#include "rover/recording/bus_replayer.hpp"

#include <chrono>
#include <cmath>
#include <memory>
#include <thread>
#include <vector>

#include "rover/base/clock.hpp"
#include "rover/runtime/topic_catalog.hpp"
#include "rover/mcap/info.hpp"
#include "rover/recording/cdr.hpp"
#include "rover/runtime/raw_sample.hpp"
#include "rover/runtime/topic_catalog.hpp"

namespace rover::recording {
namespace {

Result<dds::RawWriter> MakeWriter(const dds::Participant& p, const std::string& topic,
                                  const std::map<std::string, std::string>& overrides) {
  const auto info = dds::FindTopic(topic);
  if (!info) return InvalidArgument("topic '" + topic + "' is not in the topic catalog");
  const dds_topic_descriptor_t* desc = dds::DescriptorForType(info->type_name);
  if (desc == nullptr) {
    return Internal("no topic descriptor for " + std::string(info->type_name));
  }
  dds::QosProfile profile = info->profile;
  if (const auto it = overrides.find(topic); it != overrides.end()) {
    ROVER_ASSIGN_OR_RETURN(profile, dds::ParseQosProfile(it->second));
  }
  return dds::RawWriter::Create(p, topic, desc, profile);
}

// Sleeps until `deadline_ns` (monotonic) in short steps, so that `abort` is honoured.
bool SleepUntil(std::int64_t deadline_ns, const std::atomic<bool>* abort) {
  while (true) {
    if (abort != nullptr && abort->load()) return false;
    const std::int64_t left = deadline_ns - MonotonicNow().ns;
    if (left <= 0) return true;
    std::this_thread::sleep_for(std::chrono::nanoseconds(std::min<std::int64_t>(left, 50'000'000)));
  }
}

}  // namespace

Result<ReplayReport> ReplayOnBus(const dds::Participant& participant, const mcap::Reader& reader,
                                 const ReplayPlan& plan, const BusReplayOptions& options) {
  if (!(options.rate >= 0) || !std::isfinite(options.rate)) {
    return InvalidArgument("rate " + std::to_string(options.rate) +
                           " is not a finite number >= 0 (1 = real time, 0 = as fast as possible)");
  }
  std::vector<dds::RawWriter> writers;
  for (const auto& t : plan.topics) {
    auto w = MakeWriter(participant, t.name, options.qos_overrides);
    if (!w.ok()) return w.status().WithPrefix("replaying " + t.name);
    writers.push_back(std::move(*w));
  }
  dds::RawWriter clock_writer;
  if (plan.synthesize_clock) {
    ROVER_ASSIGN_OR_RETURN(clock_writer, MakeWriter(participant, kClockTopic, options.qos_overrides));
  }
  if (options.settle_s > 0) {
    SleepUntil(MonotonicNow().ns + static_cast<std::int64_t>(options.settle_s * 1e9), options.abort);
  }

  ReplayReport report;
  mcap::MessageFilter filter;
  filter.channel = [&](const mcap::Channel& c) { return plan.topic_of_channel.count(c.id) != 0; };
  ROVER_ASSIGN_OR_RETURN(mcap::MessageCursor cursor, reader.Messages(filter));
  ReplayPacer pacer(options.rate);
  ClockTicks ticks;
  std::uint32_t tick_seq = 0;
  const std::int64_t start = MonotonicNow().ns;
  std::int64_t last_progress = start;
  bool first = true;
  auto pace = [&](mcap::Timestamp log_time) {
    return SleepUntil(start + pacer.DueAfterNs(log_time), options.abort);
  };
  while (true) {
    ROVER_ASSIGN_OR_RETURN(std::optional<mcap::MessageEvent> event, cursor.Next());
    if (!event) break;
    const mcap::Timestamp t = event->message.log_time;
    if (first) report.first_log_time = t;
    first = false;
    report.last_log_time = t;
    if (plan.synthesize_clock) {
      for (const mcap::Timestamp tick : ticks.Before(t)) {
        if (!pace(tick)) break;
        ClockSample c;
        c.header.stamp_ns = static_cast<std::int64_t>(tick);
        c.header.frame_id = "sim";
        c.header.seq = ++tick_seq;
        c.sim_time_ns = static_cast<std::int64_t>(tick);
        c.real_time_factor = options.rate;
        const Status s = clock_writer.Write(WriteClockSample(c));
        if (!s.ok()) return s.WithPrefix("replaying a made-up sim/clock");
        ++report.clock_ticks;
      }
    }
    if (!pace(t)) {
      report.interrupted = true;
      break;
    }
    const std::size_t index = plan.topic_of_channel.at(event->channel->id);
    const Status s = writers[index].Write(event->message.data);
    if (!s.ok()) {
      return s.WithPrefix(reader.name() + ": message at log time " + mcap::FormatTimestamp(t));
    }
    ++report.published[plan.topics[index].name];
    ++report.messages;
    if (options.progress && MonotonicNow().ns - last_progress > 1'000'000'000) {
      last_progress = MonotonicNow().ns;
      options.progress(report.messages, t);
    }
  }
  // Let reliable readers have everything before the writers go.
  for (auto& w : writers) (void)dds_wait_for_acks(w.handle(), DDS_SECS(2));
  if (clock_writer.valid()) (void)dds_wait_for_acks(clock_writer.handle(), DDS_SECS(2));
  report.wall_s = static_cast<double>(MonotonicNow().ns - start) * 1e-9;
  return report;
}

}  // namespace rover::recording
