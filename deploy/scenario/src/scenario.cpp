#include "rover/deploy/scenario.hpp"


#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

#include "rover/base/format.hpp"
#include "rover/base/units.hpp"
#include "rover/base/yaml_check.hpp"
#include "rover/runtime/topic_catalog.hpp"

namespace rover::deploy {
namespace {
using yaml::CheckKeys;
using yaml::Line;
using yaml::OptionalNumber;
using Ctx = yaml::FileErrors;

Status ParseTaskSection(const YAML::Node& n, const Ctx& c, TaskSection* t) {
  t->line = Line(n);
  if (!n.IsMap()) return c.At(n, "task: expected a map");
  ROVER_RETURN_IF_ERROR(yaml::RequireKey(n, "task", "type", c));
  const YAML::Node type = n["type"];
  t->type = yaml::ScalarText(type);
  t->type_line = Line(type);
  if (t->type.empty()) return c.At(type, "task.type: expected the name of a task");
  return Status::Ok();
}

Status ParseCriteria(const YAML::Node& n, const Ctx& c, sim::judge::JudgeCriteria* cr) {
  ROVER_RETURN_IF_ERROR(CheckKeys(n, "criteria",
                                  {"target", "heading", "max_tilt_deg", "traversable_height",
                                   "max_estimate_error", "max_estimate_error_percent",
                                   "max_estimate_heading_error_deg", "min_distance",
                                   "max_hazard_contacts"},
                                  c));
  if (const YAML::Node t = n["target"]) {
    ROVER_RETURN_IF_ERROR(CheckKeys(t, "criteria.target", {"x", "y", "tolerance"}, c));
    double x = 0, y = 0;
    bool hx = false, hy = false;
    ROVER_RETURN_IF_ERROR(OptionalNumber(t, "x", "criteria.target", -1e4, 1e4, c, &x, &hx));
    ROVER_RETURN_IF_ERROR(OptionalNumber(t, "y", "criteria.target", -1e4, 1e4, c, &y, &hy));
    if (!hx || !hy) return c.At(t, "criteria.target: needs both 'x' and 'y'");
    ROVER_RETURN_IF_ERROR(
        OptionalNumber(t, "tolerance", "criteria.target", 0.001, 100, c, &cr->position_tolerance));
    cr->target_xy = Eigen::Vector2d(x, y);
  }
  if (const YAML::Node h = n["heading"]) {
    ROVER_RETURN_IF_ERROR(CheckKeys(h, "criteria.heading", {"deg", "tolerance_deg"}, c));
    double deg = 0, tol = 5;
    bool has = false;
    ROVER_RETURN_IF_ERROR(OptionalNumber(h, "deg", "criteria.heading", -360, 360, c, &deg, &has));
    if (!has) return c.At(h, "criteria.heading: needs 'deg'");
    ROVER_RETURN_IF_ERROR(
        OptionalNumber(h, "tolerance_deg", "criteria.heading", 0.01, 180, c, &tol));
    cr->target_heading = deg * kDegree;
    cr->heading_tolerance = tol * kDegree;
  }
  double tilt = cr->max_tilt / kDegree;
  ROVER_RETURN_IF_ERROR(OptionalNumber(n, "max_tilt_deg", "criteria", 0.1, 89.9, c, &tilt));
  cr->max_tilt = tilt * kDegree;
  ROVER_RETURN_IF_ERROR(
      OptionalNumber(n, "traversable_height", "criteria", 0.01, 2.0, c, &cr->traversable_height));
  double v = 0;
  bool has = false;
  ROVER_RETURN_IF_ERROR(
      OptionalNumber(n, "max_estimate_error", "criteria", 1e-4, 1e4, c, &v, &has));
  if (has) cr->max_estimate_error = v;
  ROVER_RETURN_IF_ERROR(
      OptionalNumber(n, "max_estimate_error_percent", "criteria", 1e-3, 100, c, &v, &has));
  if (has) cr->max_estimate_error_fraction = v / 100.0;
  ROVER_RETURN_IF_ERROR(
      OptionalNumber(n, "max_estimate_heading_error_deg", "criteria", 0.001, 180, c, &v, &has));
  if (has) cr->max_estimate_heading_error = v * kDegree;
  ROVER_RETURN_IF_ERROR(OptionalNumber(n, "min_distance", "criteria", 0, 1e5, c, &v, &has));
  if (has) cr->min_distance = v;
  ROVER_RETURN_IF_ERROR(OptionalNumber(n, "max_hazard_contacts", "criteria", 0, 1e6, c, &v, &has));
  if (has) {
    if (v != std::floor(v)) {
      return c.At(n["max_hazard_contacts"], "criteria.max_hazard_contacts: " +
                                                yaml::ScalarText(n["max_hazard_contacts"]) +
                                                " is not a whole number");
    }
    cr->max_hazard_contacts = static_cast<int>(v);
  }
  return cr->Validate();
}

}  // namespace

const std::vector<std::string>& SimulatorSections() {
  static const std::vector<std::string> k = {"terrain", "terrain_features", "lander",
                                             "science_targets"};
  return k;
}

recording::RecordOptions DefaultRunRecording() {
  recording::RecordOptions o;
  o.path = "run.mcap";
  // The camera head's raw frames are most of a run's bytes (a 1024 x 1024 pair is 2 MB); the
  // pairs as the stack used them (ddl/stereo_frame) stay, so dl-stereo and dl-vo can be replayed.
  // Strict lock-step's acknowledgements (one per service per tick) were 60 % of the remaining
  // bytes and say nothing a replay needs. The simulator's 100 Hz and 50 Hz hardware streams
  // (hw/imu, hw/motor_telemetry, hw/suspension_pots, hw/arm_contact) reach the stack through
  // their drivers,
  // whose outputs (ddl/imu, ddl/motor_status, ddl/joint_state) stay: every service above the
  // drivers can be replayed. Recording them cost the simulator a send per sample to one more
  // reader (about a tenth of a campaign's wall time).
  o.topics.exclude = {"hw/camera_frame", "sim/clock_ack", "hw/imu", "hw/motor_telemetry",
                      "hw/suspension_pots", "hw/arm_contact"};
  return o;
}

namespace {
std::vector<std::string> CatalogTopics() {
  std::vector<std::string> out;
  for (const auto& t : dds::TopicCatalog()) out.emplace_back(t.name);
  return out;
}
}  // namespace

Result<Scenario> ParseScenario(const std::string& text, const std::string& file,
                               const SimSectionValidator& validate_sim,
                               const TaskValidator& validate_task) {
  const Ctx c(file);
  ROVER_ASSIGN_OR_RETURN(const YAML::Node root, yaml::Load(text, c));
  if (!root.IsMap()) return c.At(1, "expected a map (a scenario)");
  std::vector<std::string> known = {"name", "description", "compose", "simulator", "estimator", "seed", "sim",
                                    "rover", "task", "faults", "criteria", "params", "record"};
  for (const auto& s : SimulatorSections()) known.push_back(s);
  ROVER_RETURN_IF_ERROR(CheckKeys(root, "", known, c));
  Scenario s;
  s.file = file;
  s.text = text;
  if (!root["name"] || root["name"].Scalar().empty()) return c.At(1, "missing 'name'");
  s.name = root["name"].Scalar();
  for (char ch : s.name) {
    if (!(std::isalnum(static_cast<unsigned char>(ch)) || ch == '-' || ch == '_')) {
      return c.At(root["name"], "name: '" + s.name + "' may only hold letters, digits, - and _");
    }
  }
  if (root["description"]) s.description = root["description"].Scalar();
  if (!root["compose"]) return c.At(1, "missing 'compose' (the service set to run)");
  {
    namespace fs = std::filesystem;
    const fs::path base = fs::path(file).parent_path();
    s.compose_path = (base / root["compose"].Scalar()).lexically_normal().string();
    if (!fs::exists(s.compose_path)) {
      return c.At(root["compose"], "compose: file '" + s.compose_path + "' does not exist");
    }
  }
  if (root["simulator"]) s.simulator = root["simulator"].Scalar();
  if (root["estimator"]) s.estimator = root["estimator"].Scalar();
  if (const YAML::Node seed = root["seed"]) {
    ROVER_ASSIGN_OR_RETURN(const double v, yaml::Number(seed, "seed", c));
    if (v < 0 || v > 4294967295.0 || v != std::floor(v)) {
      return c.At(seed, "seed: expected an integer in [0, 2^32)");
    }
    s.seed = static_cast<std::uint32_t>(v);
  }
  if (const YAML::Node sim = root["sim"]) {
    ROVER_RETURN_IF_ERROR(CheckKeys(sim, "sim",
                                    {"real_time_factor", "lockstep", "lockstep_quantum_s",
                                     "lockstep_lead_s", "time_budget_s", "wall_budget_s"},
                                    c));
    if (const YAML::Node mode = sim["lockstep"]) {
      s.lockstep = mode.IsScalar() ? mode.Scalar() : "";
      if (s.lockstep != "strict" && s.lockstep != "lead" && s.lockstep != "off") {
        return c.At(mode, "sim.lockstep: '" + s.lockstep + "' is not one of: strict, lead, off");
      }
    }
    ROVER_RETURN_IF_ERROR(
        OptionalNumber(sim, "lockstep_quantum_s", "sim", 0.01, 1, c, &s.lockstep_quantum_s));
    if (const double steps = s.lockstep_quantum_s / 0.01;
        std::abs(steps - std::round(steps)) > 1e-6) {
      return c.At(sim["lockstep_quantum_s"],
                  "sim.lockstep_quantum_s: " + FormatNumber(s.lockstep_quantum_s) +
                      " s is not a whole number of the simulator's 0.01 s periods");
    }
    ROVER_RETURN_IF_ERROR(
        OptionalNumber(sim, "lockstep_lead_s", "sim", 0, 10, c, &s.lockstep_lead_s));
    if (s.lockstep_lead_s > 0 && s.lockstep_lead_s < 0.05) {
      return c.At(sim["lockstep_lead_s"],
                  "sim.lockstep_lead_s: use 0 (free running) or at least 0.05 s");
    }
    ROVER_RETURN_IF_ERROR(
        OptionalNumber(sim, "real_time_factor", "sim", 0, 1000, c, &s.real_time_factor));
    ROVER_RETURN_IF_ERROR(OptionalNumber(sim, "time_budget_s", "sim", 1, 1e6, c, &s.time_budget_s));
    ROVER_RETURN_IF_ERROR(OptionalNumber(sim, "wall_budget_s", "sim", 1, 1e6, c, &s.wall_budget_s));
  }
  if (const YAML::Node rover = root["rover"]) {
    ROVER_RETURN_IF_ERROR(CheckKeys(rover, "rover", {"start"}, c));
    if (const YAML::Node st = rover["start"]) {
      ROVER_RETURN_IF_ERROR(CheckKeys(st, "rover.start", {"x", "y", "yaw_deg"}, c));
      double yaw = 0;
      ROVER_RETURN_IF_ERROR(OptionalNumber(st, "x", "rover.start", -1e4, 1e4, c, &s.start_x));
      ROVER_RETURN_IF_ERROR(OptionalNumber(st, "y", "rover.start", -1e4, 1e4, c, &s.start_y));
      ROVER_RETURN_IF_ERROR(OptionalNumber(st, "yaw_deg", "rover.start", -360, 360, c, &yaw));
      s.start_yaw = yaw * kDegree;
    }
  }
  if (!root["task"]) return c.At(1, "missing 'task' (what the rover is to do)");
  ROVER_RETURN_IF_ERROR(ParseTaskSection(root["task"], c, &s.task));
  if (const YAML::Node f = root["faults"]) {
    if (!f.IsSequence()) return c.At(f, "faults: expected a list");
    ROVER_ASSIGN_OR_RETURN(s.faults, ParseSetFaults(f, file));
  }
  if (const YAML::Node cr = root["criteria"]) {
    const Status st = ParseCriteria(cr, c, &s.criteria);
    if (!st.ok()) {
      // Judge validation errors have no line; attach the criteria block's.
      if (st.message().rfind(file + ":", 0) == 0) return st;
      return c.At(cr, st.message());
    }
  } else {
    return c.At(1, "missing 'criteria' (how the run is judged)");
  }
  if (const YAML::Node p = root["params"]) {
    if (!p.IsMap()) return c.At(p, "params: expected a map of service: {key: value}");
    for (const auto& kv : p) {
      if (!kv.second.IsMap())
        return c.At(kv.second, "params." + kv.first.Scalar() + ": expected a map");
      yaml::Flatten(kv.second, "", &s.params[kv.first.Scalar()]);
    }
  }
  if (const YAML::Node r = root["record"]) {
    ROVER_ASSIGN_OR_RETURN(
        s.record, recording::ParseRecordOptions(r, "record", c, s.record, CatalogTopics()));
    if (s.record.path.empty()) s.record.path = DefaultRunRecording().path;
  }
  if (validate_task) ROVER_RETURN_IF_ERROR(validate_task(s));
  if (validate_sim) ROVER_RETURN_IF_ERROR(validate_sim(text, file));
  return s;
}

Result<Scenario> LoadScenarioFile(const std::string& path, const SimSectionValidator& validate_sim,
                                  const TaskValidator& validate_task) {
  std::ifstream in(path);
  if (!in) return NotFound(path + ": cannot open scenario file");
  std::stringstream ss;
  ss << in.rdbuf();
  return ParseScenario(ss.str(), path, validate_sim, validate_task);
}

namespace {

Result<std::vector<std::uint32_t>> ParseOneRange(const std::string& text) {
  auto parse = [](const std::string& s, std::uint64_t* v) {
    if (s.empty() || s.size() > 10 || s.find_first_not_of("0123456789") != std::string::npos) return false;
    *v = std::stoull(s);
    return *v <= 4294967295ULL;
  };
  std::uint64_t a = 0, b = 0;
  const auto dots = text.find("..");
  if (dots == std::string::npos) {
    if (!parse(text, &a)) return InvalidArgument("--seeds: '" + text + "' is not a seed or a range A..B");
    b = a;
  } else if (!parse(text.substr(0, dots), &a) || !parse(text.substr(dots + 2), &b)) {
    return InvalidArgument("--seeds: '" + text + "' is not a range A..B of non-negative integers");
  }
  if (a > b) {
    return InvalidArgument("--seeds: '" + text + "' is empty: the first seed is greater than the last");
  }
  if (b - a >= 10000) return InvalidArgument("--seeds: '" + text + "' has more than 10000 seeds");
  std::vector<std::uint32_t> out;
  for (std::uint64_t s = a; s <= b; ++s) out.push_back(static_cast<std::uint32_t>(s));
  return out;
}

}  // namespace

Result<std::vector<std::uint32_t>> ParseSeedRange(const std::string& text) {
  if (text.find(',') == std::string::npos) return ParseOneRange(text);
  // A list of seeds and ranges ("3,5..7,12", what `roverctl report` prints to resubmit):
  // in the order given, each seed once.
  std::vector<std::uint32_t> out;
  std::size_t pos = 0;
  while (pos <= text.size()) {
    const std::size_t end = std::min(text.find(',', pos), text.size());
    ROVER_ASSIGN_OR_RETURN(const std::vector<std::uint32_t> part,
                           ParseOneRange(text.substr(pos, end - pos)));
    for (std::uint32_t s : part) {
      if (std::find(out.begin(), out.end(), s) == out.end()) out.push_back(s);
    }
    if (out.size() > 10000) return InvalidArgument("--seeds: '" + text + "' has more than 10000 seeds");
    pos = end + 1;
  }
  return out;
}

}  // namespace rover::deploy
