#include "rover/deploy/supervisor.hpp"

#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <thread>

#include "rover/base/clock.hpp"
#include "rover/base/log.hpp"
#include "rover/deploy/security.hpp"
#include "rover/runtime/security_files.hpp"
#include "rover/runtime/topic_access.hpp"

namespace rover::deploy {
namespace fs = std::filesystem;

namespace {
std::int64_t MonoNs() { return MonotonicNow().ns; }

const char* LifecycleName(rover_sys_LifecycleState s) {
  switch (s) {
    case rover_sys_LIFECYCLE_UNCONFIGURED: return "unconfigured";
    case rover_sys_LIFECYCLE_INACTIVE: return "inactive";
    case rover_sys_LIFECYCLE_ACTIVE: return "active";
    case rover_sys_LIFECYCLE_FINALIZED: return "finalized";
    case rover_sys_LIFECYCLE_ERROR: return "error";
  }
  return "?";
}

const char* HealthName(rover_SensorHealth h) {
  switch (h) {
    case rover_HEALTH_OK: return "ok";
    case rover_HEALTH_DEGRADED: return "degraded";
    case rover_HEALTH_FAILED: return "failed";
    case rover_HEALTH_STALE: return "stale";
  }
  return "?";
}

std::string MakeSetId(const std::string& project) {
  std::random_device rd;
  char buf[16];
  std::snprintf(buf, sizeof buf, "%08x", static_cast<unsigned>(rd()));
  return project + "." + std::to_string(getpid()) + "." + buf;
}

std::string Seconds1(double s) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f", s);
  return buf;
}

bool ShouldRestart(const ServiceSpec& s, const ExitInfo& e, int restarts) {
  switch (s.restart) {
    case RestartPolicy::kNo: return false;
    case RestartPolicy::kAlways:
    case RestartPolicy::kUnlessStopped: return true;
    case RestartPolicy::kOnFailure:
      return !e.success() && (s.max_restarts < 0 || restarts < s.max_restarts);
  }
  return false;
}
}  // namespace

const char* ServiceStateName(ServiceState s) {
  switch (s) {
    case ServiceState::kPending: return "pending";
    case ServiceState::kRunning: return "running";
    case ServiceState::kBackoff: return "restarting";
    case ServiceState::kExited: return "exited";
    case ServiceState::kFailed: return "failed";
    case ServiceState::kStopped: return "stopped";
  }
  return "?";
}

std::string DefaultStateRoot() {
  if (const char* d = std::getenv("ROVER_STATE_DIR")) return d;
  return "/tmp/rover-" + std::to_string(getuid());
}

std::map<std::string, std::string> ServiceEnvironment(const ComposeProject& project,
                                                      const ServiceSpec& s,
                                                      const SupervisorOptions& options, int domain,
                                                      const std::string& set_id) {
  std::map<std::string, std::string> env;
  const char* path = std::getenv("PATH");
  env["PATH"] = options.bin_dir + ":" + (path ? path : "/usr/bin:/bin");
  env["CYCLONEDDS_URI"] = options.dds_config_uri;
  env["ROVER_DOMAIN"] = std::to_string(domain);
  env["ROVER_SERVICE_NAME"] = s.name;
  env["ROVER_PROJECT"] = project.rover.project;
  env["ROVER_CLOCK"] = project.rover.clock;
  if (project.rover.clock == "sim" && !project.rover.lockstep.empty()) {
    env["ROVER_LOCKSTEP"] = project.rover.lockstep;
  }
  env["ROVER_STATE_DIR"] = options.state_dir;
  if (!set_id.empty()) env[kSetIdVariable] = set_id + "/" + s.name;
  if (!project.rover.qos.empty()) {
    std::string q;
    for (const auto& [topic, profile] : project.rover.qos) {
      q += (q.empty() ? "" : ",") + topic + "=" + profile;
    }
    env["ROVER_QOS_OVERRIDES"] = q;
  }
  for (const auto& [k, v] : project.rover.sim) {
    std::string key = "ROVER_SIM_" + k;
    for (char& ch : key) ch = ch == '.' ? '_' : static_cast<char>(std::toupper(ch));
    env[key] = v;
  }
  // x-rover.faults (and a scenario's faults:), written into the state folder by Preflight and
  // Create; under wall time Start() adds ROVER_FAULTS_EPOCH_NS (the set's start) to extra_env.
  if (!project.rover.faults.empty()) env["ROVER_FAULTS"] = SetFaultsPath(options.state_dir);
  if (project.rover.security) {
    env[dds::kSecurityDirVariable] = SecurityDirFor(options);
    env[dds::kSecurityIdentityVariable] = SecurityRoleOf(s);
  }
  for (const auto& [k, v] : options.extra_env) env[k] = v;
  for (const auto& [k, v] : s.environment) env[k] = v;  // never a reserved one (compose.cpp)
  return env;
}

bool IsRoverService(const ComposeProject& project, const ServiceSpec& spec,
                    const SupervisorOptions& options) {
  const auto env = ServiceEnvironment(project, spec, options, 0);
  const std::string exe = FindInPath(spec.command[0], env.at("PATH"));
  return !exe.empty() && fs::path(exe).parent_path() == fs::path(options.bin_dir);
}

Readiness ServiceReadiness(const ServiceStatus& s, std::int64_t now_wall_ns,
                           double heartbeat_timeout_s) {
  switch (s.state) {
    case ServiceState::kPending: return {false, "not started"};
    case ServiceState::kBackoff: return {false, "restarting (" + s.last_exit + ")"};
    case ServiceState::kFailed: return {false, "failed (" + s.last_exit + ")"};
    case ServiceState::kStopped: return {false, "stopped"};
    case ServiceState::kExited: return {true, ""};  // exited 0: done, under every rule
    case ServiceState::kRunning: break;
  }
  switch (s.ready_rule) {
    case ReadyRule::kStarted: return {true, ""};
    case ReadyRule::kCompleted: return {false, "still running (ready: completed)"};
    case ReadyRule::kHealthy:
    case ReadyRule::kActive: break;
  }
  if (s.last_heartbeat_wall_ns <= 0) return {false, "no heartbeat yet"};
  const double age = (now_wall_ns - s.last_heartbeat_wall_ns) * 1e-9;
  if (age > heartbeat_timeout_s) return {false, "heartbeat " + Seconds1(age) + " s old"};
  if (s.lifecycle != "active") return {false, "lifecycle " + s.lifecycle};
  if (s.ready_rule == ReadyRule::kHealthy && s.health != "ok") {
    return {false, "health " + s.health + (s.message.empty() ? "" : ": " + s.message)};
  }
  return {true, ""};
}

std::string SetReadiness::Summary() const {
  std::string out;
  for (const auto& n : not_ready) out += (out.empty() ? "" : "; ") + n;
  return out;
}

std::string SecurityRoleOf(const ServiceSpec& service) {
  return service.command.empty() ? "" : fs::path(service.command[0]).filename().string();
}

std::string SecurityDirFor(const SupervisorOptions& options) {
  return options.security_dir.empty() ? SecurityDirOf(DefaultStateRoot()) : options.security_dir;
}

namespace {

// A secured set starts only when every service's identity is there and verifies.
Status CheckSetSecurity(const ComposeProject& project, const SupervisorOptions& options) {
  const std::string dir = SecurityDirFor(options);
  std::vector<std::string> roles;
  for (const auto& spec : project.services) {
    const std::string role = SecurityRoleOf(spec);
    if (!dds::FindRole(role)) {
      return InvalidArgument(project.file + ":" + std::to_string(spec.command_line) +
                             ": services." + spec.name + ": x-rover.security is enabled but '" +
                             role + "' has no DDS Security role (core/runtime topic_access.cpp "
                             "lists the roles)");
    }
    roles.push_back(role);
  }
  const Status st = VerifySecurity(dir, roles);
  if (!st.ok()) {
    return FailedPrecondition(project.file + ": x-rover.security: " + st.message());
  }
  return Status::Ok();
}

}  // namespace

Status Preflight(const ComposeProject& project, const SupervisorOptions& options) {
  if (project.rover.security) ROVER_RETURN_IF_ERROR(CheckSetSecurity(project, options));
  std::error_code ec;
  fs::create_directories(options.state_dir + "/logs", ec);
  const std::string tmp = options.state_dir + "/logs/.preflight";
  // The services validate the set's faults with their parameters (--validate reads ROVER_FAULTS).
  if (!project.rover.faults.empty()) {
    ROVER_RETURN_IF_ERROR(WriteSetFaults(project.rover.faults, options.state_dir));
  }
  for (const auto& spec : project.services) {
    const auto env = ServiceEnvironment(project, spec, options, 0);
    const std::string exe = FindInPath(spec.command[0], env.at("PATH"));
    if (exe.empty()) {
      return InvalidArgument(project.file + ":" + std::to_string(spec.command_line) +
                             ": services." + spec.name + ".command: no such command '" +
                             spec.command[0] + "'");
    }
    if (!IsRoverService(project, spec, options)) continue;  // only they understand --validate
    SpawnOptions o;
    o.argv = spec.command;
    o.argv.push_back("--validate");
    o.env = env;
    std::remove(tmp.c_str());
    o.stderr_path = tmp;
    o.stdout_path = tmp;
    o.working_dir = spec.working_dir;
    auto p = Process::Spawn(o);
    if (!p.ok()) return p.status();
    auto e = p->WaitFor(std::chrono::seconds(20));
    if (!e) {
      p->Terminate(std::chrono::seconds(1));
      return Timeout(project.file + ":" + std::to_string(spec.command_line) + ": services." +
                     spec.name + ": parameter validation did not finish");
    }
    if (!e->success()) {
      std::ifstream in(tmp);
      std::string line, last;
      while (std::getline(in, line)) {
        if (!line.empty()) last = line;
      }
      // Services print "<name>: error: <message>"; keep only the message.
      const std::string prefix = spec.name + ": error: ";
      if (last.rfind(prefix, 0) == 0) last = last.substr(prefix.size());
      return InvalidArgument(project.file + ":" + std::to_string(spec.command_line) +
                             ": services." + spec.name + ": " +
                             (last.empty() ? e->ToString() : last));
    }
  }
  std::remove(tmp.c_str());
  return Status::Ok();
}

Result<std::unique_ptr<Supervisor>> Supervisor::Create(ComposeProject project,
                                                       SupervisorOptions options) {
  std::optional<int> domain = options.domain ? options.domain : project.rover.domain;
  if (project.rover.security && domain && *domain > 230) {
    return InvalidArgument(project.file + ": x-rover.security: domain " +
                           std::to_string(*domain) +
                           " is above 230, the highest DDS Security's documents cover");
  }
  auto lease = domain ? dds::DomainLease::Acquire(*domain) : dds::DomainLease::AcquireFree();
  if (!lease.ok()) return lease.status();
  std::error_code ec;
  fs::create_directories(options.state_dir + "/logs", ec);
  if (ec) {
    return Unavailable("cannot create state directory " + options.state_dir + ": " + ec.message());
  }
  if (!project.rover.faults.empty()) {
    ROVER_RETURN_IF_ERROR(WriteSetFaults(project.rover.faults, options.state_dir));
  }
  std::unique_ptr<Supervisor> s(
      new Supervisor(std::move(project), std::move(options), std::move(*lease)));
  setenv("CYCLONEDDS_URI", s->options_.dds_config_uri.c_str(), 1);
  if (s->project_.rover.security) {
    // Its heartbeat reader joins the secured set as "supervisor", unless this process already
    // took part under another role (roverctl run: the scenario runner's, which reads all).
    setenv(dds::kSecurityDirVariable, SecurityDirFor(s->options_).c_str(), 0);
    setenv(dds::kSecurityIdentityVariable, "supervisor", 0);
  }
  auto p = dds::Participant::Create(s->lease_.domain());
  if (!p.ok()) return p.status();
  s->participant_ = std::move(*p);
  auto r = dds::Reader<rover_sys_Heartbeat>::Create(s->participant_, "sys/health");
  if (!r.ok()) return r.status();
  s->heartbeats_ = std::make_unique<dds::Reader<rover_sys_Heartbeat>>(std::move(*r));
  s->set_id_ = MakeSetId(s->project_.rover.project);
  for (const auto& spec : s->project_.services) {
    auto c = std::make_unique<Child>();
    c->spec = &spec;
    c->status.name = spec.name;
    c->status.log_path = s->options_.state_dir + "/logs/" + spec.name + ".log";
    c->status.ready_rule = spec.ready.value_or(IsRoverService(s->project_, spec, s->options_)
                                                   ? ReadyRule::kHealthy
                                                   : ReadyRule::kStarted);
    s->by_name_[spec.name] = c.get();
    s->children_.push_back(std::move(c));
  }
  return s;
}

Supervisor::Supervisor(ComposeProject project, SupervisorOptions options, dds::DomainLease lease)
    : project_(std::move(project)), options_(std::move(options)), lease_(std::move(lease)) {}

Supervisor::~Supervisor() { Stop(); }

Status Supervisor::Spawn(Child& c) {
  SpawnOptions o;
  o.argv = c.spec->command;
  o.env = ServiceEnvironment(project_, *c.spec, options_, lease_.domain(), set_id_);
  o.stdout_path = c.status.log_path;
  o.stderr_path = c.status.log_path;
  o.working_dir = c.spec->working_dir;
  {
    std::ofstream log(c.status.log_path, std::ios::app);
    log << "---- roverctl: starting " << c.spec->name << " (restart " << c.status.restarts
        << ") on domain " << lease_.domain() << "\n";
  }
  auto p = Process::Spawn(o);
  if (!p.ok()) return p.status();
  c.process = std::move(*p);
  c.status.pid = c.process.pid();
  c.status.state = ServiceState::kRunning;
  c.status.started_wall_ns = WallNow().ns;
  c.status.lifecycle.clear();
  c.status.health.clear();
  c.status.message.clear();
  c.status.last_heartbeat_wall_ns = 0;
  c.started_mono_ns = MonoNs();
  return Status::Ok();
}

std::string Supervisor::LastLogLine(const Child& c) const {
  std::ifstream in(c.status.log_path);
  std::string line, last;
  while (std::getline(in, line)) {
    if (!line.empty() && line.rfind("---- roverctl:", 0) != 0) last = line;
  }
  return last;
}

Status Supervisor::StartupError(const Child& c, const std::string& what) const {
  const std::string last = LastLogLine(c);
  return Unavailable(project_.file + ":" + std::to_string(c.spec->line) + ": service '" +
                     c.spec->name + "' " + what + (last.empty() ? "" : ": " + last));
}

void Supervisor::ReadHeartbeats() {
  for (auto& s : heartbeats_->Take(64)) {
    auto it = by_name_.find(s->service);
    if (it == by_name_.end()) continue;
    Child& c = *it->second;
    if (s->pid != c.status.pid) continue;  // a previous incarnation
    c.status.last_heartbeat_wall_ns = s->wall_time_ns;
    c.status.lifecycle = LifecycleName(s->state);
    c.status.health = HealthName(s->health);
    c.status.message = s->message;
  }
}

void Supervisor::UpdateReadiness() {
  const std::int64_t now = WallNow().ns;
  SetReadiness r;
  r.ready = !children_.empty();
  for (auto& c : children_) {
    const Readiness one = ServiceReadiness(c->status, now, project_.rover.heartbeat_timeout_s);
    c->status.ready = one.ready;
    c->status.waiting_for = one.reason;
    if (!one.ready) {
      r.ready = false;
      r.not_ready.push_back(c->spec->name + ": " + one.reason);
    }
  }
  if (r.ready && ready_after_s_ < 0 && phase_ == "up") {
    ready_after_s_ = (MonoNs() - started_mono_ns_) * 1e-9;
    log::Info("ready", {{"after_s", ready_after_s_}});
  }
  readiness_ = std::move(r);
}

void Supervisor::StopLeftovers(const Child& c, Duration grace) {
  const MarkedStop stopped = StopMarkedProcesses(kSetIdVariable, set_id_ + "/" + c.spec->name,
                                                 EnvMatch::kExact, grace);
  if (!stopped.found.empty()) {
    log::Warn("stopped processes left over by a service",
              {{"service", c.spec->name}, {"count", stopped.found.size()},
               {"killed", stopped.killed.size()}});
  }
}

Status Supervisor::WaitForDependencies(const ServiceSpec& s, std::int64_t deadline) {
  for (const auto& d : s.depends_on) {
    Child& dep = *by_name_.at(d.service);
    while (true) {
      ReadHeartbeats();
      auto e = dep.process.Poll();
      bool done = false;
      switch (d.condition) {
        case DependencyCondition::kStarted:
          if (e && !e->success()) return StartupError(dep, "exited at once (" + e->ToString() + ")");
          done = true;
          break;
        case DependencyCondition::kHealthy:
          if (e) return StartupError(dep, "exited before becoming healthy (" + e->ToString() + ")");
          done = dep.status.lifecycle == "active";
          break;
        case DependencyCondition::kCompletedSuccessfully:
          if (e && !e->success()) return StartupError(dep, "did not complete successfully (" + e->ToString() + ")");
          done = e.has_value();
          if (done) dep.status.state = ServiceState::kExited;
          break;
      }
      if (done) break;
      if (options_.abort && options_.abort->load()) return Unavailable("start-up interrupted");
      if (MonoNs() > deadline) {
        return Timeout(project_.file + ":" + std::to_string(d.line) + ": services." + s.name +
                       ".depends_on." + d.service + ": condition " +
                       DependencyConditionName(d.condition) + " not met within " +
                       std::to_string(static_cast<int>(project_.rover.startup_timeout_s)) + " s");
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  }
  return Status::Ok();
}

Status Supervisor::Start() {
  phase_ = "starting";
  started_wall_ns_ = WallNow().ns;
  started_mono_ns_ = MonoNs();
  // Fault windows (start_s) count from the set's start under wall time, in every service and
  // across restarts; under sim time from simulated zero (docs/faults.md "Time").
  if (project_.rover.clock == "wall") {
    options_.extra_env["ROVER_FAULTS_EPOCH_NS"] = std::to_string(started_wall_ns_);
  }
  WriteState(phase_);
  const std::int64_t deadline =
      MonoNs() + static_cast<std::int64_t>(project_.rover.startup_timeout_s * 1e9);
  auto fail = [&](Status s) {
    Stop();
    phase_ = "failed";
    WriteState(phase_);
    return s;
  };
  for (auto& c : children_) {
    Status s = WaitForDependencies(*c->spec, deadline);
    if (!s.ok()) return fail(s);
    s = Spawn(*c);
    if (!s.ok()) {
      return fail(InvalidArgument(project_.file + ":" + std::to_string(c->spec->command_line) +
                                  ": services." + c->spec->name + ": " + s.message()));
    }
    log::Info("started", {{"service", c->spec->name}, {"pid", c->status.pid}});
  }
  // A service that dies within the settle window "exited at once": the set did not start.
  const std::int64_t settle_end = MonoNs() + static_cast<std::int64_t>(options_.settle_s * 1e9);
  while (MonoNs() < settle_end) {
    if (options_.abort && options_.abort->load()) return fail(Unavailable("start-up interrupted"));
    for (auto& c : children_) {
      if (c->status.state != ServiceState::kRunning) continue;
      if (auto e = c->process.Poll()) {
        if (!e->success()) return fail(StartupError(*c, "exited at once (" + e->ToString() + ")"));
        c->status.state = ServiceState::kExited;
        c->status.last_exit = e->ToString();
      }
    }
    ReadHeartbeats();
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  phase_ = "up";
  UpdateReadiness();
  WriteState(phase_);
  return Status::Ok();
}

void Supervisor::PollHeartbeats() {
  ReadHeartbeats();
  UpdateReadiness();
}

void Supervisor::Poll() {
  ReadHeartbeats();
  const std::int64_t now = MonoNs();
  for (auto& c : children_) {
    if (c->stopping) continue;
    if (c->status.state == ServiceState::kRunning) {
      auto e = c->process.Poll();
      if (!e) {
        // Healthy for a minute: forget earlier back-off.
        if (now - c->started_mono_ns > 60'000'000'000LL) c->backoff_s = 0.5;
        continue;
      }
      c->process.Signal(SIGKILL);  // leave no stragglers of its process group
      StopLeftovers(*c, Duration{0});  // nor any that left it
      c->status.last_exit = e->ToString();
      c->status.pid = 0;
      if (ShouldRestart(*c->spec, *e, c->status.restarts)) {
        c->status.state = ServiceState::kBackoff;
        c->restart_at_ns = now + static_cast<std::int64_t>(c->backoff_s * 1e9);
        log::Warn("service ended; restarting",
                  {{"service", c->spec->name}, {"how", e->ToString()}, {"in_s", c->backoff_s}});
        c->backoff_s = std::min(c->backoff_s * 2, 10.0);
      } else {
        c->status.state = e->success() ? ServiceState::kExited : ServiceState::kFailed;
        log::Warn("service ended", {{"service", c->spec->name}, {"how", e->ToString()}});
      }
    } else if (c->status.state == ServiceState::kBackoff && now >= c->restart_at_ns) {
      ++c->status.restarts;
      const Status s = Spawn(*c);
      if (!s.ok()) {
        c->status.state = ServiceState::kFailed;
        c->status.last_exit = s.message();
        log::Error("restart failed", {{"service", c->spec->name}, {"error", s.message()}});
      }
    }
  }
  UpdateReadiness();
  WriteState(phase_);
}

Status Supervisor::Signal(const std::string& service, int sig) {
  auto it = by_name_.find(service);
  if (it == by_name_.end()) return NotFound("no service '" + service + "' in the set");
  Child& c = *it->second;
  if (c.stopping || c.status.state != ServiceState::kRunning || c.process.pid() <= 0) {
    return FailedPrecondition("service '" + service + "' is not running (" +
                              ServiceStateName(c.status.state) + ")");
  }
  c.process.Signal(sig);
  return Status::Ok();
}

void Supervisor::Stop() {
  if (phase_ == "stopped") return;
  if (phase_ == "up") phase_ = "stopping";
  for (auto it = children_.rbegin(); it != children_.rend(); ++it) {
    Child& c = **it;
    c.stopping = true;
    if (c.process.pid() <= 0) continue;
    const Duration grace =
        std::chrono::milliseconds(static_cast<int>(c.spec->stop_grace_s * 1000));
    const ExitInfo e = c.process.Terminate(grace);
    StopLeftovers(c, grace);
    if (c.status.state == ServiceState::kRunning) {
      c.status.state = ServiceState::kStopped;
      c.status.last_exit = e.ToString();
    }
    c.status.pid = 0;
  }
  if (phase_ != "failed") phase_ = "stopped";
  UpdateReadiness();
  WriteState(phase_);
}

std::vector<ServiceStatus> Supervisor::Snapshot() const {
  std::vector<ServiceStatus> out;
  for (const auto& c : children_) out.push_back(c->status);
  return out;
}

void Supervisor::WriteState(const std::string& phase) const {
  nlohmann::json j;
  j["project"] = project_.rover.project;
  j["file"] = fs::absolute(project_.file).string();
  j["domain"] = lease_.domain();
  j["supervisor_pid"] = getpid();
  j["supervisor_start_ticks"] = ProcessStartTicks(getpid());
  j["set_id"] = set_id_;
  j["phase"] = phase;
  j["ready"] = readiness_.ready;
  j["not_ready"] = readiness_.not_ready;
  j["started_wall_ns"] = started_wall_ns_;
  j["ready_after_s"] = ready_after_s_;
  j["clock"] = project_.rover.clock;
  j["security_dir"] = project_.rover.security ? SecurityDirFor(options_) : "";
  j["heartbeat_timeout_s"] = project_.rover.heartbeat_timeout_s;
  j["written_wall_ns"] = WallNow().ns;
  j["services"] = nlohmann::json::array();
  for (const auto& c : children_) {
    const ServiceStatus& s = c->status;
    j["services"].push_back({{"name", s.name},
                             {"state", ServiceStateName(s.state)},
                             {"pid", s.pid},
                             {"pgid", s.pid},  // each service leads its own process group
                             {"restarts", s.restarts},
                             {"last_exit", s.last_exit},
                             {"started_wall_ns", s.started_wall_ns},
                             {"last_heartbeat_wall_ns", s.last_heartbeat_wall_ns},
                             {"lifecycle", s.lifecycle},
                             {"health", s.health},
                             {"message", s.message},
                             {"ready_rule", ReadyRuleName(s.ready_rule)},
                             {"ready", s.ready},
                             {"waiting_for", s.waiting_for},
                             {"stop_grace_s", c->spec->stop_grace_s},
                             {"log", s.log_path}});
  }
  const std::string path = options_.state_dir + "/state.json";
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp);
    out << j.dump(2) << "\n";
  }
  std::rename(tmp.c_str(), path.c_str());
}

}  // namespace rover::deploy
