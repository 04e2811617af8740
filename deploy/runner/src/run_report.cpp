#include "rover/deploy/run_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <signal.h>

namespace rover::deploy {
namespace fs = std::filesystem;

namespace {
std::string XmlEscape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default:
        // XML 1.0 forbids most control characters.
        if (static_cast<unsigned char>(c) >= 0x20 || c == '\n' || c == '\t') out += c;
    }
  }
  return out;
}

FigureStats Stats(const std::string& name, const std::string& unit, std::vector<double> v) {
  FigureStats f;
  f.name = name;
  f.unit = unit;
  f.count = static_cast<int>(v.size());
  if (v.empty()) return f;
  std::sort(v.begin(), v.end());
  double sum = 0;
  for (double x : v) sum += x;
  f.mean = sum / v.size();
  // Nearest-rank 95th percentile.
  const std::size_t rank = static_cast<std::size_t>(std::ceil(0.95 * v.size()));
  f.p95 = v[std::max<std::size_t>(1, rank) - 1];
  f.worst = v.back();
  return f;
}
nlohmann::json MobilityToJson(const MobilityOutcome& m) {
  nlohmann::json arcs = nlohmann::json::array();
  for (const auto& a : m.arcs) {
    arcs.push_back({a.x, a.y, a.yaw, a.point_turn ? 1 : 0, a.curvature, a.direction, a.turn_angle});
  }
  return {{"task", m.task},
          {"mode", m.mode},
          {"expect", m.expect},
          {"outcome", m.outcome},
          {"state", m.state},
          {"fault", m.fault},
          {"fault_class", m.fault_class},
          {"message", m.message},
          {"distance_to_goal_m", m.distance_to_goal},
          {"steps", m.steps},
          {"images", m.images},
          {"sim_start_s", m.sim_start_s},
          {"sim_end_s", m.sim_end_s},
          {"arcs", arcs},
          {"arcs_columns", {"x_m", "y_m", "yaw_rad", "point_turn", "curvature", "direction",
                            "turn_angle_rad"}}};
}

MobilityOutcome MobilityFromJson(const nlohmann::json& j) {
  MobilityOutcome m;
  m.task = j.value("task", "");
  m.mode = j.value("mode", "");
  m.expect = j.value("expect", "");
  m.outcome = j.value("outcome", "");
  m.state = j.value("state", "");
  m.fault = j.value("fault", "");
  m.fault_class = j.value("fault_class", "");
  m.message = j.value("message", "");
  m.distance_to_goal = j.value("distance_to_goal_m", -1.0);
  m.steps = j.value("steps", 0u);
  m.images = j.value("images", 0u);
  m.sim_start_s = j.value("sim_start_s", 0.0);
  m.sim_end_s = j.value("sim_end_s", 0.0);
  for (const auto& a : j.value("arcs", nlohmann::json::array())) {
    m.arcs.push_back({a.at(0), a.at(1), a.at(2), a.at(3).get<int>() != 0, a.at(4), a.at(5),
                      a.at(6)});
  }
  return m;
}

// "reached" or "NOPATH (goal error)", and "!= KEEPOUT" when it is not what was expected.
std::string OutcomeText(const MobilityOutcome& m) {
  std::string out = m.outcome;
  if (m.fault_class != "none" && !m.fault_class.empty()) out += " (" + m.fault_class + ")";
  if (m.outcome != m.expect) out += ", expected " + m.expect;
  return out;
}
}  // namespace

bool GoodnessGrid::Known(int i, int j) const {
  if (i < 0 || j < 0 || i >= width || j >= height) return false;
  const std::size_t k = static_cast<std::size_t>(j) * static_cast<std::size_t>(width) +
                        static_cast<std::size_t>(i);
  return k < flags.size() && (flags[k] & 1) != 0;
}

int GoodnessGrid::CellAt(double x, double y) const {
  if (!(resolution > 0)) return -1;
  const double fi = std::floor((x - origin_x) / resolution);
  const double fj = std::floor((y - origin_y) / resolution);
  if (!(fi >= 0 && fj >= 0 && fi < width && fj < height)) return -1;
  return static_cast<int>(fj) * width + static_cast<int>(fi);
}

nlohmann::json ToJson(const RunResult& r) {
  nlohmann::json j;
  j["scenario"] = r.scenario;
  j["seed"] = r.seed;
  j["domain"] = r.domain;
  j["pass"] = r.pass;
  j["failure"] = r.failure;
  j["criteria"] = nlohmann::json::array();
  for (const auto& c : r.criteria) {
    j["criteria"].push_back({{"name", c.name}, {"measured", c.measured}, {"limit", c.limit},
                             {"unit", c.unit}, {"pass", c.pass}, {"detail", c.detail}});
  }
  j["steps"] = nlohmann::json::array();
  for (const auto& s : r.steps) {
    j["steps"].push_back({{"primitive", s.primitive}, {"command_id", s.command_id},
                          {"state", s.state}, {"termination", s.termination},
                          {"message", s.message}, {"sim_start_s", s.sim_start_s},
                          {"sim_end_s", s.sim_end_s}});
  }
  j["distance_driven_m"] = r.distance_driven;
  j["timings"] = {
      {"sim_time_s", r.sim_time_s},
      {"wall_time_s", r.wall_time_s},
      {"startup_s", r.startup_s},
      {"ready_s", r.ready_s},
      {"teardown_s", r.teardown_s},
      {"sim_seconds_per_wall_second", r.wall_time_s > 0 ? r.sim_time_s / r.wall_time_s : 0.0},
      {"recording_mb", r.recording_mb},
      {"lockstep", r.lockstep},
      {"late_samples", r.late_samples}};
  j["timings"]["services"] = nlohmann::json::array();
  for (const auto& st : r.service_timing) {
    nlohmann::json a = nlohmann::json::object();
    for (const auto& act : st.activities) {
      a[act.name] = {{"wall_s", act.wall_s}, {"count", act.count}};
    }
    j["timings"]["services"].push_back(
        {{"service", st.service}, {"cpu_s", st.cpu_s}, {"activities", a}});
  }
  j["estimate_error"] = nlohmann::json::array();
  for (const auto& e : r.estimate_error) {
    j["estimate_error"].push_back({e.t.seconds(), e.position_error, e.heading_error});
  }
  j["estimate_error_columns"] = {"t_s", "position_error_m", "heading_error_rad"};
  j["odometry_only_error"] = nlohmann::json::array();
  for (const auto& e : r.odometry_only_error) {
    j["odometry_only_error"].push_back({e.t.seconds(), e.position_error, e.heading_error});
  }
  j["figures"] = nlohmann::json::array();
  for (const auto& f : r.figures) {
    j["figures"].push_back(
        {{"name", f.name}, {"measured", f.measured}, {"unit", f.unit}, {"detail", f.detail}});
  }
  j["crashes"] = r.crashes;
  j["run_dir"] = r.run_dir;
  j["truth_publishers"] = r.truth_publishers;
  j["terrain_digest"] = r.terrain_digest;
  j["truth_track"] = r.truth_track;
  j["truth_yaw"] = r.truth_yaw;
  if (!r.phases.empty()) {
    j["phases"] = nlohmann::json::array();
    for (const auto& [t, name] : r.phases) j["phases"].push_back({{"t", t}, {"phase", name}});
  }
  j["estimate_track"] = r.estimate_track;
  j["odometry_only_track"] = r.odometry_only_track;
  j["hazard_contacts"] = nlohmann::json::array();
  for (const auto& c : r.hazard_contacts) {
    j["hazard_contacts"].push_back({{"rock", c.rock_id}, {"x", c.xy.x()}, {"y", c.xy.y()},
                                    {"height", c.height}, {"part", c.part}, {"t_s", c.t_s}});
  }
  if (r.mobility) j["mobility"] = MobilityToJson(*r.mobility);
  j["faults"] = nlohmann::json::array();
  for (const auto& f : r.faults) {
    j["faults"].push_back({{"id", f.id}, {"name", f.name}, {"kind", f.kind}, {"topic", f.topic},
                           {"service", f.service}, {"side", f.side},
                           {"description", f.description}, {"start_s", f.start_s},
                           {"end_s", f.end_s}, {"samples_seen", f.samples_seen},
                           {"samples_hit", f.samples_hit}, {"services", f.services}});
  }
  j["health_changes"] = nlohmann::json::array();
  for (const auto& h : r.health_changes) {
    j["health_changes"].push_back({{"t_s", h.t_s}, {"service", h.service}, {"health", h.health},
                                   {"message", h.message}});
  }
  j["health_changes_dropped"] = r.health_changes_dropped;
  j["kills"] = nlohmann::json::array();
  for (const auto& k : r.kills) {
    j["kills"].push_back({{"service", k.service}, {"at_s", k.at_s}, {"killed_s", k.killed_s},
                          {"restarted_s", k.restarted_s}, {"error", k.error}});
  }
  return j;
}

namespace {

// A number written by nlohmann::json: NaN and infinities are written as null.
double NumberOrNaN(const nlohmann::json& v) {
  return v.is_null() ? std::numeric_limits<double>::quiet_NaN() : v.get<double>();
}

}  // namespace

Result<RunResult> RunResultFromJson(const nlohmann::json& j) {
  try {
    RunResult r;
    r.scenario = j.at("scenario");
    r.seed = j.at("seed");
    r.domain = j.value("domain", -1);
    r.pass = j.at("pass");
    r.failure = j.value("failure", "");
    for (const auto& c : j.at("criteria")) {
      r.criteria.push_back({c.at("name"), NumberOrNaN(c.at("measured")),
                            NumberOrNaN(c.at("limit")), c.at("unit"), c.at("pass"),
                            c.value("detail", "")});
    }
    for (const auto& s : j.value("steps", nlohmann::json::array())) {
      r.steps.push_back({s.at("primitive"), s.at("command_id"), s.at("state"),
                         s.value("termination", ""), s.value("message", ""),
                         s.value("sim_start_s", 0.0), s.value("sim_end_s", 0.0)});
    }
    r.distance_driven = j.value("distance_driven_m", 0.0);
    const auto& t = j.at("timings");
    r.sim_time_s = t.value("sim_time_s", 0.0);
    r.wall_time_s = t.value("wall_time_s", 0.0);
    r.startup_s = t.value("startup_s", 0.0);
    r.ready_s = t.value("ready_s", 0.0);
    r.teardown_s = t.value("teardown_s", 0.0);
    r.recording_mb = t.value("recording_mb", 0.0);
    r.lockstep = t.value("lockstep", std::string());
    r.late_samples = t.value("late_samples", std::uint64_t{0});
    for (const auto& st : t.value("services", nlohmann::json::array())) {
      ServiceTiming timing;
      timing.service = st.value("service", std::string());
      timing.cpu_s = st.value("cpu_s", 0.0);
      const nlohmann::json activities = st.value("activities", nlohmann::json::object());
      for (const auto& [name, a] : activities.items()) {
        timing.activities.push_back({name, a.value("wall_s", 0.0), a.value("count", 0u)});
      }
      r.service_timing.push_back(std::move(timing));
    }
    for (const auto& e : j.value("estimate_error", nlohmann::json::array())) {
      r.estimate_error.push_back({Time::FromSeconds(e.at(0)), e.at(1), e.at(2)});
    }
    for (const auto& e : j.value("odometry_only_error", nlohmann::json::array())) {
      r.odometry_only_error.push_back({Time::FromSeconds(e.at(0)), e.at(1), e.at(2)});
    }
    for (const auto& f : j.value("figures", nlohmann::json::array())) {
      r.figures.push_back({f.at("name"), NumberOrNaN(f.at("measured")),
                           std::numeric_limits<double>::quiet_NaN(), f.at("unit"), true,
                           f.value("detail", "")});
    }
    r.crashes = j.value("crashes", std::vector<std::string>{});
    r.run_dir = j.value("run_dir", "");
    r.truth_publishers = j.value("truth_publishers", 0);
    r.terrain_digest = j.value("terrain_digest", "");
    r.truth_track = j.value("truth_track", std::vector<std::array<double, 3>>{});
    r.truth_yaw = j.value("truth_yaw", std::vector<double>{});
    if (j.contains("phases")) {
      for (const auto& p : j["phases"]) {
        r.phases.emplace_back(p.value("t", 0.0), p.value("phase", std::string()));
      }
    }
    for (const auto& c : j.value("hazard_contacts", nlohmann::json::array())) {
      r.hazard_contacts.push_back({c.at("rock"), Eigen::Vector2d(c.at("x"), c.at("y")),
                                   c.at("height"), c.at("part"), c.value("t_s", 0.0)});
    }
    r.estimate_track = j.value("estimate_track", std::vector<std::array<double, 3>>{});
    r.odometry_only_track =
        j.value("odometry_only_track", std::vector<std::array<double, 3>>{});
    if (j.contains("mobility")) r.mobility = MobilityFromJson(j.at("mobility"));
    for (const auto& f : j.value("faults", nlohmann::json::array())) {
      InjectedFault x;
      x.id = f.at("id");
      x.name = f.value("name", "");
      x.kind = f.at("kind");
      x.topic = f.at("topic");
      x.service = f.value("service", "*");
      x.side = f.value("side", "");
      x.description = f.value("description", "");
      x.start_s = f.value("start_s", -1.0);
      x.end_s = f.value("end_s", -1.0);
      x.samples_seen = f.value("samples_seen", std::uint64_t{0});
      x.samples_hit = f.value("samples_hit", std::uint64_t{0});
      x.services = f.value("services", std::vector<std::string>{});
      r.faults.push_back(std::move(x));
    }
    for (const auto& h : j.value("health_changes", nlohmann::json::array())) {
      r.health_changes.push_back(
          {h.at("t_s"), h.at("service"), h.at("health"), h.value("message", "")});
    }
    r.health_changes_dropped = j.value("health_changes_dropped", std::uint64_t{0});
    for (const auto& k : j.value("kills", nlohmann::json::array())) {
      r.kills.push_back({k.at("service"), k.at("at_s"), k.value("killed_s", -1.0),
                         k.value("restarted_s", -1.0), k.value("error", "")});
    }
    return r;
  } catch (const nlohmann::json::exception& e) {
    return InvalidArgument(std::string("result.json: ") + e.what());
  }
}

bool Interrupted(const RunResult& r) { return r.failure.rfind("interrupted", 0) == 0; }

CampaignSummary Summarize(const std::vector<RunResult>& runs, double campaign_wall_s) {
  CampaignSummary s;
  s.runs = static_cast<int>(runs.size());
  if (!runs.empty()) s.scenario = runs.front().scenario;
  std::map<std::string, std::pair<std::string, std::vector<double>>> by_name;
  std::vector<std::string> order;
  // Criteria: name -> (limit, passing); a name here is not listed again among the figures.
  std::map<std::string, std::pair<double, int>> criteria;
  std::vector<double> wall, startup, ready, teardown, distance, sim_time;
  double sim_total = 0;
  for (const auto& r : runs) {
    if (Interrupted(r)) {  // cut off: its wall and simulated time count for throughput only
      ++s.interrupted;
      sim_total += r.sim_time_s;
      continue;
    }
    if (r.pass) ++s.passed;
    for (const auto& f : r.figures) {
      if (f.name == "passable" && f.measured >= 1.0) {
        ++s.passable;
        if (r.pass) ++s.passed_passable;
      }
    }
    for (const auto& c : r.criteria) {
      auto [it, fresh] = criteria.emplace(c.name, std::make_pair(c.limit, 0));
      if (!fresh && !(it->second.first == c.limit)) {
        it->second.first = std::numeric_limits<double>::quiet_NaN();
      }
      if (c.pass) ++it->second.second;
    }
    for (const auto* list : {&r.criteria, &r.figures}) {
      for (const auto& c : *list) {
        if (list == &r.figures && criteria.count(c.name)) continue;
        if (!by_name.count(c.name)) order.push_back(c.name);
        auto& e = by_name[c.name];
        e.first = c.unit;
        e.second.push_back(c.measured);
      }
    }
    wall.push_back(r.wall_time_s);
    startup.push_back(r.startup_s);
    if (r.ready_s > 0) ready.push_back(r.ready_s);
    teardown.push_back(r.teardown_s);
    distance.push_back(r.distance_driven);
    sim_time.push_back(r.sim_time_s);
    sim_total += r.sim_time_s;
  }
  const int judged = s.runs - s.interrupted;
  s.pass_rate = judged > 0 ? static_cast<double>(s.passed) / judged : 0.0;
  for (const bool criterion : {true, false}) {
    for (const auto& n : order) {
      auto it = criteria.find(n);
      if ((it != criteria.end()) != criterion) continue;
      FigureStats f = Stats(n, by_name[n].first, by_name[n].second);
      if (criterion) {
        f.criterion = true;
        f.limit = it->second.first;
        f.passing = it->second.second;
      }
      s.figures.push_back(std::move(f));
    }
  }
  if (!by_name.count("distance_driven")) s.figures.push_back(Stats("distance_driven", "m", distance));
  s.figures.push_back(Stats("sim_time", "s", sim_time));
  s.figures.push_back(Stats("wall_time", "s", wall));
  s.figures.push_back(Stats("startup", "s", startup));
  if (!ready.empty()) s.figures.push_back(Stats("ready", "s", ready));
  s.figures.push_back(Stats("teardown", "s", teardown));
  // Where the time went: per service CPU, per activity wall, mean over the runs.
  std::map<std::string, double> cpu, activity;
  std::vector<std::string> cpu_order, activity_order;
  double mb = 0;
  for (const auto& r : runs) {
    mb += r.recording_mb;
    for (const auto& st : r.service_timing) {
      if (!cpu.count(st.service)) cpu_order.push_back(st.service);
      cpu[st.service] += st.cpu_s;
      for (const auto& a : st.activities) {
        if (a.wall_s <= 0.0) continue;  // counts only (ticks_served, late_samples)
        const std::string key = a.name + " (" + st.service + ")";
        if (!activity.count(key)) activity_order.push_back(key);
        activity[key] += a.wall_s;
      }
    }
  }
  if (!runs.empty()) {
    const double n = static_cast<double>(runs.size());
    double wall_mean = 0;
    for (double w : wall) wall_mean += w / n;
    auto add = [&](const std::string& name, double total) {
      const double mean = total / n;
      s.time_shares.push_back({name, mean, wall_mean > 0 ? mean / wall_mean : 0.0});
    };
    for (const auto& name : cpu_order) add(name + " cpu", cpu[name]);
    for (const auto& name : activity_order) add(name, activity[name]);
    s.recording_mb_mean = mb / n;
  }
  s.wall_time_s = campaign_wall_s;
  s.sim_seconds_per_wall_second = campaign_wall_s > 0 ? sim_total / campaign_wall_s : 0;
  s.runs_per_hour = campaign_wall_s > 0 ? 3600.0 * s.runs / campaign_wall_s : 0;
  return s;
}

nlohmann::json ToJson(const CampaignSummary& s) {
  nlohmann::json j;
  j["scenario"] = s.scenario;
  j["runs"] = s.runs;
  j["passed"] = s.passed;
  j["interrupted_runs"] = s.interrupted;
  j["pass_rate"] = s.pass_rate;
  j["passable"] = s.passable;
  j["passed_passable"] = s.passed_passable;
  j["wall_time_s"] = s.wall_time_s;
  j["sim_seconds_per_wall_second"] = s.sim_seconds_per_wall_second;
  j["runs_per_hour"] = s.runs_per_hour;
  j["recording_mb_mean"] = s.recording_mb_mean;
  j["time"] = nlohmann::json::array();
  for (const auto& t : s.time_shares) {
    j["time"].push_back({{"name", t.name}, {"mean_s", t.mean_s}, {"share_of_wall", t.share}});
  }
  j["figures"] = nlohmann::json::array();
  for (const auto& f : s.figures) {
    nlohmann::json e = {{"name", f.name}, {"unit", f.unit}, {"mean", f.mean}, {"p95", f.p95},
                        {"worst", f.worst}, {"count", f.count}};
    if (f.criterion) {
      e["criterion"] = true;
      e["limit"] = f.limit;
      e["passing"] = f.passing;
    }
    j["figures"].push_back(std::move(e));
  }
  return j;
}

std::string ToJunitXml(const std::vector<RunResult>& runs, const std::string& suite_name) {
  int failures = 0;
  double total = 0;
  for (const auto& r : runs) {
    if (!r.pass) ++failures;
    total += r.wall_time_s;
  }
  std::ostringstream x;
  x << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  char head[256];
  std::snprintf(head, sizeof head, "<testsuites tests=\"%zu\" failures=\"%d\" time=\"%.3f\">\n",
                runs.size(), failures, total);
  x << head;
  std::snprintf(head, sizeof head, "  <testsuite name=\"%s\" tests=\"%zu\" failures=\"%d\" time=\"%.3f\">\n",
                XmlEscape(suite_name).c_str(), runs.size(), failures, total);
  x << head;
  for (const auto& r : runs) {
    char tc[512];
    std::snprintf(tc, sizeof tc, "    <testcase classname=\"%s\" name=\"seed-%u\" time=\"%.3f\"",
                  XmlEscape(r.scenario).c_str(), r.seed, r.wall_time_s);
    x << tc;
    if (r.pass) {
      x << "/>\n";
      continue;
    }
    x << ">\n      <failure message=\"" << XmlEscape(r.failure) << "\">";
    for (const auto& c : r.criteria) {
      if (!c.pass) {
        char line[256];
        std::snprintf(line, sizeof line, "%s: %.4g %s (limit %.4g) %s\n", c.name.c_str(),
                      c.measured, c.unit.c_str(), c.limit, c.detail.c_str());
        x << XmlEscape(line);
      }
    }
    for (const auto& c : r.crashes) x << XmlEscape("crash: " + c + "\n");
    x << "</failure>\n";
    x << "      <system-out>" << XmlEscape("run folder: " + r.run_dir) << "</system-out>\n";
    x << "    </testcase>\n";
  }
  x << "  </testsuite>\n</testsuites>\n";
  return x.str();
}

std::vector<MissingRun> MissingRuns(const std::string& dir, const std::string& scenario,
                                    const std::vector<std::uint32_t>& seeds,
                                    const std::vector<RunResult>& runs) {
  std::vector<MissingRun> out;
  for (std::uint32_t seed : seeds) {
    const bool have = std::any_of(runs.begin(), runs.end(),
                                  [seed](const RunResult& r) { return r.seed == seed; });
    if (have) continue;
    out.push_back(
        {seed, fs::exists(fs::path(dir) / (scenario + "-seed" + std::to_string(seed)))});
  }
  return out;
}

std::string DescribeInjected(const InjectedFault& f) {
  char when[96];
  if (f.start_s < 0) {
    std::snprintf(when, sizeof when, "never started");
  } else if (f.end_s < 0) {
    std::snprintf(when, sizeof when, "%.1f s to the end", f.start_s);
  } else {
    std::snprintf(when, sizeof when, "%.1f s to %.1f s", f.start_s, f.end_s);
  }
  std::string where;
  for (const auto& s : f.services) where += (where.empty() ? "" : ", ") + s;
  return "fault " + std::to_string(f.id) + (f.name.empty() ? "" : " '" + f.name + "'") + " " +
         f.kind + " " + f.topic + " (" + f.side + " of " + f.service + "): " + when + ", " +
         std::to_string(f.samples_hit) + " of " + std::to_string(f.samples_seen) +
         " samples hit" + (where.empty() ? "" : " in " + where);
}

std::string FormatSummaryTable(const std::vector<RunResult>& runs, const CampaignSummary& s,
                               const std::vector<MissingRun>& missing,
                               const std::vector<std::string>& ignored) {
  std::ostringstream o;
  char buf[512];
  std::snprintf(buf, sizeof buf, "%-8s %-6s %9s %9s %9s  %s\n", "seed", "result", "dist m",
                "sim s", "wall s", "failure");
  o << buf;
  std::map<std::string, int> outcomes;  // mobility tasks: "NOPATH (goal error)" -> runs
  for (const auto& r : runs) {
    const char* result = r.pass ? "PASS" : Interrupted(r) ? "INTR" : "FAIL";
    std::snprintf(buf, sizeof buf, "%-8u %-6s %9.2f %9.1f %9.1f  %s\n", r.seed, result,
                  r.distance_driven, r.sim_time_s, r.wall_time_s, r.failure.c_str());
    o << buf;
    if (r.mobility) {
      const std::string text = OutcomeText(*r.mobility);
      ++outcomes[r.mobility->outcome +
                 (r.mobility->fault_class == "none" || r.mobility->fault_class.empty()
                      ? ""
                      : " (" + r.mobility->fault_class + ")")];
      o << "         " << r.mobility->task << ": " << text << "\n";
    }
    for (const auto& f : r.faults) o << "         " << DescribeInjected(f) << "\n";
  }
  std::snprintf(buf, sizeof buf, "\n%s: %d/%d passed (%.0f%%)", s.scenario.c_str(), s.passed,
                s.runs - s.interrupted, 100.0 * s.pass_rate);
  o << buf;
  if (s.passable > 0) {
    std::snprintf(buf, sizeof buf, "; on passable fields %d/%d", s.passed_passable, s.passable);
    o << buf;
  }
  if (s.interrupted > 0) {
    o << "; " << s.interrupted << " run" << (s.interrupted == 1 ? "" : "s")
      << " interrupted (not in the rate or the figures)";
  }
  if (!missing.empty()) {
    o << "; " << missing.size() << " of " << runs.size() + missing.size()
      << " seeds have no result:\n";
    for (const auto& m : missing) {
      o << "  seed " << m.seed << ": "
        << (m.started ? "incomplete (started, no result.json)" : "not run") << "\n";
    }
  } else {
    o << "\n";
  }
  for (const auto& i : ignored) o << "ignored: " << i << "\n";
  if (!outcomes.empty()) {
    o << "outcomes:";
    for (const auto& [name, n] : outcomes) o << " " << name << " x" << n << ";";
    o << "\n";
  }
  o << "\n";
  // Criteria (each with its limit and the runs it held in), then what was measured.
  bool any_criterion = false;
  for (const auto& f : s.figures) {
    if (!f.criterion) continue;
    if (!any_criterion) {
      std::snprintf(buf, sizeof buf, "%-36s %-6s %11s %8s %11s %11s %11s\n", "criterion", "unit",
                    "limit", "held", "mean", "p95", "worst");
      o << buf;
      any_criterion = true;
    }
    const std::string held = std::to_string(f.passing) + "/" + std::to_string(s.runs);
    std::snprintf(buf, sizeof buf, "%-36s %-6s %11.4g %8s %11.4g %11.4g %11.4g\n", f.name.c_str(),
                  f.unit.c_str(), f.limit, held.c_str(), f.mean, f.p95, f.worst);
    o << buf;
  }
  if (any_criterion) o << "\n";
  std::snprintf(buf, sizeof buf, "%-36s %-6s %11s %11s %11s\n", "figure", "unit", "mean", "p95",
                "worst");
  o << buf;
  for (const auto& f : s.figures) {
    if (f.criterion) continue;
    std::snprintf(buf, sizeof buf, "%-36s %-6s %11.4g %11.4g %11.4g\n", f.name.c_str(),
                  f.unit.c_str(), f.mean, f.p95, f.worst);
    o << buf;
  }
  if (!s.time_shares.empty()) {
    o << "\nwhere the time went (mean per run; share of a run's wall time):\n";
    for (const auto& t : s.time_shares) {
      std::snprintf(buf, sizeof buf, "  %-40s %9.1f s %6.1f %%\n", t.name.c_str(), t.mean_s,
                    100.0 * t.share);
      o << buf;
    }
  }
  std::snprintf(buf, sizeof buf,
                "\ncampaign: %.1f s wall, %.2f simulated s per wall s, %.0f runs/hour, "
                "%.1f MB recorded per run\n",
                s.wall_time_s, s.sim_seconds_per_wall_second, s.runs_per_hour, s.recording_mb_mean);
  o << buf;
  return o.str();
}

bool IsRunFolder(const std::string& dir) { return fs::exists(fs::path(dir) / "campaign.json"); }

Result<std::vector<RunResult>> LoadRunFolder(const std::string& dir) {
  if (!fs::is_directory(dir)) return NotFound(dir + ": no such folder");
  if (!IsRunFolder(dir)) {
    return InvalidArgument(dir + ": not a run folder (no campaign.json; made by `roverctl run`)");
  }
  return LoadRunResults(dir);
}

Result<std::vector<RunResult>> LoadRunResults(const std::string& dir) {
  if (!fs::is_directory(dir)) return NotFound(dir + ": no such folder");
  std::vector<RunResult> out;
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(dir)) {
    if (e.is_directory() && fs::exists(e.path() / "result.json")) files.push_back(e.path() / "result.json");
  }
  std::sort(files.begin(), files.end());
  for (const auto& f : files) {
    std::ifstream in(f);
    nlohmann::json j;
    try {
      j = nlohmann::json::parse(in);
    } catch (const nlohmann::json::exception& e) {
      return InvalidArgument(f.string() + ": " + e.what());
    }
    auto r = RunResultFromJson(j);
    if (!r.ok()) return r.status().WithPrefix(f.string());
    out.push_back(std::move(*r));
  }
  std::sort(out.begin(), out.end(), [](const RunResult& a, const RunResult& b) { return a.seed < b.seed; });
  return out;
}

Result<CampaignReport> LoadCampaignReport(const std::string& dir) {
  CampaignReport report;
  ROVER_ASSIGN_OR_RETURN(std::vector<RunResult> all, LoadRunFolder(dir));
  std::string scenario;
  std::optional<std::vector<std::uint32_t>> seeds;
  int pid = 0;
  {
    std::ifstream cj(dir + "/campaign.json");
    try {
      const nlohmann::json c = nlohmann::json::parse(cj);
      scenario = c.value("scenario", "");
      pid = c.value("pid", 0);
      if (c.contains("seeds")) seeds = c["seeds"].get<std::vector<std::uint32_t>>();
    } catch (const nlohmann::json::exception& e) {
      return InvalidArgument(dir + "/campaign.json: " + e.what());
    }
  }
  for (auto& r : all) {
    const std::string folder = fs::path(r.run_dir).filename().string();
    const std::string name = folder.empty() ? r.scenario + "-seed" + std::to_string(r.seed) : folder;
    if (!scenario.empty() && r.scenario != scenario) {
      report.ignored.push_back(name + " (scenario '" + r.scenario + "', not '" + scenario + "')");
    } else if (seeds && std::find(seeds->begin(), seeds->end(), r.seed) == seeds->end()) {
      report.ignored.push_back(name + " (seed " + std::to_string(r.seed) +
                               " is not one of the last campaign's seeds)");
    } else {
      report.runs.push_back(std::move(r));
    }
  }
  double wall = 0;
  std::ifstream in(dir + "/summary.json");
  report.running = !in && pid > 0 && kill(pid, 0) == 0;
  if (in) {
    try {
      wall = nlohmann::json::parse(in).value("wall_time_s", 0.0);
    } catch (const nlohmann::json::exception&) {
    }
  }
  report.summary = Summarize(report.runs, wall);
  if (!scenario.empty()) report.summary.scenario = scenario;
  if (seeds) report.missing = MissingRuns(dir, report.summary.scenario, *seeds, report.runs);
  report.table =
      FormatSummaryTable(report.runs, report.summary, report.missing, report.ignored);
  if (report.running) {
    // Not a table of zeros: what has finished, and that the rest is under way.
    const std::size_t total = seeds ? seeds->size() : report.runs.size();
    const std::string note = "campaign still running (roverctl pid " + std::to_string(pid) +
                             "): " + std::to_string(report.runs.size()) + " of " +
                             std::to_string(total) + " runs finished so far\n\n";
    std::string table = report.table;
    const auto tail = table.rfind("\ncampaign: ");
    if (tail != std::string::npos) table.erase(tail + 1);  // no throughput before the end
    report.table = note + table;
  }
  report.all_passed = report.summary.runs > 0 && report.missing.empty() &&
                      report.summary.passed == report.summary.runs;
  return report;
}

}  // namespace rover::deploy
