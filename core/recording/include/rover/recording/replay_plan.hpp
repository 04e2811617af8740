#pragma once
/// @file
/// Replay without DDS: which channels of a recording are republished on which catalog topic
/// (every check made before anything is published), when each message is due at a given rate,
/// and the sim/clock ticks made up for recordings that have none. The bus replayer
/// (bus_replayer.hpp) publishes what this plans.
///
/// Checks (each an InvalidArgument naming the file and the topic): the topic is in the catalog;
/// the channel's message encoding is `cdr`; it has a schema, of encoding `omgidl`, whose name is
/// the catalog's type of the topic ("dl/pose: the recording has rover::dl::RangeImage, the
/// catalog rover::dl::PoseEstimate"), and whose text is this build's IDL for that type up to
/// comments and layout (else its bytes may not decode: refused unless `accept_schema_changes`).

#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "rover/base/status.hpp"
#include "rover/base/time.hpp"
#include "rover/mcap/reader.hpp"
#include "rover/mcap/writer.hpp"
#include "rover/recording/topic_filter.hpp"

namespace rover::recording {

inline constexpr const char* kClockTopic = "sim/clock";

/// A catalog topic as replay needs it.
struct CatalogTopic {
  std::string name;         ///< "dl/pose"
  std::string c_type_name;  ///< "rover_dl_PoseEstimate"
};

struct ReplaySelection {
  TopicFilter topics;  ///< which recorded topics to republish (sim/clock aside)
  /// Publish sim/clock: the recorded samples when the file has them (whatever `topics` says),
  /// else ticks made up from the log times (ClockTicks).
  bool clock = true;
  bool accept_schema_changes = false;
};

struct ReplayTopic {
  std::string name;
  std::string c_type_name;
  std::string type;                      ///< scoped IDL name
  std::vector<std::uint16_t> channels;   ///< channel ids carrying it (usually one)
  std::uint64_t messages = 0;            ///< from the file's statistics (0 when it has none)
};

struct ReplayPlan {
  std::vector<ReplayTopic> topics;
  std::map<std::uint16_t, std::size_t> topic_of_channel;  ///< channel id -> index in topics
  /// sim/clock comes from the file (it is among `topics`); false with `clock`: make it up.
  bool clock_recorded = false;
  bool synthesize_clock = false;
  std::uint64_t messages = 0;  ///< of the selected channels (statistics; 0 when unknown)
  mcap::Timestamp start_time = 0;
  mcap::Timestamp end_time = 0;
};

/// Plans the replay of an open recording onto `catalog`'s topics. InvalidArgument when no
/// channel is selected, or for the first channel failing a check above.
Result<ReplayPlan> PlanReplay(const mcap::Reader& reader, const ReplaySelection& selection,
                              std::span<const CatalogTopic> catalog);

/// When each message is due, in wall time since the first one: (log_time - first) / rate.
/// Rate 0: everything at once (as fast as the bus takes it).
class ReplayPacer {
 public:
  /// Precondition: rate >= 0 and finite.
  explicit ReplayPacer(double rate);
  /// [ns of wall time after the first call] when a message of `log_time` is due; 0 for rate 0.
  /// Log times before the first one (a simulator reset) are due at once.
  std::int64_t DueAfterNs(mcap::Timestamp log_time);

 private:
  double rate_;
  std::optional<mcap::Timestamp> first_;
};

/// Made-up sim/clock times for a recording without sim/clock: one tick per `period_ns` of log
/// time, on multiples of the period, from the first message's log time on.
class ClockTicks {
 public:
  explicit ClockTicks(std::int64_t period_ns = 10'000'000);
  /// The ticks due before a message at `log_time` (every period boundary since the last tick,
  /// and one at the first message): publish them, in order, before that message.
  std::vector<mcap::Timestamp> Before(mcap::Timestamp log_time);

 private:
  std::int64_t period_ns_;
  std::optional<mcap::Timestamp> last_;
};

}  // namespace rover::recording
