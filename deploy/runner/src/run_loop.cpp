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
  return std::unique_ptr<RunLoop>(new RunLoop(std::move(clock), limits));
}

void RunLoop::AddPump(std::function<void()> pump) { pumps_.push_back(std::move(pump)); }

void RunLoop::AddCheck(std::function<std::string()> check) { checks_.push_back(std::move(check)); }

void RunLoop::Pump() {
  for (auto& c : clock_.Take()) now_s_ = std::max(now_s_, Time{c->sim_time_ns}.seconds());
  for (auto& p : pumps_) p();
}

std::string RunLoop::Check() const {
  for (const auto& c : checks_) {
    std::string failure = c();
    if (!failure.empty()) return failure;
  }
  if (limits_.abort && limits_.abort->load()) return "interrupted";
  char b[128];
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
    if (done()) return "";
    std::string failure = Check();
    if (!failure.empty()) return failure;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
}

}  // namespace rover::deploy::runner
