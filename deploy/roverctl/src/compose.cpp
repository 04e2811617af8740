#include "rover/deploy/compose.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>
#include <string_view>

#include "rover/base/params.hpp"  // DidYouMean
#include "rover/base/yaml_check.hpp"
#include "rover/runtime/qos.hpp"
#include "rover/runtime/topic_catalog.hpp"

namespace rover::deploy {
namespace {

using yaml::CheckKeys;
using yaml::JoinNames;
using yaml::Line;
using yaml::ScalarText;
using Errors = yaml::FileErrors;

// Compose keys: every key known or an x- extension, each once; callers check maps themselves.
constexpr yaml::KeyRules kComposeKeys{.require_map = false, .allow_extensions = true};

// A service may not move itself off what roverctl sets for the whole set (a ROVER_DOMAIN of its
// own would put it on another DDS domain, silently).
Status CheckNotReserved(const std::string& key, const YAML::Node& at, const std::string& where,
                        const Errors& err) {
  for (const auto& r : ReservedEnvironment()) {
    const std::string_view k = r.key;
    const bool prefix = !k.empty() && k.back() == '*';
    const bool hit = prefix ? key.compare(0, k.size() - 1, k.substr(0, k.size() - 1)) == 0
                            : key == k;
    if (hit) {
      return err.At(at, where + ".environment." + key + ": roverctl sets " + r.key +
                            " for every service (" + r.what + "); a service may not override it");
    }
  }
  return Status::Ok();
}

Status ParseEnvironment(const YAML::Node& n, const std::string& where, const Errors& err,
                        std::map<std::string, std::string>* env) {
  if (n.IsMap()) {
    for (const auto& kv : n) {
      if (!kv.second.IsScalar() && !kv.second.IsNull()) {
        return err.At(kv.second, where + ".environment." + kv.first.Scalar() +
                                     ": expected a scalar value");
      }
      ROVER_RETURN_IF_ERROR(CheckNotReserved(kv.first.Scalar(), kv.first, where, err));
      (*env)[kv.first.Scalar()] = kv.second.IsNull() ? "" : kv.second.Scalar();
    }
    return Status::Ok();
  }
  if (n.IsSequence()) {
    for (const auto& item : n) {
      const std::string s = ScalarText(item);
      const auto eq = s.find('=');
      if (s.empty() || eq == 0) {
        return err.At(item, where + ".environment: expected KEY=VALUE, got '" + s + "'");
      }
      ROVER_RETURN_IF_ERROR(CheckNotReserved(s.substr(0, eq), item, where, err));
      (*env)[s.substr(0, eq)] = eq == std::string::npos ? "" : s.substr(eq + 1);
    }
    return Status::Ok();
  }
  return err.At(n, where + ".environment: expected a map or a list of KEY=VALUE");
}

Status ParseDependsOn(const YAML::Node& n, const std::string& where, const Errors& err,
                      std::vector<Dependency>* deps) {
  if (n.IsSequence()) {
    for (const auto& item : n) {
      if (!item.IsScalar()) return err.At(item, where + ".depends_on: expected service names");
      deps->push_back({item.Scalar(), DependencyCondition::kStarted, Line(item)});
    }
    return Status::Ok();
  }
  if (!n.IsMap()) return err.At(n, where + ".depends_on: expected a list or a map");
  for (const auto& kv : n) {
    Dependency d{kv.first.Scalar(), DependencyCondition::kStarted, Line(kv.first)};
    const std::string w = where + ".depends_on." + d.service;
    if (kv.second.IsMap()) {
      ROVER_RETURN_IF_ERROR(
          CheckKeys(kv.second, w, {"condition", "restart", "required"}, err, kComposeKeys));
      if (const auto c = kv.second["condition"]) {
        ROVER_ASSIGN_OR_RETURN(
            const std::string cond,
            yaml::OneOf(c, w + ".condition",
                        {"service_started", "service_healthy", "service_completed_successfully"},
                        err));
        d.condition = cond == "service_started"   ? DependencyCondition::kStarted
                      : cond == "service_healthy" ? DependencyCondition::kHealthy
                                                  : DependencyCondition::kCompletedSuccessfully;
      }
    } else if (!kv.second.IsNull()) {
      return err.At(kv.second, w + ": expected a map with 'condition'");
    }
    deps->push_back(d);
  }
  return Status::Ok();
}

Status ParseRestart(const YAML::Node& n, const std::string& where, const Errors& err,
                    ServiceSpec* s) {
  const std::string r = ScalarText(n);
  if (r == "no" || r == "false") {
    s->restart = RestartPolicy::kNo;
  } else if (r == "always") {
    s->restart = RestartPolicy::kAlways;
  } else if (r == "unless-stopped") {
    s->restart = RestartPolicy::kUnlessStopped;
  } else if (r.rfind("on-failure", 0) == 0) {
    s->restart = RestartPolicy::kOnFailure;
    if (r.size() > 10) {
      if (r[10] != ':' || r.size() == 11 ||
          !std::all_of(r.begin() + 11, r.end(), [](unsigned char c) { return std::isdigit(c); })) {
        return err.At(n, where + ".restart: '" + r + "' is not on-failure[:N]");
      }
      s->max_restarts = std::stoi(r.substr(11));
    }
  } else {
    return err.At(n, where + ".restart: '" + r +
                         "' is not one of: no, always, on-failure[:N], unless-stopped");
  }
  return Status::Ok();
}

// Applies YAML merge keys (`<<: *anchor` or `<<: [*a, *b]`), which yaml-cpp 0.7 leaves as an
// ordinary key: entries of the merged maps are added unless the map sets them itself.
Result<YAML::Node> ResolveMergeKeys(const YAML::Node& map, const std::string& where,
                                    const Errors& err) {
  if (!map["<<"]) return map;
  YAML::Node out(YAML::NodeType::Map);
  // String keys throughout: yaml-cpp looks Node keys up by identity, and a non-const
  // operator[] inserts a null entry for a key it does not find.
  for (const auto& kv : map) {
    if (kv.first.Scalar() != "<<") out[kv.first.Scalar()] = kv.second;
  }
  const YAML::Node merge = map["<<"];
  std::vector<YAML::Node> sources;
  if (merge.IsMap()) {
    sources.push_back(merge);
  } else if (merge.IsSequence()) {
    for (const auto& m : merge) sources.push_back(m);
  }
  for (const auto& src : sources) {
    if (!src.IsMap()) return err.At(merge, where + ".<<: can only merge maps");
    for (const auto& kv : src) {
      const std::string key = kv.first.Scalar();
      if (!static_cast<const YAML::Node&>(out)[key]) out[key] = kv.second;
    }
  }
  return out;
}

Status ParseService(const std::string& name, const YAML::Node& key, const YAML::Node& raw,
                    const Errors& err, ServiceSpec* s) {
  const std::string where = "services." + name;
  s->name = name;
  s->line = Line(key);
  if (!raw.IsMap()) return err.At(key, where + ": expected a map of service settings");
  auto merged = ResolveMergeKeys(raw, where, err);
  if (!merged.ok()) return merged.status();
  const YAML::Node n = *merged;
  ROVER_RETURN_IF_ERROR(
      CheckKeys(n, where,
                {"command", "environment", "depends_on", "restart", "stop_grace_period", "image",
                 "build", "network_mode", "working_dir", "volumes", "container_name", "stop_signal",
                 "healthcheck", "init"},
                err, kComposeKeys));
  const YAML::Node cmd = n["command"];
  if (!cmd || cmd.IsNull()) {
    return err.At(key, where + ": no 'command' (roverctl runs each service's command natively)");
  }
  s->command_line = Line(cmd);
  if (cmd.IsScalar()) {
    auto words = SplitCommand(cmd.Scalar());
    if (!words.ok()) return err.At(cmd, where + ".command: " + words.status().message());
    s->command = std::move(*words);
  } else if (cmd.IsSequence()) {
    for (const auto& w : cmd) {
      if (!w.IsScalar()) return err.At(w, where + ".command: expected strings");
      s->command.push_back(w.Scalar());
    }
  } else {
    return err.At(cmd, where + ".command: expected a string or a list of strings");
  }
  if (s->command.empty() || s->command[0].empty()) {
    return err.At(cmd, where + ".command: is empty");
  }
  if (const auto e = n["environment"]) {
    ROVER_RETURN_IF_ERROR(ParseEnvironment(e, where, err, &s->environment));
  }
  if (const auto d = n["depends_on"]) {
    ROVER_RETURN_IF_ERROR(ParseDependsOn(d, where, err, &s->depends_on));
  }
  if (const auto r = n["restart"]) ROVER_RETURN_IF_ERROR(ParseRestart(r, where, err, s));
  if (const auto g = n["stop_grace_period"]) {
    auto d = ParseDuration(ScalarText(g));
    if (!d.ok()) return err.At(g, where + ".stop_grace_period: " + d.status().message());
    s->stop_grace_s = *d;
  }
  if (const auto w = n["working_dir"]) s->working_dir = ScalarText(w);
  if (const auto x = n["x-rover"]) {
    ROVER_RETURN_IF_ERROR(CheckKeys(x, where + ".x-rover", {"ready"}, err));
    if (const auto r = x["ready"]) {
      ROVER_ASSIGN_OR_RETURN(
          const std::string rule,
          yaml::OneOf(r, where + ".x-rover.ready", {"healthy", "active", "started", "completed"},
                      err));
      for (ReadyRule k : {ReadyRule::kHealthy, ReadyRule::kActive, ReadyRule::kStarted,
                          ReadyRule::kCompleted}) {
        if (rule == ReadyRuleName(k)) s->ready = k;
      }
    }
  }
  return Status::Ok();
}

Status ParseRover(const YAML::Node& n, const Errors& err, RoverSettings* r) {
  if (!n.IsMap()) return err.At(n, "x-rover: expected a map");
  ROVER_RETURN_IF_ERROR(CheckKeys(n, "x-rover",
                                  {"project", "domain", "clock", "startup_timeout_s",
                                   "heartbeat_timeout_s", "qos", "sim", "faults", "scenario", "record",
                                   "security", "slurm"},
                                  err, kComposeKeys));
  if (const auto p = n["project"]) {
    r->project = ScalarText(p);
    if (r->project.empty()) return err.At(p, "x-rover.project: expected a name");
  }
  if (const auto d = n["domain"]) {
    ROVER_ASSIGN_OR_RETURN(const double v, yaml::Number(d, "x-rover.domain", err));
    if (v != static_cast<int>(v) || v < 0 || v > 232) {
      return err.At(d, "x-rover.domain: " + ScalarText(d) + " is not an integer in [0, 232]");
    }
    r->domain = static_cast<int>(v);
  }
  if (const auto c = n["clock"]) {
    ROVER_ASSIGN_OR_RETURN(r->clock, yaml::OneOf(c, "x-rover.clock", {"wall", "sim"}, err));
  }
  ROVER_RETURN_IF_ERROR(yaml::OptionalNumber(n, "startup_timeout_s", "x-rover",
                                             Bounds::OpenLow(0, 3600), err, &r->startup_timeout_s));
  ROVER_RETURN_IF_ERROR(yaml::OptionalNumber(
      n, "heartbeat_timeout_s", "x-rover", Bounds::OpenLow(0, 3600), err, &r->heartbeat_timeout_s));
  if (const auto q = n["qos"]) {
    if (!q.IsMap()) return err.At(q, "x-rover.qos: expected a map of topic: profile");
    for (const auto& kv : q) {
      auto p = dds::ParseQosProfile(ScalarText(kv.second));
      if (!p.ok()) {
        return err.At(kv.second, "x-rover.qos." + kv.first.Scalar() + ": " + p.status().message());
      }
      r->qos[kv.first.Scalar()] = ScalarText(kv.second);
    }
  }
  if (const auto s = n["sim"]) {
    if (!s.IsMap()) return err.At(s, "x-rover.sim: expected a map");
    yaml::Flatten(s, "", &r->sim);
  }
  if (const auto f = n["faults"]) {
    if (!f.IsSequence()) return err.At(f, "x-rover.faults: expected a list");
    ROVER_ASSIGN_OR_RETURN(r->faults, ParseSetFaults(f, err.file()));
  }
  if (const auto sl = n["slurm"]) {
    if (!sl.IsMap()) return err.At(sl, "x-rover.slurm: expected a map");
    ROVER_RETURN_IF_ERROR(CheckKeys(sl, "x-rover.slurm",
                                    {"partition", "time", "cpus_per_task", "sbatch_args"}, err,
                                    kComposeKeys));
    if (const auto p = sl["partition"]) r->slurm.partition = ScalarText(p);
    if (const auto t = sl["time"]) r->slurm.time = ScalarText(t);
    double cpus = 0;
    ROVER_RETURN_IF_ERROR(yaml::OptionalNumber(sl, "cpus_per_task", "x-rover.slurm",
                                               Bounds::Closed(1, 256), err, &cpus));
    if (cpus != std::floor(cpus)) {
      return err.At(sl["cpus_per_task"], "x-rover.slurm.cpus_per_task: " +
                                             ScalarText(sl["cpus_per_task"]) +
                                             " is not a whole number");
    }
    r->slurm.cpus_per_task = static_cast<int>(cpus);
    if (const auto a = sl["sbatch_args"]) {
      if (!a.IsSequence()) return err.At(a, "x-rover.slurm.sbatch_args: expected a list");
      for (const auto& x : a) r->slurm.sbatch_args.push_back(ScalarText(x));
    }
  }
  if (const auto sec = n["security"]) {
    ROVER_ASSIGN_OR_RETURN(const std::string v,
                           yaml::OneOf(sec, "x-rover.security", {"enabled", "disabled"}, err));
    r->security = v == "enabled";
  }
  if (const auto rec = n["record"]) {
    std::vector<std::string> topics;
    for (const auto& t : dds::TopicCatalog()) topics.emplace_back(t.name);
    ROVER_ASSIGN_OR_RETURN(r->record,
                           recording::ParseRecordOptions(rec, "x-rover.record", err, {}, topics));
  }
  return Status::Ok();
}

// Orders services so that dependencies come first; reports a cycle with its path.
Status OrderServices(std::vector<ServiceSpec>* services, const Errors& err) {
  std::map<std::string, const ServiceSpec*> by_name;
  for (const auto& s : *services) by_name[s.name] = &s;
  for (const auto& s : *services) {
    for (const auto& d : s.depends_on) {
      if (!by_name.count(d.service)) {
        std::vector<std::string> names;
        for (const auto& [n, _] : by_name) names.push_back(n);
        return err.At(d.line, "services." + s.name + ".depends_on: unknown service '" + d.service +
                                  "'" + DidYouMean(d.service, names));
      }
      if (d.service == s.name) {
        return err.At(d.line, "services." + s.name + ".depends_on: a service cannot depend on itself");
      }
    }
  }
  enum Mark { kNone, kVisiting, kDone };
  std::map<std::string, Mark> mark;
  std::vector<std::string> stack;
  std::vector<ServiceSpec> ordered;
  std::function<Status(const ServiceSpec&)> visit = [&](const ServiceSpec& s) -> Status {
    if (mark[s.name] == kDone) return Status::Ok();
    if (mark[s.name] == kVisiting) {
      auto it = std::find(stack.begin(), stack.end(), s.name);
      std::vector<std::string> cycle(it, stack.end());
      cycle.push_back(s.name);
      return err.At(s.line,
                    "services." + s.name + ": dependency cycle: " + JoinNames(cycle, " -> "));
    }
    mark[s.name] = kVisiting;
    stack.push_back(s.name);
    for (const auto& d : s.depends_on) ROVER_RETURN_IF_ERROR(visit(*by_name[d.service]));
    stack.pop_back();
    mark[s.name] = kDone;
    ordered.push_back(s);
    return Status::Ok();
  };
  for (const auto& s : *services) ROVER_RETURN_IF_ERROR(visit(s));
  *services = std::move(ordered);
  return Status::Ok();
}

std::string ProjectFromFile(const std::string& file) {
  std::string base = file.substr(file.find_last_of('/') + 1);
  base = base.substr(0, base.find('.'));
  return base.empty() ? "rover" : base;
}

}  // namespace

const char* DependencyConditionName(DependencyCondition c) {
  switch (c) {
    case DependencyCondition::kStarted: return "service_started";
    case DependencyCondition::kHealthy: return "service_healthy";
    case DependencyCondition::kCompletedSuccessfully: return "service_completed_successfully";
  }
  return "?";
}

const char* RestartPolicyName(RestartPolicy p) {
  switch (p) {
    case RestartPolicy::kNo: return "no";
    case RestartPolicy::kAlways: return "always";
    case RestartPolicy::kOnFailure: return "on-failure";
    case RestartPolicy::kUnlessStopped: return "unless-stopped";
  }
  return "?";
}

const char* ReadyRuleName(ReadyRule r) {
  switch (r) {
    case ReadyRule::kHealthy: return "healthy";
    case ReadyRule::kActive: return "active";
    case ReadyRule::kStarted: return "started";
    case ReadyRule::kCompleted: return "completed";
  }
  return "?";
}

const std::vector<ReservedVariable>& ReservedEnvironment() {
  static const std::vector<ReservedVariable> kReserved = {
      {"ROVER_DOMAIN", "the set's DDS domain: choose it with x-rover.domain or --domain"},
      {"ROVER_CLOCK", "the set's run clock: choose it with x-rover.clock"},
      {"ROVER_PROJECT", "the set's name: x-rover.project or -p"},
      {"ROVER_SERVICE_NAME", "the service's name: its key under services"},
      {"ROVER_STATE_DIR", "where the set's state and logs are: roverctl --state-dir"},
      {"ROVER_QOS_OVERRIDES", "per-topic QoS profiles: give them under x-rover.qos"},
      {"ROVER_SET_ID", "marks every process of the set, so that none is left behind"},
      {"ROVER_SIM_*", "simulator settings: give them under x-rover.sim"},
      {"CYCLONEDDS_URI", "the set's Cyclone DDS configuration: give roverctl ROVER_DDS_CONFIG"},
      {"ROVER_FAULTS", "the set's faults: give them under x-rover.faults (with `service:`)"},
      {"ROVER_FAULTS_EPOCH_NS", "what the set's fault windows count from: its start"},
      {"ROVER_SECURITY_DIR", "the set's DDS Security keys: x-rover.security and roverctl "
                             "--security-dir"},
      {"ROVER_SECURITY_IDENTITY", "the service's DDS Security identity: its executable's role"},
  };
  return kReserved;
}

const ServiceSpec* ComposeProject::Find(const std::string& name) const {
  for (const auto& s : services) {
    if (s.name == name) return &s;
  }
  return nullptr;
}

Result<std::vector<std::string>> SplitCommand(const std::string& command) {
  std::vector<std::string> words;
  std::string cur;
  bool in_word = false;
  char quote = 0;
  for (std::size_t i = 0; i < command.size(); ++i) {
    const char c = command[i];
    if (quote == '\'') {
      if (c == '\'') quote = 0; else cur += c;
    } else if (quote == '"') {
      if (c == '"') {
        quote = 0;
      } else if (c == '\\' && i + 1 < command.size() &&
                 (command[i + 1] == '"' || command[i + 1] == '\\' || command[i + 1] == '$')) {
        cur += command[++i];
      } else {
        cur += c;
      }
    } else if (c == '\'' || c == '"') {
      quote = c;
      in_word = true;
    } else if (c == '\\' && i + 1 < command.size()) {
      cur += command[++i];
      in_word = true;
    } else if (std::isspace(static_cast<unsigned char>(c))) {
      if (in_word) words.push_back(cur);
      cur.clear();
      in_word = false;
    } else {
      cur += c;
      in_word = true;
    }
  }
  if (quote != 0) return InvalidArgument(std::string("unbalanced ") + quote + " quote");
  if (in_word) words.push_back(cur);
  return words;
}

Result<double> ParseDuration(const std::string& text) {
  if (text.empty()) return InvalidArgument("empty duration");
  double total = 0;
  std::size_t i = 0;
  bool any = false;
  while (i < text.size()) {
    std::size_t j = i;
    while (j < text.size() && (std::isdigit(static_cast<unsigned char>(text[j])) || text[j] == '.')) ++j;
    if (j == i) return InvalidArgument("'" + text + "' is not a duration like 10s, 1m30s, 500ms");
    const double v = std::stod(text.substr(i, j - i));
    std::size_t k = j;
    while (k < text.size() && std::isalpha(static_cast<unsigned char>(text[k]))) ++k;
    const std::string unit = text.substr(j, k - j);
    double scale = 0;
    if (unit.empty() || unit == "s") scale = 1;
    else if (unit == "ms") scale = 1e-3;
    else if (unit == "us") scale = 1e-6;
    else if (unit == "m") scale = 60;
    else if (unit == "h") scale = 3600;
    else return InvalidArgument("'" + text + "': unknown unit '" + unit + "'");
    total += v * scale;
    any = true;
    i = k;
  }
  if (!any) return InvalidArgument("'" + text + "' is not a duration");
  return total;
}

Result<ComposeProject> ParseCompose(const std::string& text, const std::string& file) {
  const Errors err(file);
  ROVER_ASSIGN_OR_RETURN(const YAML::Node root, yaml::Load(text, err));
  if (!root.IsMap()) return err.At(1, "expected a map with a 'services' key");
  ROVER_RETURN_IF_ERROR(CheckKeys(root, "top level",
                                  {"version", "name", "services", "networks", "volumes"}, err,
                                  kComposeKeys));
  ComposeProject project;
  project.file = file;
  if (const auto r = root["x-rover"]) ROVER_RETURN_IF_ERROR(ParseRover(r, err, &project.rover));
  if (project.rover.project.empty()) {
    project.rover.project = root["name"] ? ScalarText(root["name"]) : ProjectFromFile(file);
  }
  const YAML::Node services = root["services"];
  if (!services || !services.IsMap() || services.size() == 0) {
    return err.At(services ? services : root, "'services' must be a non-empty map");
  }
  std::set<std::string> names;
  for (const auto& kv : services) {
    const std::string name = kv.first.Scalar();
    if (!names.insert(name).second) {
      return err.At(kv.first, "services: duplicate service name '" + name + "'");
    }
    if (name.empty() || name.size() > 63 ||
        !std::all_of(name.begin(), name.end(), [](unsigned char c) {
          return std::isalnum(c) || c == '-' || c == '_' || c == '.';
        })) {
      return err.At(kv.first, "services: '" + name +
                                  "' is not a valid service name ([A-Za-z0-9._-], at most 63)");
    }
    ServiceSpec s;
    ROVER_RETURN_IF_ERROR(ParseService(name, kv.first, kv.second, err, &s));
    project.services.push_back(std::move(s));
  }
  ROVER_RETURN_IF_ERROR(OrderServices(&project.services, err));
  return project;
}

Result<ComposeProject> LoadComposeFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) return NotFound(path + ": cannot open compose file");
  std::stringstream ss;
  ss << in.rdbuf();
  return ParseCompose(ss.str(), path);
}

}  // namespace rover::deploy
