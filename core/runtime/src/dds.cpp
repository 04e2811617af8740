#include "rover/runtime/dds.hpp"

#include "rover/runtime/security_files.hpp"
#include "rover/runtime/type_layout.hpp"

#include <atomic>
#include <cstdio>
#include <mutex>
#include <string>
#include <tuple>
#include <unordered_map>
#include <cstdlib>

namespace rover::dds {

Status DdsError(const std::string& what, dds_return_t rc) {
  return Unavailable(what + " failed: " + dds_strretcode(rc));
}

Result<Participant> Participant::Create(dds_domainid_t domain) {
  if (domain > 232) {
    return InvalidArgument("DDS domain " + std::to_string(domain) +
                           " is out of range [0, 232] (Cyclone's port mapping)");
  }
  ROVER_ASSIGN_OR_RETURN(const std::optional<SecurityIdentity> secured,
                         SecurityIdentityFromEnvironment());
  QosPtr qos(dds_create_qos());
  if (secured) {
    // DDS Security 1.1's participant properties: Cyclone's builtin authentication (PKI-DH),
    // access control (signed governance and permissions) and cryptography (AES-GCM-GMAC).
    const SecurityFiles f = SecurityFilesFor(secured->dir, secured->role);
    ROVER_RETURN_IF_ERROR(CheckSecurityFiles(f));
    ROVER_ASSIGN_OR_RETURN(const std::string lib, SecurityPluginDir());
    auto prop = [&](const char* name, const std::string& value) {
      dds_qset_prop(qos.get(), name, value.c_str());
    };
    // The three plugins: property prefix, library, init/finalize function suffix.
    for (const auto& [prefix, library, entry] :
         {std::tuple{"dds.sec.auth.", "auth", "authentication"},
          std::tuple{"dds.sec.access.", "ac", "access_control"},
          std::tuple{"dds.sec.crypto.", "crypto", "crypto"}}) {
      const std::string p = prefix;
      prop((p + "library.path").c_str(), lib + "/libdds_security_" + library + ".so");
      prop((p + "library.init").c_str(), std::string("init_") + entry);
      prop((p + "library.finalize").c_str(), std::string("finalize_") + entry);
    }
    prop("dds.sec.auth.identity_ca", "file:" + f.ca);
    prop("dds.sec.auth.identity_certificate", "file:" + f.certificate);
    prop("dds.sec.auth.private_key", "file:" + f.private_key);
    prop("dds.sec.access.permissions_ca", "file:" + f.ca);
    prop("dds.sec.access.governance", "file:" + f.governance);
    prop("dds.sec.access.permissions", "file:" + f.permissions);
  }
  const dds_entity_t h = dds_create_participant(domain, qos.get(), nullptr);
  if (h < 0) {
    if (secured) {
      return DdsError("creating a secured participant for identity '" + secured->role +
                          "' on domain " + std::to_string(domain) + " from " + secured->dir +
                          " (DDS Security refused the certificate, key or permissions: Cyclone's "
                          "reason is logged above; `roverctl security show` checks the files)",
                      h);
    }
    return DdsError("creating a participant on domain " + std::to_string(domain) +
                        " (check CYCLONEDDS_URI)",
                    h);
  }
  return Participant(h, domain);
}

namespace {
// ROVER_QOS_OVERRIDES="topic=profile,topic=profile" (set by roverctl from x-rover.qos).
std::optional<QosProfile> OverrideFor(const std::string& topic) {
  const char* env = std::getenv("ROVER_QOS_OVERRIDES");
  if (env == nullptr) return std::nullopt;
  const std::string all = env;
  std::size_t pos = 0;
  while (pos <= all.size()) {
    const std::size_t end = std::min(all.find(',', pos), all.size());
    const std::string item = all.substr(pos, end - pos);
    const std::size_t eq = item.find('=');
    if (eq != std::string::npos && item.substr(0, eq) == topic) {
      auto p = ParseQosProfile(item.substr(eq + 1));
      if (p.ok()) return *p;
    }
    pos = end + 1;
  }
  return std::nullopt;
}
}  // namespace

Result<QosProfile> ResolveProfile(const std::string& topic, const char* type_name,
                                  std::optional<QosProfile> requested) {
  if (auto o = OverrideFor(topic)) return *o;
  if (auto info = FindTopic(topic)) {
    if (info->type_name != type_name) {
      return InvalidArgument("topic '" + topic + "' carries " + std::string(info->type_name) +
                             " in the catalog, not " + type_name);
    }
    if (requested && *requested != info->profile) {
      return InvalidArgument("topic '" + topic + "' uses QoS profile '" +
                             QosProfileName(info->profile) + "' in the catalog, not '" +
                             QosProfileName(*requested) + "'");
    }
    return info->profile;
  }
  if (!requested) {
    return NotFound("topic '" + topic +
                    "' is not in the topic catalog; give a QoS profile for it explicitly");
  }
  return *requested;
}

namespace internal {

Result<dds_entity_t> CreateTopic(const Participant& p, const std::string& name,
                                 const dds_topic_descriptor_t* desc, QosProfile profile) {
  QosPtr qos = MakeQos(profile);
  const dds_entity_t t = dds_create_topic(p.handle(), desc, name.c_str(), qos.get(), nullptr);
  if (t < 0) return DdsError("creating topic '" + name + "'", t);
  return t;
}

Result<dds_entity_t> CreateEndpoint(const Participant& p, dds_entity_t topic, QosProfile profile,
                                    bool writer, const std::string& partition) {
  dds_entity_t parent = p.handle();
  if (!partition.empty()) {
    // A publisher / subscriber of its own (a child of the participant, deleted with it).
    QosPtr pq(dds_create_qos());
    dds_qset_partition1(pq.get(), partition.c_str());
    parent = writer ? dds_create_publisher(p.handle(), pq.get(), nullptr)
                    : dds_create_subscriber(p.handle(), pq.get(), nullptr);
    if (parent < 0) {
      return DdsError(writer ? "creating a publisher in partition '" + partition + "'"
                             : "creating a subscriber in partition '" + partition + "'",
                      parent);
    }
  }
  QosPtr qos = MakeQos(profile);
  if (lockstep::StrictProcess()) {
    // No sample may be lost (lockstep.hpp): every topic reliable, and histories deep enough
    // that neither a reader's cache nor a writer's resend buffer drops one.
    const QosSpec spec = DescribeQos(profile);
    if (!spec.reliable) dds_qset_reliability(qos.get(), DDS_RELIABILITY_RELIABLE, DDS_MSECS(100));
    const int deep = writer ? lockstep::kStrictWriterDepth : lockstep::kStrictReaderDepth;
    if (spec.history_depth != 0 && spec.history_depth < deep) {
      dds_qset_history(qos.get(), DDS_HISTORY_KEEP_LAST, deep);
    }
  }
  const dds_entity_t e = writer ? dds_create_writer(parent, topic, qos.get(), nullptr)
                                : dds_create_reader(parent, topic, qos.get(), nullptr);
  if (e < 0) {
    if (parent != p.handle()) dds_delete(parent);
    return DdsError(writer ? "creating a writer" : "creating a reader", e);
  }
  if (!writer) {
    const dds_return_t rc = dds_set_status_mask(e, DDS_DATA_AVAILABLE_STATUS);
    if (rc < 0) {
      dds_delete(parent != p.handle() ? parent : e);
      return DdsError("setting the reader status mask", rc);
    }
  }
  return e;
}

void CopySample(void* dst, const void* src, const dds_topic_descriptor_t* type) {
  auto layout = TypeLayout::For(type);
  ROVER_DEMAND_MSG(layout.ok() && (*layout)->copyable(), "CopySample on a type without a layout");
  (*layout)->CopyInto(dst, src);
}

}  // namespace internal

Result<GuardCondition> GuardCondition::Create(const Participant& p) {
  const dds_entity_t g = dds_create_guardcondition(p.handle());
  if (g < 0) return DdsError("creating a guard condition", g);
  return GuardCondition(g);
}

void GuardCondition::Trigger() { dds_set_guardcondition(handle_, true); }

bool GuardCondition::TakeTriggered() {
  bool triggered = false;
  dds_take_guardcondition(handle_, &triggered);
  return triggered;
}

Result<WaitSet> WaitSet::Create(const Participant& p) {
  const dds_entity_t w = dds_create_waitset(p.handle());
  if (w < 0) return DdsError("creating a waitset", w);
  return WaitSet(w);
}

Status WaitSet::Attach(dds_entity_t entity, dds_attach_t token) {
  const dds_return_t rc = dds_waitset_attach(handle_, entity, token);
  if (rc < 0) return DdsError("attaching to a waitset", rc);
  ++attached_;
  return Status::Ok();
}

Status WaitSet::Detach(dds_entity_t entity) {
  const dds_return_t rc = dds_waitset_detach(handle_, entity);
  if (rc < 0) return DdsError("detaching from a waitset", rc);
  --attached_;
  return Status::Ok();
}

std::vector<dds_attach_t> WaitSet::Wait(std::int64_t timeout_ns) {
  std::vector<dds_attach_t> out(attached_ + 1);
  const dds_return_t n =
      dds_waitset_wait(handle_, out.data(), out.size(), timeout_ns < 0 ? 0 : timeout_ns);
  out.resize(n > 0 ? static_cast<std::size_t>(n) : 0);
  return out;
}

}  // namespace rover::dds

namespace rover::dds::lockstep {
namespace {
thread_local std::int64_t t_write_tick = kOff;
thread_local std::int64_t t_read_gate = kOff;
std::atomic<std::uint64_t> g_late{0};
}  // namespace

void SetWriteTick(std::int64_t tick_ns) { t_write_tick = tick_ns; }
std::int64_t WriteTick() { return t_write_tick; }
void SetReadGate(std::int64_t before_ns) { t_read_gate = before_ns; }
std::int64_t ReadGate() { return t_read_gate; }

namespace {
struct WriterCount {
  dds_entity_t participant = 0;
  int topic = -1;
  std::uint64_t written = 0;
};
std::mutex g_writers_mu;
std::unordered_map<dds_entity_t, WriterCount> g_writers;
thread_local TopicCounts t_frontier;
std::atomic<std::uint64_t> g_missing{0};
}  // namespace

int CatalogIndex(std::string_view topic) {
  const auto& catalog = TopicCatalog();
  for (std::size_t i = 0; i < catalog.size(); ++i) {
    if (catalog[i].name == topic) return static_cast<int>(i);
  }
  return -1;
}

void RegisterWriter(dds_entity_t writer, dds_entity_t participant, std::string_view topic) {
  const int index = CatalogIndex(topic);
  if (index < 0) return;
  std::lock_guard lock(g_writers_mu);
  g_writers[writer] = WriterCount{participant, index, 0};
}

TopicCounts WrittenBy(dds_entity_t participant) {
  TopicCounts out(TopicCatalog().size(), 0);
  std::lock_guard lock(g_writers_mu);
  for (const auto& [w, c] : g_writers) {
    if (c.participant == participant) out[static_cast<std::size_t>(c.topic)] += c.written;
  }
  return out;
}

void SetFrontier(TopicCounts frontier) { t_frontier = std::move(frontier); }
const TopicCounts& Frontier() { return t_frontier; }
std::uint64_t MissingSamples() { return g_missing.load(std::memory_order_relaxed); }

dds_return_t Write(dds_entity_t writer, const void* sample) {
  const dds_return_t rc = t_write_tick == kOff
                              ? dds_write(writer, sample)
                              : dds_write_ts(writer, sample, static_cast<dds_time_t>(t_write_tick));
  if (rc == DDS_RETCODE_OK) {
    std::lock_guard lock(g_writers_mu);
    if (auto it = g_writers.find(writer); it != g_writers.end()) ++it->second.written;
  }
  return rc;
}

namespace {
std::atomic<bool> g_strict_process{false};
}  // namespace
void SetStrictProcess(bool strict) { g_strict_process.store(strict); }
bool StrictProcess() { return g_strict_process.load(); }

std::string ClockPartition(std::string_view service) {
  return "rover.clock." + std::string(service);
}

bool Ungated(std::string_view topic) {
  return topic == "sim/clock" || topic == "sim/clock_ack" || topic == "sim/control";
}

std::uint64_t LateSamples() { return g_late.load(std::memory_order_relaxed); }
namespace {
std::mutex g_late_mu;
std::string g_last_late;
}  // namespace

void CountLateSample(std::string_view topic, std::int64_t written_ns, std::int64_t gate_ns) {
  g_late.fetch_add(1, std::memory_order_relaxed);
  char text[64];
  std::snprintf(text, sizeof text, " written at %.3f s, handed out at %.3f s",
                static_cast<double>(written_ns) * 1e-9, static_cast<double>(gate_ns) * 1e-9);
  std::lock_guard lock(g_late_mu);
  g_last_late = std::string(topic) + text;
}

void CountMissingSamples(std::string_view topic, std::uint64_t n) {
  g_missing.fetch_add(n, std::memory_order_relaxed);
  std::lock_guard lock(g_late_mu);
  g_last_late = std::to_string(n) + " sample(s) of " + std::string(topic) + " never arrived";
}

std::string LastLateSample() {
  std::lock_guard lock(g_late_mu);
  return g_last_late;
}

}  // namespace rover::dds::lockstep
