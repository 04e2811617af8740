#pragma once
/// @file
/// The named QoS profiles, defined once for the whole stack (docs/topics.md says which topic
/// uses which):
///
/// | profile | reliability | history      | durability      | use                              |
/// |---------|-------------|--------------|-----------------|----------------------------------|
/// | state   | reliable    | keep-last 1  | volatile        | periodic state, latest wins      |
/// | stream  | best-effort | keep-last 8  | volatile        | high-rate sensor streams         |
/// | command | reliable    | keep-all     | volatile        | commands and events: none lost   |
/// | latched | reliable    | keep-last 1  | transient-local | status a late joiner must see    |

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
};

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
