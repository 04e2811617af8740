#include "rover/deploy/scenario.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <set>
#include <sstream>

#include "rover/base/params.hpp"  // EditDistance

namespace rover::deploy {
namespace {
constexpr double kDegToRad = std::numbers::pi / 180.0;

int Line(const YAML::Node& n) { return n.Mark().line + 1; }

class Ctx {
 public:
  explicit Ctx(std::string file) : file_(std::move(file)) {}
  Status Err(const YAML::Node& n, const std::string& what) const { return Err(Line(n), what); }
  Status Err(int line, const std::string& what) const {
    return InvalidArgument(file_ + ":" + std::to_string(line) + ": " + what);
  }
  const std::string& file() const { return file_; }

 private:
  std::string file_;
};

std::string Suggest(const std::string& key, const std::vector<std::string>& known) {
  std::string best;
  std::size_t best_d = 3;
  for (const auto& k : known) {
    const std::size_t d = EditDistance(key, k);
    if (d < best_d) {
      best_d = d;
      best = k;
    }
  }
  return best.empty() ? "" : " (did you mean '" + best + "'?)";
}

Status CheckKeys(const YAML::Node& map, const std::string& where,
                 const std::vector<std::string>& known, const Ctx& c) {
  if (!map.IsMap()) return c.Err(map, where + ": expected a map");
  std::set<std::string> seen;
  for (const auto& kv : map) {
    const std::string k = kv.first.Scalar();
    if (!seen.insert(k).second) return c.Err(kv.first, where + ": duplicate key '" + k + "'");
    if (std::find(known.begin(), known.end(), k) == known.end()) {
      std::string list;
      for (const auto& s : known) list += (list.empty() ? "" : ", ") + s;
      return c.Err(kv.first, (where.empty() ? "" : where + ": ") + "unknown key '" + k + "'" +
                                 Suggest(k, known) + " (known: " + list + ")");
    }
  }
  return Status::Ok();
}

Result<double> Number(const YAML::Node& n, const std::string& key, const Ctx& c) {
  if (n.IsScalar()) {
    try {
      const double v = n.as<double>();
      if (std::isfinite(v)) return v;
    } catch (const YAML::Exception&) {
    }
  }
  return c.Err(n, key + ": expected a finite number, got '" + (n.IsScalar() ? n.Scalar() : "?") + "'");
}

// Reads an optional number into `out`, checking [lo, hi].
Status OptNumber(const YAML::Node& parent, const char* name, const std::string& where, double lo,
                 double hi, const Ctx& c, double* out, bool* present = nullptr) {
  const YAML::Node n = parent[name];
  if (present) *present = static_cast<bool>(n);
  if (!n) return Status::Ok();
  auto v = Number(n, where + "." + name, c);
  if (!v.ok()) return v.status();
  if (*v < lo || *v > hi) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "%s.%s: %g is out of range [%g, %g]", where.c_str(), name, *v,
                  lo, hi);
    return c.Err(n, buf);
  }
  *out = *v;
  return Status::Ok();
}

Status ParseStep(const YAML::Node& n, const Ctx& c, DriveStep* s) {
  s->line = Line(n);
  ROVER_RETURN_IF_ERROR(CheckKeys(n, "task.steps[]",
                                  {"primitive", "distance", "curvature", "angle_deg", "speed",
                                   "timeout_s", "stop_after_s", "expect"},
                                  c));
  if (const YAML::Node e = n["expect"]) {
    static const std::vector<std::string> kTerminations = {
        "nominal", "tilt", "suspension", "motor_stall", "motor_current", "motor_fault", "timeout",
        "stop_command", "rejected_busy", "rejected_invalid", "stale_sensor"};
    s->expect = e.Scalar();
    if (std::find(kTerminations.begin(), kTerminations.end(), s->expect) == kTerminations.end()) {
      std::string list;
      for (const auto& t : kTerminations) list += (list.empty() ? "" : ", ") + t;
      return c.Err(e, "task.steps[].expect: '" + s->expect + "' is not one of: " + list +
                          Suggest(s->expect, kTerminations));
    }
  }
  ROVER_RETURN_IF_ERROR(OptNumber(n, "timeout_s", "task.steps[]", 0, 86400, c, &s->timeout_s));
  ROVER_RETURN_IF_ERROR(OptNumber(n, "stop_after_s", "task.steps[]", 0, 86400, c, &s->stop_after_s));
  const YAML::Node p = n["primitive"];
  if (!p) return c.Err(n, "task.steps[]: missing 'primitive'");
  const std::string name = p.Scalar();
  if (name == "straight") s->primitive = Primitive::kStraight;
  else if (name == "arc") s->primitive = Primitive::kArc;
  else if (name == "turn_in_place") s->primitive = Primitive::kTurnInPlace;
  else if (name == "steer") s->primitive = Primitive::kSteer;
  else if (name == "stop") s->primitive = Primitive::kStop;
  else {
    return c.Err(p, "task.steps[].primitive: '" + name +
                        "' is not one of: straight, arc, turn_in_place, steer, stop" +
                        Suggest(name, {"straight", "arc", "turn_in_place", "steer", "stop"}));
  }
  bool has_d = false, has_k = false, has_a = false;
  double angle_deg = 0;
  ROVER_RETURN_IF_ERROR(OptNumber(n, "distance", "task.steps[]", -100, 100, c, &s->distance, &has_d));
  ROVER_RETURN_IF_ERROR(OptNumber(n, "curvature", "task.steps[]", -1, 1, c, &s->curvature, &has_k));
  ROVER_RETURN_IF_ERROR(OptNumber(n, "angle_deg", "task.steps[]", -360, 360, c, &angle_deg, &has_a));
  ROVER_RETURN_IF_ERROR(OptNumber(n, "speed", "task.steps[]", 0, 0.5, c, &s->speed));
  s->angle = angle_deg * kDegToRad;
  auto need = [&](bool has, const char* what) -> Status {
    return has ? Status::Ok() : c.Err(n, "task.steps[]: '" + name + "' needs '" + what + "'");
  };
  switch (s->primitive) {
    case Primitive::kStraight: return need(has_d, "distance");
    case Primitive::kArc:
      ROVER_RETURN_IF_ERROR(need(has_d, "distance"));
      return need(has_k, "curvature");
    case Primitive::kTurnInPlace: return need(has_a, "angle_deg");
    case Primitive::kSteer: return need(has_k, "curvature");
    case Primitive::kStop: return Status::Ok();
  }
  return Status::Ok();
}

Status ParseTask(const YAML::Node& n, const Ctx& c, TaskSpec* t) {
  t->line = Line(n);
  ROVER_RETURN_IF_ERROR(CheckKeys(n, "task", {"type", "steps", "goal"}, c));
  const YAML::Node type = n["type"];
  if (!type) return c.Err(n, "task: missing 'type'");
  const std::vector<std::string> names = {"directed", "waypoint", "autonav", "long_traverse",
                                          "lander_return", "science_target"};
  auto it = std::find(names.begin(), names.end(), type.Scalar());
  if (it == names.end()) {
    return c.Err(type, "task.type: '" + type.Scalar() + "' is not one of: directed, waypoint, "
                       "autonav, long_traverse, lander_return, science_target" +
                       Suggest(type.Scalar(), names));
  }
  t->type = static_cast<TaskType>(it - names.begin());
  if (const YAML::Node g = n["goal"]) {
    ROVER_RETURN_IF_ERROR(CheckKeys(g, "task.goal", {"x", "y", "tolerance"}, c));
    double x = 0, y = 0;
    bool hx = false, hy = false;
    ROVER_RETURN_IF_ERROR(OptNumber(g, "x", "task.goal", -1e4, 1e4, c, &x, &hx));
    ROVER_RETURN_IF_ERROR(OptNumber(g, "y", "task.goal", -1e4, 1e4, c, &y, &hy));
    if (!hx || !hy) return c.Err(g, "task.goal: needs both 'x' and 'y'");
    ROVER_RETURN_IF_ERROR(OptNumber(g, "tolerance", "task.goal", 0.01, 100, c, &t->goal_tolerance));
    t->goal = Eigen::Vector2d(x, y);
  }
  if (t->type == TaskType::kDirected) {
    const YAML::Node steps = n["steps"];
    if (!steps || !steps.IsSequence() || steps.size() == 0) {
      return c.Err(steps ? steps : n, "task.steps: a directed task needs a non-empty list of steps");
    }
    for (const auto& s : steps) {
      DriveStep step;
      ROVER_RETURN_IF_ERROR(ParseStep(s, c, &step));
      t->steps.push_back(step);
    }
  } else if (!t->goal && t->type != TaskType::kLanderReturn && t->type != TaskType::kScienceTarget) {
    return c.Err(n, std::string("task: a '") + TaskTypeName(t->type) + "' task needs a 'goal'");
  }
  return Status::Ok();
}

Status ParseCriteria(const YAML::Node& n, const Ctx& c, sim::JudgeCriteria* cr) {
  ROVER_RETURN_IF_ERROR(CheckKeys(n, "criteria",
                                  {"target", "heading", "max_tilt_deg", "traversable_height",
                                   "max_estimate_error", "max_estimate_error_percent",
                                   "max_estimate_heading_error_deg", "min_distance"},
                                  c));
  if (const YAML::Node t = n["target"]) {
    ROVER_RETURN_IF_ERROR(CheckKeys(t, "criteria.target", {"x", "y", "tolerance"}, c));
    double x = 0, y = 0;
    bool hx = false, hy = false;
    ROVER_RETURN_IF_ERROR(OptNumber(t, "x", "criteria.target", -1e4, 1e4, c, &x, &hx));
    ROVER_RETURN_IF_ERROR(OptNumber(t, "y", "criteria.target", -1e4, 1e4, c, &y, &hy));
    if (!hx || !hy) return c.Err(t, "criteria.target: needs both 'x' and 'y'");
    ROVER_RETURN_IF_ERROR(
        OptNumber(t, "tolerance", "criteria.target", 0.001, 100, c, &cr->position_tolerance));
    cr->target_xy = Eigen::Vector2d(x, y);
  }
  if (const YAML::Node h = n["heading"]) {
    ROVER_RETURN_IF_ERROR(CheckKeys(h, "criteria.heading", {"deg", "tolerance_deg"}, c));
    double deg = 0, tol = 5;
    bool has = false;
    ROVER_RETURN_IF_ERROR(OptNumber(h, "deg", "criteria.heading", -360, 360, c, &deg, &has));
    if (!has) return c.Err(h, "criteria.heading: needs 'deg'");
    ROVER_RETURN_IF_ERROR(OptNumber(h, "tolerance_deg", "criteria.heading", 0.01, 180, c, &tol));
    cr->target_heading = deg * kDegToRad;
    cr->heading_tolerance = tol * kDegToRad;
  }
  double tilt = cr->max_tilt / kDegToRad;
  ROVER_RETURN_IF_ERROR(OptNumber(n, "max_tilt_deg", "criteria", 0.1, 89.9, c, &tilt));
  cr->max_tilt = tilt * kDegToRad;
  ROVER_RETURN_IF_ERROR(
      OptNumber(n, "traversable_height", "criteria", 0.01, 2.0, c, &cr->traversable_height));
  double v = 0;
  bool has = false;
  ROVER_RETURN_IF_ERROR(OptNumber(n, "max_estimate_error", "criteria", 1e-4, 1e4, c, &v, &has));
  if (has) cr->max_estimate_error = v;
  ROVER_RETURN_IF_ERROR(
      OptNumber(n, "max_estimate_error_percent", "criteria", 1e-3, 100, c, &v, &has));
  if (has) cr->max_estimate_error_fraction = v / 100.0;
  ROVER_RETURN_IF_ERROR(
      OptNumber(n, "max_estimate_heading_error_deg", "criteria", 0.001, 180, c, &v, &has));
  if (has) cr->max_estimate_heading_error = v * kDegToRad;
  ROVER_RETURN_IF_ERROR(OptNumber(n, "min_distance", "criteria", 0, 1e5, c, &v, &has));
  if (has) cr->min_distance = v;
  return cr->Validate();
}

void Flatten(const YAML::Node& n, const std::string& prefix, std::map<std::string, std::string>* out) {
  if (n.IsMap()) {
    for (const auto& kv : n) {
      Flatten(kv.second, prefix.empty() ? kv.first.Scalar() : prefix + "." + kv.first.Scalar(), out);
    }
  } else if (n.IsScalar()) {
    (*out)[prefix] = n.Scalar();
  } else {
    YAML::Emitter e;
    e << YAML::Flow << n;
    (*out)[prefix] = e.c_str();
  }
}

}  // namespace

const char* TaskTypeName(TaskType t) {
  switch (t) {
    case TaskType::kDirected: return "directed";
    case TaskType::kWaypoint: return "waypoint";
    case TaskType::kAutonav: return "autonav";
    case TaskType::kLongTraverse: return "long_traverse";
    case TaskType::kLanderReturn: return "lander_return";
    case TaskType::kScienceTarget: return "science_target";
  }
  return "?";
}

const char* PrimitiveName(Primitive p) {
  switch (p) {
    case Primitive::kStraight: return "straight";
    case Primitive::kArc: return "arc";
    case Primitive::kTurnInPlace: return "turn_in_place";
    case Primitive::kSteer: return "steer";
    case Primitive::kStop: return "stop";
  }
  return "?";
}

const std::vector<std::string>& SimulatorSections() {
  static const std::vector<std::string> k = {"terrain", "lander", "science_targets"};
  return k;
}

Result<Scenario> ParseScenario(const std::string& text, const std::string& file,
                               const SimSectionValidator& validate_sim) {
  const Ctx c(file);
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    return c.Err(e.mark.line + 1, "malformed YAML: " + e.msg);
  }
  if (!root.IsMap()) return c.Err(1, "expected a map (a scenario)");
  std::vector<std::string> known = {"name", "description", "compose", "simulator", "estimator", "seed", "sim",
                                    "rover", "task", "faults", "criteria", "params"};
  for (const auto& s : SimulatorSections()) known.push_back(s);
  ROVER_RETURN_IF_ERROR(CheckKeys(root, "", known, c));
  Scenario s;
  s.file = file;
  s.text = text;
  if (!root["name"] || root["name"].Scalar().empty()) return c.Err(1, "missing 'name'");
  s.name = root["name"].Scalar();
  for (char ch : s.name) {
    if (!(std::isalnum(static_cast<unsigned char>(ch)) || ch == '-' || ch == '_')) {
      return c.Err(root["name"], "name: '" + s.name + "' may only hold letters, digits, - and _");
    }
  }
  if (root["description"]) s.description = root["description"].Scalar();
  if (!root["compose"]) return c.Err(1, "missing 'compose' (the service set to run)");
  {
    namespace fs = std::filesystem;
    const fs::path base = fs::path(file).parent_path();
    s.compose_path = (base / root["compose"].Scalar()).lexically_normal().string();
    if (!fs::exists(s.compose_path)) {
      return c.Err(root["compose"], "compose: file '" + s.compose_path + "' does not exist");
    }
  }
  if (root["simulator"]) s.simulator = root["simulator"].Scalar();
  if (root["estimator"]) s.estimator = root["estimator"].Scalar();
  if (const YAML::Node seed = root["seed"]) {
    auto v = Number(seed, "seed", c);
    if (!v.ok()) return v.status();
    if (*v < 0 || *v > 4294967295.0 || *v != std::floor(*v)) {
      return c.Err(seed, "seed: expected an integer in [0, 2^32)");
    }
    s.seed = static_cast<std::uint32_t>(*v);
  }
  if (const YAML::Node sim = root["sim"]) {
    ROVER_RETURN_IF_ERROR(CheckKeys(
        sim, "sim", {"real_time_factor", "lockstep_lead_s", "time_budget_s", "wall_budget_s"}, c));
    ROVER_RETURN_IF_ERROR(OptNumber(sim, "lockstep_lead_s", "sim", 0, 10, c, &s.lockstep_lead_s));
    if (s.lockstep_lead_s > 0 && s.lockstep_lead_s < 0.05) {
      return c.Err(sim["lockstep_lead_s"],
                   "sim.lockstep_lead_s: use 0 (free running) or at least 0.05 s");
    }
    ROVER_RETURN_IF_ERROR(OptNumber(sim, "real_time_factor", "sim", 0, 1000, c, &s.real_time_factor));
    ROVER_RETURN_IF_ERROR(OptNumber(sim, "time_budget_s", "sim", 1, 1e6, c, &s.time_budget_s));
    ROVER_RETURN_IF_ERROR(OptNumber(sim, "wall_budget_s", "sim", 1, 1e6, c, &s.wall_budget_s));
  }
  if (const YAML::Node rover = root["rover"]) {
    ROVER_RETURN_IF_ERROR(CheckKeys(rover, "rover", {"start"}, c));
    if (const YAML::Node st = rover["start"]) {
      ROVER_RETURN_IF_ERROR(CheckKeys(st, "rover.start", {"x", "y", "yaw_deg"}, c));
      double yaw = 0;
      ROVER_RETURN_IF_ERROR(OptNumber(st, "x", "rover.start", -1e4, 1e4, c, &s.start_x));
      ROVER_RETURN_IF_ERROR(OptNumber(st, "y", "rover.start", -1e4, 1e4, c, &s.start_y));
      ROVER_RETURN_IF_ERROR(OptNumber(st, "yaw_deg", "rover.start", -360, 360, c, &yaw));
      s.start_yaw = yaw * kDegToRad;
    }
  }
  if (!root["task"]) return c.Err(1, "missing 'task' (what the rover is to do)");
  ROVER_RETURN_IF_ERROR(ParseTask(root["task"], c, &s.task));
  if (const YAML::Node f = root["faults"]) {
    if (!f.IsSequence()) return c.Err(f, "faults: expected a list");
    for (const auto& item : f) {
      if (!item.IsMap()) return c.Err(item, "faults[]: expected a map");
      std::map<std::string, std::string> m;
      Flatten(item, "", &m);
      s.faults.push_back(std::move(m));
    }
  }
  if (const YAML::Node cr = root["criteria"]) {
    const Status st = ParseCriteria(cr, c, &s.criteria);
    if (!st.ok()) {
      // Judge validation errors have no line; attach the criteria block's.
      if (st.message().rfind(file + ":", 0) == 0) return st;
      return c.Err(cr, st.message());
    }
  } else {
    return c.Err(1, "missing 'criteria' (how the run is judged)");
  }
  if (const YAML::Node p = root["params"]) {
    if (!p.IsMap()) return c.Err(p, "params: expected a map of service: {key: value}");
    for (const auto& kv : p) {
      if (!kv.second.IsMap()) return c.Err(kv.second, "params." + kv.first.Scalar() + ": expected a map");
      Flatten(kv.second, "", &s.params[kv.first.Scalar()]);
    }
  }
  if (validate_sim) ROVER_RETURN_IF_ERROR(validate_sim(text, file));
  return s;
}

Result<Scenario> LoadScenarioFile(const std::string& path, const SimSectionValidator& validate_sim) {
  std::ifstream in(path);
  if (!in) return NotFound(path + ": cannot open scenario file");
  std::stringstream ss;
  ss << in.rdbuf();
  return ParseScenario(ss.str(), path, validate_sim);
}

Result<std::vector<std::uint32_t>> ParseSeedRange(const std::string& text) {
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

}  // namespace rover::deploy
