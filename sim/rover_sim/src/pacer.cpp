#include "rover/sim/rover_sim/pacer.hpp"

#include "rover/base/format.hpp"
#include "rover/base/param_binder.hpp"
#include "rover/base/range_check.hpp"

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
  return CheckRange("lockstep_stall_s", lockstep_stall_s, 0.1, 3600.0, "s");
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
}

Pacer::Pacer(const PacerOptions& options)
    : options_(options), rtf_(options.real_time_factor), paused_(options.start_paused) {}

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
  if (lockstep()) {
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
