#pragma once
/// @file
/// Replay on the bus: publishes what a ReplayPlan selected from a recording, in log-time order,
/// through raw writers (rover/runtime/raw_sample.hpp) with each topic's catalog QoS, paced at a
/// rate (1 = as recorded, 2 = twice as fast, 0 = as fast as the bus takes it), with sim/clock
/// from the recording or made up from the log times (ClockTicks). The recorded bytes go out as
/// they are. Before the first message it waits `settle_s` for discovery, so that the readers of
/// a service started beside it are matched; at the end it waits for reliable readers to
/// acknowledge what it sent.

#include <atomic>
#include <cstdint>
#include <functional>
#include <map>
#include <string>

#include "rover/base/status.hpp"
#include "rover/mcap/reader.hpp"
#include "rover/recording/replay_plan.hpp"
#include "rover/runtime/dds.hpp"

namespace rover::recording {

struct BusReplayOptions {
  double rate = 1.0;     ///< >= 0
  double settle_s = 1.0; ///< [s] wall, before the first message
  /// topic -> QoS profile name (a set's x-rover.qos).
  std::map<std::string, std::string> qos_overrides;
  const std::atomic<bool>* abort = nullptr;  ///< set (Ctrl-C) to stop early
  /// Called about once per wall second with the messages published so far and the log time.
  std::function<void(std::uint64_t published, mcap::Timestamp log_time)> progress;
};

struct ReplayReport {
  std::map<std::string, std::uint64_t> published;  ///< per topic
  std::uint64_t messages = 0;                      ///< recorded messages published
  std::uint64_t clock_ticks = 0;                   ///< made-up sim/clock samples
  mcap::Timestamp first_log_time = 0;
  mcap::Timestamp last_log_time = 0;
  double wall_s = 0;
  bool interrupted = false;
};

/// Publishes `plan` from `reader` on `participant`'s domain. Errors: a DDS failure, a recorded
/// sample Cyclone refuses as its topic's type (naming topic and log time), a read error of the
/// file (the reader's, naming the offset).
Result<ReplayReport> ReplayOnBus(const dds::Participant& participant, const mcap::Reader& reader,
                                 const ReplayPlan& plan, const BusReplayOptions& options);

}  // namespace rover::recording
