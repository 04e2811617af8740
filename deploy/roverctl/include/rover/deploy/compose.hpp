#pragma once
/// @file
/// The compose-file subset roverctl understands, and its parser.
///
/// A compose file is a Compose Specification file (so `docker-compose config` accepts it, and
/// the same file runs in containers) whose services roverctl runs natively as supervised
/// processes. Supported service keys: command, environment, depends_on (list, or map with
/// condition service_started | service_healthy | service_completed_successfully), restart
/// (no | always | on-failure[:N] | unless-stopped), stop_grace_period; image, build, network_mode,
/// working_dir, volumes, container_name and x-* keys are accepted (working_dir is honoured, the
/// others only matter in containers). A service's own `x-rover: {ready: RULE}` says when it counts
/// as ready (ReadyRule). `environment` may not set what roverctl sets for every service of the set
/// (ROVER_DOMAIN, ROVER_CLOCK, ROVER_SIM_*, CYCLONEDDS_URI, ...: ReservedEnvironment). Project
/// settings live under the top-level `x-rover` key:
///
///   x-rover:
///     project: smoke             # name (default: file name up to the first '.')
///     domain: 42                 # DDS domain (default: a free one is leased)
///     clock: wall                # wall | sim
///     startup_timeout_s: 30      # wait for service_healthy dependencies
///     heartbeat_timeout_s: 5     # a heartbeat older than this marks a service stale in `ps`
///     qos: {dl/pose: stream}     # per-topic QoS profile overrides
///     sim: {...}                 # simulator settings, passed to the simulator as ROVER_SIM_*
///     faults: [...]              # fault injection (list of maps; docs/faults.md), validated
///                                # here and given to every service in ROVER_FAULTS
///     record: {path, topics, exclude, size_cap_mb, compression}   # MCAP recording of the set
///                                # while it is up (or true/false; rover/recording/record_options.hpp)
///
/// Every error names the file, line and key: "deploy/x.yaml:12: services.loco: unknown key
/// 'comand' (did you mean 'command'?)".

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "rover/base/status.hpp"
#include "rover/deploy/set_faults.hpp"
#include "rover/recording/record_options.hpp"

namespace rover::deploy {

enum class DependencyCondition { kStarted, kHealthy, kCompletedSuccessfully };
const char* DependencyConditionName(DependencyCondition c);

struct Dependency {
  std::string service;
  DependencyCondition condition = DependencyCondition::kStarted;
  int line = 0;
};

enum class RestartPolicy { kNo, kAlways, kOnFailure, kUnlessStopped };
const char* RestartPolicyName(RestartPolicy p);

/// When a running service counts as ready (`roverctl up --wait`, `ps`, a scenario run):
///   healthy    its heartbeat on sys/health is from this process, fresh, lifecycle ACTIVE and
///              health OK (the default for rover services);
///   active     the same, whatever the health says;
///   started    the process is running (the default for other commands, which send no heartbeat);
///   completed  it has exited with code 0 (a one-shot job).
/// A service that exited with code 0 counts as ready under every rule.
enum class ReadyRule { kHealthy, kActive, kStarted, kCompleted };
const char* ReadyRuleName(ReadyRule r);

/// The environment variables roverctl sets for every service (see ServiceEnvironment), each with
/// where the set chooses it; an `environment:` entry may not override them. A key ending in '*'
/// is a prefix.
struct ReservedVariable {
  const char* key;
  const char* what;
};
const std::vector<ReservedVariable>& ReservedEnvironment();

struct ServiceSpec {
  std::string name;
  int line = 0;          ///< line of the service's key
  int command_line = 0;  ///< line of its `command`
  std::vector<std::string> command;
  std::map<std::string, std::string> environment;
  std::vector<Dependency> depends_on;
  RestartPolicy restart = RestartPolicy::kNo;
  int max_restarts = -1;  ///< on-failure:N; -1 = unlimited
  double stop_grace_s = 10.0;
  std::string working_dir;
  std::optional<ReadyRule> ready;  ///< x-rover.ready; unset: by kind of command (ReadyRule)
};

struct RoverSettings {
  std::string project;
  std::optional<int> domain;
  std::string clock = "wall";
  /// Under clock "sim": how the services keep in step with the simulator, "lead" or "strict"
  /// (ROVER_LOCKSTEP; core/runtime lockstep.hpp). Empty: the services' default (lead). Set by
  /// the scenario runner, not read from compose files.
  std::string lockstep;
  double startup_timeout_s = 30.0;
  double heartbeat_timeout_s = 5.0;
  std::map<std::string, std::string> qos;  ///< topic -> profile name (validated)
  std::map<std::string, std::string> sim;  ///< flattened simulator settings
  /// x-rover.faults, validated (set_faults.hpp); every service gets them in ROVER_FAULTS.
  std::vector<SetFault> faults;
  /// x-rover.record; nullopt (or enabled = false) records nothing. A relative path is taken
  /// from the directory roverctl runs in; no path: <state>/<project>/recording.mcap.
  std::optional<recording::RecordOptions> record;
  /// x-rover.security: enabled. Every service then starts with its role's DDS Security identity
  /// (docs/security.md); roverctl checks the keys before anything starts.
  bool security = false;
  /// x-rover.slurm: sbatch settings for `roverctl run --backend slurm` (its flags override).
  struct Slurm {
    std::string partition;
    std::string time;                      ///< per task, Slurm's forms
    int cpus_per_task = 0;                 ///< 0 = not given
    std::vector<std::string> sbatch_args;  ///< passed as they are
  } slurm;
};

struct ComposeProject {
  std::string file;
  RoverSettings rover;
  /// Services in a start order that respects depends_on (dependencies first).
  std::vector<ServiceSpec> services;
  const ServiceSpec* Find(const std::string& name) const;
};

/// Parses and validates a compose file. Nothing is started.
Result<ComposeProject> LoadComposeFile(const std::string& path);
/// Same, from text; `file` is the name used in messages.
Result<ComposeProject> ParseCompose(const std::string& text, const std::string& file);

/// Splits a command string the way a POSIX shell splits words (quotes and backslashes; no
/// expansion). Unbalanced quotes are an error.
Result<std::vector<std::string>> SplitCommand(const std::string& command);

/// Parses Compose durations: "10s", "1m30s", "500ms", "2" (seconds).
Result<double> ParseDuration(const std::string& text);

}  // namespace rover::deploy
