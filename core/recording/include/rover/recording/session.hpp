#pragma once
/// @file
/// One recording: serialised samples of known topics into an MCAP file (rover_mcap), without
/// DDS. The bus recorder (bus_recorder.hpp) takes samples off the bus and hands them here.
///
/// Each topic becomes one channel (message encoding `cdr`) on the schema of its type (encoding
/// `omgidl`, name the scoped IDL type name, schema.hpp); a channel is written when its first
/// message arrives, so the file lists the topics that carried data. Per message: log time = the
/// run clock when the recorder received it, publish time = the sample's header.stamp_ns (the
/// run-clock time of validity its publisher gave it; the log time when that is not positive),
/// sequence = the message's number on its channel (from 1).
///
/// Ends: the size cap (the writer refuses every message from the first that would not fit: the
/// file is a complete prefix, marked truncated, and the session counts what it dropped; not an
/// error), an I/O error (sticky: every later Write and Close return it, and the file keeps no
/// footer, so no reader takes it for complete).

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "rover/base/status.hpp"
#include "rover/mcap/writer.hpp"
#include "rover/recording/cdr.hpp"

namespace rover::recording {

/// The Metadata record a session writes at Close about the recording (name and keys).
inline constexpr const char* kRecorderMetadataName = "rover_recorder";

struct TopicStats {
  std::string topic;
  std::string type;                 ///< scoped IDL type name
  std::uint64_t messages = 0;       ///< written
  std::uint64_t bytes = 0;          ///< serialised bytes written
  std::uint64_t dropped = 0;        ///< refused after the size cap
  std::uint64_t lost = 0;           ///< reported lost by the transport (CountLost)
  std::uint64_t header_errors = 0;  ///< samples whose header could not be read (still written)
};

struct SessionStats {
  std::uint64_t messages = 0;
  std::uint64_t bytes = 0;
  std::uint64_t dropped = 0;
  std::uint64_t lost = 0;
  bool capped = false;
  std::uint64_t file_bytes = 0;  ///< written to the file so far (the final size after Close)
  std::int64_t first_log_time_ns = -1;
  std::int64_t last_log_time_ns = -1;
  std::vector<TopicStats> topics;  ///< in AddTopic order
};

class RecordingSession {
 public:
  /// Creates (truncates) `path`; its directory must exist. Errors name the path.
  static Result<std::unique_ptr<RecordingSession>> Create(const std::string& path,
                                                          const mcap::WriterOptions& options);
  /// Onto a sink (tests).
  static Result<std::unique_ptr<RecordingSession>> Create(std::unique_ptr<mcap::Sink> sink,
                                                          const mcap::WriterOptions& options);

  /// Registers a topic of catalog type `c_type_name`; its schema is built now (NotFound for a
  /// type this build has no IDL for). `metadata` goes onto the channel (e.g. its QoS profile).
  /// Returns the topic's index for Write.
  Result<std::size_t> AddTopic(const std::string& topic, const std::string& c_type_name,
                               const mcap::StringMap& metadata = {});

  /// One serialised sample of topic `index` received at run-clock time `log_time_ns` (negative
  /// times are recorded as 0). Ok also when the size cap refused it (see capped()); the first
  /// I/O error otherwise.
  Status Write(std::size_t index, std::int64_t log_time_ns, ByteSpan sample);
  /// Samples of topic `index` the transport reports lost.
  void CountLost(std::size_t index, std::uint64_t count);

  /// Writes `metadata` (as Metadata "rover_recorder", with the counts added), the summary and the
  /// footer; returns the first error of the recording, if any. A second call returns the same.
  Status Close(mcap::StringMap metadata = {});

  bool capped() const { return writer_->capped(); }
  /// The first I/O error, or Ok.
  const Status& failure() const { return failure_; }
  const SessionStats& stats() const { return stats_; }
  const std::string& name() const { return writer_->name(); }

 private:
  explicit RecordingSession(std::unique_ptr<mcap::Writer> writer) : writer_(std::move(writer)) {}

  struct Topic {
    std::string name;
    std::string schema_name;
    std::string schema_text;
    mcap::StringMap metadata;
    std::uint16_t channel = 0;  ///< 0 until the first message
    std::uint32_t sequence = 0;
  };

  std::unique_ptr<mcap::Writer> writer_;
  std::vector<Topic> topics_;
  SessionStats stats_;
  Status failure_;
  bool closed_ = false;
  Status close_status_;
};

/// Where a recorder's log times come from: the latest sim/clock sample heard (kSim; 0 before
/// the first), or the wall clock (kWall: CLOCK_REALTIME, as the run clock of a wall-clock set).
class LogClock {
 public:
  enum class Mode { kSim, kWall };
  explicit LogClock(Mode mode) : mode_(mode) {}
  /// A sim/clock sample; ignored in kWall mode and when it cannot be read (counted).
  void OnClockSample(ByteSpan sample);
  /// [ns] the run clock now.
  std::int64_t Now() const;
  Mode mode() const { return mode_; }
  bool heard_clock() const { return heard_; }
  std::uint64_t unreadable() const { return unreadable_; }

 private:
  Mode mode_;
  std::int64_t sim_ns_ = 0;
  bool heard_ = false;
  std::uint64_t unreadable_ = 0;
};

}  // namespace rover::recording
