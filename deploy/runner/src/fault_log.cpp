#include "rover/deploy/runner/fault_log.hpp"

#include <algorithm>

#include "rover/deploy/set_faults.hpp"

namespace rover::deploy::runner {

namespace {

double Seconds(Time t) { return static_cast<double>(t.ns) * 1e-9; }

InjectedFault FromSpec(const faults::FaultSpec& s) {
  InjectedFault f;
  f.id = s.id;
  f.name = s.name;
  f.kind = faults::FaultKindName(s.kind);
  f.topic = s.topic;
  f.service = s.service;
  f.side = faults::SideName(s.side);
  f.description = s.Describe();
  return f;
}

}  // namespace

FaultLog::FaultLog(std::vector<faults::FaultSpec> specs) {
  for (const auto& s : specs) entries_[s.id].fault = FromSpec(s);
}

FaultLog::Entry& FaultLog::EntryFor(const faults::FaultRecord& r) {
  auto [it, added] = entries_.try_emplace(r.fault_id);
  if (added) {  // not one of the set's specs (added over sys/fault_control): what the record says
    InjectedFault& f = it->second.fault;
    f.id = r.fault_id;
    f.kind = faults::FaultKindName(r.kind);
    f.topic = r.topic;
    f.description = r.detail;
  }
  return it->second;
}

void FaultLog::Add(const faults::FaultRecord& r) {
  using Event = faults::FaultRecord::Event;
  if (r.event == Event::kRejected || r.fault_id == 0) return;
  Entry& e = EntryFor(r);
  PerService& p = e.services[r.service];
  p.seen = std::max(p.seen, r.seen);
  p.hit = std::max(p.hit, r.hit);
  InjectedFault& f = e.fault;
  if (!AppliesInService(r)) return;  // held there, acting elsewhere
  const bool listed_active = r.event == Event::kListed && r.detail.rfind("active", 0) == 0;
  const bool listed_ended = r.event == Event::kListed && r.detail.rfind("ended", 0) == 0;
  if (r.event == Event::kStarted || r.event == Event::kCount || listed_active ||
      (listed_ended && r.seen > 0) || (r.event == Event::kEnded && r.seen > 0)) {
    p.started = true;
    if (f.start_s < 0 || Seconds(r.start) < f.start_s) f.start_s = Seconds(r.start);
  }
  double end = -1;
  if (r.event == Event::kEnded) end = Seconds(r.at);
  if (listed_ended) end = r.end ? Seconds(*r.end) : Seconds(r.at);
  if (end >= 0 && (f.end_s < 0 || end < f.end_s)) f.end_s = end;
}

std::vector<InjectedFault> FaultLog::Summary() const {
  std::vector<InjectedFault> out;
  for (const auto& [id, e] : entries_) {
    InjectedFault f = e.fault;
    f.samples_seen = 0;
    f.samples_hit = 0;
    f.services.clear();
    for (const auto& [name, p] : e.services) {
      f.samples_seen += p.seen;
      f.samples_hit += p.hit;
      if (p.started) f.services.push_back(name);
    }
    if (f.start_s < 0) f.end_s = -1;  // never started: no end either
    out.push_back(std::move(f));
  }
  return out;
}

}  // namespace rover::deploy::runner
