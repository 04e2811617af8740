#pragma once
/// @file
/// The fault engine: one per service process, behind the seam of every typed reader and writer
/// (seam.hpp). It holds the faults added to the process (fault_spec.hpp), decides per sample
/// which ones hit it, and reports what it did as records (sys/fault_event in a service).
///
/// Cost: every endpoint gets a seam once the engine is installed, whatever the faults. With no
/// fault matching an endpoint, the typed wrappers find the seam Idle() (two atomic loads,
/// inline) and skip it (the fast path); faults added later are seen at once because each seam
/// compares the engine's generation with the one it last matched against.
///
/// Per sample (slow path, only for endpoints a fault matches), the faults whose window
/// [start, start + duration) contains the run-clock time act in order of id on the list of
/// samples to pass on (initially the sample itself):
///   drop, partition   empty the list
///   delay             push the samples' due time back by a draw of the delay distribution
///   duplicate         append `copies` more of each
///   reorder           hold the samples until the endpoint's next sample has passed (at most
///                     `delay`, default 1 s), then pass them after it
///   freeze            replace each by the last sample seen before the window opened (or the
///                     first one in it)
///   corrupt, noise, bias  change the selected field of a private copy (in place on a reader)
/// Samples due now go on at once (dds_write, or to the service on a reader); later ones are
/// copied and queued: the executor's pump writes writer-side ones when due, readers hand
/// reader-side ones to the service (Executor, Reader::TakeEach).
///
/// Determinism: whether fault F hits the n-th sample an endpoint passes during F's window is
/// a pure function of (F's seed, the topic name, reader or writer, n), and so is every random
/// draw made for that sample (delay, noise, bit positions). Other topics, other threads and
/// other faults do not change it.

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "rover/base/clock.hpp"
#include "rover/base/status.hpp"
#include "rover/runtime/fault_spec.hpp"
#include "rover/runtime/seam.hpp"

namespace rover::faults {

enum class FaultState { kPending, kActive, kEnded };
const char* FaultStateName(FaultState s);

/// A fault held by the engine, for List().
struct FaultStatus {
  FaultSpec spec;
  Time start{0};            ///< run clock
  std::optional<Time> end;  ///< none = until removed
  FaultState state = FaultState::kPending;
  std::uint64_t seen = 0;   ///< samples of matching endpoints while active
  std::uint64_t hit = 0;    ///< samples it acted on
};

/// What the engine reports; a service publishes each on sys/fault_event.
struct FaultRecord {
  enum class Event { kAdded, kStarted, kCount, kEnded, kRemoved, kListed, kRejected };
  Event event = Event::kAdded;
  std::uint32_t fault_id = 0;
  FaultKind kind = FaultKind::kDrop;
  std::string service;      ///< the reporting service
  std::string topic;        ///< the fault's topic pattern
  std::uint64_t seen = 0;
  std::uint64_t hit = 0;
  Time start{0};
  std::optional<Time> end;
  Time at{0};               ///< run clock when reported
  std::string detail;       ///< the fault in one line, or why it was rejected
};
const char* FaultEventName(FaultRecord::Event e);

namespace internal {
class EngineCore;
}

class FaultEngine {
 public:
  struct Options {
    std::string service;           ///< this process's service name (matched against `service`)
    const Clock* clock = nullptr;  ///< run clock; must outlive the engine
    Time epoch{0};                 ///< what a kRunEpoch fault's start_s counts from
    Duration report_period = std::chrono::seconds(1);  ///< run clock between count records
  };

  explicit FaultEngine(Options options);
  /// Uninstalls if installed and ends every fault; seams that outlive the engine pass samples.
  ~FaultEngine();
  FaultEngine(const FaultEngine&) = delete;
  FaultEngine& operator=(const FaultEngine&) = delete;

  /// Makes this engine the process's seam factory and seam pump. Endpoints created afterwards
  /// get a seam; install before creating them.
  void Install();
  void Uninstall();

  /// The seam for a new endpoint (what the installed factory returns): nullptr for topics no
  /// fault can name (outside the catalog, the fault topics themselves).
  std::shared_ptr<dds::TopicSeam> MakeSeam(const std::string& topic, dds::Direction direction);

  /// Validates and adds a fault (replacing one with the same id). Its window starts at
  /// epoch + start_s, or now + start_s for StartMode::kOnReceipt. Reports kAdded.
  Status Add(const FaultSpec& spec);
  /// Times every fault on `clock` from now on (it must outlive the engine), with run-epoch
  /// faults counting from `epoch`: for a process whose own clock is not the run clock (the
  /// simulator runs on wall time and makes the run clock). Windows that have not opened move to
  /// the new clock; open ones keep their times.
  void UseClock(const Clock& clock, Time epoch);
  /// Ends a fault; false if the engine has none with that id.
  bool Remove(std::uint32_t id);
  /// Ends every fault.
  void Clear();
  /// Pending and active faults, then recently ended ones (the last 64).
  std::vector<FaultStatus> List() const;

  /// Writes delayed writer-side samples that are due, opens and closes windows and reports.
  /// Cheap when idle; the executor calls it on every pass (through the installed pump).
  void Pump();
  /// Run-clock time of the earliest held sample, if any.
  std::optional<Time> NextDue() const;

  using RecordSink = std::function<void(const FaultRecord&)>;
  /// Where records go (called outside the engine's locks, from the thread that caused them).
  void SetRecordSink(RecordSink sink);

  const std::string& service() const;

 private:
  std::shared_ptr<internal::EngineCore> core_;
};

}  // namespace rover::faults
