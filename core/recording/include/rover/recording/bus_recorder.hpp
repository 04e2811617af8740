#pragma once
/// @file
/// The recorder on the bus: raw readers (rover/runtime/raw_sample.hpp) on every catalog topic a
/// RecordOptions filter selects, each with the topic's QoS from the catalog (or the set's
/// x-rover.qos override) but keep-all history, feeding a RecordingSession on a thread of its
/// own. Log times come from the run clock: the latest sim/clock sample (read first on every
/// pass, so a sample is stamped with the clock as it stood when the sample was taken) or the
/// wall clock.
///
///   ROVER_ASSIGN_OR_RETURN(auto rec, BusRecorder::Create(participant, options));
///   ROVER_RETURN_IF_ERROR(rec->Start());
///   ...                                  // rec->health() turns to the first I/O error
///   RecordingReport report = rec->Stop();  // the file is closed; report.status says how
///
/// The participant must outlive the recorder. On an I/O error the recorder stops taking
/// samples (its readers are deleted) and keeps the error; the file keeps no footer.

#include <atomic>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "rover/base/status.hpp"
#include "rover/recording/record_options.hpp"
#include "rover/recording/session.hpp"
#include "rover/runtime/dds.hpp"
#include "rover/recording/replay_plan.hpp"
#include "rover/runtime/raw_sample.hpp"

namespace rover::recording {

struct BusRecorderOptions {
  RecordOptions record;  ///< record.path is the file; it must be set
  LogClock::Mode clock = LogClock::Mode::kSim;
  /// topic -> QoS profile name (a set's x-rover.qos), so the readers match its writers.
  std::map<std::string, std::string> qos_overrides;
  /// Added to the "rover_recorder" metadata record (domain, project, ...).
  mcap::StringMap metadata;
  /// [s] wall: longest wait for samples before the recorder checks for Stop().
  double poll_s = 0.05;
};

struct RecordingReport {
  std::string path;
  Status status;  ///< Ok, or the first error (the file then is not complete)
  SessionStats stats;
  double wall_s = 0;  ///< from Start to Stop
  double cpu_s = 0;   ///< CPU time of the recorder's thread
};

class BusRecorder {
 public:
  /// Creates the file and the readers (nothing is taken before Start). Errors: bad options, a
  /// path that cannot be created, a DDS failure.
  static Result<std::unique_ptr<BusRecorder>> Create(const dds::Participant& participant,
                                                     BusRecorderOptions options);
  ~BusRecorder();

  Status Start();
  /// Stops the thread, takes what has arrived, closes the file. Idempotent.
  RecordingReport Stop();

  /// Ok while all is well; the first I/O error once the recording failed. Thread-safe.
  Status health() const;
  /// The counts so far. Thread-safe.
  SessionStats Snapshot() const;
  /// [ns] the run clock as the recorder sees it now (its log time for a sample taken now); in
  /// sim mode 0 until the first sim/clock sample. Thread-safe.
  std::int64_t RunClockNs() const;
  /// False in sim mode until a sim/clock sample has arrived. Thread-safe.
  bool clock_valid() const;
  /// The topics it records, in catalog order (sim/clock first).
  std::vector<std::string> topics() const;
  const std::string& path() const { return options_.record.path; }

 private:
  BusRecorder(const dds::Participant& participant, BusRecorderOptions options)
      : participant_(participant), options_(std::move(options)), clock_(options_.clock) {}
  struct Input {
    dds::RawReader reader;
    std::size_t topic = 0;  ///< index in the session
    std::uint64_t lost_seen = 0;
    bool recorded = true;   ///< false: the clock reader of an excluded sim/clock
  };
  void Run();
  /// One pass over every reader (the clock first). Caller holds mu_.
  void PumpLocked();
  void CountLostLocked();

  const dds::Participant& participant_;
  BusRecorderOptions options_;
  LogClock clock_;
  std::unique_ptr<RecordingSession> session_;
  std::vector<Input> inputs_;  ///< the clock's first when there is one
  bool has_clock_input_ = false;
  dds::WaitSet waitset_;
  dds::GuardCondition stop_guard_;
  std::thread thread_;
  std::atomic<bool> stop_{false};
  mutable std::mutex mu_;
  Status failure_;
  bool started_ = false;
  bool stopped_ = false;
  RecordingReport report_;
  std::int64_t start_mono_ns_ = 0;
  double cpu_s_ = 0;
};

/// Every catalog topic with its C type name (for PlanReplay).
std::vector<CatalogTopic> CatalogTopics();

}  // namespace rover::recording
