#include "rover/deploy/slurm_campaign.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <thread>

#include "rover/base/clock.hpp"
#include "rover/base/format.hpp"

namespace rover::deploy {
namespace {

namespace fs = std::filesystem;

constexpr const char* kTerminalStates[] = {
    "COMPLETED", "FAILED",        "CANCELLED", "TIMEOUT", "NODE_FAIL",
    "PREEMPTED", "OUT_OF_MEMORY", "BOOT_FAIL", "DEADLINE"};

Result<CommandOutput> Slurm(const SlurmCampaignOptions& o, const std::vector<std::string>& argv) {
  if (o.run) return o.run(argv);
  return RunCommand(argv, o.out_dir, std::chrono::seconds(60));
}

std::string Quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::string RunDirOf(const std::string& dir, const std::string& scenario, std::uint32_t seed) {
  return dir + "/" + scenario + "-seed" + std::to_string(seed);
}

// The task index -> seed map of every job of the campaign, newest job last.
struct JobRecord {
  std::string id;
  std::vector<std::uint32_t> seeds;  // index = array task id
};

Result<nlohmann::json> ReadCampaign(const std::string& dir) {
  std::ifstream in(dir + "/campaign.json");
  if (!in) return NotFound(dir + "/campaign.json: missing (not a campaign folder)");
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    return InvalidArgument(dir + "/campaign.json: " + e.what());
  }
}

std::vector<JobRecord> JobsOf(const nlohmann::json& c) {
  std::vector<JobRecord> jobs;
  for (const auto& j : c.value("slurm_jobs", nlohmann::json::array())) {
    jobs.push_back({j.value("job_id", ""), j.value("seeds", std::vector<std::uint32_t>{})});
  }
  return jobs;
}

// Parses `scontrol show job -o` lines (one per array task) into states.
void ParseScontrol(const std::string& text, const JobRecord& job,
                   std::map<std::uint32_t, SlurmTask>* tasks) {
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    std::map<std::string, std::string> kv;
    std::istringstream words(line);
    for (std::string w; words >> w;) {
      const std::size_t eq = w.find('=');
      if (eq != std::string::npos) kv[w.substr(0, eq)] = w.substr(eq + 1);
    }
    if (kv["ArrayJobId"] != job.id || kv["ArrayTaskId"].empty()) continue;
    // One task ("3"), or the tasks not yet split off the array, as ranges ("0-1", "2,4-5%2"):
    // a pending array cancelled as a whole is one record.
    std::string ids = kv["ArrayTaskId"];
    ids = ids.substr(0, ids.find('%'));
    ids.erase(std::remove(ids.begin(), ids.end(), '['), ids.end());
    ids.erase(std::remove(ids.begin(), ids.end(), ']'), ids.end());
    std::istringstream parts(ids);
    for (std::string part; std::getline(parts, part, ',');) {
      const std::size_t dash = part.find('-');
      const std::string a = part.substr(0, dash);
      const std::string b = dash == std::string::npos ? a : part.substr(dash + 1);
      if (a.empty() || b.empty() || (a + b).find_first_not_of("0123456789") != std::string::npos) {
        continue;
      }
      for (std::size_t index = std::stoul(a); index <= std::stoul(b); ++index) {
        if (index >= job.seeds.size()) break;
        SlurmTask& t = (*tasks)[job.seeds[index]];
        t.seed = job.seeds[index];
        t.state = kv["JobState"];
        t.exit_code = kv["ExitCode"];
      }
    }
  }
}

// Parses `squeue -h -r -j JOB -o %i|%T` ("12_3|RUNNING").
void ParseSqueue(const std::string& text, const JobRecord& job,
                 std::map<std::uint32_t, SlurmTask>* tasks) {
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    const std::size_t bar = line.find('|');
    const std::size_t us = line.find('_');
    if (bar == std::string::npos || us == std::string::npos || us > bar) continue;
    if (line.substr(0, us) != job.id) continue;
    const std::string idx = line.substr(us + 1, bar - us - 1);
    if (idx.empty() || idx.find_first_not_of("0123456789") != std::string::npos) continue;
    const std::size_t index = std::stoul(idx);
    if (index >= job.seeds.size()) continue;
    SlurmTask& t = (*tasks)[job.seeds[index]];
    t.seed = job.seeds[index];
    t.state = line.substr(bar + 1);
  }
}

// A result.json for a task Slurm ended without one, so that the summary shows what happened.
void WriteEndedWithoutResult(const std::string& dir, const std::string& scenario,
                             const SlurmTask& t, std::size_t index) {
  const std::string run_dir = RunDirOf(dir, scenario, t.seed);
  if (fs::exists(run_dir + "/result.json")) return;
  std::error_code ec;
  fs::create_directories(run_dir, ec);
  RunResult r;
  r.scenario = scenario;
  r.seed = t.seed;
  r.run_dir = run_dir;
  r.failure = "slurm: " + t.state + ", exit code " + (t.exit_code.empty() ? "?" : t.exit_code) +
              " (no result; log: slurm/task-" + std::to_string(index) + ".log)";
  std::ofstream(run_dir + "/result.json") << ToJson(r).dump(2) << "\n";
}

bool SlurmEnded(const RunResult& r) { return r.failure.rfind("slurm: ", 0) == 0; }

}  // namespace

bool SlurmTask::ended() const {
  return std::any_of(std::begin(kTerminalStates), std::end(kTerminalStates),
                     [&](const char* s) { return state.rfind(s, 0) == 0; });
}

Status SlurmOptions::Validate() const {
  if (cpus_per_task < 1 || cpus_per_task > 256) {
    return InvalidArgument("--cpus-per-task: " + std::to_string(cpus_per_task) +
                           " is not in [1, 256]");
  }
  if (time_limit.find_first_not_of("0123456789:-") != std::string::npos) {
    return InvalidArgument("--time: '" + time_limit +
                           "' is not a Slurm time (minutes, MM:SS, HH:MM:SS or D-HH)");
  }
  if (!(poll_s >= 0.2 && poll_s <= 60)) {
    return InvalidArgument("slurm poll: " + FormatNumber(poll_s) + " s is not in [0.2, 60]");
  }
  return Status::Ok();
}

Result<std::string> SubmitSlurmCampaign(const Scenario& scenario,
                                        const SlurmCampaignOptions& o) {
  ROVER_RETURN_IF_ERROR(o.slurm.Validate());
  if (o.seeds.empty()) return InvalidArgument("no seeds to run");
  if (!o.run && FindInPath("sbatch", std::getenv("PATH") ? std::getenv("PATH") : "").empty()) {
    return NotFound("sbatch is not installed: Slurm is needed for --backend slurm (Debian "
                    "packages slurm-client, slurmctld, slurmd; scripts/slurm-local.sh starts a "
                    "one-node cluster); nothing submitted");
  }
  ROVER_RETURN_IF_ERROR(CheckOutputFolder(o.out_dir, scenario.name));
  const std::string dir = fs::absolute(o.out_dir).lexically_normal().string();
  std::error_code ec;
  fs::create_directories(dir + "/slurm", ec);
  if (ec) return Unavailable("cannot create " + dir + "/slurm: " + ec.message());

  // The task script: every node must see the build and the folder at these paths.
  const std::string script = dir + "/slurm/job-" + std::to_string(WallNow().ns) + ".sh";
  {
    std::ofstream s(script);
    s << "#!/bin/bash\n"
         "# Written by roverctl run --backend slurm: one task per seed of '" << scenario.name
      << "'.\nset -u\nSEEDS=(";
    for (std::uint32_t seed : o.seeds) s << seed << " ";
    s << ")\nROVERCTL=" << Quote(o.roverctl) << "\n"
      << "if [ ! -x \"$ROVERCTL\" ]; then\n"
         "  echo \"rover task: node $(hostname) has no build at $ROVERCTL (the build and the "
         "campaign folder must be on storage every node sees)\" >&2\n"
         "  exit 3\n"
         "fi\n"
      << "exec \"$ROVERCTL\""
      << (o.security && !o.security_dir.empty() ? " --security-dir " + Quote(o.security_dir) : "")
      << " run-task " << Quote(fs::absolute(scenario.file).string())
      << " --seed \"${SEEDS[$SLURM_ARRAY_TASK_ID]}\" --out " << Quote(dir)
      << (o.security ? " --security" : "") << "\n";
  }
  chmod(script.c_str(), 0755);

  std::vector<std::string> argv = {"sbatch", "--parsable",
                                   "--job-name=rover-" + scenario.name,
                                   "--array=0-" + std::to_string(o.seeds.size() - 1),
                                   "--output=" + dir + "/slurm/task-%a.log",
                                   "--cpus-per-task=" + std::to_string(o.slurm.cpus_per_task)};
  if (!o.slurm.partition.empty()) argv.push_back("--partition=" + o.slurm.partition);
  if (!o.slurm.time_limit.empty()) argv.push_back("--time=" + o.slurm.time_limit);
  argv.insert(argv.end(), o.slurm.sbatch_args.begin(), o.slurm.sbatch_args.end());
  argv.push_back(script);
  auto r = Slurm(o, argv);
  if (!r.ok()) return Unavailable("sbatch: " + r.status().message() + "; nothing submitted");
  if (!r->exit.success()) {
    std::string flags;
    if (!o.slurm.partition.empty()) flags += " --partition " + o.slurm.partition;
    if (!o.slurm.time_limit.empty()) flags += " --time " + o.slurm.time_limit;
    for (const auto& a : o.slurm.sbatch_args) flags += " " + a;
    return FailedPrecondition("sbatch refused the job (" + r->exit.ToString() + "): " +
                              r->LastErrorLine() +
                              (flags.empty() ? "" : " [given:" + flags + "]") +
                              "; nothing submitted");
  }
  std::string job = r->out.substr(0, r->out.find_first_of(";\n"));
  if (job.empty() || job.find_first_not_of("0123456789") != std::string::npos) {
    return Internal("sbatch answered '" + r->out + "', not a job id");
  }

  // campaign.json: the seeds of every submission to this folder, and each job's tasks.
  nlohmann::json c = nlohmann::json::object();
  if (auto old = ReadCampaign(dir); old.ok() && old->value("backend", "") == "slurm") c = *old;
  std::set<std::uint32_t> seeds(o.seeds.begin(), o.seeds.end());
  for (std::uint32_t s : c.value("seeds", std::vector<std::uint32_t>{})) seeds.insert(s);
  c["scenario"] = scenario.name;
  c["scenario_file"] = fs::absolute(scenario.file).string();
  c["seeds"] = std::vector<std::uint32_t>(seeds.begin(), seeds.end());
  c["backend"] = "slurm";
  c["pid"] = o.slurm.detach ? 0 : static_cast<int>(getpid());
  c["submitted_wall_ns"] = WallNow().ns;
  if (!c.contains("slurm_jobs")) c["slurm_jobs"] = nlohmann::json::array();
  c["slurm_jobs"].push_back({{"job_id", job}, {"seeds", o.seeds}, {"script", script}});
  // Results of earlier submissions that Slurm ended are replaced by this one's tasks.
  for (std::uint32_t s : o.seeds) fs::remove_all(RunDirOf(dir, scenario.name, s), ec);
  fs::remove(dir + "/summary.json", ec);
  std::ofstream(dir + "/campaign.json") << c.dump(2) << "\n";
  return job;
}

Status QuerySlurmTasks(const SlurmCampaignOptions& o, const std::string& job_id,
                       std::map<std::uint32_t, SlurmTask>* tasks) {
  ROVER_ASSIGN_OR_RETURN(const nlohmann::json c, ReadCampaign(o.out_dir));
  for (const JobRecord& job : JobsOf(c)) {
    if (job.id != job_id) continue;
    for (std::uint32_t s : job.seeds) {
      if (!tasks->count(s)) (*tasks)[s] = SlurmTask{s, "PENDING", ""};
    }
    auto q = Slurm(o, {"squeue", "-h", "-r", "-j", job.id, "-o", "%i|%T"});
    if (q.ok() && q->exit.success()) ParseSqueue(q->out, job, tasks);
    auto sc = Slurm(o, {"scontrol", "show", "job", "-o", job.id});
    if (sc.ok() && sc->exit.success()) ParseScontrol(sc->out, job, tasks);
    if (!q.ok() && !sc.ok()) return Unavailable("cannot ask Slurm: " + q.status().message());
  }
  return Status::Ok();
}

Result<CampaignResult> WaitSlurmCampaign(const Scenario& scenario,
                                         const SlurmCampaignOptions& options,
                                         const std::string& job_id) {
  SlurmCampaignOptions o = options;
  o.out_dir = fs::absolute(options.out_dir).lexically_normal().string();
  ROVER_ASSIGN_OR_RETURN(const nlohmann::json c, ReadCampaign(o.out_dir));
  const std::vector<JobRecord> jobs = JobsOf(c);
  const auto job = std::find_if(jobs.begin(), jobs.end(),
                                [&](const JobRecord& j) { return j.id == job_id; });
  if (job == jobs.end()) return NotFound("slurm job " + job_id + " is not in campaign.json");
  const Time start = MonotonicNow();
  std::map<std::uint32_t, SlurmTask> tasks;
  std::set<std::uint32_t> reported;
  std::string last_line;
  bool interrupted = false;
  while (true) {
    const Status st = QuerySlurmTasks(o, job_id, &tasks);
    if (!st.ok()) std::fprintf(stderr, "roverctl: %s (asking again)\n", st.message().c_str());
    int finished = 0, running = 0, pending = 0;
    for (const auto& [seed, t] : tasks) {
      if (t.ended()) {
        ++finished;
        if (reported.insert(seed).second) {
          const std::string rj = RunDirOf(o.out_dir, scenario.name, seed) + "/result.json";
          std::string what = t.state + " " + t.exit_code;
          try {
            std::ifstream in(rj);
            if (in) {
              auto r = RunResultFromJson(nlohmann::json::parse(in));
              if (r.ok()) {
                char b[160];
                std::snprintf(b, sizeof b, "%s  %.2f m  %.1f sim s  %.1f wall s",
                              r->pass ? "PASS" : "FAIL", r->distance_driven, r->sim_time_s,
                              r->wall_time_s);
                what = b;
              }
            }
          } catch (const nlohmann::json::exception&) {
          }
          std::printf("seed %u: %s\n", seed, what.c_str());
        }
      } else if (t.state == "RUNNING" || t.state == "COMPLETING" || t.state == "CONFIGURING") {
        ++running;
      } else {
        ++pending;
      }
    }
    const std::string line = "slurm job " + job_id + ": " + std::to_string(finished) +
                             " finished, " + std::to_string(running) + " running, " +
                             std::to_string(pending) + " pending";
    if (line != last_line) {
      std::printf("%s\n", line.c_str());
      last_line = line;
    }
    std::fflush(stdout);
    if (finished == static_cast<int>(job->seeds.size())) break;
    if (o.abort && o.abort->load()) {
      interrupted = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::duration<double>(o.slurm.poll_s));
  }
  for (std::size_t i = 0; i < job->seeds.size(); ++i) {
    const auto it = tasks.find(job->seeds[i]);
    if (it != tasks.end() && it->second.ended()) {
      WriteEndedWithoutResult(o.out_dir, scenario.name, it->second, i);
    }
  }
  ROVER_ASSIGN_OR_RETURN(CampaignReport report, LoadCampaignReport(o.out_dir));
  CampaignResult out;
  out.runs = std::move(report.runs);
  out.interrupted = interrupted;
  if (interrupted) {
    out.errors.push_back("stopped waiting; slurm job " + job_id +
                         " runs on: `roverctl report " + o.out_dir + "` gathers it later");
  }
  WriteCampaignFiles(o.out_dir, scenario.name, c.value("seeds", std::vector<std::uint32_t>{}),
                     ToSeconds(MonotonicNow() - start), &out);
  return out;
}

Result<int> GatherSlurmCampaign(const std::string& dir_in) {
  const std::string dir = fs::absolute(dir_in).lexically_normal().string();
  ROVER_ASSIGN_OR_RETURN(const nlohmann::json c, ReadCampaign(dir));
  if (c.value("backend", "") != "slurm") return InvalidArgument(dir + ": not a Slurm campaign");
  SlurmCampaignOptions o;
  o.out_dir = dir;
  const std::string scenario = c.value("scenario", "");
  int open = 0;
  for (const JobRecord& job : JobsOf(c)) {
    std::map<std::uint32_t, SlurmTask> tasks;
    ROVER_RETURN_IF_ERROR(QuerySlurmTasks(o, job.id, &tasks));
    for (std::size_t i = 0; i < job.seeds.size(); ++i) {
      const SlurmTask& t = tasks[job.seeds[i]];
      if (t.ended()) {
        WriteEndedWithoutResult(dir, scenario, t, i);
      } else if (!fs::exists(RunDirOf(dir, scenario, job.seeds[i]) + "/result.json")) {
        ++open;
      }
    }
  }
  if (open == 0 && !fs::exists(dir + "/summary.json")) {
    ROVER_ASSIGN_OR_RETURN(CampaignReport report, LoadCampaignReport(dir));
    CampaignResult out;
    out.runs = std::move(report.runs);
    const double wall =
        ToSeconds(WallNow() - Time{c.value("submitted_wall_ns", std::int64_t{0})});
    WriteCampaignFiles(dir, scenario, c.value("seeds", std::vector<std::uint32_t>{}), wall, &out);
  }
  return open;
}

std::string ResubmitCommand(const std::string& dir) {
  auto c = ReadCampaign(dir);
  if (!c.ok() || c->value("backend", "") != "slurm") return "";
  auto report = LoadCampaignReport(dir);
  if (!report.ok()) return "";
  std::set<std::uint32_t> todo;
  for (const auto& m : report->missing) todo.insert(m.seed);
  for (const auto& r : report->runs) {
    if (SlurmEnded(r)) todo.insert(r.seed);
  }
  if (todo.empty()) return "";
  std::string seeds;
  for (std::uint32_t s : todo) seeds += (seeds.empty() ? "" : ",") + std::to_string(s);
  return "roverctl run " + c->value("scenario_file", std::string("SCENARIO")) +
         " --backend slurm --seeds " + seeds + " --out " + dir;
}

}  // namespace rover::deploy
