#pragma once
/// @file
/// Helpers shared by the tests: an isolated DDS domain per test process on loopback, paths to the
/// build and source trees, and waiting on conditions with a deadline.

#include <chrono>
#include <functional>
#include <string>

#include "rover/runtime/domain.hpp"

namespace rover::testing {

/// Points CYCLONEDDS_URI at deploy/cyclonedds/loopback.xml and leases a DDS domain no other
/// test or run on this machine uses. Keep the returned lease alive for the test's duration.
dds::DomainLease IsolatedDomain();

std::string SourceDir();
std::string BinaryDir();
/// build/bin: where services and roverctl are.
std::string BinDir();
/// A fresh empty directory under the system temp dir, removed by the caller if wanted.
std::string MakeTempDir(const std::string& prefix);
/// Reads a whole file ("" if missing).
std::string ReadFile(const std::string& path);

/// Polls `condition` every 10 ms until it holds or `timeout` (wall time) passes; returns whether
/// it held. Wall time is right here: these are liveness limits of the test harness, never
/// assertions on speed.
bool WaitFor(const std::function<bool()>& condition,
             std::chrono::milliseconds timeout = std::chrono::seconds(20));

}  // namespace rover::testing
