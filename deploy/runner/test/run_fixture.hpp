#pragma once
// In-process run pieces for the runner's tests: a participant on an isolated DDS domain, the run
// loop, the recorder and a task context, and a scripted simulator clock. No processes.

#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "rover/deploy/runner/recorder.hpp"
#include "rover/deploy/runner/run_loop.hpp"
#include "rover/deploy/runner/task.hpp"
#include "rover/testing/test_support.hpp"

namespace rover::deploy::runner::testing {

// A scenario "s.yaml" whose text is `task_yaml` from line 2 on, starting at (1, 2).
inline Scenario ScenarioWithTask(const std::string& task_yaml) {
  Scenario s;
  s.file = "s.yaml";
  s.text = "name: x\n" + task_yaml;
  s.task.line = 2;
  s.start_x = 1;
  s.start_y = 2;
  return s;
}

// Publishes sim/clock as the simulator would, one step each time it is told to.
class ScriptedClock {
 public:
  explicit ScriptedClock(const dds::Participant& p, double step_s = 0.1)
      : writer_(dds::Writer<rover_sim_Clock>::Create(p, "sim/clock").value()), step_s_(step_s) {}
  void Tick() {
    now_s_ += step_s_;
    rover_sim_Clock c{};
    c.header.stamp_ns = Time::FromSeconds(now_s_).ns;
    c.sim_time_ns = Time::FromSeconds(now_s_).ns;
    (void)writer_.Write(c);
  }
  double now() const { return now_s_; }

 private:
  dds::Writer<rover_sim_Clock> writer_;
  double step_s_;
  double now_s_ = 0;
};

// Run limits for a test: a simulated time budget, a generous wall budget (a liveness limit of
// the harness, never an assertion on speed).
inline LoopLimits Limits(double time_budget_s = 1e4, const std::atomic<bool>* abort = nullptr) {
  LoopLimits l;
  l.time_budget_s = time_budget_s;
  l.wall_budget_s = 600;
  l.abort = abort;
  return l;
}

// The runner's side of a run: its participant, loop, recorder, result and task context.
class RunFixture {
 public:
  explicit RunFixture(LoopLimits limits = Limits()) : lease_(rover::testing::IsolatedDomain()) {
    auto p = dds::Participant::Create(lease_.domain());
    EXPECT_TRUE(p.ok()) << p.status().message();
    participant_ = std::move(*p);
    limits.wall_start = MonotonicNow();
    auto loop = RunLoop::Create(participant_, limits);
    EXPECT_TRUE(loop.ok()) << loop.status().message();
    loop_ = std::move(*loop);
    auto rec = Recorder::Create(participant_, nullptr, &result_);
    EXPECT_TRUE(rec.ok()) << rec.status().message();
    recorder_ = std::move(*rec);
    loop_->AddPump([this] { recorder_->Pump(); });
    scenario_.file = "s.yaml";
    scenario_.name = "fixture";
  }

  int domain() const { return lease_.domain(); }
  const dds::Participant& participant() const { return participant_; }
  RunLoop& loop() { return *loop_; }
  Recorder& recorder() { return *recorder_; }
  RunResult& result() { return result_; }
  Scenario& scenario() { return scenario_; }
  TaskContext Context() {
    return TaskContext{scenario_, participant_, *loop_, *recorder_,
                       [this](const std::string& n) { notes.push_back(n); }};
  }

  std::vector<std::string> notes;

 private:
  dds::DomainLease lease_;
  dds::Participant participant_;
  Scenario scenario_;
  RunResult result_;
  std::unique_ptr<RunLoop> loop_;
  std::unique_ptr<Recorder> recorder_;
};

}  // namespace rover::deploy::runner::testing
