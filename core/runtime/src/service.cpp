#include "rover/runtime/service.hpp"

#include <CLI/CLI.hpp>
#include <pthread.h>
#include <signal.h>
#include <unistd.h>

#include <cstdlib>
#include <malloc.h>
#include <iostream>
#include <sstream>
#include <thread>

#include "rover/base/log.hpp"

namespace rover {

const char* LifecycleStateName(LifecycleState s) {
  switch (s) {
    case LifecycleState::kUnconfigured: return "unconfigured";
    case LifecycleState::kInactive: return "inactive";
    case LifecycleState::kActive: return "active";
    case LifecycleState::kFinalized: return "finalized";
  }
  return "?";
}

namespace {
rover_sys_LifecycleState ToIdl(LifecycleState s) {
  switch (s) {
    case LifecycleState::kUnconfigured: return rover_sys_LIFECYCLE_UNCONFIGURED;
    case LifecycleState::kInactive: return rover_sys_LIFECYCLE_INACTIVE;
    case LifecycleState::kActive: return rover_sys_LIFECYCLE_ACTIVE;
    case LifecycleState::kFinalized: return rover_sys_LIFECYCLE_FINALIZED;
  }
  return rover_sys_LIFECYCLE_ERROR;
}

// FAILED > STALE > DEGRADED > OK (as msg::WorseHealth orders them).
int HealthRank(rover_SensorHealth h) {
  switch (h) {
    case rover_HEALTH_OK: return 0;
    case rover_HEALTH_DEGRADED: return 1;
    case rover_HEALTH_STALE: return 2;
    case rover_HEALTH_FAILED: return 3;
  }
  return 3;
}

rover_SensorHealth HealthOfInputs(const runtime::InputReport& r) {
  if (r.verdict == runtime::InputVerdict::kNominal) return rover_HEALTH_OK;
  if (r.verdict == runtime::InputVerdict::kDegraded) return rover_HEALTH_DEGRADED;
  return r.findings.front().problem == runtime::InputProblem::kStale ? rover_HEALTH_STALE
                                                                     : rover_HEALTH_FAILED;
}

rover_sys_Severity ToSeverity(log::Level l) {
  switch (l) {
    case log::Level::kDebug: return rover_sys_SEVERITY_DEBUG;
    case log::Level::kInfo: return rover_sys_SEVERITY_INFO;
    case log::Level::kWarning: return rover_sys_SEVERITY_WARNING;
    case log::Level::kError: return rover_sys_SEVERITY_ERROR;
  }
  return rover_sys_SEVERITY_ERROR;
}
}  // namespace

Status ValidateOptions(const ServiceOptions& o) {
  if (o.clock != "wall" && o.clock != "sim") {
    return InvalidArgument("--clock: '" + o.clock + "' is not one of: wall, sim");
  }
  if (o.lockstep != "lead" && o.lockstep != "strict") {
    return InvalidArgument("--lockstep: '" + o.lockstep + "' is not one of: lead, strict");
  }
  if (o.domain < 0 || o.domain > 232) {
    return InvalidArgument("--domain: " + std::to_string(o.domain) +
                           " is out of range [0, 232]");
  }
  if (!(o.heartbeat_period_s > 0.0)) {
    return InvalidArgument("heartbeat period must be > 0 s");
  }
  return Status::Ok();
}

// ---- ServiceContext ----------------------------------------------------------------------------

Result<std::unique_ptr<ServiceContext>> ServiceContext::Create(const ServiceOptions& options) {
  ROVER_RETURN_IF_ERROR(ValidateOptions(options));
  std::unique_ptr<ServiceContext> ctx(new ServiceContext());
  ctx->name_ = options.name;
  auto monitor = runtime::InputMonitor::Create(runtime::InputMonitorOptions{});
  if (!monitor.ok()) return monitor.status();
  ctx->inputs_ = std::make_unique<runtime::InputMonitor>(std::move(*monitor));
  auto p = dds::Participant::Create(options.domain);
  if (!p.ok()) return p.status();
  ctx->participant_ = std::move(*p);
  // Before any reader exists (lockstep.hpp: no sample may be lost to a shallow history).
  // The simulator (on wall time, the source of ticks) is part of it too: its writers must be as
  // reliable as the services' readers expect.
  if (options.lockstep == "strict") dds::lockstep::SetStrictProcess(true);

  if (options.clock == "sim") {
    auto clock = std::make_unique<ManualClock>(Time{0}, /*valid=*/false);
    ctx->sim_clock_ = clock.get();
    ctx->clock_ = std::move(clock);
  } else {
    ctx->clock_ = std::make_unique<WallClock>();
  }
  if (options.fault_injection) {
    const Time epoch = options.fault_epoch_ns ? Time{*options.fault_epoch_ns}
                       : ctx->sim_clock_ != nullptr ? Time{0}
                                                    : ctx->clock_->Now();
    ctx->faults_ = faults::FaultAgent::Install(
        *ctx->clock_, faults::FaultAgent::Options{options.name, options.faults, epoch});
  }
  auto exec = Executor::Create(ctx->participant_, *ctx->clock_);
  if (!exec.ok()) return exec.status();
  ctx->executor_ = std::move(*exec);

  if (ctx->sim_clock_ != nullptr) {
    // Strict lock-step: only the ticks this service must serve, on its own partition
    // (lockstep.hpp "idle"); the simulator must name it in sim.lockstep_services.
    auto r = options.lockstep == "strict"
                 ? dds::Reader<rover_sim_Clock>::CreateInPartition(
                       ctx->participant_, "sim/clock", dds::lockstep::ClockPartition(options.name))
                 : dds::Reader<rover_sim_Clock>::Create(ctx->participant_, "sim/clock");
    if (!r.ok()) return r.status();
    ctx->clock_reader_ = std::make_unique<dds::Reader<rover_sim_Clock>>(std::move(*r));
    ManualClock* sim = ctx->sim_clock_;
    ServiceContext* me = ctx.get();
    ROVER_RETURN_IF_ERROR(ctx->executor_->Subscribe<rover_sim_Clock>(
        *ctx->clock_reader_,
        [sim, me](const dds::Sample<rover_sim_Clock>& s) {
          sim->Set(Time{s->sim_time_ns});
          ++me->clock_samples_;
          // Strict lock-step: what the tick's readers must have received first.
          if (me->strict_lockstep_) {
            dds::lockstep::SetFrontier(dds::lockstep::TopicCounts(
                s->written._buffer, s->written._buffer + s->written._length));
          }
        },
        /*always=*/true));
    if (options.lockstep == "strict") {
      ctx->strict_lockstep_ = true;
      ctx->executor_->SetStrictTicks(true);
    }
    auto ack = dds::Writer<rover_sim_ClockAck>::Create(ctx->participant_, "sim/clock_ack");
    if (!ack.ok()) return ack.status();
    ctx->clock_ack_writer_ = std::move(*ack);
    ServiceContext* self = ctx.get();
    ctx->executor_->SetAfterSpin([self] { self->AcknowledgeClock(); });
  }

  auto hb = dds::Writer<rover_sys_Heartbeat>::Create(ctx->participant_, "sys/health");
  if (!hb.ok()) return hb.status();
  ctx->heartbeat_writer_ = std::move(*hb);
  auto ev = dds::Writer<rover_sys_Event>::Create(ctx->participant_, "sys/event");
  if (!ev.ok()) return ev.status();
  ctx->event_writer_ = std::move(*ev);

  if (ctx->faults_) ROVER_RETURN_IF_ERROR(ctx->faults_->Attach(ctx->participant_, *ctx->executor_));

  ServiceContext* raw = ctx.get();
  ctx->executor_->AddTimer(Seconds(options.heartbeat_period_s),
                           [raw] { raw->PublishHeartbeat(); }, Executor::TimerBase::kWall,
                           /*always=*/true);
  // Stale inputs show without any sample arriving: re-evaluate on the run clock while active.
  ctx->executor_->AddTimer(Seconds(kInputCheckPeriodS), [raw] { raw->UpdateInputHealth(); });
  // Warnings and errors also go out on sys/event for operators and the run report.
  log::SetSink(
      [raw](log::Level level, std::string_view message, std::string_view fields) {
        rover_sys_Event e{};
        raw->Stamp(e.header, "");
        dds::CopyString(e.service, raw->name_);
        e.severity = ToSeverity(level);
        dds::CopyString(e.text, "msg=\"" + std::string(message) + "\"" + std::string(fields));
        (void)raw->event_writer_.Write(e);
      },
      log::Level::kWarning);
  return ctx;
}

ServiceContext::~ServiceContext() { log::SetSink(nullptr, log::Level::kError); }

void ServiceContext::AcknowledgeClock() {
  // Every 25 ms of simulated time at most: the simulator's lead (sim.lockstep_lead_s, at least
  // 50 ms) covers the granularity.
  constexpr std::int64_t kClockAckPeriodNs = 25'000'000;
  if (!sim_clock_->valid()) return;
  const Time now = sim_clock_->Now();
  if (strict_lockstep_) {
    // Each tick once served, and again whenever the simulator repeats its clock (it does while
    // it waits: an acknowledgement sent before it listened, or lost, is made good).
    const auto served = executor_->last_tick();
    if (!served || *served != now || clock_samples_ == clock_samples_acked_) return;
    if (const std::uint64_t late = dds::lockstep::LateSamples(); late > late_reported_) {
      log::Warn("lock-step: samples arrived a tick late; this run may not be reproducible",
                {{"late_samples", late},
                 {"sim_time_s", now.seconds()},
                 {"last", dds::lockstep::LastLateSample()}});
      // Counted in the heartbeat's activities, so the run report can say so.
      for (std::uint64_t i = late_reported_; i < late; ++i) {
        activities_.Add("late_samples", Duration::zero());
      }
      late_reported_ = late;
    }
    if (const std::uint64_t missing = dds::lockstep::MissingSamples(); missing > missing_reported_) {
      log::Warn("lock-step: samples written before this tick never arrived; this run may not be "
                "reproducible",
                {{"missing_samples", missing},
                 {"sim_time_s", now.seconds()},
                 {"last", dds::lockstep::LastLateSample()}});
      for (std::uint64_t i = missing_reported_; i < missing; ++i) {
        activities_.Add("late_samples", Duration::zero());
      }
      missing_reported_ = missing;
    }
    // Ticks served, counted once each (a repeated tick is acknowledged again, not served).
    if (!last_served_counted_ || *last_served_counted_ != now) {
      activities_.Add("ticks_served", Duration::zero());
      last_served_counted_ = now;
    }
    rover_sim_ClockAck a{};
    a.header.stamp_ns = now.ns;
    dds::CopyString(a.service, name_);
    a.sim_time_ns = now.ns;
    dds::lockstep::TopicCounts written = dds::lockstep::WrittenBy(participant_.handle());
    a.written._buffer = written.data();
    a.written._length = a.written._maximum = static_cast<std::uint32_t>(written.size());
    a.written._release = false;
    a.next_due_ns = executor_->next_due_ns();
    a.reads = executor_->reads();
    if (clock_ack_writer_.Write(a).ok()) {
      clock_samples_acked_ = clock_samples_;
      last_ack_ = now;
      acked_once_ = true;
    }
    return;
  }
  if (acked_once_ && now.ns - last_ack_.ns < kClockAckPeriodNs && now.ns >= last_ack_.ns) return;
  rover_sim_ClockAck a{};
  a.header.stamp_ns = now.ns;
  dds::CopyString(a.service, name_);
  a.sim_time_ns = now.ns;
  if (clock_ack_writer_.Write(a).ok()) {
    last_ack_ = now;
    acked_once_ = true;
  }
}

void ServiceContext::Stamp(rover_Header& header, std::string_view frame_id) {
  header.stamp_ns = clock_->Now().ns;
  dds::CopyString(header.frame_id, frame_id);
  header.seq = 0;  // numbered by the writer
}

void ServiceContext::SetHealth(rover_SensorHealth health, std::string message) {
  const bool changed = health != health_ || message != health_message_;
  health_ = health;
  health_message_ = std::move(message);
  if (changed) PublishHeartbeat();
}

double ServiceContext::ToleratedLoss(dds::QosProfile profile) {
  const dds::QosSpec q = dds::DescribeQos(profile);
  if (q.history_depth == 1) return 1.0;
  return q.reliable ? 0.0 : runtime::kStreamTolerableLoss;
}

void ServiceContext::SetInputMonitor(runtime::InputMonitor monitor) {
  ROVER_DEMAND_MSG(subscriptions_ == 0, "SetInputMonitor after Subscribe");
  *inputs_ = std::move(monitor);
}

bool ServiceContext::InputsStarted() {
  if (inputs_started_) return true;
  if (state_ != LifecycleState::kActive || !clock_->valid()) return false;
  inputs_->Start(Now());
  inputs_started_ = true;
  return true;
}

void ServiceContext::UpdateInputHealth() {
  if (!InputsStarted()) return;
  const runtime::InputReport r = inputs_->Report(Now());
  const rover_SensorHealth h = HealthOfInputs(r);
  // Published at once when the level or the worst finding changes; a changed reason alone goes
  // out with the next periodic heartbeat (so a flickering message cannot flood sys/health).
  std::string key = std::to_string(static_cast<int>(h));
  if (!r.findings.empty()) {
    key += " " + r.findings.front().topic + " " +
           runtime::InputProblemName(r.findings.front().problem) + " " +
           std::to_string(r.findings.size());
  }
  const bool worse = HealthRank(h) > HealthRank(input_health_);
  input_health_ = h;
  input_reason_ = r.reason;
  if (key == input_key_) return;
  input_key_ = std::move(key);
  if (worse) {
    log::Warn("input problem", {{"verdict", runtime::InputVerdictName(r.verdict)},
                                {"reason", input_reason_}});
  }
  PublishHeartbeat();
}

void ServiceContext::LogCallbackFailure(const std::string& topic, const Status& s) {
  log::Error("sample handler failed", {{"topic", topic}, {"error", s.message()}});
}

void ServiceContext::SetLifecycleState(LifecycleState state) {
  state_ = state;
  if (state == LifecycleState::kActive) {
    inputs_started_ = false;
    (void)InputsStarted();
    input_health_ = rover_HEALTH_OK;
    input_reason_.clear();
    input_key_.clear();
  }
  PublishHeartbeat();
}

void ServiceContext::PublishHeartbeat() {
  rover_sys_Heartbeat hb{};
  Stamp(hb.header, "");
  dds::CopyString(hb.service, name_);
  hb.pid = static_cast<int32_t>(getpid());
  hb.state = ToIdl(state_);
  // The worse of the service's own health and its inputs' (the service's own on a tie).
  const bool inputs_worse = HealthRank(input_health_) > HealthRank(health_);
  hb.health = inputs_worse ? input_health_ : health_;
  hb.count = ++heartbeat_count_;
  hb.wall_time_ns = WallNow().ns;
  dds::CopyString(hb.message, inputs_worse ? input_reason_ : health_message_);
  hb.cpu_s = runtime::ProcessCpuSeconds();
  const auto& entries = activities_.entries();
  std::vector<rover_sys_ActivityTime> times(entries.size());
  for (std::size_t i = 0; i < entries.size(); ++i) {
    dds::CopyString(times[i].name, entries[i].name);
    times[i].wall_s = entries[i].wall_s;
    times[i].count = entries[i].count;
  }
  hb.activities._buffer = times.data();
  hb.activities._length = hb.activities._maximum = static_cast<std::uint32_t>(times.size());
  hb.activities._release = false;
  (void)heartbeat_writer_.Write(hb);
}

// ---- parameters and lifecycle ------------------------------------------------------------------

Status LoadFaults(ServiceOptions* options) {
  options->faults.clear();
  if (options->faults_file.empty()) return Status::Ok();
  if (!options->fault_injection) {
    return InvalidArgument("faults file '" + options->faults_file +
                           "' given but fault injection is off (ROVER_FAULT_INJECTION)");
  }
  auto specs = faults::LoadFaultsFile(options->faults_file);
  if (!specs.ok()) return specs.status();
  options->faults = std::move(*specs);
  return Status::Ok();
}

Status LoadParameters(Service& service, const ServiceOptions& options, ParamSet* params) {
  *params = ParamSet(options.name.empty() ? service.kind() : options.name);
  runtime::DeclareInputParams(*params, service.Inputs());
  service.DeclareParameters(*params);
  for (const auto& f : options.param_files) ROVER_RETURN_IF_ERROR(params->LoadYamlFile(f));
  for (const auto& o : options.overrides) ROVER_RETURN_IF_ERROR(params->SetFromString(o));
  ROVER_RETURN_IF_ERROR(params->Validate());
  ROVER_RETURN_IF_ERROR(runtime::InputMonitor::FromParams(*params, service.Inputs()).status());
  return service.ValidateParameters(*params);
}

Lifecycle::Lifecycle(Service& service, ServiceContext& ctx, ServiceOptions options)
    : service_(service), ctx_(ctx), options_(std::move(options)) {}

void Lifecycle::Enter(LifecycleState s) {
  state_ = s;
  ctx_.SetLifecycleState(s);
}

Status Lifecycle::Fail(Status s) {
  last_error_ = s.message();
  return s;
}

Status Lifecycle::Configure() {
  if (state_ != LifecycleState::kUnconfigured) {
    return Fail(FailedPrecondition("cannot configure '" + ctx_.name() + "' in state " +
                                   LifecycleStateName(state_)));
  }
  Status s = LoadParameters(service_, options_, &params_);
  if (!s.ok()) return Fail(s);
  auto monitor = runtime::InputMonitor::FromParams(params_, service_.Inputs());
  if (!monitor.ok()) return Fail(monitor.status());
  ctx_.SetInputMonitor(std::move(*monitor));
  s = service_.OnConfigure(ctx_, params_);
  if (!s.ok()) return Fail(s.WithPrefix("configure"));
  last_error_.clear();
  Enter(LifecycleState::kInactive);
  return Status::Ok();
}

Status Lifecycle::Activate() {
  if (state_ == LifecycleState::kUnconfigured) {
    return Fail(FailedPrecondition(
        "cannot activate '" + ctx_.name() + "': not configured" +
        (last_error_.empty() ? std::string() : " (" + last_error_ + ")")));
  }
  if (state_ != LifecycleState::kInactive) {
    return Fail(FailedPrecondition("cannot activate '" + ctx_.name() + "' in state " +
                                   LifecycleStateName(state_)));
  }
  Status s = service_.OnActivate(ctx_);
  if (!s.ok()) return Fail(s.WithPrefix("activate"));
  s = ctx_.executor().SetActive(true);
  if (!s.ok()) return Fail(s);
  Enter(LifecycleState::kActive);
  return Status::Ok();
}

Status Lifecycle::Deactivate() {
  if (state_ != LifecycleState::kActive) {
    return Fail(FailedPrecondition("cannot deactivate '" + ctx_.name() + "' in state " +
                                   LifecycleStateName(state_)));
  }
  Status s = ctx_.executor().SetActive(false);
  Status t = service_.OnDeactivate(ctx_);
  Enter(LifecycleState::kInactive);
  if (!s.ok()) return Fail(s);
  if (!t.ok()) return Fail(t.WithPrefix("deactivate"));
  return Status::Ok();
}

Status Lifecycle::Shutdown() {
  if (state_ == LifecycleState::kFinalized) return Status::Ok();
  if (state_ == LifecycleState::kActive) (void)Deactivate();
  if (state_ == LifecycleState::kInactive) service_.OnShutdown(ctx_);
  Enter(LifecycleState::kFinalized);
  return Status::Ok();
}

// ---- main --------------------------------------------------------------------------------------

namespace {

std::vector<std::string> SplitColon(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ':')) {
    if (!item.empty()) out.push_back(item);
  }
  return out;
}

}  // namespace

int RunServiceMain(Service& service, int argc, char** argv) {
  // Services allocate the same large buffers every cycle (images, dl-pose's covariance with its
  // clones, 1 MB): keep them on the heap rather than mapping, zero-filling and unmapping them
  // each time (glibc maps blocks above 128 kB and trims the heap top above 128 kB by default).
  mallopt(M_MMAP_THRESHOLD, 64 << 20);
  mallopt(M_TRIM_THRESHOLD, 128 << 20);
  ServiceOptions options;
  if (const char* e = std::getenv("ROVER_SERVICE_NAME")) options.name = e;
  if (const char* e = std::getenv("ROVER_DOMAIN")) options.domain = std::atoi(e);
  if (const char* e = std::getenv("ROVER_CLOCK")) options.clock = e;
  if (const char* e = std::getenv("ROVER_LOCKSTEP")) options.lockstep = e;
  if (const char* e = std::getenv("ROVER_PARAMS")) options.param_files = SplitColon(e);
  if (const char* e = std::getenv("ROVER_FAULTS")) options.faults_file = e;
  if (const char* e = std::getenv("ROVER_FAULT_INJECTION")) {
    options.fault_injection = std::string(e) != "off" && std::string(e) != "0";
  }
  std::string epoch_text;
  if (const char* e = std::getenv("ROVER_FAULTS_EPOCH_NS")) epoch_text = e;

  CLI::App app{"rover service '" + service.kind() + "'"};
  bool validate_only = false, help_params = false, print_params = false;
  app.add_option("--name", options.name, "instance name (heartbeat key)");
  app.add_option("--domain", options.domain, "DDS domain id");
  app.add_option("--clock", options.clock, "run clock: wall or sim");
  app.add_option("--lockstep", options.lockstep,
                 "under sim/clock: lead (acknowledge every 25 ms) or strict (serve every tick)");
  app.add_option("--params", options.param_files, "YAML parameter files");
  app.add_option("--set", options.overrides, "parameter override key=value");
  app.add_option("--faults", options.faults_file, "YAML file of faults to inject (docs/faults.md)");
  app.add_flag("--validate", validate_only, "validate the parameters and faults and exit");
  app.add_flag("--help-params", help_params, "describe the parameters and exit");
  app.add_flag("--print-params", print_params, "print the effective parameters at start");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    return rc == 0 ? 0 : 2;
  }
  if (options.name.empty()) options.name = service.kind();
  log::InitFromEnvironment(options.name);

  ParamSet params;
  if (help_params) {
    params = ParamSet(options.name);
    runtime::DeclareInputParams(params, service.Inputs());
    service.DeclareParameters(params);
    std::cout << "Parameters of " << service.kind() << ":\n" << params.DescribeAll();
    return 0;
  }
  Status s = ValidateOptions(options);
  if (s.ok() && !epoch_text.empty()) {
    char* end = nullptr;
    const long long v = std::strtoll(epoch_text.c_str(), &end, 10);
    if (end == epoch_text.c_str() || *end != '\0') {
      s = InvalidArgument("ROVER_FAULTS_EPOCH_NS: '" + epoch_text + "' is not a whole number of ns");
    } else {
      options.fault_epoch_ns = v;
    }
  }
  if (s.ok()) s = LoadParameters(service, options, &params);
  if (s.ok()) s = LoadFaults(&options);
  if (!s.ok()) {
    std::cerr << options.name << ": error: " << s.message() << "\n";
    return 2;
  }
  if (validate_only) return 0;
  if (print_params) std::cerr << params.DumpYaml();

  // Block SIGINT/SIGTERM in every thread (DDS threads inherit this mask) and wait for them in
  // one dedicated thread, which stops the executor.
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &set, nullptr);

  auto ctx = ServiceContext::Create(options);
  if (!ctx.ok()) {
    std::cerr << options.name << ": error: " << ctx.status().message() << "\n";
    return 1;
  }
  Executor& exec = (*ctx)->executor();
  std::thread signal_thread([&set, &exec] {
    int sig = 0;
    sigwait(&set, &sig);
    if (sig != 0) exec.Stop();
  });

  Lifecycle lifecycle(service, **ctx, options);
  int rc = 0;
  s = lifecycle.Configure();
  if (s.ok()) s = lifecycle.Activate();
  if (!s.ok()) {
    std::cerr << options.name << ": error: " << s.message() << "\n";
    log::Error("failed to start", {{"error", s.message()}});
    rc = s.code() == StatusCode::kInvalidArgument || s.code() == StatusCode::kOutOfRange ? 2 : 1;
  } else {
    log::Info("active", {{"domain", options.domain},
                         {"clock", options.clock},
                         {"lockstep", options.clock == "sim" ? options.lockstep : "none"}});
    exec.Spin();
    log::Info("stopping");
  }
  (void)lifecycle.Shutdown();
  // Wake the signal thread if no signal came.
  pthread_kill(signal_thread.native_handle(), SIGTERM);
  signal_thread.join();
  return rc;
}

}  // namespace rover
