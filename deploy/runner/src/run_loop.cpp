#include "rover/deploy/runner/run_loop.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <thread>

namespace rover::deploy::runner {

Result<std::unique_ptr<RunLoop>> RunLoop::Create(const dds::Participant& participant,
                                                 LoopLimits limits) {
  ROVER_ASSIGN_OR_RETURN(auto clock,
                         dds::Reader<rover_sim_Clock>::Create(participant, "sim/clock"));
  std::unique_ptr<RunLoop> loop(new RunLoop(std::move(clock), limits));
  loop->participant_ = participant.handle();
  ROVER_ASSIGN_OR_RETURN(auto ws, dds::WaitSet::Create(participant));
  loop->waitset_ = std::make_unique<dds::WaitSet>(std::move(ws));
  ROVER_RETURN_IF_ERROR(loop->waitset_->Attach(loop->clock_.handle(), 0));
  if (limits.strict_lockstep) {
    ROVER_ASSIGN_OR_RETURN(loop->ack_,
                           dds::Writer<rover_sim_ClockAck>::Create(participant, "sim/clock_ack"));
    // Until the first tick is heard: writes belong to tick 0, nothing simulated is visible.
    dds::lockstep::SetWriteTick(0);
    dds::lockstep::SetReadGate(0);
  }
  return loop;
}

RunLoop::~RunLoop() {
  if (limits_.strict_lockstep) {
    dds::lockstep::SetWriteTick(dds::lockstep::kOff);
    dds::lockstep::SetReadGate(dds::lockstep::kOff);
    dds::lockstep::SetFrontier({});
  }
}

void RunLoop::Acknowledge() {
  if (!limits_.strict_lockstep || !heard_ || clock_samples_ == acked_samples_) return;
  rover_sim_ClockAck a{};
  a.header.stamp_ns = tick_ns_;
  dds::CopyString(a.service, kRunnerName);
  a.sim_time_ns = tick_ns_;
  dds::lockstep::TopicCounts written = dds::lockstep::WrittenBy(participant_);
  a.written._buffer = written.data();
  a.written._length = a.written._maximum = static_cast<std::uint32_t>(written.size());
  a.written._release = false;
  if (ack_.Write(a).ok()) acked_samples_ = clock_samples_;
}

void RunLoop::AddPump(std::function<void()> pump) { pumps_.push_back(std::move(pump)); }

void RunLoop::AddCheck(std::function<std::string()> check) { checks_.push_back(std::move(check)); }

void RunLoop::Pump() {
  // The clock itself is never held back.
  const std::int64_t gate = dds::lockstep::ReadGate();
  dds::lockstep::SetReadGate(dds::lockstep::kOff);
  for (auto& c : clock_.Take()) {
    ++clock_samples_;
    heard_ = true;
    tick_ns_ = c->sim_time_ns;  // a reset goes back: follow it
    now_s_ = Time{c->sim_time_ns}.seconds();
    if (limits_.strict_lockstep) {
      dds::lockstep::SetFrontier(dds::lockstep::TopicCounts(
          c->written._buffer, c->written._buffer + c->written._length));
    }
  }
  if (limits_.strict_lockstep) {
    dds::lockstep::SetReadGate(heard_ ? tick_ns_ : gate);
    if (heard_) dds::lockstep::SetWriteTick(tick_ns_);
  } else {
    dds::lockstep::SetReadGate(gate);
  }
  for (auto& p : pumps_) p();
}

std::string RunLoop::Check() const {
  for (const auto& c : checks_) {
    std::string failure = c();
    if (!failure.empty()) return failure;
  }
  char b[160];
  if (limits_.abort && limits_.abort->load()) {
    std::snprintf(b, sizeof b,
                  "interrupted: roverctl was stopped (Ctrl-C or a termination signal) at %.1f "
                  "simulated s",
                  now_s_);
    return b;
  }
  if (now_s_ > limits_.time_budget_s) {
    std::snprintf(b, sizeof b, "time budget of %.0f simulated s exceeded", limits_.time_budget_s);
    return b;
  }
  if (ToSeconds(MonotonicNow() - limits_.wall_start) > limits_.wall_budget_s) {
    std::snprintf(b, sizeof b, "hung: wall budget of %.0f s exceeded at %.1f simulated s",
                  limits_.wall_budget_s, now_s_);
    return b;
  }
  return "";
}

std::string RunLoop::WaitUntil(const std::function<bool()>& done) {
  while (true) {
    Pump();
    // Strict lock-step: a running tick is decided once, on its first pass. A later pass of the
    // same tick (the wait timed out, or the simulator repeated the tick) comes after the
    // acknowledgement, so what it wrote would miss the frontier and reach its reader a tick late
    // or not, as the machine's load decides. Tick 0 (the simulator paused, before the run) is
    // asked on every pass.
    const bool decided = limits_.strict_lockstep && heard_ && tick_ns_ > 0 &&
                         tick_ns_ == decided_tick_ns_;
    if (!decided) {
      decided_tick_ns_ = tick_ns_;
      if (done()) return "";
    }
    std::string failure = Check();
    if (!failure.empty()) return failure;
    Acknowledge();
    (void)waitset_->Wait(std::chrono::nanoseconds(std::chrono::milliseconds(5)).count());
  }
}

}  // namespace rover::deploy::runner
