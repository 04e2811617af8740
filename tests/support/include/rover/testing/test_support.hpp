#pragma once
/// @file
/// Helpers shared by the tests: the DDS configuration and an isolated DDS domain per test, paths
/// to the build and source trees, and waiting on conditions with a deadline. In-process service
/// tests use rover/testing/service_harness.hpp on top of these.
///
/// DDS configuration: a test never relies on what the shell exported. Before it creates a
/// participant or spawns a process that talks DDS, it calls UseLoopbackDds (IsolatedDomain and
/// JoinDomain do), so CYCLONEDDS_URI names deploy/cyclonedds/loopback.xml in this process and in
/// every child it spawns afterwards.

#include <chrono>
#include <functional>
#include <string>

#include "rover/base/status.hpp"
#include "rover/runtime/dds.hpp"
#include "rover/runtime/domain.hpp"

namespace rover::testing {

/// Points CYCLONEDDS_URI at deploy/cyclonedds/loopback.xml (whatever it was before). Cyclone
/// reads it when a domain is first used in the process, so call it before the first participant.
void UseLoopbackDds();

/// UseLoopbackDds, then leases a DDS domain no other test or run on this machine uses. Keep the
/// returned lease alive for the test's duration.
dds::DomainLease IsolatedDomain();

/// UseLoopbackDds, then a participant on `domain`: for a test that talks to a service set
/// someone else started on that domain (roverctl up, a spawned service).
Result<dds::Participant> JoinDomain(int domain);

std::string SourceDir();
std::string BinaryDir();
/// build/bin: where services and roverctl are.
std::string BinDir();
/// A fresh empty directory under the system temp dir, removed by the caller if wanted.
std::string MakeTempDir(const std::string& prefix);
/// Reads a whole file ("" if missing).
std::string ReadFile(const std::string& path);
/// Runs a shell command line and returns what it wrote on stdout ("" if it could not start).
std::string CaptureStdout(const std::string& command);

/// Polls `condition` every 10 ms until it holds or `timeout` (wall time) passes; returns whether
/// it held. Wall time is right here: these are liveness limits of the test harness, never
/// assertions on speed.
bool WaitFor(const std::function<bool()>& condition,
             std::chrono::milliseconds timeout = std::chrono::seconds(20));

}  // namespace rover::testing
