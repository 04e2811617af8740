#pragma once
/// @file
/// Fault injection over DDS: the agent every service runs (FaultAgent: the process's fault
/// engine, fed by ROVER_FAULTS and sys/fault_control, reporting on sys/fault_event) and the
/// client tools use to drive it (FaultClient: add, remove, clear, list).
///
/// Protocol (docs/faults.md "Delivery"): a FaultControl ADD carries one spec (ToControl);
/// every service answers each control message on sys/fault_event: ADDED or REJECTED (with the
/// reason) for ADD, ENDED/REMOVED for REMOVE and CLEAR, one LISTED record per fault it holds
/// for LIST. While a fault is active each service where it applies reports STARTED, a COUNT of
/// the samples it touched every report period, and ENDED with the final count. The seam leaves
/// sys/fault_control and sys/fault_event alone, so a partitioned service still hears `clear`.

#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "rover/base/clock.hpp"
#include "rover/runtime/dds.hpp"
#include "rover/runtime/executor.hpp"
#include "rover/runtime/fault_engine.hpp"

namespace rover::faults {

/// Fault injection inside one service process.
class FaultAgent {
 public:
  struct Options {
    std::string service;              ///< the service's instance name
    std::vector<FaultSpec> initial;   ///< e.g. from ROVER_FAULTS; added by Attach()
    Time epoch{0};                    ///< what start_s of kRunEpoch faults counts from
    Duration report_period = std::chrono::seconds(1);
  };

  /// Creates the engine and installs it as the process's seam factory and pump. Call before
  /// the service creates any reader or writer. `clock` must outlive the agent.
  static std::unique_ptr<FaultAgent> Install(const Clock& clock, Options options);
  /// Creates the sys/fault_event writer, subscribes sys/fault_control (served in every
  /// lifecycle state) and adds the initial faults (already validated by the caller; an
  /// invalid one is an error here too).
  Status Attach(const dds::Participant& participant, Executor& executor);
  ~FaultAgent();

  FaultEngine& engine() { return engine_; }
  /// Times faults and stamps fault events on `clock` (FaultEngine::UseClock); it must outlive
  /// the agent.
  void UseClock(const Clock& clock, Time epoch);

 private:
  FaultAgent(const Clock& clock, Options options);
  void OnControl(const rover_sys_FaultControl& m);
  void Publish(const FaultRecord& r);
  void Reject(std::uint32_t id, rover_sys_FaultKind kind, const std::string& why);

  const Clock* clock_;
  Options options_;
  FaultEngine engine_;
  dds::Writer<rover_sys_FaultEvent> events_;
  std::unique_ptr<dds::Reader<rover_sys_FaultControl>> control_;
  std::uint32_t seq_ = 0;
};

/// The FaultEvent message of a record / the record of a message.
void ToIdl(const FaultRecord& r, rover_sys_FaultEvent* out);
FaultRecord FromIdl(const rover_sys_FaultEvent& e);

/// Drives the fault agents of a running set (roverctl fault add|list|clear, scenario runner).
class FaultClient {
 public:
  static Result<FaultClient> Create(const dds::Participant& participant);

  /// Waits (wall time, at most `timeout`) until `services` agents are matched both ways, so
  /// that nothing sent is lost to discovery. Timeout names how many were seen.
  Status WaitForServices(int services, Duration timeout);
  /// Sends a validated spec (spec.id > 0; pick one that is not in use, e.g. from List()).
  Status Add(const FaultSpec& spec);
  Status Remove(std::uint32_t id);
  Status Clear();
  /// Asks every agent to list its faults, collects the LISTED answers for `collect` (wall).
  std::vector<FaultRecord> List(Duration collect);
  /// sys/fault_event records received so far (answers, starts, counts, ends).
  std::vector<FaultRecord> TakeRecords();

 private:
  Status Send(rover_sys_FaultControl& m);

  dds::Writer<rover_sys_FaultControl> control_;
  dds::Reader<rover_sys_FaultEvent> events_;
  std::uint32_t seq_ = 0;
};

}  // namespace rover::faults
