#include "rover/base/process.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>
#include <thread>
#include <utility>

#include "rover/base/clock.hpp"

extern char** environ;

namespace rover {
namespace {
ExitInfo FromWaitStatus(int status) {
  ExitInfo e;
  if (WIFSIGNALED(status)) {
    e.signaled = true;
    e.signal = WTERMSIG(status);
  } else if (WIFEXITED(status)) {
    e.code = WEXITSTATUS(status);
  }
  return e;
}
}  // namespace

std::string ExitInfo::ToString() const {
  if (signaled) {
    const char* abbrev = sigabbrev_np(signal);
    return "killed by signal " + std::to_string(signal) +
           (abbrev ? " (SIG" + std::string(abbrev) + ")" : "");
  }
  return "exit code " + std::to_string(code);
}

std::string FindInPath(const std::string& program, const std::string& path_env) {
  if (program.find('/') != std::string::npos) {
    return access(program.c_str(), X_OK) == 0 ? program : "";
  }
  std::stringstream ss(path_env);
  std::string dir;
  while (std::getline(ss, dir, ':')) {
    if (dir.empty()) dir = ".";
    const std::string candidate = dir + "/" + program;
    struct stat st {};
    if (stat(candidate.c_str(), &st) == 0 && S_ISREG(st.st_mode) &&
        access(candidate.c_str(), X_OK) == 0) {
      return candidate;
    }
  }
  return "";
}

Process::Process(Process&& o) noexcept : pid_(std::exchange(o.pid_, -1)), exit_(o.exit_) {}

Process& Process::operator=(Process&& o) noexcept {
  pid_ = std::exchange(o.pid_, -1);
  exit_ = o.exit_;
  return *this;
}

Result<Process> Process::Spawn(const SpawnOptions& options) {
  if (options.argv.empty() || options.argv[0].empty()) {
    return InvalidArgument("empty command");
  }
  // Environment: ours, then the overrides.
  std::map<std::string, std::string> env;
  for (char** e = environ; *e != nullptr; ++e) {
    const char* eq = std::strchr(*e, '=');
    if (eq) env[std::string(*e, static_cast<std::size_t>(eq - *e))] = eq + 1;
  }
  for (const auto& [k, v] : options.env) env[k] = v;
  const std::string path = env.count("PATH") ? env["PATH"] : "/usr/bin:/bin";
  const std::string exe = FindInPath(options.argv[0], path);
  if (exe.empty()) {
    return NotFound("no such command '" + options.argv[0] + "' (searched PATH=" + path + ")");
  }
  std::vector<std::string> env_strings;
  for (const auto& [k, v] : env) env_strings.push_back(k + "=" + v);
  std::vector<char*> envp, argv;
  for (auto& s : env_strings) envp.push_back(s.data());
  envp.push_back(nullptr);
  std::vector<std::string> args = options.argv;
  for (auto& s : args) argv.push_back(s.data());
  argv.push_back(nullptr);

  int err_pipe[2];
  if (pipe2(err_pipe, O_CLOEXEC) != 0) return Unavailable(std::string("pipe: ") + strerror(errno));
  const pid_t parent = getpid();
  const pid_t pid = fork();
  if (pid < 0) {
    close(err_pipe[0]);
    close(err_pipe[1]);
    return Unavailable(std::string("fork: ") + strerror(errno));
  }
  if (pid == 0) {
    // Child: only async-signal-safe calls from here on.
    setpgid(0, 0);
    if (options.die_with_parent) {
      prctl(PR_SET_PDEATHSIG, SIGTERM);
      if (getppid() != parent) _exit(127);
    }
    sigset_t none;
    sigemptyset(&none);
    sigprocmask(SIG_SETMASK, &none, nullptr);
    signal(SIGINT, SIG_DFL);
    signal(SIGTERM, SIG_DFL);
    signal(SIGPIPE, SIG_DFL);
    auto redirect = [](const std::string& p, int target) {
      if (p.empty()) return true;
      const int fd = open(p.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
      if (fd < 0) return false;
      if (dup2(fd, target) < 0) return false;
      return true;
    };
    int e = 0;
    if (!redirect(options.stdout_path, STDOUT_FILENO) ||
        !redirect(options.stderr_path, STDERR_FILENO)) {
      e = errno;
    } else if (!options.working_dir.empty() && chdir(options.working_dir.c_str()) != 0) {
      e = errno;
    } else {
      execve(exe.c_str(), argv.data(), envp.data());
      e = errno;
    }
    (void)!write(err_pipe[1], &e, sizeof e);
    _exit(127);
  }
  // Parent. Also set the group here, to avoid racing with a Signal() right after Spawn().
  setpgid(pid, pid);
  close(err_pipe[1]);
  int child_errno = 0;
  const ssize_t n = read(err_pipe[0], &child_errno, sizeof child_errno);
  close(err_pipe[0]);
  Process p;
  p.pid_ = pid;
  if (n == static_cast<ssize_t>(sizeof child_errno)) {
    int status = 0;
    waitpid(pid, &status, 0);
    return Unavailable("cannot start '" + options.argv[0] + "': " + strerror(child_errno));
  }
  return p;
}

std::optional<ExitInfo> Process::Poll() {
  if (exit_) return exit_;
  if (pid_ <= 0) return std::nullopt;
  int status = 0;
  const pid_t r = waitpid(pid_, &status, WNOHANG);
  if (r == pid_) exit_ = FromWaitStatus(status);
  return exit_;
}

std::optional<ExitInfo> Process::WaitFor(Duration timeout) {
  const Time deadline = MonotonicNow() + timeout;
  while (true) {
    if (auto e = Poll()) return e;
    if (MonotonicNow() >= deadline) return std::nullopt;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
}

void Process::Signal(int sig) const {
  if (pid_ > 0) kill(-pid_, sig);
}

ExitInfo Process::Terminate(Duration grace) {
  if (auto e = Poll()) {
    // The leader is gone; make sure nothing else of its group survives.
    if (pid_ > 0) kill(-pid_, SIGKILL);
    return *e;
  }
  Signal(SIGTERM);
  auto e = WaitFor(grace);
  if (pid_ > 0) kill(-pid_, SIGKILL);  // leader or stragglers in its group
  if (!e) e = WaitFor(std::chrono::seconds(5));
  return e.value_or(ExitInfo{true, 0, SIGKILL});
}

bool ProcessGroupAlive(pid_t pgid) {
  if (pgid <= 0) return false;
  return kill(-pgid, 0) == 0 || errno == EPERM;
}

bool ProcessAlive(pid_t pid) {
  if (pid <= 0 || kill(pid, 0) != 0) return false;
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string content;
  std::getline(stat, content);
  const auto rparen = content.rfind(')');
  if (rparen == std::string::npos || rparen + 2 >= content.size()) return true;
  return content[rparen + 2] != 'Z';
}

namespace {

// /proc/<pid>/stat fields after the command name: "S ppid pgrp ..." (the name may hold spaces
// and parentheses, so parse from the last ')').
std::vector<std::string> StatFields(pid_t pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
  std::string content;
  std::getline(in, content);
  const auto rparen = content.rfind(')');
  std::vector<std::string> fields;
  if (rparen == std::string::npos) return fields;
  std::istringstream rest(content.substr(rparen + 1));
  std::string f;
  while (rest >> f) fields.push_back(f);
  return fields;  // [0] state, [1] ppid, [2] pgrp, ..., [19] starttime
}

bool EnvironmentMatches(pid_t pid, std::string_view key, std::string_view value, EnvMatch match) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/environ", std::ios::binary);
  if (!in) return false;
  const std::string env((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::size_t pos = 0;
  while (pos < env.size()) {
    std::size_t end = env.find('\0', pos);
    if (end == std::string::npos) end = env.size();
    const std::string_view entry(env.data() + pos, end - pos);
    if (entry.size() > key.size() && entry.compare(0, key.size(), key) == 0 &&
        entry[key.size()] == '=') {
      const std::string_view v = entry.substr(key.size() + 1);
      return match == EnvMatch::kExact ? v == value : v.compare(0, value.size(), value) == 0;
    }
    pos = end + 1;
  }
  return false;
}

std::vector<pid_t> AllPids() {
  std::vector<pid_t> pids;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator("/proc", ec)) {
    const std::string name = e.path().filename().string();
    if (name.empty() || name.find_first_not_of("0123456789") != std::string::npos) continue;
    pids.push_back(static_cast<pid_t>(std::stol(name)));
  }
  return pids;
}

// The processes StopMarkedProcesses is after, and their groups, as they are now.
struct MarkedTree {
  std::vector<pid_t> pids;
  std::set<pid_t> groups;
};

MarkedTree FindMarkedTree(std::string_view key, std::string_view value, EnvMatch match) {
  const pid_t self = getpid();
  const pid_t own_group = getpgrp();
  MarkedTree t;
  std::vector<std::pair<pid_t, pid_t>> live;  // pid, group
  for (pid_t pid : AllPids()) {
    if (pid == self || !ProcessAlive(pid)) continue;
    const pid_t group = ProcessGroupOf(pid);
    if (group < 0) continue;
    live.emplace_back(pid, group);
    if (EnvironmentMatches(pid, key, value, match) && group != own_group) t.groups.insert(group);
  }
  for (const auto& [pid, group] : live) {
    if (t.groups.count(group) || (group != own_group && EnvironmentMatches(pid, key, value, match))) {
      t.pids.push_back(pid);
    }
  }
  return t;
}

void SignalTree(const MarkedTree& t, int sig) {
  for (pid_t g : t.groups) kill(-g, sig);
  for (pid_t p : t.pids) kill(p, sig);
}

}  // namespace

std::vector<pid_t> ProcessesWithEnvironment(std::string_view key, std::string_view value,
                                            EnvMatch match) {
  std::vector<pid_t> out;
  const pid_t self = getpid();
  for (pid_t pid : AllPids()) {
    if (pid != self && EnvironmentMatches(pid, key, value, match) && ProcessAlive(pid)) {
      out.push_back(pid);
    }
  }
  return out;
}

pid_t ProcessGroupOf(pid_t pid) {
  const auto f = StatFields(pid);
  return f.size() > 2 ? static_cast<pid_t>(std::stol(f[2])) : -1;
}

long long ProcessStartTicks(pid_t pid) {
  const auto f = StatFields(pid);
  return f.size() > 19 ? std::stoll(f[19]) : -1;
}

MarkedStop StopMarkedProcesses(std::string_view key, std::string_view value, EnvMatch match,
                               Duration grace) {
  MarkedStop out;
  MarkedTree tree = FindMarkedTree(key, value, match);
  out.found = tree.pids;
  if (tree.pids.empty()) return out;
  SignalTree(tree, SIGTERM);
  auto wait_gone = [&](Duration limit) {
    const Time deadline = MonotonicNow() + limit;
    while (true) {
      tree = FindMarkedTree(key, value, match);
      if (tree.pids.empty() || MonotonicNow() >= deadline) return tree.pids.empty();
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  };
  if (wait_gone(grace)) return out;
  out.killed = tree.pids;
  SignalTree(tree, SIGKILL);
  out.all_gone = wait_gone(std::chrono::seconds(5));
  return out;
}

std::string CommandOutput::LastErrorLine() const {
  const std::string& text = err.find_first_not_of(" \n\r\t") == std::string::npos ? out : err;
  const std::size_t end = text.find_last_not_of(" \n\r\t");
  if (end == std::string::npos) return "";
  const std::size_t nl = text.rfind('\n', end);
  const std::size_t start = nl == std::string::npos ? 0 : nl + 1;
  return text.substr(start, end - start + 1);
}

Result<CommandOutput> RunCommand(const std::vector<std::string>& argv,
                                 const std::string& scratch_dir, Duration timeout,
                                 const std::map<std::string, std::string>& env) {
  static std::atomic<int> n{0};
  const std::string base = scratch_dir + "/.cmd-" + std::to_string(getpid()) + "-" +
                           std::to_string(n.fetch_add(1));
  SpawnOptions o;
  o.argv = argv;
  o.env = env;
  o.stdout_path = base + ".out";
  o.stderr_path = base + ".err";
  ROVER_ASSIGN_OR_RETURN(Process p, Process::Spawn(o));
  std::optional<ExitInfo> exit = p.WaitFor(timeout);
  auto slurp = [](const std::string& path) {
    std::ifstream in(path);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::remove(path.c_str());
    return text;
  };
  CommandOutput c;
  c.out = slurp(o.stdout_path);
  c.err = slurp(o.stderr_path);
  if (!exit) {
    p.Terminate(std::chrono::seconds(1));
    return Timeout(argv.front() + " did not finish in " +
                   std::to_string(static_cast<int>(ToSeconds(timeout))) + " s");
  }
  c.exit = *exit;
  return c;
}

}  // namespace rover
