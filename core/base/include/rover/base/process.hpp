#pragma once
/// @file
/// Child processes for the supervisor (roverctl) and for multi-process tests: spawn in a new
/// process group with per-process log files, poll, signal the whole group, stop with a grace
/// period; find and stop a process tree by a marker in its environment, even after its parent
/// died. No DDS.

#include <sys/types.h>

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "rover/base/status.hpp"
#include "rover/base/time.hpp"

namespace rover {

struct ExitInfo {
  bool signaled = false;  ///< killed by a signal (then `signal` is set), else exited with `code`
  int code = 0;
  int signal = 0;
  bool success() const { return !signaled && code == 0; }
  /// "exit code 2" or "killed by signal 9 (SIGKILL)".
  std::string ToString() const;
};

struct SpawnOptions {
  std::vector<std::string> argv;             ///< argv[0] is looked up in PATH (of `env`)
  std::map<std::string, std::string> env;    ///< added to (or replacing in) the environment
  std::string stdout_path;                   ///< append stdout here; empty = inherit
  std::string stderr_path;                   ///< append stderr here; empty = inherit
  std::string working_dir;                   ///< empty = inherit
  bool die_with_parent = true;               ///< SIGTERM the child if the parent dies
};

class Process {
 public:
  Process() = default;
  Process(Process&& o) noexcept;
  Process& operator=(Process&& o) noexcept;
  Process(const Process&) = delete;
  Process& operator=(const Process&) = delete;
  /// Does not kill the child; call Terminate() for that.
  ~Process() = default;

  /// Starts the child in its own process group. Fails (NotFound) if the program cannot be
  /// executed, e.g. "no such command 'foo' in PATH".
  static Result<Process> Spawn(const SpawnOptions& options);

  pid_t pid() const { return pid_; }
  bool running() const { return pid_ > 0 && !exit_.has_value(); }
  /// Non-blocking: the exit status if the child has ended.
  std::optional<ExitInfo> Poll();
  /// Blocks up to `timeout` (wall time) for the child to end.
  std::optional<ExitInfo> WaitFor(Duration timeout);
  /// Sends `sig` to the child's whole process group.
  void Signal(int sig) const;
  /// SIGTERM to the group, up to `grace` to end, then SIGKILL to the group. Returns how it ended.
  ExitInfo Terminate(Duration grace);

 private:
  pid_t pid_ = -1;
  std::optional<ExitInfo> exit_;
};

/// What a command printed and how it ended (RunCommand).
struct CommandOutput {
  ExitInfo exit;
  std::string out;  ///< its stdout
  std::string err;  ///< its stderr
  /// The last non-empty line of stderr (else of stdout): a tool's own reason for failing.
  std::string LastErrorLine() const;
};

/// Runs `argv` (argv[0] through PATH) to its end with its output captured in files under
/// `scratch_dir` (removed after), at most `timeout` (then terminated: Timeout). NotFound when
/// the program cannot be started. A non-zero exit is not an error here: see `exit`.
Result<CommandOutput> RunCommand(const std::vector<std::string>& argv,
                                 const std::string& scratch_dir, Duration timeout,
                                 const std::map<std::string, std::string>& env = {});

/// True if any process is in process group `pgid` (used to prove nothing was left behind).
bool ProcessGroupAlive(pid_t pgid);
/// True if `pid` exists and is not a zombie.
bool ProcessAlive(pid_t pid);
/// Resolves `program` through PATH; empty if not found or not executable.
std::string FindInPath(const std::string& program, const std::string& path_env);

/// How ProcessesWithEnvironment compares an environment entry's value.
enum class EnvMatch { kExact, kPrefix };

/// Live processes (zombies excluded), other than the caller, whose environment holds `key` with
/// the value `value` (kExact) or a value starting with `value` (kPrefix). Reads /proc/<pid>/environ,
/// which is readable for processes of the same user: the only ones the caller may signal anyway.
/// The environment a process started with is inherited by everything it starts, so a marker set
/// by a supervisor finds a whole process tree, whichever process group or parent it ended up
/// with (unless a process cleared its environment or exec'd a set-uid program).
std::vector<pid_t> ProcessesWithEnvironment(std::string_view key, std::string_view value,
                                            EnvMatch match = EnvMatch::kExact);

/// The process group of `pid`, or -1 if it does not exist.
pid_t ProcessGroupOf(pid_t pid);
/// When `pid` started, in clock ticks after boot (/proc/<pid>/stat field 22), or -1 if it does
/// not exist: with the pid, it names one process even after the pid is reused.
long long ProcessStartTicks(pid_t pid);

/// What StopMarkedProcesses found and did.
struct MarkedStop {
  std::vector<pid_t> found;   ///< alive when it started (marked, or in a group with one that is)
  std::vector<pid_t> killed;  ///< still alive after the grace period: SIGKILLed
  bool all_gone = true;       ///< nothing of them was left when it returned
};

/// Stops a process tree that may have lost its supervisor: every process whose environment
/// matches (see ProcessesWithEnvironment) and every process in a process group with one of them
/// (so a child that cleared its environment but stayed in its group goes too; a group with no
/// marked process is never signalled, so a re-used group id is safe). SIGTERM to each group and
/// process, up to `grace` for them to end, then SIGKILL to what is left; waits up to 5 s more
/// for them to disappear. Never signals the caller or its process group.
MarkedStop StopMarkedProcesses(std::string_view key, std::string_view value, EnvMatch match,
                               Duration grace);

}  // namespace rover
