// roverctl: the one command-line entry point of the rover stack.
//
//   roverctl up FILE [-d] [--wait[=S]] [--domain N] [--for S]   start a service set
//   roverctl down [PROJECT]                                     stop it (even if roverctl died)
//   roverctl ps [PROJECT]                                       state, health, readiness
//   roverctl logs SERVICE [-p PROJECT] [-f] [-n LINES]          a service's log
//   roverctl config FILE                                        validate a compose file
//   roverctl run SCENARIO [--seeds A..B] [--jobs J] [--out DIR] end-to-end scenario campaign
//   roverctl run SCENARIO --faults FILE [--seeds ..] [--jobs ..]  fault campaign (each fault alone)
//   roverctl report DIR                                         re-print a campaign's summary
//   roverctl record [-p P | --domain D] -o FILE [--topics G...] record a set's topics to MCAP
//   roverctl replay FILE [--topics G...] [--rate R] (--domain D | -p P)   republish a recording
//   roverctl info FILE                                          topics, types, counts, time span
//   roverctl fault add [SPEC] [--kind K --topic T ...] [-f FILE] [-p P]   inject a fault
//   roverctl fault list [-p P] [--json]                         faults per service, with counts
//   roverctl fault clear [ID] [-p P]                            remove one fault, or all
//
// See docs/roverctl.md.
#include <CLI/CLI.hpp>
#include <signal.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <ctime>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <thread>

#include "rover/base/clock.hpp"
#include "rover/base/log.hpp"
#include "rover/base/process.hpp"
#include "rover/deploy/campaign.hpp"
#include "rover/deploy/fault_campaign.hpp"
#include "rover/deploy/compose.hpp"
#include "rover/deploy/fault_commands.hpp"
#include "rover/deploy/seq_commands.hpp"
#include "rover/deploy/run_report.hpp"
#include "rover/deploy/scenario.hpp"
#include "rover/deploy/security.hpp"
#include "rover/deploy/slurm_campaign.hpp"
#include "rover/deploy/supervisor.hpp"
#include "rover/runtime/domain.hpp"
#include "rover/runtime/security_files.hpp"
#include "rover/runtime/topic_access.hpp"
#include "src/recording_commands.hpp"

namespace fs = std::filesystem;
using rover::Status;

namespace {

std::atomic<bool> g_stop{false};
void OnSignal(int) { g_stop.store(true); }

std::string SelfDir() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  return ec ? std::string(".") : exe.parent_path().string();
}

// The loopback Cyclone configuration: $ROVER_DDS_CONFIG, the install tree, or the source tree.
std::string DdsConfigUri() {
  if (const char* c = std::getenv("ROVER_DDS_CONFIG")) {
    return std::string(c).rfind("file://", 0) == 0 ? c : "file://" + std::string(c);
  }
  const fs::path installed = fs::path(SelfDir()) / "../share/rover/cyclonedds/loopback.xml";
  if (fs::exists(installed)) return "file://" + fs::canonical(installed).string();
  return rover::dds::LoopbackConfigUri(ROVER_SOURCE_DIR);
}

int Fail(const std::string& message, int code = 1) {
  std::cerr << "roverctl: error: " << message << "\n";
  return code;
}

nlohmann::json ReadState(const std::string& dir) {
  std::ifstream in(dir + "/state.json");
  if (!in) return nullptr;
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception&) {
    return nullptr;
  }
}

// The supervisor named by the state file is alive (the same process: its start time matches,
// so a re-used pid does not count).
bool SupervisorAlive(const nlohmann::json& state) {
  if (state.is_null()) return false;
  const int pid = state.value("supervisor_pid", 0);
  if (!rover::ProcessAlive(pid)) return false;
  const long long ticks = state.value("supervisor_start_ticks", -1LL);
  return ticks < 0 || rover::ProcessStartTicks(pid) == ticks;
}

// The processes of the set that are still alive (they carry its ROVER_SET_ID).
std::vector<pid_t> SetProcesses(const nlohmann::json& state) {
  const std::string set_id = state.value("set_id", "");
  if (set_id.empty()) return {};
  return rover::ProcessesWithEnvironment(rover::deploy::kSetIdVariable, set_id + "/",
                                         rover::EnvMatch::kPrefix);
}

// Projects with a state file under the state root.
std::vector<std::string> KnownProjects(const std::string& root) {
  std::vector<std::string> out;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(root, ec)) {
    if (fs::exists(e.path() / "state.json")) out.push_back(e.path().filename().string());
  }
  std::sort(out.begin(), out.end());
  return out;
}

// Picks the project: explicit, else the only live one.
rover::Result<std::string> ResolveProject(const std::string& root, const std::string& given) {
  if (!given.empty()) {
    if (!fs::exists(root + "/" + given + "/state.json")) {
      return rover::NotFound("no project '" + given + "' under " + root);
    }
    return given;
  }
  std::vector<std::string> live;
  for (const auto& p : KnownProjects(root)) {
    if (SupervisorAlive(ReadState(root + "/" + p))) live.push_back(p);
  }
  if (live.size() == 1) return live[0];
  if (live.empty()) return rover::NotFound("no service set is up (state root " + root + ")");
  std::string names;
  for (const auto& p : live) names += " " + p;
  return rover::InvalidArgument("several projects are up; name one of:" + names);
}

std::string Age(std::int64_t wall_ns) {
  if (wall_ns <= 0) return "-";
  const double s = (rover::WallNow().ns - wall_ns) * 1e-9;
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1fs ago", s);
  return buf;
}

// ---- up --------------------------------------------------------------------------------------

struct UpArgs {
  std::string file;
  int domain = -1;
  bool detach = false;
  bool no_preflight = false;
  double run_for_s = 0;
  double wait_s = -1;  ///< --wait: seconds to wait for the set to be ready; < 0: do not wait
  std::string state_root;
  std::string project;
  std::string security_dir;  ///< --security-dir; "" = <state root>/security
};

constexpr double kDefaultWaitS = 120;

// Which x-rover.slurm settings the command line overrides.
struct SlurmFlags {
  bool partition = false, time = false, cpus = false, sbatch_args = false;
};

// The supervisor: starts the set, reports "ok <domain>" (and with --wait "ready <s>") on
// `notify_fd`, then supervises until Ctrl-C, SIGTERM, `down` or --for.
int RunSupervisor(const rover::deploy::ComposeProject& project,
                  rover::deploy::SupervisorOptions options, const UpArgs& args, int notify_fd) {
  const rover::Time up_start = rover::MonotonicNow();
  auto notify = [&notify_fd](const std::string& msg, bool last) {
    if (notify_fd < 0) return;
    const std::string line = msg + "\n";
    (void)!write(notify_fd, line.data(), line.size());
    if (last) {
      close(notify_fd);
      notify_fd = -1;
    }
  };
  const bool wait = args.wait_s >= 0;
  options.abort = &g_stop;
  if (project.rover.security && project.rover.record && project.rover.record->enabled) {
    // One identity per process: with x-rover.record it is the recorder's (which also reads the
    // heartbeats the supervisor needs).
    setenv(rover::dds::kSecurityDirVariable, rover::deploy::SecurityDirFor(options).c_str(), 1);
    setenv(rover::dds::kSecurityIdentityVariable, "recorder", 1);
  }
  auto sup = rover::deploy::Supervisor::Create(project, options);
  if (!sup.ok()) {
    notify("error: " + sup.status().message(), true);
    return Fail(sup.status().message());
  }
  std::cout << "roverctl: starting '" << project.rover.project << "' (" << project.services.size()
            << " services) on DDS domain " << (*sup)->domain() << "\n" << std::flush;
  // x-rover.record: the recorder starts first, so that it hears the set from its first sample.
  auto recording = rover::deploy::SetRecording::Start(project, (*sup)->domain(), options.state_dir);
  if (!recording.ok()) {
    notify("error: " + recording.status().message(), true);
    return Fail(recording.status().message(), 2);
  }
  if (*recording) std::cout << "roverctl: recording to " << (*recording)->path() << "\n";
  const Status s = (*sup)->Start();
  if (!s.ok()) {
    if (*recording) (void)(*recording)->Stop();
    notify("error: " + s.message(), true);
    return Fail(s.message());
  }
  for (const auto& st : (*sup)->Snapshot()) {
    std::cout << "  " << st.name << "  pid " << st.pid << "  log " << st.log_path << "\n";
  }
  std::cout << "roverctl: '" << project.rover.project << "' is up on domain " << (*sup)->domain()
            << "; `roverctl ps`, `roverctl logs SERVICE`, Ctrl-C or `roverctl down` to stop\n"
            << std::flush;
  notify("ok " + std::to_string((*sup)->domain()), !wait);
  const rover::Time start = rover::MonotonicNow();
  bool waiting = wait;
  int rc = 0;
  while (!g_stop.load()) {
    (*sup)->Poll();
    if (waiting && (*sup)->readiness().ready) {
      waiting = false;
      const double after = rover::ToSeconds(rover::MonotonicNow() - up_start);
      char line[160];
      std::snprintf(line, sizeof line, "ready %.1f %.1f", after, (*sup)->ready_after_s());
      std::printf("roverctl: '%s' is ready after %.1f s (%.1f s after its services started)\n",
                  project.rover.project.c_str(), after, (*sup)->ready_after_s());
      std::fflush(stdout);
      notify(line, true);
    } else if (waiting && rover::ToSeconds(rover::MonotonicNow() - up_start) >= args.wait_s) {
      char within[64];
      std::snprintf(within, sizeof within, "%g", args.wait_s);
      const std::string msg = "'" + project.rover.project + "' is not ready within " + within +
                              " s: " + (*sup)->readiness().Summary() + "; stopping it";
      notify("error: " + msg, true);
      Fail(msg);
      rc = 1;
      break;
    }
    if (args.run_for_s > 0 && rover::ToSeconds(rover::MonotonicNow() - start) >= args.run_for_s) break;
    if (*recording && !(*recording)->health().ok()) {
      // The set was to be recorded: a failed recording fails the set (stopped, exit 1).
      std::cerr << "roverctl: error: the recording failed: " << (*recording)->health().message()
                << "; stopping '" << project.rover.project << "'\n";
      rc = 1;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  std::cout << "roverctl: stopping '" << project.rover.project << "'\n" << std::flush;
  (*sup)->Stop();
  if (*recording) {
    const auto report = (*recording)->Stop();
    if (report.status.ok()) {
      std::cout << "roverctl: " << rover::deploy::DescribeReport(report);
    } else {
      std::cerr << "roverctl: error: the recording failed: " << report.status.message() << "; "
                << report.path << " is incomplete\n";
      rc = 1;
    }
  }
  std::cout << "roverctl: stopped\n";
  if (waiting && rc == 0) notify("error: stopped before the set was ready", true);
  return rc;
}

int Up(const UpArgs& args) {
  auto project = rover::deploy::LoadComposeFile(args.file);
  if (!project.ok()) return Fail(project.status().message(), 2);
  if (!args.project.empty()) project->rover.project = args.project;
  rover::deploy::SupervisorOptions options;
  options.bin_dir = SelfDir();
  options.state_dir = args.state_root + "/" + project->rover.project;
  options.security_dir = args.security_dir.empty()
                             ? rover::deploy::SecurityDirOf(args.state_root)
                             : args.security_dir;
  options.dds_config_uri = DdsConfigUri();
  if (args.domain >= 0) options.domain = args.domain;

  const auto existing = ReadState(options.state_dir);
  if (SupervisorAlive(existing)) {
    return Fail("project '" + project->rover.project + "' is already up (roverctl pid " +
                    std::to_string(existing.value("supervisor_pid", 0)) +
                    "); run `roverctl down " + project->rover.project + "` first",
                2);
  }
  if (!args.no_preflight) {
    const Status s = rover::deploy::Preflight(*project, options);
    if (!s.ok()) return Fail(s.message(), 2);
  }
  if (!args.detach) return RunSupervisor(*project, options, args, -1);

  // Detached: the supervising process is a new session; we wait for its start-up verdict.
  int fds[2];
  if (pipe2(fds, O_CLOEXEC) != 0) return Fail("pipe failed");
  const pid_t pid = fork();
  if (pid < 0) return Fail("fork failed");
  if (pid == 0) {
    close(fds[0]);
    setsid();
    const std::string log = options.state_dir + "/roverctl.log";
    fs::create_directories(options.state_dir);
    FILE* f = std::freopen(log.c_str(), "a", stdout);
    (void)f;
    dup2(fileno(stdout), fileno(stderr));
    _exit(RunSupervisor(*project, options, args, fds[1]));
  }
  close(fds[1]);
  // Lines: "ok <domain>", then with --wait "ready <s> <s>" or "error: ..."; EOF ends it.
  std::string text;
  char buf[512];
  ssize_t n;
  while ((n = read(fds[0], buf, sizeof buf)) > 0) text.append(buf, static_cast<std::size_t>(n));
  close(fds[0]);
  std::istringstream lines(text);
  std::string line;
  bool up = false, ready = false;
  std::string error;
  while (std::getline(lines, line)) {
    if (line.rfind("ok ", 0) == 0) {
      up = true;
      std::cout << "roverctl: '" << project->rover.project << "' is up on DDS domain "
                << line.substr(3) << " (supervisor pid " << pid << ")\n";
    } else if (line.rfind("ready ", 0) == 0) {
      ready = true;
      double after = 0, services = 0;
      std::istringstream(line.substr(6)) >> after >> services;
      std::printf("roverctl: '%s' is ready after %.1f s (%.1f s after its services started)\n",
                  project->rover.project.c_str(), after, services);
    } else if (line.rfind("error: ", 0) == 0) {
      error = line.substr(7);
    }
  }
  std::cout << std::flush;
  if (!error.empty()) return Fail(error);
  if (!up) return Fail("the supervisor died during start-up");
  if (args.wait_s >= 0 && !ready) return Fail("the supervisor died before the set was ready");
  return 0;
}

// ---- down / ps / logs ------------------------------------------------------------------------

// Stops what is left of a set whose supervisor is gone (or did not stop everything): every
// process carrying the set's ROVER_SET_ID, and their process groups (StopMarkedProcesses).
rover::MarkedStop StopLeftovers(const nlohmann::json& state) {
  double grace = 1;
  for (const auto& s : state["services"]) grace = std::max(grace, s.value("stop_grace_s", 10.0));
  const std::string set_id = state.value("set_id", "");
  if (set_id.empty()) return {};
  return rover::StopMarkedProcesses(rover::deploy::kSetIdVariable, set_id + "/",
                                    rover::EnvMatch::kPrefix, rover::Seconds(grace));
}

// Marks the state file stopped (the supervisor that would have done it is gone).
void MarkStopped(const std::string& dir, nlohmann::json state) {
  state["phase"] = "stopped";
  state["ready"] = false;
  for (auto& s : state["services"]) {
    if (s.value("state", "") == "running" || s.value("state", "") == "restarting") {
      s["state"] = "stopped";
    }
    s["pid"] = 0;
    s["ready"] = false;
  }
  const std::string tmp = dir + "/state.json.tmp";
  std::ofstream(tmp) << state.dump(2) << "\n";
  std::rename(tmp.c_str(), (dir + "/state.json").c_str());
}

std::string PidList(const std::vector<pid_t>& pids) {
  std::string out;
  for (pid_t p : pids) out += (out.empty() ? "" : " ") + std::to_string(p);
  return out;
}

int Down(const std::string& root, const std::string& given, double timeout_s) {
  auto project = ResolveProject(root, given);
  if (!project.ok()) return Fail(project.status().message());
  const std::string dir = root + "/" + *project;
  const auto state = ReadState(dir);
  if (!SupervisorAlive(state)) {
    const rover::MarkedStop left = StopLeftovers(state);
    if (left.found.empty()) {
      std::cout << "roverctl: '" << *project << "' is not running\n";
      return 0;
    }
    MarkStopped(dir, state);
    std::cout << "roverctl: '" << *project << "' was not running (supervisor pid "
              << state.value("supervisor_pid", 0) << " is gone); stopped " << left.found.size()
              << " processes it left behind: " << PidList(left.found)
              << (left.killed.empty() ? "" : " (SIGKILL: " + PidList(left.killed) + ")") << "\n";
    if (!left.all_gone) return Fail("some processes of '" + *project + "' did not stop");
    return 0;
  }
  const int pid = state.value("supervisor_pid", 0);
  kill(pid, SIGTERM);
  const rover::Time deadline = rover::MonotonicNow() + rover::Seconds(timeout_s);
  while (rover::ProcessAlive(pid) && rover::MonotonicNow() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  if (rover::ProcessAlive(pid)) return Fail("supervisor " + std::to_string(pid) + " did not stop");
  // The supervisor stops whole trees; anything it still missed goes now.
  const rover::MarkedStop left = StopLeftovers(state);
  std::cout << "roverctl: '" << *project << "' stopped";
  if (!left.found.empty()) {
    std::cout << "; stopped " << left.found.size() << " more processes: " << PidList(left.found);
  }
  std::cout << "\n";
  return 0;
}

std::string Clip(std::string s, std::size_t n) {
  if (s.size() > n) s = s.substr(0, n - 3) + "...";
  return s;
}

nlohmann::json RunningCampaigns(const std::string& root);
void PrintCampaigns(const nlohmann::json& campaigns);

int Ps(const std::string& root, const std::string& given, bool json) {
  std::vector<std::string> projects;
  if (!given.empty()) {
    auto p = ResolveProject(root, given);
    if (!p.ok()) return Fail(p.status().message());
    projects.push_back(*p);
  } else {
    projects = KnownProjects(root);
  }
  nlohmann::json all = nlohmann::json::array();
  for (const auto& p : projects) {
    auto state = ReadState(root + "/" + p);
    if (state.is_null()) continue;
    const bool alive = SupervisorAlive(state);
    const std::vector<pid_t> left = alive ? std::vector<pid_t>{} : SetProcesses(state);
    if (json) {
      state["supervisor_alive"] = alive;
      state["left_behind"] = left;
      all.push_back(state);
      continue;
    }
    std::string readiness;
    if (alive && state.value("phase", "") == "up") {
      const auto not_ready = state.value("not_ready", std::vector<std::string>{});
      readiness = state.value("ready", false)
                      ? "ready"
                      : "not ready: " + std::to_string(not_ready.size()) + " of " +
                            std::to_string(state["services"].size()) + " services";
    }
    std::printf("%s  (%s%s%s, domain %d, %s)\n", p.c_str(),
                alive ? state.value("phase", "?").c_str() : "not running",
                readiness.empty() ? "" : ", ", readiness.c_str(), state.value("domain", -1),
                state.value("file", "").c_str());
    if (!alive && !left.empty()) {
      std::printf("  supervisor pid %d is gone; %zu processes of the set are still alive (%s): "
                  "`roverctl down %s` stops them\n",
                  state.value("supervisor_pid", 0), left.size(), PidList(left).c_str(), p.c_str());
    }
    std::printf("  %-22s %-10s %-8s %-3s %-9s %-8s %-5s %-14s %s\n", "SERVICE", "STATE", "PID",
                "RST", "LIFECYCLE", "HEALTH", "READY", "HEARTBEAT", "MESSAGE / LAST EXIT");
    const double timeout = state.value("heartbeat_timeout_s", 5.0);
    for (const auto& s : state["services"]) {
      std::string hb = Age(s.value("last_heartbeat_wall_ns", std::int64_t{0}));
      const std::int64_t last = s.value("last_heartbeat_wall_ns", std::int64_t{0});
      if (last > 0 && (rover::WallNow().ns - last) * 1e-9 > timeout && s.value("state", "") == "running") {
        hb += " STALE";
      }
      std::string note = s.value("message", "");
      const std::string waiting = s.value("waiting_for", "");
      if (note.empty() && alive && !s.value("ready", false) && !waiting.empty()) note = waiting;
      const std::string exit = s.value("last_exit", "");
      if (!exit.empty()) note += (note.empty() ? "" : "; ") + std::string("last exit: ") + exit;
      // A stopped set's last heartbeats say what the services were, not what they are.
      const std::string health = alive ? s.value("health", "") : "";
      const std::string lifecycle = alive ? s.value("lifecycle", "") : "-";
      if (!alive && last > 0) hb += " (stopped)";
      std::printf("  %-22s %-10s %-8d %-3d %-9s %-8s %-5s %-14s %s\n", s.value("name", "").c_str(),
                  alive ? s.value("state", "").c_str() : "-", s.value("pid", 0),
                  s.value("restarts", 0), lifecycle.c_str(),
                  health.empty() ? "-" : health.c_str(),
                  alive ? (s.value("ready", false) ? "yes" : "no") : "-", hb.c_str(),
                  Clip(note, 120).c_str());
    }
  }
  // Campaigns (`roverctl run`) keep their runs' state in the campaign folder: name them here.
  const nlohmann::json campaigns =
      given.empty() ? RunningCampaigns(root) : nlohmann::json::array();
  if (json) {
    std::cout << nlohmann::json{{"sets", all}, {"campaigns", campaigns}}.dump(2) << "\n";
  } else {
    PrintCampaigns(campaigns);
  }
  return 0;
}

int Logs(const std::string& root, const std::string& given, const std::string& service,
         bool follow, int lines) {
  auto project = ResolveProject(root, given);
  if (!project.ok()) return Fail(project.status().message());
  const std::string path = root + "/" + *project + "/logs/" + service + ".log";
  std::ifstream in(path);
  if (!in) {
    const auto state = ReadState(root + "/" + *project);
    std::string names;
    if (!state.is_null()) {
      for (const auto& s : state["services"]) names += " " + s.value("name", "");
    }
    return Fail("no service '" + service + "' in project '" + *project + "' (services:" + names + ")");
  }
  std::vector<std::string> all;
  std::string line;
  while (std::getline(in, line)) all.push_back(line);
  const std::size_t from = lines > 0 && all.size() > static_cast<std::size_t>(lines)
                               ? all.size() - static_cast<std::size_t>(lines) : 0;
  for (std::size_t i = from; i < all.size(); ++i) std::cout << all[i] << "\n";
  std::cout << std::flush;
  if (!follow) return 0;
  in.clear();
  while (!g_stop.load()) {
    if (std::getline(in, line)) {
      std::cout << line << "\n" << std::flush;
    } else {
      in.clear();
      std::this_thread::sleep_for(std::chrono::milliseconds(200));
    }
  }
  return 0;
}

int Config(const std::string& file, bool no_preflight) {
  auto project = rover::deploy::LoadComposeFile(file);
  if (!project.ok()) return Fail(project.status().message(), 2);
  // What `up` would check before starting anything: every rover service validates its
  // parameters (--validate), in a scratch state folder removed afterwards.
  if (!no_preflight) {
    std::string scratch = (fs::temp_directory_path() / "roverctl-config-XXXXXX").string();
    if (mkdtemp(scratch.data()) == nullptr) return Fail("cannot make a scratch folder");
    rover::deploy::SupervisorOptions options;
    options.bin_dir = SelfDir();
    options.state_dir = scratch;
    options.dds_config_uri = DdsConfigUri();
    const Status s = rover::deploy::Preflight(*project, options);
    std::error_code ec;
    fs::remove_all(scratch, ec);
    if (!s.ok()) return Fail(s.message(), 2);
  }
  std::cout << "project: " << project->rover.project << "\nclock: " << project->rover.clock
            << "\ndomain: " << (project->rover.domain ? std::to_string(*project->rover.domain) : "auto")
            << "\nservices (start order):\n";
  for (const auto& s : project->services) {
    std::cout << "  " << s.name << ": ";
    for (const auto& w : s.command) std::cout << w << " ";
    std::cout << "[restart " << rover::deploy::RestartPolicyName(s.restart) << "]";
    for (const auto& d : s.depends_on) {
      std::cout << " after " << d.service << " (" << rover::deploy::DependencyConditionName(d.condition) << ")";
    }
    std::cout << "\n";
  }
  if (!project->rover.faults.empty()) {
    std::cout << "faults (x-rover.faults, given to every service):\n";
    for (const auto& f : project->rover.faults) std::cout << "  " << f.spec.Describe() << "\n";
  }
  return 0;
}

// ---- record / replay / info --------------------------------------------------------------------

// A set that is up: its project (given, or the only one up), state file and DDS domain.
struct LiveSet {
  std::string project;
  nlohmann::json state;
  int domain = -1;
};

rover::Result<LiveSet> ResolveLiveSet(const std::string& root, const std::string& given) {
  LiveSet set;
  ROVER_ASSIGN_OR_RETURN(set.project, ResolveProject(root, given));
  set.state = ReadState(root + "/" + set.project);
  if (!SupervisorAlive(set.state)) {
    return rover::FailedPrecondition("project '" + set.project + "' is not running");
  }
  set.domain = set.state.value("domain", -1);
  if (set.domain < 0) {
    return rover::Internal("the state file of '" + set.project + "' has no domain");
  }
  return set;
}

// The set a recording command works on: --domain D alone, or a project (given, or the only one
// up) with its domain, clock and QoS overrides.
rover::Result<rover::deploy::TargetSet> ResolveTarget(const std::string& root,
                                                      const std::string& given, int domain,
                                                      bool domain_alone_ok) {
  rover::deploy::TargetSet t;
  if (domain >= 0 && given.empty()) {
    t.domain = domain;
    return t;
  }
  if (domain >= 0) return rover::InvalidArgument("give --domain or --project, not both");
  if (given.empty() && !domain_alone_ok) {
    return rover::InvalidArgument("give --domain D (e.g. a service started by hand) or "
                                  "--project P (a running set)");
  }
  ROVER_ASSIGN_OR_RETURN(const LiveSet set, ResolveLiveSet(root, given));
  t.project = set.project;
  t.domain = set.domain;
  if (auto compose = rover::deploy::LoadComposeFile(set.state.value("file", "")); compose.ok()) {
    t.clock = compose->rover.clock;
    t.qos = compose->rover.qos;
  }
  const std::string dir = root + "/" + t.project;
  t.alive = [dir] { return SupervisorAlive(ReadState(dir)); };
  t.security_dir = set.state.value("security_dir", "");
  return t;
}

// A secured set (state.json's security_dir) is joined with `role`'s identity; nothing to do
// for an open one.
void JoinAs(const std::string& security_dir, const char* role) {
  if (security_dir.empty()) return;
  setenv(rover::dds::kSecurityDirVariable, security_dir.c_str(), 1);
  setenv(rover::dds::kSecurityIdentityVariable, role, 1);
}

// ---- fault ----------------------------------------------------------------------------------

// The running set a fault command talks to, and the services that run a fault agent: those
// running that have sent a heartbeat (every rover service does both).
rover::Result<rover::deploy::FaultTarget> ResolveFaultTarget(const std::string& root,
                                                             const std::string& given) {
  rover::deploy::FaultTarget t;
  ROVER_ASSIGN_OR_RETURN(const LiveSet set, ResolveLiveSet(root, given));
  t.project = set.project;
  t.domain = set.domain;
  t.security_dir = set.state.value("security_dir", "");
  for (const auto& s : set.state["services"]) {
    if (s.value("state", "") == "running" && s.value("last_heartbeat_wall_ns", std::int64_t{0}) > 0) {
      t.services.push_back(s.value("name", ""));
    }
  }
  if (t.services.empty()) {
    return rover::FailedPrecondition("no service of '" + t.project +
                                     "' has sent a heartbeat yet; try again when `roverctl ps` "
                                     "shows them running");
  }
  return t;
}

// ---- run / report ------------------------------------------------------------------------------

std::string NowStamp() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  localtime_r(&t, &tm);
  char b[32];
  std::strftime(b, sizeof b, "%Y%m%d-%H%M%S", &tm);
  return b;
}

// A fault campaign's exit code: 0 when every run has a result and every fault run was safe.
int FaultCampaignExit(const rover::deploy::FaultCampaignTable& t) {
  return t.missing == 0 && t.errors.empty() && !t.interrupted && t.safe_runs == t.fault_runs ? 0 : 1;
}

// A campaign under way, registered in the state root (`<root>/campaigns/<pid>.json`) for as
// long as this roverctl runs it, so that `roverctl ps` can list it.
class CampaignRegistration {
 public:
  CampaignRegistration(const std::string& root, const std::string& scenario,
                       const std::string& out, const std::string& kind) {
    std::error_code ec;
    fs::create_directories(root + "/campaigns", ec);
    path_ = root + "/campaigns/" + std::to_string(getpid()) + ".json";
    const nlohmann::json j = {{"pid", static_cast<int>(getpid())},
                              {"scenario", scenario},
                              {"kind", kind},
                              {"out", fs::absolute(out).string()},
                              {"started", NowStamp()}};
    std::ofstream(path_) << j.dump(2) << "\n";
  }
  ~CampaignRegistration() {
    std::error_code ec;
    fs::remove(path_, ec);
  }
  CampaignRegistration(const CampaignRegistration&) = delete;
  CampaignRegistration& operator=(const CampaignRegistration&) = delete;

 private:
  std::string path_;
};

// Running campaigns (registrations whose roverctl is alive; stale ones are removed): each
// registration with its progress (`finished` runs, `total` seeds of a seed campaign, 0 else) and
// the run folders whose service set is up (`running`).
nlohmann::json RunningCampaigns(const std::string& root) {
  nlohmann::json all = nlohmann::json::array();
  std::error_code ec;
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(root + "/campaigns", ec)) {
    if (e.path().extension() == ".json") files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  for (const auto& f : files) {
    nlohmann::json j;
    try {
      std::ifstream in(f);
      j = nlohmann::json::parse(in);
    } catch (const nlohmann::json::exception&) {
      continue;
    }
    const int pid = j.value("pid", 0);
    if (pid <= 0 || kill(pid, 0) != 0) {
      fs::remove(f, ec);
      continue;
    }
    const std::string out = j.value("out", "");
    std::size_t finished = 0;
    std::vector<std::string> running;
    for (const auto& e : fs::recursive_directory_iterator(out, ec)) {
      if (e.path().filename() == "result.json") ++finished;
      if (e.path().filename() == "state.json" &&
          SupervisorAlive(ReadState(e.path().parent_path().string()))) {
        running.push_back(e.path().parent_path().string());
      }
    }
    std::size_t total = 0;
    if (j.value("kind", "") == "campaign") {
      try {
        std::ifstream in(out + "/campaign.json");
        total = nlohmann::json::parse(in).value("seeds", std::vector<std::uint32_t>{}).size();
      } catch (const nlohmann::json::exception&) {
      }
    }
    j["finished"] = finished;
    j["total"] = total;
    j["running"] = running;
    all.push_back(std::move(j));
  }
  return all;
}

// One line per running campaign with its progress and the runs under way.
void PrintCampaigns(const nlohmann::json& campaigns) {
  for (const auto& j : campaigns) {
    const std::size_t total = j.value("total", std::size_t{0});
    const std::string out = j.value("out", "");
    std::printf("%s '%s'  (roverctl pid %d, since %s): %zu %s finished, into %s\n",
                j.value("kind", "campaign").c_str(), j.value("scenario", "").c_str(),
                j.value("pid", 0), j.value("started", "").c_str(),
                j.value("finished", std::size_t{0}),
                total > 0 ? ("of " + std::to_string(total) + " runs").c_str() : "runs",
                out.c_str());
    for (const auto& r : j["running"]) {
      const fs::path run(r.get<std::string>());
      std::printf("  running: %s  (roverctl --state-dir %s ps)\n", run.filename().c_str(),
                  run.parent_path().c_str());
    }
    std::printf("  the table so far: roverctl report %s\n", out.c_str());
  }
}

int Run(const std::string& file, const std::string& seeds_text, int jobs, std::string out,
        const std::string& faults_file, const std::string& state_root, bool security,
        const std::string& security_dir, const std::string& backend,
        rover::deploy::SlurmOptions slurm, const SlurmFlags& given) {
  auto scenario = rover::deploy::LoadScenario(file);
  if (!scenario.ok()) return Fail(scenario.status().message(), 2);
  std::vector<std::uint32_t> seeds = {scenario->seed};
  if (!seeds_text.empty()) {
    auto s = rover::deploy::ParseSeedRange(seeds_text);
    if (!s.ok()) return Fail(s.status().message(), 2);
    seeds = *s;
  }
  // A fault campaign's file is checked whole before anything else happens.
  std::vector<rover::deploy::CampaignFault> faults;
  if (!faults_file.empty()) {
    auto f = rover::deploy::LoadCampaignFaults(faults_file);
    if (!f.ok()) return Fail(f.status().message(), 2);
    faults = std::move(*f);
    for (const auto& one : faults) {
      if (one.kill) continue;
      std::vector<rover::deploy::SetFault> joined = scenario->faults;
      if (const Status s = rover::deploy::AppendSetFaults({one.fault}, &joined); !s.ok()) {
        return Fail(s.message(), 2);
      }
    }
  }
  if (out.empty()) {
    out = "runs/" + scenario->name + (faults_file.empty() ? "" : "-faults") + "-" + NowStamp();
  }
  const Status folder = faults_file.empty()
                            ? rover::deploy::CheckOutputFolder(out, scenario->name)
                            : rover::deploy::CheckFaultCampaignFolder(out, scenario->name);
  if (!folder.ok()) return Fail(folder.message(), 2);
  if (const Status s = rover::deploy::CheckCampaignKills(*scenario, faults); !s.ok()) {
    return Fail(s.message(), 2);
  }
  rover::deploy::CampaignOptions o;
  o.seeds = seeds;
  o.jobs = jobs;
  o.out_dir = out;
  o.bin_dir = SelfDir();
  o.dds_config_uri = DdsConfigUri();
  o.tty = isatty(STDERR_FILENO) != 0;
  o.abort = &g_stop;
  o.security = security;
  o.security_dir = security_dir;
  {
    // Everything that can be checked before a process starts, checked once for the campaign.
    rover::deploy::RunOptions ro;
    ro.out_dir = out + "/.preflight";
    ro.bin_dir = o.bin_dir;
    ro.dds_config_uri = o.dds_config_uri;
    ro.security = security;
    ro.security_dir = security_dir;
    const Status s = rover::deploy::PreflightScenario(*scenario, seeds.front(), ro);
    std::error_code ec;
    std::filesystem::remove_all(ro.out_dir, ec);
    if (std::filesystem::exists(out) && std::filesystem::is_empty(out)) std::filesystem::remove(out, ec);
    if (!s.ok()) return Fail(s.message(), 2);
  }
  if (backend == "slurm") {
    if (!faults_file.empty()) {
      return Fail("--backend slurm runs seed campaigns; a fault campaign (--faults) runs locally",
                  2);
    }
    // x-rover.slurm in the scenario's compose file, then the flags given.
    if (auto compose = rover::deploy::LoadComposeFile(scenario->compose_path); compose.ok()) {
      const auto& x = compose->rover.slurm;
      if (!given.partition && !x.partition.empty()) slurm.partition = x.partition;
      if (!given.time && !x.time.empty()) slurm.time_limit = x.time;
      if (!given.cpus && x.cpus_per_task > 0) slurm.cpus_per_task = x.cpus_per_task;
      if (!given.sbatch_args) slurm.sbatch_args = x.sbatch_args;
    }
    rover::deploy::SlurmCampaignOptions so;
    so.seeds = seeds;
    so.out_dir = out;
    so.roverctl = SelfDir() + "/roverctl";
    so.security = security;
    so.security_dir = security_dir;
    so.slurm = slurm;
    so.abort = &g_stop;
    auto job = rover::deploy::SubmitSlurmCampaign(*scenario, so);
    if (!job.ok()) {
      return Fail(job.status().message(), job.status().code() == rover::StatusCode::kInvalidArgument ? 2 : 1);
    }
    std::printf("roverctl: submitted '%s' for %zu seed%s as slurm job %s (one task per seed), "
                "into %s\n",
                scenario->name.c_str(), seeds.size(), seeds.size() == 1 ? "" : "s", job->c_str(),
                out.c_str());
    std::fflush(stdout);
    if (slurm.detach) {
      std::printf("detached: `roverctl report %s` gathers the results\n", out.c_str());
      return 0;
    }
    const CampaignRegistration registered(state_root, scenario->name, out, "campaign");
    auto r = rover::deploy::WaitSlurmCampaign(*scenario, so, *job);
    if (!r.ok()) return Fail(r.status().message(), 1);
    std::printf("\n%s", rover::deploy::FormatSummaryTable(r->runs, r->summary, r->missing).c_str());
    for (const auto& e : r->errors) std::printf("error: %s\n", e.c_str());
    const std::string again = rover::deploy::ResubmitCommand(out);
    if (!again.empty()) std::printf("resubmit what has no result: %s\n", again.c_str());
    std::printf("\nreport: %s/summary.json  junit: %s/junit.xml\n", out.c_str(), out.c_str());
    return r->all_passed() ? 0 : 1;
  }
  if (!faults_file.empty()) {
    std::printf("roverctl: fault campaign '%s': %zu faults x %zu seed%s + baseline, %d at a time, "
                "into %s\n",
                scenario->name.c_str(), faults.size(), seeds.size(), seeds.size() == 1 ? "" : "s",
                jobs, out.c_str());
    std::fflush(stdout);
    rover::deploy::FaultCampaignOptions fo;
    fo.seeds = seeds;
    fo.jobs = jobs;
    fo.out_dir = out;
    fo.bin_dir = o.bin_dir;
    fo.dds_config_uri = o.dds_config_uri;
    fo.abort = &g_stop;
    fo.security = security;
    fo.security_dir = security_dir;
    const CampaignRegistration registered(state_root, scenario->name, out, "fault campaign");
    auto t = rover::deploy::RunFaultCampaign(*scenario, faults_file, faults, fo);
    if (!t.ok()) return Fail(t.status().message(), 2);
    std::printf("\n%s\ntable: %s/campaign.txt  %s/campaign.json\n",
                rover::deploy::FormatCampaignTable(*t).c_str(), out.c_str(), out.c_str());
    return FaultCampaignExit(*t);
  }
  std::printf("roverctl: running '%s' for %zu seed%s, %d at a time, into %s\n",
              scenario->name.c_str(), seeds.size(), seeds.size() == 1 ? "" : "s", jobs, out.c_str());
  std::fflush(stdout);
  const CampaignRegistration registered(state_root, scenario->name, out, "campaign");
  auto r = rover::deploy::RunCampaign(*scenario, o);
  if (!r.ok()) return Fail(r.status().message(), 2);
  std::printf("\n%s", rover::deploy::FormatSummaryTable(r->runs, r->summary, r->missing).c_str());
  for (const auto& e : r->errors) std::printf("error: %s\n", e.c_str());
  if (r->interrupted) std::printf("interrupted: %zu of %zu runs finished and were kept\n", r->runs.size(), seeds.size());
  std::printf("\nreport: %s/summary.json  junit: %s/junit.xml\n", out.c_str(), out.c_str());
  if (!r->runs.empty()) {
    const auto& first = r->runs.front();
    std::printf("plots:  %s/map.png  %s/estimate_error.png  (one folder per run, with logs/)\n",
                first.run_dir.c_str(), first.run_dir.c_str());
  }
  return r->all_passed() ? 0 : 1;
}

int Report(const std::string& dir) {
  if (rover::deploy::IsFaultCampaignFolder(dir)) {
    auto t = rover::deploy::LoadFaultCampaignReport(dir);
    if (!t.ok()) return Fail(t.status().message(), 2);
    std::printf("%s", rover::deploy::FormatCampaignTable(*t).c_str());
    return FaultCampaignExit(*t);
  }
  bool slurm = false;
  try {
    std::ifstream in(dir + "/campaign.json");
    slurm = in && nlohmann::json::parse(in).value("backend", "") == "slurm";
  } catch (const nlohmann::json::exception&) {
  }
  int open = 0;
  if (slurm) {
    // A Slurm campaign is gathered here: tasks Slurm ended without a result get one saying so,
    // and once none is queued or running the summary files are written.
    auto g = rover::deploy::GatherSlurmCampaign(dir);
    if (!g.ok()) return Fail(g.status().message(), 1);
    open = *g;
  }
  auto report = rover::deploy::LoadCampaignReport(dir);
  if (!report.ok()) return Fail(report.status().message(), 2);
  std::printf("%s", report->table.c_str());
  if (slurm) {
    if (open > 0) std::printf("slurm: %d task(s) still queued or running\n", open);
    const std::string again = rover::deploy::ResubmitCommand(dir);
    if (!again.empty() && open == 0) std::printf("resubmit what has no result: %s\n", again.c_str());
  }
  return report->all_passed && open == 0 ? 0 : 1;
}

// One seed of a Slurm campaign (`run-task`, what each array task runs): the same single run as
// a local campaign's, into the campaign folder; exit 0 when a result was written.
int RunTask(const std::string& file, std::uint32_t seed, const std::string& out, bool security,
            const std::string& security_dir) {
  auto scenario = rover::deploy::LoadScenario(file);
  if (!scenario.ok()) return Fail(scenario.status().message(), 2);
  rover::deploy::RunOptions ro;
  ro.out_dir = out;
  ro.bin_dir = SelfDir();
  ro.dds_config_uri = DdsConfigUri();
  ro.security = security;
  ro.security_dir = security_dir;
  ro.abort = &g_stop;
  auto r = rover::deploy::RunScenario(*scenario, seed, ro);
  if (!r.ok()) return Fail("seed " + std::to_string(seed) + ": " + r.status().message(), 1);
  std::printf("seed %u: %s  %.2f m  %.1f sim s  %.1f wall s%s%s\n", seed,
              r->pass ? "PASS" : "FAIL", r->distance_driven, r->sim_time_s, r->wall_time_s,
              r->failure.empty() ? "" : "  ", r->failure.c_str());
  return 0;
}

}  // namespace

// A usage error CLI11 words badly, said plainly: an unknown command is named, and an option
// with an optional value (up --wait) given its value as the next word is shown the '=' form.
// Empty when CLI11's own message is the better one.
std::string UsageHint(const CLI::App& app, int argc, char** argv) {
  if (argc >= 2 && argv[1][0] != '-') {
    const std::string word = argv[1];
    std::string names;
    bool known = false;
    for (const CLI::App* sub : app.get_subcommands({})) {
      known = known || sub->get_name() == word;
      if (sub->get_group().empty()) continue;  // internal (run-task)
      names += (names.empty() ? "" : ", ") + sub->get_name();
    }
    if (!known) return "unknown command '" + word + "' (the commands: " + names + ")";
  }
  for (int i = 1; i + 1 < argc; ++i) {
    const std::string a = argv[i];
    const std::string next = argv[i + 1];
    if (a == "--wait" && !next.empty() &&
        next.find_first_not_of("0123456789.") == std::string::npos) {
      return "--wait takes its seconds after '=': write --wait=" + next + " (a word after --wait "
             "is the compose file)";
    }
  }
  return "";
}

int main(int argc, char** argv) {
  rover::log::Init("roverctl", rover::log::Level::kWarning);
  CLI::App app{"roverctl: run, inspect and stop rover service sets"};
  app.require_subcommand(1);
  std::string state_root = rover::deploy::DefaultStateRoot();
  app.add_option("--state-dir", state_root, "where project state and logs live")
      ->envname("ROVER_STATE_DIR");
  std::string security_dir_flag;
  app.add_option("--security-dir", security_dir_flag,
                 "DDS Security keys (default: <state dir>/security; docs/security.md)");

  UpArgs up;
  auto* up_cmd = app.add_subcommand("up", "start the services of a compose file");
  up_cmd->add_option("file", up.file, "compose file")->required();
  up_cmd->add_option("-p,--project", up.project, "project name (default: x-rover.project or the file name)");
  up_cmd->add_option("--domain", up.domain, "DDS domain (default: x-rover.domain or a free one)")
      ->check(CLI::Range(0, 232));
  up_cmd->add_flag("-d,--detach", up.detach, "run in the background");
  up_cmd->add_flag("--no-preflight", up.no_preflight, "skip parameter validation");
  up_cmd->add_option("--for", up.run_for_s, "stop by itself after this many seconds");
  double wait_s = kDefaultWaitS;
  auto* wait_flag = up_cmd->add_flag(
      "--wait{" + std::to_string(static_cast<int>(kDefaultWaitS)) + "}", wait_s,
      "return (with -d) or report once every service is ready, waiting at most S seconds "
      "(--wait=S; default " + std::to_string(static_cast<int>(kDefaultWaitS)) +
          "); not ready by then: the set is stopped, exit code 1");

  std::string project;
  double down_timeout = 60;
  auto* down_cmd = app.add_subcommand("down", "stop a running service set");
  down_cmd->add_option("project", project, "project name (default: the only one up)");
  down_cmd->add_option("--timeout", down_timeout, "seconds to wait");

  bool json = false;
  auto* ps_cmd = app.add_subcommand("ps", "list services: state, pid, restarts, last heartbeat");
  ps_cmd->add_option("project", project, "project name (default: all)");
  ps_cmd->add_flag("--json", json, "machine-readable output");

  std::string service;
  bool follow = false;
  int lines = 0;
  auto* logs_cmd = app.add_subcommand("logs", "print a service's log");
  logs_cmd->add_option("service", service, "service name")->required();
  logs_cmd->add_option("-p,--project", project, "project name");
  logs_cmd->add_flag("-f,--follow", follow, "keep printing new lines");
  logs_cmd->add_option("-n,--lines", lines, "only the last N lines");

  std::string config_file;
  auto* config_cmd = app.add_subcommand("config", "validate a compose file and print the plan");
  config_cmd->add_option("file", config_file, "compose file")->required();
  bool config_no_preflight = false;
  config_cmd->add_flag("--no-preflight", config_no_preflight,
                       "skip the services' parameter validation (the file is still checked)");

  std::string scenario_file, seeds, out_dir, report_dir;
  int jobs = 1;
  bool run_secure = false;
  auto* run_cmd = app.add_subcommand("run", "run a scenario end to end over a range of seeds");
  run_cmd->add_flag("--security", run_secure,
                    "run the set with DDS Security (as x-rover.security: enabled)");
  run_cmd->add_option("scenario", scenario_file, "scenario file")->required();
  run_cmd->add_option("--seeds", seeds, "seed or range A..B (default: the scenario's seed)");
  run_cmd->add_option("--jobs", jobs, "runs at a time")->check(CLI::Range(1, 16));
  run_cmd->add_option("--out", out_dir, "campaign folder (default: runs/<scenario>-<time>)");
  std::string faults_file;
  run_cmd->add_option("--faults", faults_file,
                      "fault campaign: run each fault of FILE alone over the seeds, plus a "
                      "fault-free baseline per seed (docs/faults.md \"Campaigns\")");
  std::string backend = "local";
  run_cmd->add_option("--backend", backend, "local (runs here, --jobs at a time) or slurm (an "
                                            "array job, one task per seed)")
      ->check(CLI::IsMember({"local", "slurm"}));
  rover::deploy::SlurmOptions slurm;
  auto* slurm_partition_opt =
      run_cmd->add_option("--partition", slurm.partition, "slurm: partition (x-rover.slurm)");
  auto* slurm_time_opt =
      run_cmd->add_option("--time", slurm.time_limit, "slurm: time limit per task");
  auto* slurm_cpus_opt = run_cmd->add_option("--cpus-per-task", slurm.cpus_per_task,
                                             "slurm: CPUs per task (default 1)");
  auto* slurm_args_opt = run_cmd->add_option("--sbatch-arg", slurm.sbatch_args,
                                             "slurm: one more sbatch option (repeatable)");
  run_cmd->add_flag("--detach", slurm.detach,
                    "slurm: submit and return; `roverctl report DIR` gathers");
  // What each Slurm array task runs (not for people): one seed into the campaign folder.
  std::string task_scenario, task_out;
  std::uint32_t task_seed = 0;
  bool task_secure = false;
  auto* run_task_cmd = app.add_subcommand("run-task", "");  // hidden: the group name is empty
  run_task_cmd->group("");
  run_task_cmd->add_option("scenario", task_scenario)->required();
  run_task_cmd->add_option("--seed", task_seed)->required();
  run_task_cmd->add_option("--out", task_out)->required();
  run_task_cmd->add_flag("--security", task_secure);
  auto* report_cmd = app.add_subcommand("report", "print the summary of a campaign folder");
  report_cmd->add_option("dir", report_dir, "campaign folder")->required();

  std::string rec_out, rec_compression = "zstd", rec_clock = "auto";
  std::vector<std::string> rec_topics, rec_exclude;
  double rec_cap_mb = 0, rec_duration = 0;
  int rec_domain = -1;
  auto* record_cmd = app.add_subcommand("record", "record a running set's topics to an MCAP file");
  record_cmd->add_option("-p,--project", project, "project (default: the only one up)");
  record_cmd->add_option("--domain", rec_domain, "DDS domain instead of a project")
      ->check(CLI::Range(0, 232));
  record_cmd->add_option("-o,--output", rec_out, "MCAP file to write")->required();
  record_cmd->add_option("--topics", rec_topics, "topic globs to record (default: every topic)");
  record_cmd->add_option("--exclude", rec_exclude, "topic globs to leave out");
  record_cmd->add_option("--size-cap", rec_cap_mb, "stop recording at this file size [MB]");
  record_cmd->add_option("--compression", rec_compression, "chunk compression: zstd, lz4, none");
  record_cmd->add_option("--duration", rec_duration, "stop after this many run-clock seconds");
  record_cmd->add_option("--clock", rec_clock, "log time: auto (the set's), sim or wall");

  std::string replay_file;
  std::vector<std::string> rep_topics, rep_exclude;
  double rep_rate = 1.0;
  int rep_domain = -1;
  bool rep_no_clock = false, rep_force = false, rep_accept = false;
  auto* replay_cmd = app.add_subcommand("replay", "republish a recording onto a DDS domain");
  replay_cmd->add_option("file", replay_file, "MCAP recording")->required();
  replay_cmd->add_option("--topics", rep_topics, "topic globs to replay (default: all)");
  replay_cmd->add_option("--exclude", rep_exclude, "topic globs to leave out");
  replay_cmd->add_option("--rate", rep_rate, "1 = as recorded, 2 = twice as fast, 0 = at once");
  replay_cmd->add_option("--domain", rep_domain, "DDS domain to publish on")
      ->check(CLI::Range(0, 232));
  replay_cmd->add_option("-p,--project", project, "a running set to publish into");
  replay_cmd->add_flag("--no-clock", rep_no_clock, "publish no sim/clock");
  replay_cmd->add_flag("--force", rep_force, "publish even where others publish the same topics");
  replay_cmd->add_flag("--accept-schema-changes", rep_accept,
                       "replay topics whose recorded IDL differs from this build's");

  auto* security_cmd = app.add_subcommand(
      "security", "DDS Security keys for secured sets (x-rover.security): init, show, rotate");
  security_cmd->require_subcommand(1);
  std::string security_site = "rover";
  int security_days = 365;
  bool security_new_ca = false;
  auto* security_init_cmd = security_cmd->add_subcommand(
      "init", "make the authority (kept if present), an identity per role, governance and "
              "permissions from the topic catalog");
  security_init_cmd->add_flag("--new-authority", security_new_ca,
                              "replace the authority too (every identity is remade)");
  auto* security_rotate_cmd = security_cmd->add_subcommand(
      "rotate", "new keys and certificates for every role and new documents, same authority");
  auto* security_show_cmd = security_cmd->add_subcommand(
      "show", "the authority, each identity's expiry and grants, and whether all verify");
  for (auto* c : {security_init_cmd, security_rotate_cmd}) {
    c->add_option("--site", security_site, "O= of every subject (letters, digits, - _ . space)");
    c->add_option("--days", security_days, "validity of identities and permissions [days]");
  }

  std::string info_file;
  auto* info_cmd = app.add_subcommand("info", "print a recording's topics, types, counts and span");
  info_cmd->add_option("file", info_file, "MCAP recording")->required();

  auto* fault_cmd = app.add_subcommand("fault", "inject, list and clear faults in a running set");
  fault_cmd->require_subcommand(1);
  rover::deploy::FaultAddArgs fault_add;
  std::string fault_project;
  auto* fault_add_cmd = fault_cmd->add_subcommand(
      "add", "inject a fault (keys as in x-rover.faults, docs/faults.md); applied by every "
             "service it names, from now unless --from-epoch");
  fault_add_cmd->add_option("spec", fault_add.inline_spec,
                            "the fault as a YAML map, e.g. '{kind: drop, topic: dl/pose}'");
  fault_add_cmd->add_option("-f,--file", fault_add.file, "a YAML file of faults (a list)");
  fault_add_cmd->add_option("-p,--project", fault_project, "project (default: the only one up)");
  fault_add_cmd->add_flag("--from-epoch", fault_add.from_epoch,
                          "count --start from the run's epoch instead of from now");
  // One flag per key; a flag given overrides the same key of SPEC.
  const std::vector<std::pair<std::string, std::string>> kFaultKeys = {
      {"kind", "drop, delay, duplicate, reorder, freeze, corrupt, noise, bias, partition"},
      {"topic", "topic globs, comma-separated; !glob excludes"},
      {"service", "service glob (default: every service)"},
      {"side", "writer, reader or both"},
      {"field", "field path (corrupt, noise, bias), e.g. pose.position.x"},
      {"mode", "corrupt: nan, inf, -inf, value, out_of_range, bitflip"},
      {"value", "corrupt value / bias offset"},
      {"sigma", "noise standard deviation"},
      {"bits", "bitflip: bits per value"},
      {"copies", "duplicate: extra copies"},
      {"probability", "share of the samples hit, [0, 1]"},
      {"delay", "seconds, or a YAML map such as '{distribution: uniform, min: 0.1, max: 0.5}'"},
      {"start_s", "window start [s] (from now, or the epoch with --from-epoch)"},
      {"duration_s", "window length [s]; 0 = until cleared"},
      {"seed", "the fault's random stream"},
      {"id", "fault id (default: the next free one)"},
      {"name", "a label"}};
  std::map<std::string, std::string> fault_keys;
  std::vector<std::pair<std::string, CLI::Option*>> fault_key_opts;
  for (const auto& [key, help] : kFaultKeys) {
    std::string flag = "--" + key;
    if (key == "start_s") flag = "--start,--start_s";
    if (key == "duration_s") flag = "--duration,--duration_s";
    fault_key_opts.push_back({key, fault_add_cmd->add_option(flag, fault_keys[key], help)});
  }
  auto* fault_list_cmd = fault_cmd->add_subcommand(
      "list", "the faults each service holds, with the samples seen and hit");
  fault_list_cmd->add_option("-p,--project", fault_project, "project (default: the only one up)");
  fault_list_cmd->add_flag("--json", json, "machine-readable output");
  std::int64_t fault_clear_id = 0;
  auto* fault_clear_cmd = fault_cmd->add_subcommand("clear", "remove one fault (by id), or all");
  fault_clear_cmd->add_option("id", fault_clear_id, "fault id (default: every fault)")
      ->check(CLI::Range(std::int64_t{1}, std::int64_t{4294967295}));
  fault_clear_cmd->add_option("-p,--project", fault_project, "project (default: the only one up)");

  auto* seq_cmd = app.add_subcommand("seq", "run command sequences on a running set");
  seq_cmd->require_subcommand(1);
  rover::deploy::SeqRunArgs seq_run;
  std::string seq_project;
  auto* seq_run_cmd = seq_cmd->add_subcommand(
      "run", "send a sequence file to apl-sequencer and follow it to DONE or FAILED "
             "(docs/services/apl-sequencer.md)");
  seq_run_cmd->add_option("file", seq_run.file, "the sequence (apl/sequencer/README.md)")->required();
  seq_run_cmd->add_option("--set", seq_run.sets,
                          "name=value: replaces the text's TARGET or CONST definition (repeatable), "
                          "e.g. --set 'target=(5.2, 0.4, 0)'");
  seq_run_cmd->add_option("-p,--project", seq_project, "project (default: the only one up)");
  seq_run_cmd->add_flag("--no-wait", seq_run.no_wait, "return after the first status");
  seq_run_cmd->add_option("--timeout", seq_run.timeout_s, "[s] wall: stop waiting after this (0 = never)")
      ->check(CLI::NonNegativeNumber);

  // Usage errors are exit code 2 (docs/roverctl.md), not CLI11's own codes; --help is 0.
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (const std::string hint = UsageHint(app, argc, argv); !hint.empty()) {
      std::fprintf(stderr, "roverctl: %s\nRun with --help for more information.\n",
                   hint.c_str());
      return 2;
    }
    return app.exit(e) == 0 ? 0 : 2;
  }
  if (*wait_flag) {
    if (!(wait_s > 0)) return Fail("--wait: " + std::to_string(wait_s) + " is not > 0 s", 2);
    up.wait_s = wait_s;
  }

  struct sigaction sa {};
  sa.sa_handler = OnSignal;
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
  signal(SIGPIPE, SIG_IGN);

  up.state_root = state_root;
  up.security_dir = security_dir_flag;
  if (*up_cmd) return Up(up);
  if (*down_cmd) return Down(state_root, project, down_timeout);
  if (*ps_cmd) return Ps(state_root, project, json);
  if (*logs_cmd) return Logs(state_root, project, service, follow, lines);
  if (*config_cmd) return Config(config_file, config_no_preflight);
  const std::string security_dir =
      security_dir_flag.empty() ? rover::deploy::SecurityDirOf(state_root) : security_dir_flag;
  if (*run_cmd) {
    SlurmFlags given;
    given.partition = slurm_partition_opt->count() > 0;
    given.time = slurm_time_opt->count() > 0;
    given.cpus = slurm_cpus_opt->count() > 0;
    given.sbatch_args = slurm_args_opt->count() > 0;
    return Run(scenario_file, seeds, jobs, out_dir, faults_file, state_root, run_secure,
               security_dir, backend, slurm, given);
  }
  if (*run_task_cmd) {
    return RunTask(task_scenario, task_seed, task_out, task_secure,
                   security_dir_flag.empty() ? "" : security_dir);
  }
  if (*security_cmd) {
    rover::deploy::SecurityOptions so;
    so.dir = security_dir;
    so.site = security_site;
    so.identity_days = security_days;
    if (const Status v = so.Validate(); !v.ok()) return Fail(v.message(), 2);
    if (*security_show_cmd) {
      auto d = rover::deploy::DescribeSecurity(security_dir);
      if (!d.ok()) return Fail(d.status().message());
      std::cout << *d;
      return rover::deploy::VerifySecurity(security_dir).ok() ? 0 : 1;
    }
    if (*security_init_cmd && !security_new_ca &&
        std::filesystem::exists(security_dir + "/ca.pem")) {
      std::cout << "roverctl: keeping the authority in " << security_dir
                << " (--new-authority makes a new one; every set must then get new keys)\n";
    }
    const Status st = *security_init_cmd ? rover::deploy::InitSecurity(so, security_new_ca)
                                         : rover::deploy::RotateSecurity(so);
    if (!st.ok()) return Fail(st.message());
    std::cout << "roverctl: " << (*security_init_cmd ? "made" : "rotated") << " "
              << rover::dds::RoleAccessTable().size() << " identities, governance and "
              << "permissions in " << security_dir << "; `roverctl security show` lists them\n";
    return 0;
  }
  if (*report_cmd) return Report(report_dir);
  if (*info_cmd) return rover::deploy::RunInfo(info_file, std::cout, std::cerr);
  if (*fault_cmd) {
    for (const auto& [key, opt] : fault_key_opts) {
      if (opt->count() > 0) fault_add.keys[key] = fault_keys[key];
    }
    if (*fault_add_cmd) {
      // A bad spec is a usage error whether or not a set is up: check it first.
      if (auto specs = rover::deploy::BuildFaultSpecs(fault_add, {}); !specs.ok()) {
        return Fail(specs.status().message(), 2);
      }
    }
    auto target = ResolveFaultTarget(state_root, fault_project);
    if (!target.ok()) return Fail(target.status().message());
    setenv("CYCLONEDDS_URI", DdsConfigUri().c_str(), 0);  // the set's own configuration
    JoinAs(target->security_dir, "fault-controller");
    if (*fault_add_cmd) return rover::deploy::RunFaultAdd(*target, fault_add, std::cout, std::cerr);
    if (*fault_list_cmd) return rover::deploy::RunFaultList(*target, json, std::cout, std::cerr);
    const std::optional<std::uint32_t> id =
        fault_clear_id > 0 ? std::optional<std::uint32_t>(static_cast<std::uint32_t>(fault_clear_id))
                           : std::nullopt;
    return rover::deploy::RunFaultClear(*target, id, std::cout, std::cerr);
  }
  if (*seq_cmd) {
    auto set = ResolveLiveSet(state_root, seq_project);
    if (!set.ok()) return Fail(set.status().message());
    setenv("CYCLONEDDS_URI", DdsConfigUri().c_str(), 0);  // the set's own configuration
    JoinAs(set->state.value("security_dir", ""), "sequence-operator");
    return rover::deploy::RunSeqRun(set->domain, seq_run, std::cout, std::cerr);
  }
  if (*record_cmd) {
    auto target = ResolveTarget(state_root, project, rec_domain, true);
    if (!target.ok()) return Fail(target.status().message(), 2);
    JoinAs(target->security_dir, "recorder");
    rover::deploy::RecordArgs a;
    a.target = std::move(*target);
    a.record.path = rec_out;
    a.record.topics = {rec_topics, rec_exclude};
    a.record.size_cap_mb = rec_cap_mb;
    auto c = rover::recording::ParseCompression(rec_compression);
    if (!c.ok()) return Fail("record: --" + c.status().message(), 2);
    a.record.compression = *c;
    a.clock = rec_clock;
    a.duration_s = rec_duration;
    a.stop = &g_stop;
    return rover::deploy::RunRecord(a, std::cout, std::cerr);
  }
  if (*replay_cmd) {
    auto target = ResolveTarget(state_root, project, rep_domain, false);
    if (!target.ok()) return Fail(target.status().message(), 2);
    JoinAs(target->security_dir, "replayer");
    rover::deploy::ReplayArgs a;
    a.file = replay_file;
    a.target = std::move(*target);
    a.topics = {rep_topics, rep_exclude};
    a.rate = rep_rate;
    a.clock = !rep_no_clock;
    a.force = rep_force;
    a.accept_schema_changes = rep_accept;
    a.stop = &g_stop;
    return rover::deploy::RunReplay(a, std::cout, std::cerr);
  }
  return 1;
}
