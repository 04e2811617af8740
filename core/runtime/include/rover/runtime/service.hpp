#pragma once
/// @file
/// The service base: every process of the stack is one Service run by RunServiceMain().
///
/// Lifecycle (after ROS 2 managed nodes, reduced to what the stack needs):
///
///   UNCONFIGURED --Configure--> INACTIVE --Activate--> ACTIVE --Deactivate--> INACTIVE
///        any state --Shutdown--> FINALIZED
///
/// Configure declares, loads and validates the parameters, then calls OnConfigure (create
/// readers and writers there). A service whose parameters are invalid stays UNCONFIGURED and
/// refuses to activate, naming the bad parameter. Only while ACTIVE are its subscriptions and
/// run-clock timers served. A heartbeat on sys/health reports the state once per wall second.
///
/// Command line of every service (environment variables in brackets, set by roverctl):
///   --name NAME [ROVER_SERVICE_NAME]   instance name, the heartbeat key
///   --domain N [ROVER_DOMAIN]           DDS domain id
///   --clock wall|sim [ROVER_CLOCK]      run clock: wall time, or sim/clock from the simulator
///   --lockstep lead|strict [ROVER_LOCKSTEP]  under sim/clock: acknowledge every 25 ms served
///                                       (lead, the default) or serve the simulator's ticks
///                                       strictly (lockstep.hpp; scenario runs)
///   --params FILE ... [ROVER_PARAMS]    YAML parameter files (ROVER_PARAMS is ':'-separated)
///   --set key=value ...                 overrides, applied after the files
///   --faults FILE [ROVER_FAULTS]         faults to inject from the start (docs/faults.md)
///   --validate                          load and validate parameters and faults, then exit
///                                       (no DDS)
///   --help-params / --print-params      list declared / effective parameters
/// Exit codes: 0 clean stop, 1 runtime failure, 2 bad configuration.
///
/// Fault injection: every service installs the fault engine (fault_control.hpp) before it
/// creates any reader or writer, so faults can be added at run time over sys/fault_control.
/// ROVER_FAULTS_EPOCH_NS (run-clock ns) is what start_s of the faults counts from (default:
/// run clock zero under sim/clock, the service's start under wall time);
/// ROVER_FAULT_INJECTION=off leaves the seam out entirely.
///
/// Input monitoring (issue 12, input_monitor.hpp): every typed subscription made with
/// ServiceContext::Subscribe passes through the context's InputMonitor: header.seq per writer,
/// the callback's verdict (a callback that returns a non-ok Status rejected the sample, with
/// that message; one that throws did too) and the age of the newest accepted sample against
/// the limits the service declares in Service::Inputs() (parameters `inputs.<topic>.*`). Every
/// heartbeat carries the worse of the service's own health (SetHealth) and the monitor's worst
/// finding: a stale input is HEALTH_STALE, a rejection or a seq gap HEALTH_DEGRADED, with the
/// finding's reason ("dl/pose stale: last sample 1.8 s ago (limit 0.5 s)"). A change of the
/// verdict is published at once; findings are re-evaluated every kInputCheckPeriodS of run time
/// while active.

#include <exception>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "rover/base/clock.hpp"
#include "rover/base/params.hpp"
#include "rover/base/status.hpp"
#include "rover/runtime/activity.hpp"
#include "rover/runtime/dds.hpp"
#include "rover/runtime/executor.hpp"
#include "rover/runtime/fault_control.hpp"
#include "rover/runtime/input_monitor.hpp"

namespace rover {

enum class LifecycleState { kUnconfigured, kInactive, kActive, kFinalized };
const char* LifecycleStateName(LifecycleState s);

struct ServiceOptions {
  std::string name;                      ///< instance name; defaults to the service kind
  int domain = 0;                        ///< DDS domain id
  std::string clock = "wall";            ///< "wall" or "sim"
  std::vector<std::string> param_files;  ///< YAML files, applied in order
  std::vector<std::string> overrides;    ///< key=value, applied after the files
  double heartbeat_period_s = 1.0;       ///< wall seconds between heartbeats
  bool fault_injection = true;           ///< install the fault seam (ROVER_FAULT_INJECTION)
  std::string faults_file;               ///< initial faults (ROVER_FAULTS / --faults)
  std::vector<faults::FaultSpec> faults; ///< initial faults, parsed (LoadFaults fills it)
  std::optional<std::int64_t> fault_epoch_ns;  ///< ROVER_FAULTS_EPOCH_NS
  std::string lockstep = "lead";               ///< "lead" or "strict" (only with clock "sim")
};

/// Parses options.faults_file into options.faults (nothing when the name is empty).
Status LoadFaults(ServiceOptions* options);

/// Checks the options themselves (clock name, domain range, heartbeat period).
Status ValidateOptions(const ServiceOptions& options);

/// What a service uses at run time: its participant, clock, executor and topic helpers.
class ServiceContext {
 public:
  /// Creates the DDS participant, the run clock (subscribing to sim/clock for "sim"), the
  /// executor and the heartbeat writer.
  static Result<std::unique_ptr<ServiceContext>> Create(const ServiceOptions& options);
  ~ServiceContext();

  const std::string& name() const { return name_; }
  const dds::Participant& participant() const { return participant_; }
  const Clock& clock() const { return *clock_; }
  Executor& executor() { return *executor_; }
  Time Now() const { return clock_->Now(); }

  /// A writer; QoS from the topic catalog (or `profile` for a topic outside it).
  template <class T>
  Result<dds::Writer<T>> MakeWriter(const std::string& topic,
                                    std::optional<dds::QosProfile> profile = std::nullopt) {
    return dds::Writer<T>::Create(participant_, topic, profile);
  }

  /// Subscribes `callback` to a topic; the context owns the reader. `always` subscriptions are
  /// served in every lifecycle state. The callback takes a `const dds::Sample<T>&` and returns
  /// void (every sample counts as accepted) or Status (non-ok: the sample was rejected, e.g. its
  /// conversion failed; the message reaches sys/health). Every sample passes through the input
  /// monitor (see the file comment); an exception out of the callback is caught, logged and
  /// counts as a rejection, so no sample can stop the service.
  template <class T, class F>
  Status Subscribe(const std::string& topic, F callback,
                   std::optional<dds::QosProfile> profile = std::nullopt, bool always = false) {
    auto r = dds::Reader<T>::Create(participant_, topic, profile);
    if (!r.ok()) return r.status();
    auto holder = std::make_shared<dds::Reader<T>>(std::move(*r));
    readers_.push_back(holder);
    const std::size_t input = inputs_->Watch(topic, ToleratedLoss(holder->profile()));
    ++subscriptions_;
    std::function<void(const dds::Sample<T>&)> wrapped =
        [this, input, topic, cb = std::move(callback)](const dds::Sample<T>& s) mutable {
          const Time now = Now();
          const bool watched = InputsStarted();  // not before the run clock is valid
          bool changed = false;
          Time stamp{0};
          if constexpr (dds::HasHeader<T>) {
            if (watched) {
              changed =
                  inputs_->OnArrival(input, s.info().publication_handle, s->header.seq, now);
            }
            stamp = Time{s->header.stamp_ns};
          }
          Status result = Status::Ok();
          try {
            if constexpr (std::is_same_v<std::invoke_result_t<F&, const dds::Sample<T>&>,
                                         Status>) {
              result = cb(s);
            } else {
              cb(s);
            }
          } catch (const std::exception& e) {
            result = Internal(std::string("handling the sample threw: ") + e.what());
            LogCallbackFailure(topic, result);
          } catch (...) {
            result = Internal("handling the sample threw a non-standard exception");
            LogCallbackFailure(topic, result);
          }
          if (!watched) return;
          if (result.ok()) {
            inputs_->OnAccepted(input, stamp, now);
          } else {
            inputs_->OnRejected(input, result.message(), now);
            changed = true;
          }
          if (changed || input_health_ != rover_HEALTH_OK) UpdateInputHealth();
        };
    return executor_->Subscribe<T>(*holder, std::move(wrapped), always);
  }

  /// The input monitor (Lifecycle::Configure installs the one the parameters describe).
  runtime::InputMonitor& inputs() { return *inputs_; }
  const runtime::InputMonitor& inputs() const { return *inputs_; }
  /// Replaces the input monitor; only before the first Subscribe (a programming error after).
  void SetInputMonitor(runtime::InputMonitor monitor);
  /// Re-evaluates the input findings at Now(); publishes a heartbeat at once when the level or
  /// the worst finding (topic, problem, number of findings) changed.
  void UpdateInputHealth();
  /// The input part of the heartbeat: health and reason.
  rover_SensorHealth input_health() const { return input_health_; }
  const std::string& input_reason() const { return input_reason_; }
  /// The lost-sample share of a reader that is no finding (input_monitor.hpp): keep-last-1
  /// topics may overwrite samples (1: gaps never count), best-effort streams lose some by design
  /// (runtime::kStreamTolerableLoss), keep-all topics none (0).
  static double ToleratedLoss(dds::QosProfile profile);
  /// Period of the run-clock timer that re-evaluates the input findings (while active).
  static constexpr double kInputCheckPeriodS = 0.1;

  /// Stamps a header: the run clock's time and `frame_id`; header.seq is set to 0, so that the
  /// writer that publishes the sample numbers it (per writer, dds::Writer).
  void Stamp(rover_Header& header, std::string_view frame_id);

  /// The service's own health, reported in every heartbeat.
  void SetHealth(rover_SensorHealth health, std::string message);
  /// Also (re)starts the input monitor when the state becomes ACTIVE (ages count from there, or
  /// from the first valid run-clock time after it).
  void SetLifecycleState(LifecycleState state);
  LifecycleState lifecycle_state() const { return state_; }
  /// Sends a heartbeat now.
  void PublishHeartbeat();
  /// The fault agent (nullptr when injection is off).
  faults::FaultAgent* faults() { return faults_.get(); }
  /// Wall time per named activity (physics, render, stereo, vo, planning, ...), sent with every
  /// heartbeat beside the process's CPU time (activity.hpp).
  runtime::ActivityLog& activities() { return activities_; }

 private:
  ServiceContext() = default;

  std::string name_;
  dds::Participant participant_;
  std::unique_ptr<Clock> clock_;
  ManualClock* sim_clock_ = nullptr;  // == clock_ when simulated
  // Before every reader and writer (and destroyed after the executor that serves its reader).
  std::unique_ptr<faults::FaultAgent> faults_;
  std::vector<std::shared_ptr<void>> readers_;
  std::unique_ptr<dds::Reader<rover_sim_Clock>> clock_reader_;
  std::unique_ptr<Executor> executor_;
  dds::Writer<rover_sys_Heartbeat> heartbeat_writer_;
  dds::Writer<rover_sys_Event> event_writer_;
  // Under sim/clock: sim/clock_ack after each executor pass that saw the clock advance by
  // kClockAckPeriod (or stand still after an advance).
  void AcknowledgeClock();
  dds::Writer<rover_sim_ClockAck> clock_ack_writer_;
  std::optional<Time> last_served_counted_;  // strict: the last tick counted in ticks_served
  Time last_ack_;
  bool acked_once_ = false;
  bool strict_lockstep_ = false;
  std::uint64_t clock_samples_ = 0;        // sim/clock samples heard
  std::uint64_t clock_samples_acked_ = 0;  // ... when the last acknowledgement went out
  std::uint64_t late_reported_ = 0;        // lock-step late samples already warned about
  std::uint64_t missing_reported_ = 0;     // lock-step missing samples already warned about
  LifecycleState state_ = LifecycleState::kUnconfigured;
  rover_SensorHealth health_ = rover_HEALTH_OK;
  std::string health_message_;
  std::uint64_t heartbeat_count_ = 0;
  runtime::ActivityLog activities_;
  // Input monitoring.
  void LogCallbackFailure(const std::string& topic, const Status& s);
  // Starts the monitor at the first valid run-clock time after activation (under sim/clock a
  // service may be activated before the clock is heard, or restarted mid-run); true once it is.
  bool InputsStarted();
  bool inputs_started_ = false;
  std::unique_ptr<runtime::InputMonitor> inputs_;
  int subscriptions_ = 0;  // made through Subscribe
  rover_SensorHealth input_health_ = rover_HEALTH_OK;
  std::string input_reason_;
  std::string input_key_;  // level and worst finding last published
};

/// Base class of every service. Override OnConfigure at least.
class Service {
 public:
  /// `kind` names the service type (e.g. "dl-smoke"); it is the default instance name.
  explicit Service(std::string kind) : kind_(std::move(kind)) {}
  virtual ~Service() = default;
  Service(const Service&) = delete;
  Service& operator=(const Service&) = delete;

  const std::string& kind() const { return kind_; }

  /// Declare every parameter the service reads.
  virtual void DeclareParameters(ParamSet& params) { (void)params; }
  /// The inputs whose limits the service declares (staleness, seq checks); their parameters
  /// `inputs.<topic>.*` are declared for it. Inputs subscribed but not listed are still
  /// monitored for rejections and seq problems, with no staleness limit.
  virtual std::vector<runtime::InputSpec> Inputs() const { return {}; }
  /// Checks rules that span several parameters (ranges are already checked). Runs in
  /// `--validate`, so `roverctl up` reports these errors before anything starts. No DDS here.
  virtual Status ValidateParameters(const ParamSet& params) const {
    (void)params;
    return Status::Ok();
  }
  /// Read parameters, create readers, writers and timers. Parameters are already valid.
  virtual Status OnConfigure(ServiceContext& ctx, const ParamSet& params) = 0;
  virtual Status OnActivate(ServiceContext& ctx) {
    (void)ctx;
    return Status::Ok();
  }
  virtual Status OnDeactivate(ServiceContext& ctx) {
    (void)ctx;
    return Status::Ok();
  }
  virtual void OnShutdown(ServiceContext& ctx) { (void)ctx; }

 private:
  std::string kind_;
};

/// Declares the service's parameters into `params`, loads the option's files and overrides,
/// and validates. Needs no DDS.
Status LoadParameters(Service& service, const ServiceOptions& options, ParamSet* params);

/// Drives one Service through its lifecycle and keeps the state machine honest.
class Lifecycle {
 public:
  Lifecycle(Service& service, ServiceContext& ctx, ServiceOptions options);

  LifecycleState state() const { return state_; }
  /// The error of the last failed transition (empty when none failed).
  const std::string& last_error() const { return last_error_; }

  Status Configure();
  Status Activate();
  Status Deactivate();
  Status Shutdown();
  const ParamSet& params() const { return params_; }

 private:
  void Enter(LifecycleState s);
  Status Fail(Status s);

  Service& service_;
  ServiceContext& ctx_;
  ServiceOptions options_;
  ParamSet params_;
  LifecycleState state_ = LifecycleState::kUnconfigured;
  std::string last_error_;
};

/// Parses the command line, configures and activates the service, spins until SIGINT or
/// SIGTERM, then deactivates and shuts it down. Returns the process exit code.
int RunServiceMain(Service& service, int argc, char** argv);

}  // namespace rover
