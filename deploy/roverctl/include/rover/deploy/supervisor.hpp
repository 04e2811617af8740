#pragma once
/// @file
/// Runs a compose project's services as supervised child processes on one DDS domain.
///
/// Start-up is all-or-nothing: parameters of every rover service are validated first
/// (`<service> --validate`), then services start in dependency order, each waiting for its
/// depends_on conditions (service_started: spawned and alive; service_healthy: its heartbeat on
/// sys/health says ACTIVE; service_completed_successfully: exited 0). If any service fails to
/// start or exits non-zero during start-up, everything already started is stopped and the error
/// names the compose file, line and service. Afterwards crashed services are restarted per their
/// restart policy with exponential back-off. Stop() sends SIGTERM to each process group in
/// reverse start order, then SIGKILL after the grace period: no process is left behind.

#include <atomic>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "rover/base/process.hpp"
#include "rover/deploy/compose.hpp"
#include "rover/runtime/dds.hpp"
#include "rover/runtime/domain.hpp"

namespace rover::deploy {

struct SupervisorOptions {
  std::string bin_dir;             ///< rover executables; prepended to PATH
  std::string state_dir;           ///< where state.json and logs/ go
  std::string dds_config_uri;      ///< CYCLONEDDS_URI given to services
  std::optional<int> domain;       ///< overrides x-rover.domain
  bool preflight = true;           ///< run `--validate` on rover services first
  double settle_s = 1.0;           ///< a service exiting this soon after start "exited at once"
  std::map<std::string, std::string> extra_env;  ///< added to every service's environment
  const std::atomic<bool>* abort = nullptr;      ///< set (e.g. by SIGINT) to abandon Start()
};

/// The environment a service runs with on `domain` (PATH, CYCLONEDDS_URI, ROVER_* variables,
/// then the compose file's own `environment`, which has the last word).
std::map<std::string, std::string> ServiceEnvironment(const ComposeProject& project,
                                                      const ServiceSpec& service,
                                                      const SupervisorOptions& options, int domain);

/// Checks that every command exists and runs `<command> --validate` for rover services (those
/// in options.bin_dir), so bad parameters are reported before anything starts. Needs no DDS.
Status Preflight(const ComposeProject& project, const SupervisorOptions& options);

enum class ServiceState { kPending, kRunning, kBackoff, kExited, kFailed, kStopped };
const char* ServiceStateName(ServiceState s);

struct ServiceStatus {
  std::string name;
  ServiceState state = ServiceState::kPending;
  int pid = 0;
  int restarts = 0;
  std::string last_exit;            ///< e.g. "killed by signal 9 (SIGKILL)"
  std::int64_t started_wall_ns = 0;
  std::int64_t last_heartbeat_wall_ns = 0;
  std::string lifecycle;            ///< from the last heartbeat
  std::string log_path;
};

class Supervisor {
 public:
  static Result<std::unique_ptr<Supervisor>> Create(ComposeProject project,
                                                    SupervisorOptions options);
  ~Supervisor();

  /// Starts all services (see file comment). On error nothing is left running.
  Status Start();
  /// One supervision step: reap, restart, read heartbeats, write the state file.
  void Poll();
  /// Stops every service, reverse start order.
  void Stop();

  int domain() const { return lease_.domain(); }
  const ComposeProject& project() const { return project_; }
  const std::string& state_dir() const { return options_.state_dir; }
  std::vector<ServiceStatus> Snapshot() const;
  /// Writes state.json atomically; `phase` is "starting", "up", "stopping", "stopped" or "failed".
  void WriteState(const std::string& phase) const;

 private:
  struct Child {
    const ServiceSpec* spec = nullptr;
    Process process;
    ServiceStatus status;
    double backoff_s = 0.5;
    std::int64_t restart_at_ns = 0;  // monotonic
    std::int64_t started_mono_ns = 0;
    bool stopping = false;
  };

  Supervisor(ComposeProject project, SupervisorOptions options, dds::DomainLease lease);
  Status Spawn(Child& c);
  Status WaitForDependencies(const ServiceSpec& s, std::int64_t deadline_mono_ns);
  void ReadHeartbeats();
  std::string LastLogLine(const Child& c) const;
  Status StartupError(const Child& c, const std::string& what) const;

  ComposeProject project_;
  SupervisorOptions options_;
  dds::DomainLease lease_;
  std::vector<std::unique_ptr<Child>> children_;
  std::map<std::string, Child*> by_name_;
  dds::Participant participant_;
  std::unique_ptr<dds::Reader<rover_sys_Heartbeat>> heartbeats_;
  std::string phase_ = "starting";
};

/// Resolves the default state root: $ROVER_STATE_DIR or /tmp/rover-<uid>.
std::string DefaultStateRoot();

}  // namespace rover::deploy
