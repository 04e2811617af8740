#include "rover/deploy/fault_commands.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cstdio>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <thread>

#include "rover/base/clock.hpp"
#include "rover/deploy/set_faults.hpp"
#include "rover/runtime/dds.hpp"
#include "rover/runtime/fault_control.hpp"
#include "rover/runtime/fault_yaml.hpp"

namespace rover::deploy {
namespace {

using faults::FaultRecord;
using Event = faults::FaultRecord::Event;

constexpr const char* kSource = "fault add";
constexpr const char* kNotHere = " (not for this service)";

// Messages about an inline spec or flags name "fault add", not a line of a text nobody wrote.
Status Unlined(const Status& s) {
  if (s.ok()) return s;
  static const std::regex kPrefix(R"(^fault add(:[0-9]+|: fault [0-9]+): )");
  return InvalidArgument(std::regex_replace(
      s.message(), kPrefix, "fault add: ", std::regex_constants::format_first_only));
}

Result<YAML::Node> InlineMap(const FaultAddArgs& a) {
  YAML::Node map(YAML::NodeType::Map);
  if (!a.inline_spec.empty()) {
    try {
      map = YAML::Load(a.inline_spec);
    } catch (const YAML::ParserException& e) {
      return InvalidArgument(std::string(kSource) + ": malformed YAML spec: " + e.msg);
    }
    if (!map.IsMap()) {
      return InvalidArgument(std::string(kSource) +
                             ": the spec is a YAML map, e.g. '{kind: drop, topic: dl/pose}'");
    }
  }
  for (const auto& [key, value] : a.keys) {
    if (key == "delay" && value.find('{') != std::string::npos) {
      try {
        map[key] = YAML::Load(value);
      } catch (const YAML::ParserException& e) {
        return InvalidArgument(std::string(kSource) + ": --delay: malformed YAML: " + e.msg);
      }
    } else {
      map[key] = value;  // a plain scalar, whatever it starts with ('*', '!')
    }
  }
  return map;
}

bool Applies(const FaultRecord& r) { return AppliesInService(r); }

std::string Names(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out.empty() ? "none" : out;
}

// A participant and a fault client on the set's domain, matched with every agent.
struct Session {
  dds::Participant participant;
  std::optional<faults::FaultClient> client;
};

Result<std::unique_ptr<Session>> Open(const FaultTarget& t) {
  auto s = std::make_unique<Session>();
  ROVER_ASSIGN_OR_RETURN(s->participant, dds::Participant::Create(t.domain));
  ROVER_ASSIGN_OR_RETURN(auto client, faults::FaultClient::Create(s->participant));
  s->client.emplace(std::move(client));
  const int n = static_cast<int>(t.services.size());
  const Status w = s->client->WaitForServices(n, Seconds(t.discovery_s));
  if (!w.ok()) {
    return Unavailable("'" + t.project + "' on domain " + std::to_string(t.domain) + ": " +
                       w.message() + " (expected: " + Names(t.services) + "); nothing was sent");
  }
  return s;
}

// Collects records until every service has sent one that `answers` accepts, or `answer_s`.
std::vector<FaultRecord> Collect(faults::FaultClient& client, const FaultTarget& t,
                                 const std::function<bool(const FaultRecord&)>& answers,
                                 std::vector<FaultRecord>* others = nullptr) {
  std::vector<FaultRecord> got;
  std::set<std::string> answered;
  const Time end = MonotonicNow() + Seconds(t.answer_s);
  while (MonotonicNow() < end && answered.size() < t.services.size()) {
    for (auto& r : client.TakeRecords()) {
      if (answers(r)) {
        answered.insert(r.service);
        got.push_back(std::move(r));
      } else if (others != nullptr) {
        others->push_back(std::move(r));
      }
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return got;
}

std::vector<std::string> Missing(const FaultTarget& t, const std::vector<FaultRecord>& got) {
  std::vector<std::string> out;
  for (const auto& s : t.services) {
    if (std::none_of(got.begin(), got.end(), [&](const auto& r) { return r.service == s; })) {
      out.push_back(s);
    }
  }
  return out;
}

}  // namespace

Result<std::vector<faults::FaultSpec>> BuildFaultSpecs(const FaultAddArgs& a,
                                                       const std::vector<std::uint32_t>& used) {
  std::vector<faults::FaultSpec> specs;
  if (!a.file.empty()) {
    if (!a.inline_spec.empty() || !a.keys.empty()) {
      return InvalidArgument("fault add: give a file (-f) or a spec and flags, not both");
    }
    ROVER_ASSIGN_OR_RETURN(specs, faults::LoadFaultsFile(a.file));
    if (specs.empty()) return InvalidArgument(a.file + ": holds no faults");
  } else {
    if (a.inline_spec.empty() && a.keys.empty()) {
      return InvalidArgument(
          "fault add: give a spec ('{kind: drop, topic: dl/pose}'), flags "
          "(--kind drop --topic dl/pose) or a file (-f FILE)");
    }
    ROVER_ASSIGN_OR_RETURN(YAML::Node map, InlineMap(a));
    YAML::Node list(YAML::NodeType::Sequence);
    list.push_back(map);
    auto parsed = faults::ParseFaults(list, kSource);
    if (!parsed.ok()) return Unlined(parsed.status());
    specs = std::move(*parsed);
  }
  std::uint32_t next = 1;
  for (std::uint32_t id : used) next = std::max(next, id + 1);
  std::set<std::uint32_t> taken(used.begin(), used.end());
  for (auto& s : specs) {
    if (s.key_lines.count("id") == 0) {
      while (taken.count(next)) ++next;
      s.id = next++;
    }
    taken.insert(s.id);
    if (!a.from_epoch) s.start_mode = faults::StartMode::kOnReceipt;
    ROVER_RETURN_IF_ERROR(a.file.empty() ? Unlined(s.Validate()) : s.Validate());
  }
  return specs;
}

std::string FormatFaultList(const std::vector<FaultRecord>& listed) {
  std::vector<FaultRecord> rows = listed;
  std::sort(rows.begin(), rows.end(), [](const auto& a, const auto& b) {
    return a.fault_id != b.fault_id ? a.fault_id < b.fault_id : a.service < b.service;
  });
  std::string out;
  char buf[256];
  std::snprintf(buf, sizeof buf, "%-4s %-10s %-8s %-22s %10s %10s  %s\n", "ID", "KIND", "STATE",
                "SERVICE", "SEEN", "HIT", "FAULT");
  out += buf;
  std::set<std::uint32_t> ids, shown;
  for (const auto& r : rows) {
    ids.insert(r.fault_id);
    if (!Applies(r)) continue;
    shown.insert(r.fault_id);
    const std::size_t colon = r.detail.find(": ");
    const std::string state = colon == std::string::npos ? "?" : r.detail.substr(0, colon);
    const std::string what = colon == std::string::npos ? r.detail : r.detail.substr(colon + 2);
    std::snprintf(buf, sizeof buf, "%-4u %-10s %-8s %-22s %10llu %10llu  ", r.fault_id,
                  faults::FaultKindName(r.kind), state.c_str(), r.service.c_str(),
                  static_cast<unsigned long long>(r.seen), static_cast<unsigned long long>(r.hit));
    out += buf + what + "\n";
  }
  for (const auto& r : rows) {  // held everywhere, applied nowhere (its service matches none)
    if (shown.count(r.fault_id)) continue;
    shown.insert(r.fault_id);
    std::string what =
        r.detail.substr(0, r.detail.size() - std::char_traits<char>::length(kNotHere));
    const std::size_t colon = what.find(": ");
    const std::string state = colon == std::string::npos ? "?" : what.substr(0, colon);
    if (colon != std::string::npos) what = what.substr(colon + 2);
    std::snprintf(buf, sizeof buf, "%-4u %-10s %-8s %-22s %10s %10s  ", r.fault_id,
                  faults::FaultKindName(r.kind), state.c_str(), "-", "-", "-");
    out += buf + what + " (no service of the set matches)\n";
  }
  if (ids.empty()) out += "(no faults)\n";
  return out;
}

int RunFaultAdd(const FaultTarget& t, const FaultAddArgs& a, std::ostream& out, std::ostream& err) {
  // Everything that can be checked without the set, before talking to it.
  if (auto pre = BuildFaultSpecs(a, {}); !pre.ok()) {
    err << "roverctl: error: " << pre.status().message() << "\n";
    return 2;
  }
  auto session = Open(t);
  if (!session.ok()) {
    err << "roverctl: error: " << session.status().message() << "\n";
    return 1;
  }
  faults::FaultClient& client = *(*session)->client;
  std::vector<std::uint32_t> used;
  for (const auto& r : client.List(Seconds(std::min(1.0, t.answer_s)))) used.push_back(r.fault_id);
  auto specs = BuildFaultSpecs(a, used);
  if (!specs.ok()) {
    err << "roverctl: error: " << specs.status().message() << "\n";
    return 2;
  }
  std::vector<std::uint32_t> sent;
  int rc = 0;
  for (const auto& spec : *specs) {
    if (const Status s = client.Add(spec); !s.ok()) {
      err << "roverctl: error: fault " << spec.id << ": " << s.message() << "\n";
      rc = 1;
      break;
    }
    sent.push_back(spec.id);
    std::vector<FaultRecord> other;
    const auto answers = Collect(
        client, t,
        [&](const FaultRecord& r) {
          return r.fault_id == spec.id && (r.event == Event::kAdded || r.event == Event::kRejected);
        },
        &other);
    std::vector<std::string> applied, held, rejected, started;
    for (const auto& r : answers) {
      if (r.event == Event::kRejected) {
        rejected.push_back(r.service + ": " + r.detail);
      } else {
        held.push_back(r.service);
        if (Applies(r)) applied.push_back(r.service);
      }
    }
    for (const auto& r : other) {
      if (r.fault_id == spec.id && r.event == Event::kStarted) started.push_back(r.service);
    }
    const auto missing = Missing(t, answers);
    if (!rejected.empty() || !missing.empty()) {
      for (const auto& j : rejected)
        err << "roverctl: error: fault " << spec.id << " rejected by " << j << "\n";
      if (!missing.empty()) {
        err << "roverctl: error: fault " << spec.id << ": no answer from " << Names(missing)
            << " within " << t.answer_s << " s\n";
      }
      rc = 1;
      break;
    }
    out << "roverctl: " << spec.Describe() << "\n"
        << "  applies in: " << Names(applied) << " (held by " << held.size() << " of "
        << t.services.size() << " services)";
    if (!started.empty()) out << "; started in: " << Names(started);
    out << "\n";
    if (applied.empty()) {
      out << "  warning: its service pattern '" << spec.service
          << "' matches no service of the set\n";
    }
  }
  if (rc != 0 && !sent.empty()) {
    // All or nothing: take back what was sent.
    for (std::uint32_t id : sent) (void)client.Remove(id);
    (void)Collect(client, t, [](const FaultRecord&) { return false; });
    err << "roverctl: nothing applied (fault" << (sent.size() > 1 ? "s" : "");
    for (std::uint32_t id : sent) err << " " << id;
    err << " removed again)\n";
  }
  out << std::flush;
  return rc;
}

int RunFaultList(const FaultTarget& t, bool json, std::ostream& out, std::ostream& err) {
  auto session = Open(t);
  if (!session.ok()) {
    err << "roverctl: error: " << session.status().message() << "\n";
    return 1;
  }
  const auto listed = (*session)->client->List(Seconds(std::min(1.5, t.answer_s)));
  if (json) {
    nlohmann::json all = nlohmann::json::array();
    for (const auto& r : listed) {
      const std::size_t colon = r.detail.find(": ");
      all.push_back({{"id", r.fault_id},
                     {"kind", faults::FaultKindName(r.kind)},
                     {"service", r.service},
                     {"applies", Applies(r)},
                     {"state", colon == std::string::npos ? "" : r.detail.substr(0, colon)},
                     {"topic", r.topic},
                     {"samples_seen", r.seen},
                     {"samples_hit", r.hit},
                     {"start_ns", r.start.ns},
                     {"end_ns", r.end ? r.end->ns : 0},
                     {"detail", r.detail}});
    }
    out << all.dump(2) << "\n";
  } else {
    out << FormatFaultList(listed);
  }
  out << std::flush;
  return 0;
}

int RunFaultClear(const FaultTarget& t, std::optional<std::uint32_t> id, std::ostream& out,
                  std::ostream& err) {
  auto session = Open(t);
  if (!session.ok()) {
    err << "roverctl: error: " << session.status().message() << "\n";
    return 1;
  }
  faults::FaultClient& client = *(*session)->client;
  (void)client.TakeRecords();
  const Status s = id ? client.Remove(*id) : client.Clear();
  if (!s.ok()) {
    err << "roverctl: error: " << s.message() << "\n";
    return 1;
  }
  auto ends = [](const FaultRecord& r) {
    return r.event == Event::kEnded || r.event == Event::kRemoved;
  };
  if (!id) {
    // Services without faults do not answer CLEAR: wait the whole answer time.
    std::vector<FaultRecord> got;
    const Time end = MonotonicNow() + Seconds(std::min(1.5, t.answer_s));
    while (MonotonicNow() < end) {
      for (auto& r : client.TakeRecords()) {
        if (ends(r)) got.push_back(std::move(r));
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    std::set<std::uint32_t> ids;
    std::set<std::string> services;
    for (const auto& r : got) {
      ids.insert(r.fault_id);
      services.insert(r.service);
    }
    out << "roverctl: cleared " << ids.size() << " fault" << (ids.size() == 1 ? "" : "s") << " in "
        << services.size() << " service" << (services.size() == 1 ? "" : "s") << "\n";
    for (const auto& r : got) {
      if (Applies(r) && r.event == Event::kEnded) {
        out << "  fault " << r.fault_id << " in " << r.service << ": " << r.hit << " of " << r.seen
            << " samples hit\n";
      }
    }
    out << std::flush;
    return 0;
  }
  const auto answers = Collect(client, t, [&](const FaultRecord& r) {
    return r.fault_id == *id && (ends(r) || r.event == Event::kRejected);
  });
  std::vector<std::string> removed;
  std::uint64_t hit = 0, seen = 0;
  for (const auto& r : answers) {
    if (r.event == Event::kRejected) continue;
    removed.push_back(r.service);
    hit += r.hit;
    seen += r.seen;
  }
  if (removed.empty()) {
    err << "roverctl: error: no fault " << *id << " in '" << t.project
        << "' (`roverctl fault list` shows the ids)\n";
    return 1;
  }
  out << "roverctl: fault " << *id << " removed in " << Names(removed) << "; " << hit << " of "
      << seen << " samples hit in all\n";
  if (const auto missing = Missing(t, answers); !missing.empty()) {
    out << "  warning: no answer from " << Names(missing) << "\n";
  }
  out << std::flush;
  return 0;
}

}  // namespace rover::deploy
