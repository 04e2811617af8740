#pragma once
/// @file
/// The fault-injection seam. Every typed Writer and Reader passes its samples through a
/// TopicSeam if one is installed for its topic, so faults (drop, delay, duplicate, corrupt, ...)
/// can be injected per topic without any change to a service. Without an installed factory
/// samples go straight to DDS; services install the fault engine's factory at start
/// (fault_engine.hpp, docs/faults.md).
///
/// Deferred work: a seam may hold samples back (delay, reorder). Writer-side samples are
/// written later by the process-wide SeamPump, which every Executor runs on each pass and does
/// not sleep past; reader-side samples are handed to the service by the reader itself when the
/// executor sees the seam HasDue() (Reader::TakeEach releases them before new samples).

#include <dds/dds.h>

#include <atomic>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>

#include "rover/base/time.hpp"

namespace rover::dds {

enum class Direction { kWrite, kRead };

/// Receives the samples a reader-side seam lets through, for the service to see.
class SampleSink {
 public:
  virtual ~SampleSink() = default;
  /// `sample` is valid only during the call.
  virtual void Deliver(const void* sample, const dds_sample_info_t& info) = 0;
};

/// Intercepts the samples of one topic endpoint (one writer or one reader) in one process.
/// Thread-safe: a writer may be used from several threads.
///
/// Fast path: a seam that knows it would pass every sample through unchanged says so through
/// Idle(), and one that holds no samples back through !Holding(); both are inline atomic loads,
/// and the typed wrappers then skip the virtual calls, so an endpoint no fault matches costs
/// next to nothing. A seam that does not maintain them (generation never set) is never idle.
class TopicSeam {
 public:
  virtual ~TopicSeam() = default;

  /// True when OnWrite/OnRead would pass samples through unchanged right now.
  bool Idle() const {
    return generation_ != nullptr &&
           state_.load(std::memory_order_acquire) ==
               generation_->load(std::memory_order_acquire) * 2 + 1;
  }
  /// True when the seam holds samples back (reader side: ReleaseDue has work, maybe later).
  bool Holding() const { return held_due_ns_.load(std::memory_order_acquire) != kNotHeld; }

  /// Called for each sample a writer is asked to send. The seam sends it (or a modified copy,
  /// or several copies, or none, now or later) with dds_write(writer, ...). Returns the DDS
  /// return code to report to the caller (DDS_RETCODE_OK when it chose to drop or defer).
  virtual dds_return_t OnWrite(dds_entity_t writer, const void* sample,
                               const dds_topic_descriptor_t* type) = 0;
  /// Called for each valid sample a reader took, before the service sees it: hands `out` what
  /// the service sees now (nothing; the sample, possibly changed in place; copies). It may keep
  /// copies and hand them out later from ReleaseDue().
  virtual void OnRead(void* sample, const dds_sample_info_t& info,
                      const dds_topic_descriptor_t* type, SampleSink& out) = 0;
  /// Reader side: whether samples held back are due now. Cheap; called on every executor pass.
  virtual bool HasDue() const { return false; }
  /// Reader side: hands the held samples that are due to `out`, oldest first.
  virtual void ReleaseDue(SampleSink& out) { (void)out; }

 protected:
  static constexpr std::int64_t kNotHeld = std::numeric_limits<std::int64_t>::max();
  /// The owner's generation counter: Idle() holds while state_ == generation * 2 + 1.
  const std::atomic<std::uint64_t>* generation_ = nullptr;
  std::atomic<std::uint64_t> state_{0};
  /// Run-clock ns of the earliest held sample, kNotHeld when none.
  std::atomic<std::int64_t> held_due_ns_{kNotHeld};
};

/// Returns the seam for (topic, direction), or nullptr for none.
using SeamFactory =
    std::function<std::shared_ptr<TopicSeam>(const std::string& topic, Direction direction)>;

/// Installs the process-wide seam factory; readers and writers created afterwards use it.
void InstallSeamFactory(SeamFactory factory);
/// The seam for a new reader or writer (nullptr when no factory is installed).
std::shared_ptr<TopicSeam> SeamFor(const std::string& topic, Direction direction);

/// Deferred work of the seams of this process (writer-side delayed samples, fault records).
class SeamPump {
 public:
  virtual ~SeamPump() = default;
  /// Does what is due now. Called from executor threads, often; cheap when nothing is due.
  virtual void Pump() = 0;
  /// Run-clock time of the earliest deferred sample (reader or writer side), if any.
  virtual std::optional<Time> NextDue() const = 0;
};

/// Installs the process-wide pump (nullptr removes it).
void InstallSeamPump(std::shared_ptr<SeamPump> pump);
/// The installed pump, or nullptr.
std::shared_ptr<SeamPump> CurrentSeamPump();

}  // namespace rover::dds
