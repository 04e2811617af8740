#include "rover/deploy/fault_campaign.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <sstream>
#include <thread>

#include "rover/base/clock.hpp"
#include "rover/base/range_check.hpp"
#include "rover/base/yaml_check.hpp"
#include "rover/deploy/compose.hpp"

namespace rover::deploy {
namespace fs = std::filesystem;

namespace {

constexpr const char* kBaseline = "baseline";
constexpr const char* kCampaignType = "fault_campaign";

std::string Slug(const std::string& text) {
  std::string out;
  for (char ch : text) {
    const auto c = static_cast<unsigned char>(ch);
    if (std::isalnum(c)) {
      out += static_cast<char>(std::tolower(c));
    } else if (!out.empty() && out.back() != '-') {
      out += '-';
    }
    if (out.size() >= 40) break;
  }
  while (!out.empty() && out.back() == '-') out.pop_back();
  return out.empty() ? "fault" : out;
}

const sim::judge::Criterion* FindCriterion(const RunResult& r, const std::string& name) {
  for (const auto& c : r.criteria) {
    if (c.name == name) return &c;
  }
  return nullptr;
}

bool StackEndedStep(const StepResult& s) { return s.state == "failed" || s.state == "rejected"; }

// `v` with `decimals` digits after the point.
std::string Fixed(double v, int decimals) {
  char b[64];
  std::snprintf(b, sizeof b, "%.*f", decimals, v);
  return b;
}

std::string YesNo(bool b) { return b ? "yes" : "no"; }

std::string Share(int n, int of) {
  if (of == 0) return "n/a";
  return Fixed(100.0 * n / of, 0) + "%";
}

// The campaign's fault in a fault run: the last of the set's faults (it joins the scenario's
// own faults after them, renumbered, so its id may differ from the file's).
const InjectedFault* CampaignFaultOf(const RunResult& r) {
  return r.faults.empty() ? nullptr : &r.faults.back();
}

// The fault's start on the run clock: what the services reported, else the spec's start.
// Kill faults: when the service was killed, else when it was to be.
double FaultStart(const RunResult& r, const CampaignFault& f) {
  if (f.kill) {
    for (const auto& k : r.kills) {
      if (k.service == f.kill->service && k.killed_s >= 0) return k.killed_s;
    }
    return f.kill->at_s;
  }
  const InjectedFault* x = CampaignFaultOf(r);
  return x && x->start_s >= 0 ? x->start_s : f.fault.spec.start_s;
}

std::uint64_t SamplesHit(const RunResult& r, const CampaignFault& f) {
  if (f.kill) return 0;
  const InjectedFault* x = CampaignFaultOf(r);
  return x ? x->samples_hit : 0;
}

}  // namespace

// ---- the file ----------------------------------------------------------------------------------

Result<std::vector<CampaignFault>> ParseCampaignFaults(const std::string& text,
                                                       const std::string& file) {
  const yaml::FileErrors err(file);
  ROVER_ASSIGN_OR_RETURN(YAML::Node root, yaml::Load(text, err));
  YAML::Node list = root;
  if (root.IsMap()) {
    for (const auto& kv : root) {
      if (kv.first.Scalar() != "faults") {
        return err.At(kv.first, "key '" + kv.first.Scalar() +
                                    "': not a campaign key (expected only 'faults', a list)");
      }
    }
    list = root["faults"];
    if (!list) return err.At(root, "missing 'faults' (a list of faults)");
  }
  if (!list.IsSequence()) return err.At(list, "expected a list of faults");
  if (list.size() == 0) return err.At(list, "the campaign lists no fault");
  // Kill entries are the campaign's own; the topic faults go to the seam's parser together.
  std::vector<CampaignFault> out(list.size());
  YAML::Node topic_faults(YAML::NodeType::Sequence);
  std::vector<std::size_t> topic_index;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const YAML::Node entry = list[i];
    CampaignFault& c = out[i];
    c.source = file + ":" + std::to_string(yaml::Line(entry));
    c.yaml = FlowYaml(entry);
    if (!(entry.IsMap() && entry["kill"])) {
      topic_faults.push_back(entry);
      topic_index.push_back(i);
      continue;
    }
    ROVER_RETURN_IF_ERROR(yaml::CheckKeys(entry, "kill fault", {"name", "kill"}, err));
    const YAML::Node k = entry["kill"];
    if (!k.IsMap()) return err.At(k, "key 'kill': expected a map {service, at_s}");
    ROVER_RETURN_IF_ERROR(yaml::CheckKeys(k, "kill", {"service", "at_s"}, err));
    ROVER_RETURN_IF_ERROR(yaml::RequireKey(k, "kill", "service", err));
    ROVER_RETURN_IF_ERROR(yaml::RequireKey(k, "kill", "at_s", err));
    ServiceKill kill;
    kill.service = yaml::ScalarText(k["service"]);
    if (kill.service.empty()) return err.At(k["service"], "key 'kill.service': expected a service name");
    ROVER_ASSIGN_OR_RETURN(kill.at_s, yaml::Number(k["at_s"], "kill.at_s", err));
    if (const Status s = CheckNonNegative("kill.at_s", kill.at_s, "s"); !s.ok()) {
      return err.At(k["at_s"], "key " + s.message());
    }
    const std::string name = entry["name"] ? yaml::ScalarText(entry["name"]) : "";
    c.name = name.empty() ? "kill -9 " + kill.service + " at " + Fixed(kill.at_s, 1) + " s" : name;
    c.kill = std::move(kill);
  }
  if (topic_faults.size() > 0) {
    ROVER_ASSIGN_OR_RETURN(std::vector<SetFault> faults, ParseSetFaults(topic_faults, file));
    for (std::size_t j = 0; j < faults.size(); ++j) {
      CampaignFault& c = out[topic_index[j]];
      c.name = faults[j].spec.name.empty() ? faults[j].spec.Describe() : faults[j].spec.name;
      c.fault = std::move(faults[j]);
    }
  }
  for (std::size_t i = 0; i < out.size(); ++i) {
    char index[24];
    std::snprintf(index, sizeof index, "%02zu-", i + 1);
    out[i].label = index + Slug(out[i].name);
  }
  return out;
}

Status CheckCampaignKills(const Scenario& scenario, const std::vector<CampaignFault>& faults) {
  bool any = false;
  for (const auto& f : faults) any = any || f.kill.has_value();
  if (!any) return Status::Ok();
  ROVER_ASSIGN_OR_RETURN(ComposeProject project, LoadComposeFile(scenario.compose_path));
  for (const auto& f : faults) {
    if (f.kill && project.Find(f.kill->service) == nullptr) {
      return InvalidArgument(f.source + ": key 'kill.service': no service '" + f.kill->service +
                             "' in " + scenario.compose_path);
    }
  }
  return Status::Ok();
}

Result<std::vector<CampaignFault>> LoadCampaignFaults(const std::string& path) {
  std::ifstream in(path);
  if (!in) return NotFound(path + ": cannot read the fault campaign file");
  std::stringstream ss;
  ss << in.rdbuf();
  return ParseCampaignFaults(ss.str(), path);
}

// ---- judging one run ---------------------------------------------------------------------------

Detection FirstDetection(const RunResult& r, double after_s) {
  Detection d;
  auto consider = [&](double t, std::string by) {
    if (t < after_s) return;
    if (!d.detected || t < d.t_s) d = {true, t, std::move(by)};
  };
  // A run whose clock stopped short of the start (sim/clock frozen: under strict lock-step the
  // whole run stalls) stamped its last heartbeats with its last tick, although they were taken
  // after the fault started: those count as taken at the start.
  const bool frozen_before = r.sim_time_s > 0 && r.sim_time_s < after_s;
  for (const auto& h : r.health_changes) {
    const double t = frozen_before && h.t_s >= r.sim_time_s ? after_s : h.t_s;
    if (t >= after_s && h.health != "ok" && !h.message.empty()) {
      consider(t, "sys/health " + h.service + " " + h.health + ": " + h.message);
    }
  }
  if (r.mobility && !r.mobility->fault.empty() && r.mobility->fault != "NONE") {
    consider(r.mobility->sim_end_s,
             "apl/mobility_status " + r.mobility->fault + ": " + r.mobility->message);
  }
  for (const auto& s : r.steps) {
    if (StackEndedStep(s)) {
      consider(s.sim_end_s, "dl/drive_status " + s.primitive + " " + s.state +
                                (s.termination.empty() ? "" : " (" + s.termination + ")") +
                                (s.message.empty() ? "" : ": " + s.message));
    }
  }
  return d;
}

std::string Response(const RunResult& r, double after_s) {
  if (!r.crashes.empty()) return "crashed";
  if (r.mobility && !r.mobility->fault.empty() && r.mobility->fault != "NONE" &&
      r.mobility->sim_end_s >= after_s) {
    return "stopped";
  }
  for (const auto& s : r.steps) {
    if (StackEndedStep(s) && s.sim_end_s >= after_s) return "stopped";
  }
  for (const auto& k : r.kills) {
    if (k.restarted_s >= 0) return "restarted";
  }
  return FirstDetection(r, after_s).detected ? "degraded" : "none";
}

bool IsSafe(const RunResult& r, std::string* why) {
  std::string w;
  const sim::judge::Criterion* tilt = FindCriterion(r, "max_tilt");
  if (tilt == nullptr) {
    w = "not judged: " + (r.failure.empty() ? std::string("no verdict") : r.failure);
  } else {
    if (!tilt->pass) {
      w = "tilt " + Fixed(tilt->measured, 1) + " deg over " + Fixed(tilt->limit, 1);
    }
    if (const auto* h = FindCriterion(r, "hazard_contacts"); h && h->measured > 0) {
      w += (w.empty() ? "" : "; ") + Fixed(h->measured, 0) + " hazard contacts";
    }
    if (const auto* k = FindCriterion(r, "keep_out_entries"); k && k->measured > 0) {
      w += (w.empty() ? "" : "; ") + Fixed(k->measured, 0) + " keep-out entries";
    }
  }
  if (why) *why = w;
  return w.empty();
}

bool GoalReached(const RunResult& r) {
  if (r.mobility) return r.mobility->outcome == "reached";
  if (r.steps.empty()) return false;
  for (const auto& s : r.steps) {
    if (s.state != "done") return false;
  }
  const sim::judge::Criterion* p = FindCriterion(r, "final_position_error");
  return p == nullptr || p->pass;
}

// ---- the table ---------------------------------------------------------------------------------

FaultCampaignTable MakeCampaignTable(const std::string& scenario, const std::string& faults_file,
                                     const std::vector<std::uint32_t>& seeds,
                                     const std::vector<CampaignFault>& faults,
                                     const std::map<std::string, std::vector<RunResult>>& results) {
  FaultCampaignTable t;
  t.scenario = scenario;
  t.faults_file = faults_file;
  t.seeds = seeds;
  t.faults = faults;
  auto find = [&](const std::string& label, std::uint32_t seed) -> const RunResult* {
    auto it = results.find(label);
    if (it == results.end()) return nullptr;
    for (const auto& r : it->second) {
      if (r.seed == seed) return &r;
    }
    return nullptr;
  };
  auto fill = [](CampaignRow* row, const RunResult& r, double start) {
    row->has_result = true;
    row->pass = r.pass;
    row->failure = r.failure;
    const Detection d = FirstDetection(r, start);
    row->detected = d.detected;
    row->detection_delay_s = d.detected ? d.t_s - start : -1;
    row->detected_by = d.by;
    row->response = Response(r, start);
    row->safe = IsSafe(r, &row->unsafe_why);
    row->goal = GoalReached(r);
    row->wall_time_s = r.wall_time_s;
  };
  for (std::uint32_t seed : seeds) {
    CampaignRow row;
    row.fault = kBaseline;
    row.name = "no fault";
    row.seed = seed;
    if (const RunResult* b = find(kBaseline, seed)) {
      fill(&row, *b, 0);
      // A baseline row has no fault to detect: its "detections" are its alarms from the start.
    } else {
      ++t.missing;
    }
    t.rows.push_back(std::move(row));
  }
  for (const auto& f : faults) {
    for (std::uint32_t seed : seeds) {
      CampaignRow row;
      row.fault = f.label;
      row.name = f.name;
      row.seed = seed;
      row.fault_start_s = f.start_s();
      const RunResult* r = find(f.label, seed);
      const RunResult* b = find(kBaseline, seed);
      if (r) {
        row.fault_start_s = FaultStart(*r, f);
        row.samples_hit = SamplesHit(*r, f);
        fill(&row, *r, row.fault_start_s);
      } else {
        ++t.missing;
      }
      if (b) {
        row.baseline_has_result = true;
        row.baseline_goal = GoalReached(*b);
        row.baseline_safe = IsSafe(*b);
        row.baseline_pass = b->pass;
        row.baseline_detected = FirstDetection(*b, row.fault_start_s).detected;
      }
      if (r && b) {
        row.differs = row.goal != row.baseline_goal || row.safe != row.baseline_safe ||
                      row.pass != row.baseline_pass;
      }
      if (r) {
        ++t.fault_runs;
        t.safe_runs += row.safe;
        if (row.detected || row.differs) {
          ++t.relevant;
          t.detected += row.detected;
          t.detected_within_1s += row.detected && row.detection_delay_s <= 1.0;
        }
      }
      t.rows.push_back(std::move(row));
    }
  }
  return t;
}

std::string FormatCampaignTable(const FaultCampaignTable& t) {
  std::string out = "fault campaign: " + t.scenario + " with " + t.faults_file + ", " +
                    std::to_string(t.faults.size()) + " faults x " +
                    std::to_string(t.seeds.size()) + " seeds + baseline\n";
  char line[512];
  std::snprintf(line, sizeof line, "%-34s %5s %4s %8s %7s %-9s %4s %4s %-13s %6s  %s\n", "fault",
                "seed", "det", "delay_s", "hit", "response", "safe", "goal", "base goal/saf",
                "wall_s", "first detection / why unsafe");
  out += line;
  for (const auto& r : t.rows) {
    const std::string label = r.fault.substr(0, 34);
    if (!r.has_result) {
      std::snprintf(line, sizeof line, "%-34s %5u  (no result)\n", label.c_str(), r.seed);
      out += line;
      continue;
    }
    const bool base = r.fault == kBaseline;
    const std::string delay = r.detected && !base ? Fixed(r.detection_delay_s, 2) : "-";
    const std::string bgs = base || !r.baseline_has_result
                                ? "-"
                                : YesNo(r.baseline_goal) + "/" + YesNo(r.baseline_safe) +
                                      (r.differs ? " *" : "");
    std::string note = r.detected ? r.detected_by : "";
    if (!r.safe) note = "UNSAFE " + r.unsafe_why + (note.empty() ? "" : "; " + note);
    if (note.size() > 110) note = note.substr(0, 107) + "...";
    std::snprintf(line, sizeof line, "%-34s %5u %4s %8s %7llu %-9s %4s %4s %-13s %6.1f  %s\n",
                  label.c_str(), r.seed, base ? "-" : YesNo(r.detected).c_str(), delay.c_str(),
                  static_cast<unsigned long long>(r.samples_hit),
                  base ? "-" : r.response.c_str(), YesNo(r.safe).c_str(), YesNo(r.goal).c_str(),
                  bgs.c_str(), r.wall_time_s, note.c_str());
    out += line;
  }
  out += "(* = goal, safety or pass differ from the seed's baseline; det / delay_s: first "
         "detection at or after the fault's start, docs/faults.md \"Campaigns\")\n";
  for (const auto& e : t.errors) out += "error: " + e + "\n";
  if (t.missing > 0) out += std::to_string(t.missing) + " runs have no result\n";
  if (t.interrupted) out += "interrupted: the campaign was stopped before every run finished\n";
  if (t.wall_time_s > 0) out += "wall time: " + Fixed(t.wall_time_s, 1) + " s\n";
  out += "detection: " + std::to_string(t.detected) + " of " + std::to_string(t.relevant) +
         " fault runs detected (" + Share(t.detected, t.relevant) + "; " +
         std::to_string(t.detected_within_1s) +
         " within 1 s), counting the runs that were detected or whose outcome differs from "
         "the baseline\n";
  out += "safe: " + std::to_string(t.safe_runs) + " of " + std::to_string(t.fault_runs) +
         " fault runs safe (" + Share(t.safe_runs, t.fault_runs) + ")\n";
  return out;
}

nlohmann::json ToJson(const FaultCampaignTable& t) {
  nlohmann::json j;
  j["type"] = kCampaignType;
  j["scenario"] = t.scenario;
  j["faults_file"] = t.faults_file;
  j["seeds"] = t.seeds;
  j["faults"] = nlohmann::json::array();
  for (const auto& f : t.faults) {
    j["faults"].push_back({{"label", f.label}, {"name", f.name},
                           {"description", f.kill ? f.name : f.fault.spec.Describe()},
                           {"yaml", f.yaml}, {"source", f.source}, {"start_s", f.start_s()}});
  }
  j["rows"] = nlohmann::json::array();
  for (const auto& r : t.rows) {
    j["rows"].push_back({{"fault", r.fault}, {"name", r.name}, {"seed", r.seed},
                         {"has_result", r.has_result}, {"fault_start_s", r.fault_start_s},
                         {"detected", r.detected}, {"detection_delay_s", r.detection_delay_s},
                         {"detected_by", r.detected_by}, {"response", r.response},
                         {"safe", r.safe}, {"unsafe", r.unsafe_why}, {"goal", r.goal},
                         {"pass", r.pass}, {"failure", r.failure},
                         {"samples_hit", r.samples_hit}, {"wall_time_s", r.wall_time_s},
                         {"baseline", {{"has_result", r.baseline_has_result},
                                       {"goal", r.baseline_goal}, {"safe", r.baseline_safe},
                                       {"pass", r.baseline_pass},
                                       {"detected", r.baseline_detected}}},
                         {"differs", r.differs}});
  }
  j["detection"] = {{"relevant", t.relevant}, {"detected", t.detected},
                    {"within_1s", t.detected_within_1s},
                    {"share", t.relevant ? static_cast<double>(t.detected) / t.relevant : 0.0}};
  j["safety"] = {{"fault_runs", t.fault_runs}, {"safe", t.safe_runs},
                 {"share", t.fault_runs ? static_cast<double>(t.safe_runs) / t.fault_runs : 0.0}};
  j["missing"] = t.missing;
  j["errors"] = t.errors;
  j["interrupted"] = t.interrupted;
  j["wall_time_s"] = t.wall_time_s;
  return j;
}

// ---- running it --------------------------------------------------------------------------------

bool IsFaultCampaignFolder(const std::string& dir) {
  std::ifstream in(dir + "/campaign.json");
  if (!in) return false;
  try {
    return nlohmann::json::parse(in).value("type", "") == kCampaignType;
  } catch (const nlohmann::json::exception&) {
    return false;
  }
}

Status CheckFaultCampaignFolder(const std::string& dir, const std::string& scenario) {
  if (!fs::exists(dir)) return Status::Ok();
  if (!fs::is_directory(dir)) return InvalidArgument("--out " + dir + ": exists and is not a folder");
  if (fs::is_empty(dir)) return Status::Ok();
  if (!IsFaultCampaignFolder(dir)) {
    return InvalidArgument("--out " + dir +
                           ": exists and is not a fault campaign folder; choose another folder");
  }
  std::ifstream in(dir + "/campaign.json");
  const std::string earlier = nlohmann::json::parse(in, nullptr, false).value("scenario", "");
  if (earlier != scenario) {
    return InvalidArgument("--out " + dir + ": holds a fault campaign of scenario '" + earlier +
                           "', not '" + scenario + "'; choose another folder");
  }
  return Status::Ok();
}

Result<FaultCampaignTable> RunFaultCampaign(const Scenario& scenario, const std::string& faults_file,
                                            const std::vector<CampaignFault>& faults,
                                            const FaultCampaignOptions& options) {
  ROVER_RETURN_IF_ERROR(CheckFaultCampaignFolder(options.out_dir, scenario.name));
  if (options.seeds.empty()) return InvalidArgument("no seeds to run");
  if (options.jobs < 1 || options.jobs > 16) return InvalidArgument("--jobs must be in [1, 16]");
  // Each fault joins the scenario's own faults: check every one before anything starts.
  ROVER_RETURN_IF_ERROR(CheckCampaignKills(scenario, faults));
  struct Variant {
    std::string label;
    Scenario scenario;
    std::vector<ServiceKill> kills;
  };
  struct Job {
    const Variant* variant = nullptr;
    std::uint32_t seed = 0;
  };
  std::vector<Variant> variants = {{kBaseline, scenario, {}}};
  for (const auto& f : faults) {
    Variant v{f.label, scenario, {}};
    if (f.kill) {
      v.kills.push_back(*f.kill);
    } else {
      ROVER_RETURN_IF_ERROR(AppendSetFaults({f.fault}, &v.scenario.faults));
    }
    variants.push_back(std::move(v));
  }
  std::vector<Job> jobs;
  for (std::uint32_t seed : options.seeds) {
    for (const auto& v : variants) jobs.push_back({&v, seed});
  }
  std::error_code ec;
  fs::create_directories(options.out_dir, ec);
  if (ec) return Unavailable("cannot create " + options.out_dir + ": " + ec.message());
  FaultCampaignTable table0 = MakeCampaignTable(scenario.name, faults_file, options.seeds, faults, {});
  std::ofstream(options.out_dir + "/campaign.json") << ToJson(table0).dump(2) << "\n";

  const Time start = MonotonicNow();
  std::mutex mu;
  std::size_t next = 0;
  std::map<std::string, std::vector<RunResult>> results;
  std::vector<std::string> errors;
  auto worker = [&] {
    while (true) {
      const Job* job = nullptr;
      {
        std::lock_guard lock(mu);
        if (next >= jobs.size() || (options.abort && options.abort->load())) return;
        job = &jobs[next++];
      }
      const std::string& label = job->variant->label;
      RunOptions ro;
      ro.out_dir = options.out_dir + "/" + label;
      ro.kills = job->variant->kills;
      ro.bin_dir = options.bin_dir;
      ro.dds_config_uri = options.dds_config_uri;
      ro.security = options.security;
      ro.security_dir = options.security_dir;
      ro.abort = options.abort;
      const Scenario& sc = job->variant->scenario;
      auto r = options.run_one ? options.run_one(sc, job->seed, ro)
                               : RunScenario(sc, job->seed, ro);
      std::lock_guard lock(mu);
      if (!r.ok()) {
        errors.push_back(label + " seed " + std::to_string(job->seed) + ": " +
                         r.status().message());
        std::printf("%s seed %u: ERROR %s\n", label.c_str(), job->seed,
                    r.status().message().c_str());
      } else {
        std::printf("%s seed %u: %s  %.1f sim s  %.1f wall s%s%s\n", label.c_str(), job->seed,
                    r->pass ? "PASS" : "FAIL", r->sim_time_s, r->wall_time_s,
                    r->failure.empty() ? "" : "  ", r->failure.c_str());
        results[label].push_back(std::move(*r));
      }
      std::fflush(stdout);
    }
  };
  std::vector<std::thread> threads;
  for (int j = 0; j < options.jobs; ++j) threads.emplace_back(worker);
  for (auto& t : threads) t.join();

  FaultCampaignTable table = MakeCampaignTable(scenario.name, faults_file, options.seeds, faults, results);
  table.errors = std::move(errors);
  table.interrupted = options.abort && options.abort->load();
  table.wall_time_s = ToSeconds(MonotonicNow() - start);
  const std::string text = FormatCampaignTable(table);
  std::ofstream(options.out_dir + "/campaign.json") << ToJson(table).dump(2) << "\n";
  std::ofstream(options.out_dir + "/campaign.txt") << text;
  std::ofstream(options.out_dir + "/summary.txt") << text;
  return table;
}

Result<FaultCampaignTable> LoadFaultCampaignReport(const std::string& dir) {
  std::ifstream in(dir + "/campaign.json");
  if (!in) return NotFound(dir + "/campaign.json: cannot read");
  nlohmann::json c;
  try {
    c = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    return InvalidArgument(dir + "/campaign.json: " + e.what());
  }
  if (c.value("type", "") != kCampaignType) {
    return InvalidArgument(dir + "/campaign.json: not a fault campaign");
  }
  try {
    const std::string file = c.value("faults_file", "");
    std::vector<CampaignFault> faults;
    std::string text;
    for (const auto& f : c.at("faults")) text += "- " + f.at("yaml").get<std::string>() + "\n";
    ROVER_ASSIGN_OR_RETURN(faults, ParseCampaignFaults(text, dir + "/campaign.json"));
    for (std::size_t i = 0; i < faults.size() && i < c["faults"].size(); ++i) {
      faults[i].label = c["faults"][i].at("label");
      faults[i].name = c["faults"][i].value("name", faults[i].name);
    }
    std::map<std::string, std::vector<RunResult>> results;
    std::vector<std::string> labels = {kBaseline};
    for (const auto& f : faults) labels.push_back(f.label);
    for (const auto& label : labels) {
      if (!fs::is_directory(dir + "/" + label)) continue;
      ROVER_ASSIGN_OR_RETURN(results[label], LoadRunResults(dir + "/" + label));
    }
    FaultCampaignTable t = MakeCampaignTable(c.value("scenario", ""), file,
                                             c.at("seeds").get<std::vector<std::uint32_t>>(),
                                             faults, results);
    t.wall_time_s = c.value("wall_time_s", 0.0);
    t.errors = c.value("errors", std::vector<std::string>{});
    t.interrupted = c.value("interrupted", false);
    return t;
  } catch (const nlohmann::json::exception& e) {
    return InvalidArgument(dir + "/campaign.json: " + e.what());
  }
}

}  // namespace rover::deploy
