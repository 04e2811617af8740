#pragma once
/// @file
/// The named QoS profiles, defined once for the whole stack (docs/topics.md says which topic
/// uses which):
///
/// | profile | reliability | history      | durability        | use                            |
/// |---------|-------------|--------------|-------------------|--------------------------------|
/// | state   | reliable    | keep-last 1  | volatile          | periodic state, latest wins    |
/// | stream  | best-effort | keep-last 8  | volatile          | high-rate sensor streams       |
/// | command | reliable    | keep-all     | transient-local,  | commands and events: none lost |
/// |         |             |              | fresh only        |                                |
/// | latched | reliable    | keep-last 1  | transient-local   | status a late joiner must see  |
///
/// Commands are transient-local so that none is lost to discovery: a command written after its
/// reader was created but before the two matched (the writer had no reader yet, or the reader had
/// not matched the writer) stays in the writer's history (the last kCommandHistoryDepth) and
/// reaches the reader when they match, whichever side matched first. "Fresh only": a reader drops
/// every sample written before the reader itself was created (source timestamp older than its
/// creation), so a service that joins late or restarts never executes an old command from that
/// history. Both ends stamp on this machine's CLOCK_REALTIME; across machines their clocks must
/// agree to well within the discovery time.

#include <dds/dds.h>

#include <memory>
#include <string>
#include <string_view>

#include "rover/base/status.hpp"

namespace rover::dds {

enum class QosProfile { kState, kStream, kCommand, kLatched };

/// What a profile means, in plain fields (for docs, tests and the benchmark).
struct QosSpec {
  bool reliable = true;
  int history_depth = 1;  ///< 0 = keep-all
  bool transient_local = false;
  /// Readers drop samples written before they were created (see the command profile above).
  bool fresh_only = false;
};

/// Samples a command writer keeps for readers that match after the write.
inline constexpr int kCommandHistoryDepth = 16;

QosSpec DescribeQos(QosProfile profile);
const char* QosProfileName(QosProfile profile);
/// Parses "state", "stream", "command" or "latched"; anything else is InvalidArgument naming
/// the bad value and the valid ones.
Result<QosProfile> ParseQosProfile(std::string_view name);

struct QosDeleter {
  void operator()(dds_qos_t* q) const { dds_delete_qos(q); }
};
using QosPtr = std::unique_ptr<dds_qos_t, QosDeleter>;

/// A new dds_qos_t for the profile (readers and writers use the same one).
QosPtr MakeQos(QosProfile profile);

}  // namespace rover::dds
