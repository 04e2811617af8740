#include "rover/runtime/discovery.hpp"

#include <cstdio>
#include <cstring>
#include <map>
#include <thread>

namespace rover::dds {
namespace {

std::string GuidPrefix(const dds_guid_t& g) {
  char b[40];
  std::snprintf(b, sizeof b, "%02x%02x%02x%02x:%02x%02x%02x%02x:%02x%02x%02x%02x", g.v[0],
                g.v[1], g.v[2], g.v[3], g.v[4], g.v[5], g.v[6], g.v[7], g.v[8], g.v[9], g.v[10],
                g.v[11]);
  return b;
}

bool SameParticipant(const dds_guid_t& a, const dds_guid_t& b) {
  return std::memcmp(a.v, b.v, 12) == 0;
}

// "pid 123 (ddl-imu)" from the properties Cyclone announces with a participant, if any.
std::map<std::string, std::string> ParticipantNames(dds_entity_t p) {
  std::map<std::string, std::string> out;
  const dds_entity_t r = dds_create_reader(p, DDS_BUILTIN_TOPIC_DCPSPARTICIPANT, nullptr, nullptr);
  if (r < 0) return out;
  void* ptrs[64] = {nullptr};
  dds_sample_info_t infos[64];
  const dds_return_t n = dds_read(r, ptrs, infos, 64, 64);
  for (dds_return_t i = 0; i < n; ++i) {
    if (!infos[i].valid_data) continue;
    const auto* s = static_cast<const dds_builtintopic_participant_t*>(ptrs[i]);
    char* pid = nullptr;
    char* name = nullptr;
    std::string text;
    if (s->qos && dds_qget_prop(s->qos, "__Pid", &pid) && pid) text = std::string("pid ") + pid;
    if (s->qos && dds_qget_prop(s->qos, "__ProcessName", &name) && name) {
      text += (text.empty() ? "" : " ") + std::string("(") + name + ")";
    }
    dds_free(pid);
    dds_free(name);
    if (!text.empty()) out[GuidPrefix(s->key)] = text;
  }
  if (n > 0) dds_return_loan(r, ptrs, n);
  dds_delete(r);
  return out;
}

}  // namespace

Result<std::vector<RemoteWriter>> DiscoverRemoteWriters(const Participant& p, Duration wait) {
  dds_guid_t self{};
  if (const dds_return_t rc = dds_get_guid(p.handle(), &self); rc < 0) {
    return DdsError("reading the participant's GUID", rc);
  }
  const dds_entity_t r =
      dds_create_reader(p.handle(), DDS_BUILTIN_TOPIC_DCPSPUBLICATION, nullptr, nullptr);
  if (r < 0) return DdsError("reading the built-in publication topic", r);
  std::this_thread::sleep_for(wait);
  std::vector<RemoteWriter> out;
  constexpr std::uint32_t kBatch = 64;
  void* ptrs[kBatch];
  dds_sample_info_t infos[kBatch];
  std::vector<std::pair<std::string, RemoteWriter>> found;
  while (true) {
    ptrs[0] = nullptr;
    const dds_return_t n =
        dds_take_mask(r, ptrs, infos, kBatch, kBatch, DDS_ANY_SAMPLE_STATE | DDS_ANY_VIEW_STATE |
                                                          DDS_ALIVE_INSTANCE_STATE);
    if (n <= 0) break;
    for (dds_return_t i = 0; i < n; ++i) {
      if (!infos[i].valid_data) continue;
      const auto* e = static_cast<const dds_builtintopic_endpoint_t*>(ptrs[i]);
      if (SameParticipant(e->participant_key, self)) continue;
      found.push_back({GuidPrefix(e->participant_key),
                       {e->topic_name ? e->topic_name : "", e->type_name ? e->type_name : "", ""}});
    }
    dds_return_loan(r, ptrs, n);
    if (static_cast<std::uint32_t>(n) < kBatch) break;
  }
  dds_delete(r);
  const auto names = found.empty() ? std::map<std::string, std::string>{}
                                   : ParticipantNames(p.handle());
  for (auto& [guid, w] : found) {
    const auto it = names.find(guid);
    w.participant = it != names.end() ? it->second + " " + guid : guid;
    out.push_back(std::move(w));
  }
  return out;
}

}  // namespace rover::dds
