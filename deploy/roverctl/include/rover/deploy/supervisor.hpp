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
/// restart policy with exponential back-off.
///
/// Readiness: "up" means every process runs; "ready" means every service is ready by its rule
/// (ReadyRule in compose.hpp; by default a rover service's heartbeat says ACTIVE and health OK,
/// so an estimator still levelling is not ready). Poll() keeps it current; ps and the state file
/// show it, `roverctl up --wait` and a scenario run wait for it.
///
/// Process trees: every service runs in its own process group, and its environment carries
/// ROVER_SET_ID=<set id>/<service>, which everything it starts inherits. Stop() sends SIGTERM to
/// each process group in reverse start order, then SIGKILL after the grace period, then stops
/// whatever still carries the service's ROVER_SET_ID (a grandchild that left the group). The
/// state file records the set id and the process groups, so `roverctl down` can do the same
/// when the supervisor itself is gone (StopMarkedProcesses in rover/base/process.hpp).

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
  /// DDS Security keys for a set with x-rover.security: enabled (deploy/security.hpp); empty =
  /// SecurityDirOf(DefaultStateRoot()).
  std::string security_dir;
  const std::atomic<bool>* abort = nullptr;      ///< set (e.g. by SIGINT) to abandon Start()
};

/// The environment a service runs with on `domain`: PATH, CYCLONEDDS_URI and the ROVER_*
/// variables roverctl sets (ReservedEnvironment in compose.hpp; ROVER_SET_ID=<set_id>/<service>
/// when `set_id` is given), options.extra_env, then the compose file's own `environment` (which
/// the compose parser keeps off the reserved variables).
std::map<std::string, std::string> ServiceEnvironment(const ComposeProject& project,
                                                      const ServiceSpec& service,
                                                      const SupervisorOptions& options, int domain,
                                                      const std::string& set_id = "");

/// The environment variable that marks every process of a set (value "<set id>/<service>").
inline constexpr const char* kSetIdVariable = "ROVER_SET_ID";

/// True if the service's command is a rover executable (in options.bin_dir): one that takes
/// --validate and sends heartbeats.
bool IsRoverService(const ComposeProject& project, const ServiceSpec& service,
                    const SupervisorOptions& options);

/// The DDS Security role of a service: its command's executable name ("dl-pose").
std::string SecurityRoleOf(const ServiceSpec& service);
/// The security directory a secured set uses (options.security_dir or the default).
std::string SecurityDirFor(const SupervisorOptions& options);

/// Checks that every command exists and runs `<command> --validate` for rover services (those
/// in options.bin_dir), so bad parameters are reported before anything starts. For a secured
/// set, also that every service's role has an identity in the security directory that verifies
/// (deploy/security.hpp VerifySecurity), naming the service, the file and what is wrong. Needs
/// no DDS.
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
  std::string health;               ///< from the last heartbeat: ok, degraded, failed, stale
  std::string message;              ///< the last heartbeat's message ("" when healthy)
  std::string log_path;
  ReadyRule ready_rule = ReadyRule::kHealthy;
  bool ready = false;
  std::string waiting_for;          ///< why it is not ready ("" when it is)
};

/// Whether one service is ready by its rule at wall time `now_wall_ns` (see ReadyRule); a
/// heartbeat older than `heartbeat_timeout_s` does not count. `reason` says why not, e.g.
/// "health degraded: levelling: waiting for stationary ddl/imu samples". No DDS, no processes.
struct Readiness {
  bool ready = false;
  std::string reason;
};
Readiness ServiceReadiness(const ServiceStatus& s, std::int64_t now_wall_ns,
                           double heartbeat_timeout_s);

/// The whole set: ready when every service is; `not_ready` holds "service: reason".
struct SetReadiness {
  bool ready = false;
  std::vector<std::string> not_ready;
  /// "a: reason; b: reason".
  std::string Summary() const;
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
  /// Only the heartbeats and the readiness they give (cheap: no process polling, no state file);
  /// the scenario runner does this every simulated tick and Poll() a few times a second.
  void PollHeartbeats();
  /// Stops every service, reverse start order.
  void Stop();
  /// Sends `sig` to a running service's process group (a fault campaign's kill -9); the next
  /// Poll() sees it end and applies its restart policy, as for any crash.
  Status Signal(const std::string& service, int sig);

  int domain() const { return lease_.domain(); }
  const ComposeProject& project() const { return project_; }
  const std::string& state_dir() const { return options_.state_dir; }
  /// "<project>.<pid>.<random>": the value every process of the set carries in ROVER_SET_ID
  /// (followed by "/<service>").
  const std::string& set_id() const { return set_id_; }
  std::vector<ServiceStatus> Snapshot() const;
  /// Readiness as of the last Poll() (or Start()).
  const SetReadiness& readiness() const { return readiness_; }
  /// Wall seconds from the start of Start() to the first Poll() that found the set ready; < 0
  /// while it never was.
  double ready_after_s() const { return ready_after_s_; }
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
  void UpdateReadiness();
  // Stops whatever of the service's process tree is still alive (it carries its ROVER_SET_ID).
  void StopLeftovers(const Child& c, Duration grace);
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
  std::string set_id_;
  std::int64_t started_wall_ns_ = 0;  // when Start() began
  std::int64_t started_mono_ns_ = 0;
  SetReadiness readiness_;
  double ready_after_s_ = -1;
};

/// Resolves the default state root: $ROVER_STATE_DIR or /tmp/rover-<uid>.
std::string DefaultStateRoot();

}  // namespace rover::deploy
