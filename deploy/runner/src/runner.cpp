// RunScenario: the four pieces of a run (launch, record, task, judge) in order. Each piece is
// in its own file; this one only sequences them.
#include "rover/deploy/runner.hpp"

#include <filesystem>
#include <map>
#include <optional>

#include "rover/base/clock.hpp"
#include "rover/deploy/runner/fault_log.hpp"
#include "rover/deploy/runner/judging.hpp"
#include "rover/deploy/runner/recorder.hpp"
#include "rover/deploy/runner/run_loop.hpp"
#include "rover/deploy/runner/service_set.hpp"
#include "rover/deploy/runner/task.hpp"
#include "rover/msg/health_idl.hpp"
#include "rover/runtime/activity.hpp"
#include "rover/runtime/fault_control.hpp"

namespace rover::deploy {
namespace fs = std::filesystem;
using namespace runner;  // NOLINT(google-build-using-namespace): this file is the runner's glue

Status ValidateSimulatorSections(const std::string& text, const std::string& file) {
  ParamSet p("rover-sim");
  sim::world::DeclareWorldParams(p);
  ROVER_RETURN_IF_ERROR(p.LoadYamlSections(text, file, sim::world::WorldSections()));
  // Ranges and cross-field rules (rock density, objects on the map) need the world itself; the
  // runner builds it anyway (for the judge and the map), so do it now, before anything starts.
  ROVER_RETURN_IF_ERROR(p.Validate());
  auto w = sim::world::BuildWorld(p);
  return w.ok() ? Status::Ok() : w.status();
}

Result<Scenario> LoadScenario(const std::string& path) {
  return LoadScenarioFile(path, ValidateSimulatorSections, ValidateTask);
}

Status PreflightScenario(const Scenario& scenario, std::uint32_t seed, const RunOptions& options) {
  ROVER_RETURN_IF_ERROR(ValidateTask(scenario));
  ROVER_ASSIGN_OR_RETURN(PreparedRun prepared, PrepareRun(scenario, seed, options));
  std::error_code ec;
  fs::remove_all(prepared.run_dir, ec);
  return Status::Ok();
}

Result<RunResult> RunScenario(const Scenario& scenario, std::uint32_t seed,
                              const RunOptions& options) {
  const Time wall_start = MonotonicNow();
  // Strict lock-step: the runner's readers (recorder, judge, task, supervisor) lose no sample.
  if (scenario.lockstep == "strict") dds::lockstep::SetStrictProcess(true);
  // Declared first so that it is destroyed last: the task's, recorder's and loop's DDS entities
  // belong to its participant.
  std::unique_ptr<ServiceSet> set;
  // The run's run.mcap (on the operator's participant, so after `set`, destroyed before it).
  std::unique_ptr<recording::BusRecorder> recording;
  ROVER_ASSIGN_OR_RETURN(std::unique_ptr<Task> task, TaskRegistry::Builtin().Make(scenario));
  RunResult result;
  result.scenario = scenario.name;
  result.seed = seed;
  auto progress = [&](const std::string& n, double t) {
    if (options.progress) options.progress(n, t);
  };

  // (a) Launch.
  ROVER_ASSIGN_OR_RETURN(PreparedRun prepared, PrepareRun(scenario, seed, options));
  result.run_dir = prepared.run_dir;
  result.terrain_digest = TerrainDigest(prepared.world.terrain);
  progress("starting", 0);
  // The set's faults (x-rover.faults, then the scenario's), and what the services say they did.
  std::vector<faults::FaultSpec> specs;
  for (const auto& f : prepared.project.rover.faults) specs.push_back(f.spec);
  FaultLog fault_log(specs);
  std::optional<faults::FaultClient> fault_client;
  ROVER_ASSIGN_OR_RETURN(set, ServiceSet::Create(prepared));
  result.domain = set->domain();
  const Status started = set->Start();
  result.startup_s = ToSeconds(MonotonicNow() - wall_start);
  // (d) Judging and the outputs, however the run ends.
  std::map<std::string, ServiceTiming> timing;  // each service's last heartbeat's figures
  const double runner_cpu_start = runtime::ThreadCpuSeconds();
  result.lockstep = scenario.lockstep;
  auto finish = [&](std::string failure) -> Result<RunResult> {
    const Time t0 = MonotonicNow();
    for (auto& [name, t] : timing) {
      for (const auto& a : t.activities) {
        if (a.name == "late_samples") result.late_samples += a.count;
      }
      result.service_timing.push_back(t);
    }
    // The final counts: every service answers LIST with what each fault touched so far.
    if (fault_client && !specs.empty()) {
      for (const auto& r : fault_client->List(std::chrono::milliseconds(500))) fault_log.Add(r);
    }
    result.faults = fault_log.Summary();
    set->Stop();
    // After the set: the recording keeps what the services said while stopping. A recording
    // that failed fails the run.
    // The runner's own share: its thread (this one) and the recorder's.
    result.service_timing.push_back(
        {"scenario-runner", runtime::ThreadCpuSeconds() - runner_cpu_start, {}});
    double recorder_cpu = 0;
    if (const std::string r = FinishRunRecording(recording.get(), &recorder_cpu); !r.empty()) {
      failure = failure.empty() ? r : failure + "; " + r;
    }
    if (recording) {
      result.service_timing.push_back({"recorder", recorder_cpu, {}});
      std::error_code ec;
      const auto bytes = fs::file_size(recording->path(), ec);
      if (!ec) result.recording_mb = static_cast<double>(bytes) * 1e-6;
    }
    recording.reset();
    result.teardown_s = ToSeconds(MonotonicNow() - t0);
    result.wall_time_s = ToSeconds(MonotonicNow() - wall_start);
    ROVER_RETURN_IF_ERROR(
        WriteRunOutputs(&result, failure, prepared.world.terrain, task->PlannedPath()));
    return result;
  };
  if (!started.ok()) return finish("service set did not start: " + started.message());
  if (const Status s = set->OpenOperator(); !s.ok()) return finish(s.message());
  {
    auto r = StartRunRecording(set->participant(), scenario, seed, prepared.run_dir,
                               result.domain, prepared.project.rover.qos);
    if (!r.ok()) return finish("cannot record the run: " + r.status().message());
    recording = std::move(*r);
  }
  if (!specs.empty()) {
    auto c = faults::FaultClient::Create(set->participant());
    if (!c.ok()) return finish("cannot create the runner's DDS endpoints: " + c.status().message());
    fault_client.emplace(std::move(*c));
  }
  auto judge = MakeJudge(scenario, prepared.world);
  if (!judge.ok()) return finish(judge.status().message());

  // (b) Recording, and the loop every wait goes through.
  auto recorder = Recorder::Create(set->participant(), &*judge, &result);
  if (!recorder.ok()) {
    return finish("cannot create the runner's DDS endpoints: " + recorder.status().message());
  }
  auto loop = RunLoop::Create(set->participant(),
                              LoopLimits{scenario.time_budget_s, scenario.wall_budget_s, wall_start,
                                         options.abort, scenario.lockstep == "strict"});
  if (!loop.ok()) {
    return finish("cannot create the runner's DDS endpoints: " + loop.status().message());
  }
  // The services' health (sys/health), for fault campaigns: each service's first heartbeat and
  // every change of its health or message, at the run-clock time the runner heard it (a
  // restarted service's first stamps may not be on the run clock yet).
  std::map<std::string, std::pair<std::string, std::string>> last_health;
  const Status health_recorded = (*recorder)->Record<rover_sys_Heartbeat>(
      "sys/health", [&](const dds::Sample<rover_sys_Heartbeat>& s) {
        auto h = msg::HealthFromIdl(s->health);
        const std::string health = h.ok() ? msg::SensorHealthName(*h) : "?";
        std::pair<std::string, std::string> now{health, s->message};
        {
          ServiceTiming& t = timing[s->service];
          t.service = s->service;
          t.cpu_s = s->cpu_s;
          t.activities.clear();
          for (std::uint32_t i = 0; i < s->activities._length; ++i) {
            const auto& a = s->activities._buffer[i];
            t.activities.push_back({a.name, a.wall_s, a.count});
          }
        }
        auto [it, first] = last_health.try_emplace(s->service, now);
        if (!first && it->second == now) return;
        it->second = now;
        if (result.health_changes.size() >= RunResult::kMaxHealthChanges) {
          ++result.health_changes_dropped;
          return;
        }
        result.health_changes.push_back(
            {(**loop).now(), s->service, health, s->message});
      });
  if (!health_recorded.ok()) {
    return finish("cannot create the runner's DDS endpoints: " + health_recorded.message());
  }
  RunLoop& run_loop = **loop;
  run_loop.AddPump([&] { (*recorder)->Pump(); });
  if (fault_client) {
    run_loop.AddPump([&] {
      for (const auto& r : fault_client->TakeRecords()) fault_log.Add(r);
    });
  }
  // The kills asked for: each at its run-clock time, then watched until the service runs again.
  for (const auto& k : options.kills) {
    KillRecord record;
    record.service = k.service;
    record.at_s = k.at_s;
    result.kills.push_back(std::move(record));
  }
  if (!result.kills.empty()) {
    run_loop.AddPump([&] {
      for (auto& k : result.kills) {
        if (k.killed_s < 0 && k.error.empty() && run_loop.now() >= k.at_s) {
          const Status s = set->Kill(k.service);
          if (s.ok()) {
            k.killed_s = run_loop.now();
          } else {
            k.error = s.message();
          }
        } else if (k.killed_s >= 0 && k.restarted_s < 0 && set->RunsAgain(k.service)) {
          k.restarted_s = run_loop.now();
        }
      }
    });
  }
  run_loop.AddCheck([&] { return set->CheckServices(&result.crashes); });
  // A simulator that failed (a step that failed, strict lock-step stalled on a service) ends
  // the run with its reason.
  run_loop.AddCheck([&]() -> std::string {
    auto it = last_health.find(scenario.simulator);
    if (it == last_health.end() || it->second.first != "failed") return "";
    return scenario.simulator + " failed: " + it->second.second;
  });
  run_loop.AddCheck([&] { return (*recorder)->CrossTalk(result.domain); });
  run_loop.AddCheck([&]() -> std::string {
    if (!recording) return "";
    const Status h = recording->health();
    return h.ok() ? "" : "recording failed: " + h.message();
  });

  // (c) The task.
  TaskContext ctx{scenario, set->participant(), run_loop, **recorder,
                  [&](const std::string& n) { progress(n, run_loop.now()); }, &prepared.world,
                  seed};
  if (const Status s = task->Open(ctx); !s.ok()) {
    return finish("cannot create the runner's DDS endpoints: " + s.message());
  }
  // Start simulated time once the simulator and the services the task commands hear us.
  std::string failure =
      run_loop.WaitUntil([&] { return set->SimulatorHearsUs() && task->Ready(); });
  if (!failure.empty()) return finish(failure);
  if (const Status s = set->ResumeSimulator(); !s.ok()) return finish(s.message());
  progress("running", 0);
  // Wait until the set is ready (every service's heartbeat ACTIVE and health OK: the estimator
  // has levelled, locomotion has fresh joint states and a pose, so a drive command is accepted)
  // and the runner itself hears the estimate.
  failure = run_loop.WaitUntil([&] {
    return run_loop.now() > 0 && set->Ready() && (*recorder)->has_estimate() && task->Ready();
  });
  if (!failure.empty()) {
    return finish(failure + (set->Ready() ? "" : " (not ready: " + set->NotReady() + ")"));
  }
  result.ready_s = set->ready_after_s();
  TaskOutcome outcome = task->Run(ctx);
  result.steps = std::move(outcome.steps);
  failure = outcome.failure;
  // Let the last truth and estimate samples arrive (half a simulated second).
  if (failure.empty()) {
    const double until = run_loop.now() + 0.5;
    failure = run_loop.WaitUntil([&] { return run_loop.now() >= until; });
  }
  run_loop.Pump();
  result.sim_time_s = run_loop.now();
  ScoreRun(*judge, (*recorder)->Figures(), &result, &failure);
  AddMobilityFigures(scenario, prepared.world, &result, &failure);
  AddRendezvousFigures(prepared.world, (*recorder)->rendezvous(), &result, &failure);
  return finish(failure);
}

}  // namespace rover::deploy
