#include "rover/sim/rover_sim/pacer.hpp"

#include <algorithm>

#include "rover/base/format.hpp"
#include "rover/base/param_binder.hpp"
#include "rover/base/range_check.hpp"
#include "rover/base/lockstep_rule.hpp"

namespace rover::sim::rover_sim {

Status PacerOptions::Validate() const {
  ROVER_RETURN_IF_ERROR(CheckRange("real_time_factor", real_time_factor, 0.0, 1000.0));
  ROVER_RETURN_IF_ERROR(CheckRange("lockstep_lead_s", lockstep_lead_s, 0.0, 10.0, "s"));
  if (lockstep_lead_s > 0.0 && lockstep_lead_s < kMinLockstepLeadS) {
    return InvalidArgument(Describe("lockstep_lead_s", lockstep_lead_s, "s") +
                           " is below the services' acknowledgement granularity; use 0 (free "
                           "running) or at least " +
                           FormatNumber(kMinLockstepLeadS) + " s");
  }
  ROVER_RETURN_IF_ERROR(CheckRange("lockstep_stall_s", lockstep_stall_s, 0.1, 3600.0, "s"));
  ROVER_RETURN_IF_ERROR(CheckRange("lockstep_quantum_s", lockstep_quantum_s, 0.001, 1.0, "s"));
  if (lockstep_services.find_first_of(" \t") != std::string::npos) {
    return InvalidArgument("lockstep_services: '" + lockstep_services +
                           "' has a space; give the names comma-separated");
  }
  if (lockstep_strict && Pacer::ParseServices(lockstep_services).empty()) {
    return InvalidArgument(
        "lockstep_services: empty, but lockstep_strict is on: name the services to wait for "
        "(comma-separated, as their --name)");
  }
  return Status::Ok();
}

std::vector<std::string> Pacer::ParseServices(const std::string& list) {
  std::vector<std::string> out;
  std::size_t pos = 0;
  while (pos <= list.size()) {
    const std::size_t end = std::min(list.find(',', pos), list.size());
    if (end > pos) out.push_back(list.substr(pos, end - pos));
    pos = end + 1;
  }
  return out;
}

void PacerOptions::BindParams(ParamBinder<PacerOptions>& b) {
  b.Bind("real_time_factor", &PacerOptions::real_time_factor, "",
         "simulated seconds per wall second; 0 = as fast as possible")
      .Range(0.0, 1000.0);
  b.Bind("start_paused", &PacerOptions::start_paused,
         "wait for a SIM_RESUME on sim/control before running");
  b.Bind("lockstep_lead_s", &PacerOptions::lockstep_lead_s, "s",
         "run at most this far ahead of the slowest service's sim/clock_ack (0 = free running)")
      .Range(0.0, 10.0);
  b.Bind("lockstep_stall_s", &PacerOptions::lockstep_stall_s, "s",
         "wall time a service may go without acknowledging before lock-step stops waiting for it "
         "(until it acknowledges again)")
      .Range(0.1, 3600.0);
  b.Bind("lockstep_strict", &PacerOptions::lockstep_strict,
         "strict lock-step: sim/clock only at quantum ends, each quantum only after every "
         "service in lockstep_services has served the last (reproducible runs)");
  b.Bind("lockstep_quantum_s", &PacerOptions::lockstep_quantum_s, "s",
         "simulated time between two strict lock-step barriers (a whole number of periods)")
      .Range(0.001, 1.0);
  b.Bind("lockstep_services", &PacerOptions::lockstep_services,
         "the services strict lock-step waits for, comma-separated (their --name)");
  b.Bind("lockstep_pipelined", &PacerOptions::lockstep_pipelined,
         "strict: step a quantum while the services serve the tick that began it (their inputs "
         "apply one quantum later; faster, not yet bit-reproducible: docs/scenarios.md)");
}

Pacer::Pacer(const PacerOptions& options)
    : options_(options),
      rtf_(options.real_time_factor),
      paused_(options.start_paused),
      expected_(options.lockstep_strict ? ParseServices(options.lockstep_services)
                                        : std::vector<std::string>{}) {}

void Pacer::SetBarrier(std::int64_t sim_ns, Time wall_now) {
  if (sim_ns < barrier_ns_) {
    // Time went back (a reset): what was acknowledged before says nothing about the new time.
    for (auto& [name, s] : acks_) s.seen = false;
  }
  barrier_ns_ = sim_ns;
  barrier_wall_ = wall_now;
}

std::vector<std::string> Pacer::Missing() const {
  std::vector<std::string> out;
  const bool idle_known = frontier_ns_ == barrier_ns_;
  for (const auto& name : expected_) {
    if (idle_known && std::find(idle_.begin(), idle_.end(), name) != idle_.end()) continue;
    auto it = acks_.find(name);
    if (it == acks_.end() || !it->second.seen || it->second.sim_time_ns < barrier_ns_) {
      out.push_back(name);
    }
  }
  return out;
}

void Pacer::Anchor(Time wall_now, double sim_s) {
  wall_anchor_ = wall_now;
  sim_anchor_ = sim_s;
}

void Pacer::Resume(Time wall_now, double sim_s) {
  paused_ = false;
  Anchor(wall_now, sim_s);
}

Status Pacer::SetRealTimeFactor(double rtf, Time wall_now, double sim_s) {
  ROVER_RETURN_IF_ERROR(CheckRange("real_time_factor", rtf, 0.0, 1000.0));
  rtf_ = rtf;
  Anchor(wall_now, sim_s);
  return Status::Ok();
}

std::string Pacer::OnAck(const std::string& service, std::int64_t acked_ns, Time wall_now) {
  if (service == self_) return {};
  AckState& s = acks_[service];
  if (s.seen && acked_ns == s.sim_time_ns) return {};
  s.seen = true;
  s.sim_time_ns = acked_ns;
  s.changed = wall_now;
  if (s.waited_on) return {};
  s.waited_on = true;
  return service;
}

Duration Pacer::UntilNextStep(Time wall_now, double sim_s, std::vector<std::string>* dropped) {
  if (paused_) return kPausedPoll;
  if (options_.lockstep_strict) {
    if (!stalled_.empty()) return kPausedPoll;
    if (!options_.lockstep_pipelined) {
      const Duration d = UntilBarrierServed(wall_now);
      if (d > Duration::zero()) return d;
    }
  } else if (lockstep()) {
    const std::int64_t need = Time::FromSeconds(sim_s - options_.lockstep_lead_s).ns;
    for (auto& [name, s] : acks_) {
      if (!s.waited_on || s.sim_time_ns >= need) continue;
      if (wall_now - s.changed > Seconds(options_.lockstep_stall_s)) {
        s.waited_on = false;
        if (dropped != nullptr) dropped->push_back(name);
        continue;
      }
      return kLockstepPoll;
    }
  }
  if (rtf_ > 0.0) {
    const Time due = wall_anchor_ + Seconds((sim_s - sim_anchor_) / rtf_);
    if (wall_now < due) return due - wall_now;
  }
  return Duration::zero();
}

void Pacer::OnWritten(const std::string& service, std::vector<std::uint64_t> counts) {
  written_[service] = std::move(counts);
}

std::vector<std::uint64_t> Pacer::CurrentCounts(const std::vector<std::uint64_t>& own) const {
  std::vector<std::uint64_t> out = own;
  for (const auto& [service, counts] : written_) {
    if (counts.size() > out.size()) out.resize(counts.size(), 0);
    for (std::size_t i = 0; i < counts.size(); ++i) out[i] += counts[i];
  }
  return out;
}

const std::vector<std::uint64_t>& Pacer::FrontierFor(std::int64_t tick_ns,
                                                     const std::vector<std::uint64_t>& own,
                                                     bool* fresh) {
  const bool compute = frontier_ns_ != tick_ns || frontier_.empty();
  if (compute) {
    frontier_ = CurrentCounts(own);
    frontier_ns_ = tick_ns;
    recent_frontiers_.emplace_back(tick_ns, frontier_);
    constexpr std::size_t kRecentFrontiers = 8;
    while (recent_frontiers_.size() > kRecentFrontiers) recent_frontiers_.pop_front();
    // Who has nothing to do at this tick: the same rule the participants apply.
    idle_.clear();
    for (const auto& name : expected_) {
      auto it = acks_.find(name);
      if (it == acks_.end() || !it->second.idle_known) continue;
      const AckState& a = it->second;
      if (!lockstep::MustServe(tick_ns, frontier_, a.reads, a.served, a.next_due_ns)) {
        idle_.push_back(name);
      }
    }
  }
  if (fresh != nullptr) *fresh = compute;
  return frontier_;
}

bool Pacer::SendsTickTo(const std::string& service, bool repeat) const {
  return repeat || std::find(idle_.begin(), idle_.end(), service) == idle_.end();
}

void Pacer::OnIdleState(const std::string& service, std::int64_t acked_ns,
                        std::int64_t next_due_ns, std::uint64_t reads) {
  if (service == self_) return;
  AckState& s = acks_[service];
  auto it = std::find_if(recent_frontiers_.begin(), recent_frontiers_.end(),
                         [acked_ns](const auto& f) { return f.first == acked_ns; });
  s.idle_known = it != recent_frontiers_.end();
  if (s.idle_known) s.served = it->second;
  s.next_due_ns = next_due_ns;
  s.reads = reads;
}

Duration Pacer::UntilBarrierServed(Time wall_now) {
  if (!stalled_.empty()) return kPausedPoll;
  const std::vector<std::string> missing = Missing();
  if (missing.empty()) return Duration::zero();
  // Stalled: no acknowledgement of the barrier for lockstep_stall_s since it was set (or, for a
  // service that acknowledged something later, since then).
  for (const auto& name : missing) {
    auto it = acks_.find(name);
    const Time since = it != acks_.end() && it->second.seen
                           ? std::max(it->second.changed, barrier_wall_)
                           : barrier_wall_;
    if (wall_now - since > Seconds(options_.lockstep_stall_s)) {
      stalled_ = name;
      return kPausedPoll;
    }
  }
  return kStrictWait;
}

double Pacer::MeasuredRealTimeFactor(Time wall_now, double sim_s) const {
  const double wall = ToSeconds(wall_now - wall_anchor_);
  return wall > 0.0 ? (sim_s - sim_anchor_) / wall : 0.0;
}

std::vector<std::string> Pacer::services_waited_on() const {
  std::vector<std::string> out;
  for (const auto& [name, s] : acks_) {
    if (s.waited_on) out.push_back(name);
  }
  return out;
}

}  // namespace rover::sim::rover_sim
