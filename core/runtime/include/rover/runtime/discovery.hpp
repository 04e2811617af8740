#pragma once
/// @file
/// Who else is on a DDS domain: the writers other participants have announced (Cyclone's
/// built-in DCPSPublication topic). Replay uses it to refuse a domain where someone already
/// publishes a topic it would publish.

#include <string>
#include <vector>

#include "rover/base/status.hpp"
#include "rover/base/time.hpp"
#include "rover/runtime/dds.hpp"

namespace rover::dds {

struct RemoteWriter {
  std::string topic;
  std::string type;         ///< DDS type name, "rover::dl::PoseEstimate"
  std::string participant;  ///< GUID prefix (hex), or "pid 123 (ddl-imu)" when it says so
};

/// The writers of other participants on `p`'s domain, after waiting `wait` (wall) for
/// discovery; `p`'s own are left out.
Result<std::vector<RemoteWriter>> DiscoverRemoteWriters(const Participant& p, Duration wait);

}  // namespace rover::dds
