#pragma once
/// @file
/// roverctl's fault commands: `roverctl fault add|list|clear` against a running set, over
/// sys/fault_control (core/runtime fault_control.hpp: every service's fault agent validates,
/// applies and answers on sys/fault_event). roverctl_main.cpp finds the project; these do the
/// work. docs/roverctl.md "fault", docs/faults.md.

#include <cstdint>
#include <map>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "rover/base/status.hpp"
#include "rover/runtime/fault_engine.hpp"

namespace rover::deploy {

/// The set a fault command talks to.
struct FaultTarget {
  std::string project;
  int domain = -1;
  /// The services that run a fault agent (running rover services that send heartbeats): the
  /// command waits for all of them, so that nothing it sends is lost to discovery.
  std::vector<std::string> services;
  double discovery_s = 10;  ///< [s] wall: how long to wait for them
  double answer_s = 3;      ///< [s] wall: how long to wait for every service's answer
  std::string security_dir; ///< a secured set's keys (state.json); "" = open
};

/// What `fault add` was given: an inline YAML map (`'{kind: drop, topic: dl/pose}'`), a file
/// of faults (`-f`), and/or key flags (`--kind drop --topic dl/pose`; a flag overrides the same
/// key of the inline map). Keys are those of x-rover.faults (docs/faults.md).
struct FaultAddArgs {
  std::string inline_spec;
  std::string file;
  std::map<std::string, std::string> keys;  ///< key -> value text
  bool from_epoch = false;  ///< start_s from the run's epoch instead of from receipt
};

/// The specs `fault add` sends, validated (unknown kind or key, a topic pattern matching no
/// catalog topic, a field the type lacks, a probability outside [0, 1]: a one-line error
/// "fault add: key 'kind': ..." or "<file>:<line>: key ...", and nothing is sent). Ids: the
/// given `id`, else the next ones above `used`.
Result<std::vector<faults::FaultSpec>> BuildFaultSpecs(const FaultAddArgs& args,
                                                       const std::vector<std::uint32_t>& used);

/// The `fault list` table: one row per fault and service it applies to, with the samples seen
/// and hit, in id order; faults no service applies show once with service "-".
std::string FormatFaultList(const std::vector<faults::FaultRecord>& listed);

/// The commands. Exit codes: 0 done; 1 the set did not answer or a service refused (nothing
/// left applied); 2 a bad spec or usage (nothing sent).
int RunFaultAdd(const FaultTarget& target, const FaultAddArgs& args, std::ostream& out,
                std::ostream& err);
int RunFaultList(const FaultTarget& target, bool json, std::ostream& out, std::ostream& err);
int RunFaultClear(const FaultTarget& target, std::optional<std::uint32_t> id, std::ostream& out,
                  std::ostream& err);

}  // namespace rover::deploy
