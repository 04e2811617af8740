#pragma once
/// @file
/// The run's record of its injected faults (run_report.hpp InjectedFault): the set's fault
/// specs, and the sys/fault_event records the services send about them (STARTED when a window
/// opens in a service with a matching endpoint, COUNT while it acts, ENDED when it closes or is
/// removed, LISTED in answer to the runner's final LIST). DDS-free: the runner feeds it.
///
/// Per fault and service the counts are the largest heard (records only grow); the fault's
/// counts are their sums over services. Its start is the window start the services report, its
/// end the earliest ENDED (or, from a LISTED "ended" answer, the window's end).

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "rover/deploy/run_report.hpp"
#include "rover/runtime/fault_engine.hpp"

namespace rover::deploy::runner {

class FaultLog {
 public:
  explicit FaultLog(std::vector<faults::FaultSpec> specs);

  void Add(const faults::FaultRecord& record);
  /// Every spec's fault (and any other fault heard of), in id order.
  std::vector<InjectedFault> Summary() const;

 private:
  struct PerService {
    std::uint64_t seen = 0, hit = 0;
    bool started = false;
  };
  struct Entry {
    InjectedFault fault;
    std::map<std::string, PerService> services;
  };
  Entry& EntryFor(const faults::FaultRecord& r);

  std::map<std::uint32_t, Entry> entries_;
};

}  // namespace rover::deploy::runner
