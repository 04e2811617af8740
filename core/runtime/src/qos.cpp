#include "rover/runtime/qos.hpp"

namespace rover::dds {

QosSpec DescribeQos(QosProfile profile) {
  switch (profile) {
    case QosProfile::kState: return {true, 1, false};
    case QosProfile::kStream: return {false, 8, false};
    case QosProfile::kCommand: return {true, 0, true, true};
    case QosProfile::kLatched: return {true, 1, true};
  }
  return {};
}

const char* QosProfileName(QosProfile profile) {
  switch (profile) {
    case QosProfile::kState: return "state";
    case QosProfile::kStream: return "stream";
    case QosProfile::kCommand: return "command";
    case QosProfile::kLatched: return "latched";
  }
  return "?";
}

Result<QosProfile> ParseQosProfile(std::string_view name) {
  for (QosProfile p : {QosProfile::kState, QosProfile::kStream, QosProfile::kCommand,
                       QosProfile::kLatched}) {
    if (name == QosProfileName(p)) return p;
  }
  return InvalidArgument("unknown QoS profile '" + std::string(name) +
                         "' (known: state, stream, command, latched)");
}

QosPtr MakeQos(QosProfile profile) {
  const QosSpec spec = DescribeQos(profile);
  QosPtr q(dds_create_qos());
  if (spec.reliable) {
    dds_qset_reliability(q.get(), DDS_RELIABILITY_RELIABLE, DDS_MSECS(100));
  } else {
    dds_qset_reliability(q.get(), DDS_RELIABILITY_BEST_EFFORT, 0);
  }
  if (spec.history_depth == 0) {
    dds_qset_history(q.get(), DDS_HISTORY_KEEP_ALL, 0);
  } else {
    dds_qset_history(q.get(), DDS_HISTORY_KEEP_LAST, spec.history_depth);
  }
  dds_qset_durability(q.get(), spec.transient_local ? DDS_DURABILITY_TRANSIENT_LOCAL
                                                    : DDS_DURABILITY_VOLATILE);
  if (spec.transient_local && spec.history_depth == 0) {
    // Keep-all while unacknowledged; for readers that match later, the last few.
    dds_qset_durability_service(q.get(), 0, DDS_HISTORY_KEEP_LAST, kCommandHistoryDepth,
                                DDS_LENGTH_UNLIMITED, DDS_LENGTH_UNLIMITED, DDS_LENGTH_UNLIMITED);
  }
  return q;
}

}  // namespace rover::dds
