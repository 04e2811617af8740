#include "rover/deploy/runner.hpp"

#include <yaml-cpp/yaml.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <random>
#include <set>
#include <thread>
#include <unistd.h>

#include "rover/base/clock.hpp"
#include "rover/base/log.hpp"
#include "rover/deploy/compose.hpp"
#include "rover/deploy/plots.hpp"
#include "rover/deploy/supervisor.hpp"
#include "rover/runtime/dds.hpp"
#include "rover/sim/world/world.hpp"

namespace rover::deploy {
namespace fs = std::filesystem;

namespace {

Eigen::Isometry3d ToIsometry(const rover_Pose3& p) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translation() = Eigen::Vector3d(p.position.x, p.position.y, p.position.z);
  t.linear() = Eigen::Quaterniond(p.orientation.w, p.orientation.x, p.orientation.y, p.orientation.z)
                   .normalized()
                   .toRotationMatrix();
  return t;
}

rover_dl_DrivePrimitive ToIdl(Primitive p) {
  switch (p) {
    case Primitive::kStraight: return rover_dl_PRIMITIVE_STRAIGHT;
    case Primitive::kArc: return rover_dl_PRIMITIVE_ARC;
    case Primitive::kTurnInPlace: return rover_dl_PRIMITIVE_TURN_IN_PLACE;
    case Primitive::kSteer: return rover_dl_PRIMITIVE_STEER;
    case Primitive::kStop: return rover_dl_PRIMITIVE_STOP;
  }
  return rover_dl_PRIMITIVE_STOP;
}

const char* TerminationName(rover_dl_DriveTermination t) {
  switch (t) {
    case rover_dl_TERMINATION_NONE: return "none";
    case rover_dl_TERMINATION_NOMINAL: return "nominal";
    case rover_dl_TERMINATION_TILT: return "tilt";
    case rover_dl_TERMINATION_SUSPENSION: return "suspension";
    case rover_dl_TERMINATION_MOTOR_STALL: return "motor_stall";
    case rover_dl_TERMINATION_MOTOR_CURRENT: return "motor_current";
    case rover_dl_TERMINATION_MOTOR_FAULT: return "motor_fault";
    case rover_dl_TERMINATION_TIMEOUT: return "timeout";
    case rover_dl_TERMINATION_STOP_COMMAND: return "stop_command";
    case rover_dl_TERMINATION_REJECTED_BUSY: return "rejected_busy";
    case rover_dl_TERMINATION_REJECTED_INVALID: return "rejected_invalid";
    case rover_dl_TERMINATION_STALE_SENSOR: return "stale_sensor";
  }
  return "?";
}

// The simulator's parameter file for this run: the scenario's world sections, with the start
// pose and seeds of the run.
std::string SimParamsYaml(const Scenario& s, std::uint32_t seed) {
  YAML::Node root = YAML::Load(s.text);
  YAML::Node out(YAML::NodeType::Map);
  for (const auto& sec : sim::WorldSections()) {
    if (root[sec]) out[sec] = root[sec];
  }
  if (!out["terrain"]) out["terrain"] = YAML::Node(YAML::NodeType::Map);
  // A scenario that fixes terrain.seed keeps its terrain; otherwise each run seed is a new one.
  if (!out["terrain"]["seed"]) out["terrain"]["seed"] = seed;
  out["rover"]["start"]["x"] = s.start_x;
  out["rover"]["start"]["y"] = s.start_y;
  out["rover"]["start"]["yaw_deg"] = s.start_yaw * 180.0 / M_PI;
  out["sim"]["seed"] = seed;
  out["sim"]["real_time_factor"] = s.real_time_factor;
  out["sim"]["lockstep_lead_s"] = s.lockstep_lead_s;
  // Simulated time starts when the runner says so, once every service is up.
  out["sim"]["start_paused"] = true;
  YAML::Emitter e;
  e << out;
  return std::string(e.c_str()) + "\n";
}

std::string ParamsYaml(const std::map<std::string, std::string>& flat) {
  std::string out;
  for (const auto& [k, v] : flat) out += k + ": " + v + "\n";
  return out;
}

// Planned path of a directed task from the start pose (dead reckoning of the commands).
std::vector<Eigen::Vector2d> PlannedPath(const Scenario& s) {
  std::vector<Eigen::Vector2d> pts{{s.start_x, s.start_y}};
  double x = s.start_x, y = s.start_y, th = s.start_yaw;
  for (const auto& st : s.task.steps) {
    if (st.primitive == Primitive::kTurnInPlace) {
      th += st.angle;
      continue;
    }
    if (st.primitive != Primitive::kStraight && st.primitive != Primitive::kArc) continue;
    const double k = st.primitive == Primitive::kArc ? st.curvature : 0.0;
    const int n = std::max(1, static_cast<int>(std::abs(st.distance) / 0.1));
    const double ds = st.distance / n;
    for (int i = 0; i < n; ++i) {
      x += ds * std::cos(th + 0.5 * k * ds);
      y += ds * std::sin(th + 0.5 * k * ds);
      th += k * ds;
      pts.emplace_back(x, y);
    }
  }
  if (s.task.goal) pts.push_back(*s.task.goal);
  return pts;
}

std::string TerrainDigest(const sim::Terrain& t) {
  std::uint64_t h = 1469598103934665603ULL;
  auto mix = [&h](const void* data, std::size_t n) {
    const auto* b = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < n; ++i) h = (h ^ b[i]) * 1099511628211ULL;
  };
  const auto& heights = t.ground.heights();
  mix(heights.data(), heights.size() * sizeof(float));
  for (const auto& r : t.rocks) {
    mix(r.position.data(), 3 * sizeof(double));
    mix(&r.diameter, sizeof r.diameter);
  }
  char buf[24];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

std::string UniqueProject(const Scenario& s, std::uint32_t seed) {
  std::random_device rd;
  char buf[16];
  std::snprintf(buf, sizeof buf, "%04x", static_cast<unsigned>(rd() & 0xffff));
  return s.name + "-seed" + std::to_string(seed) + "-" + std::to_string(getpid()) + buf;
}

}  // namespace

Status ValidateSimulatorSections(const std::string& text, const std::string& file) {
  ParamSet p("rover-sim");
  sim::DeclareWorldParams(p);
  ROVER_RETURN_IF_ERROR(p.LoadYamlSections(text, file, sim::WorldSections()));
  // Ranges and cross-field rules (rock density, objects on the map) need the world itself; the
  // runner builds it anyway (for the judge and the map), so do it now, before anything starts.
  ROVER_RETURN_IF_ERROR(p.Validate());
  auto w = sim::BuildWorld(p);
  return w.ok() ? Status::Ok() : w.status();
}

namespace {
struct Prepared {
  std::string run_dir;
  sim::World world;
  ComposeProject project;
  SupervisorOptions sup_opts;
};

// Builds the run folder, the world, the service set and its parameters; validates it all.
Result<Prepared> Prepare(const Scenario& scenario, std::uint32_t seed, const RunOptions& options) {
  const std::string run_dir = options.out_dir + "/" + scenario.name + "-seed" + std::to_string(seed);
  std::error_code ec;
  fs::remove_all(run_dir, ec);
  fs::create_directories(run_dir + "/params", ec);
  if (ec) return Unavailable("cannot create " + run_dir + ": " + ec.message());

  // The world, exactly as the simulator will build it.
  const std::string sim_yaml = SimParamsYaml(scenario, seed);
  const std::string sim_params_path = run_dir + "/params/" + scenario.simulator + ".yaml";
  std::ofstream(sim_params_path) << sim_yaml;
  ParamSet world_params("world");
  sim::DeclareWorldParams(world_params);
  ROVER_RETURN_IF_ERROR(world_params.LoadYamlSections(sim_yaml, sim_params_path, sim::WorldSections()));
  ROVER_RETURN_IF_ERROR(world_params.Validate());
  auto world = sim::BuildWorld(world_params);
  if (!world.ok()) return world.status();

  // The service set.
  auto project = LoadComposeFile(scenario.compose_path);
  if (!project.ok()) return project.status();
  project->rover.project = UniqueProject(scenario, seed);
  project->rover.clock = "sim";
  project->rover.domain.reset();
  bool has_sim = false;
  for (auto& svc : project->services) {
    std::vector<std::string> files;
    if (svc.name == scenario.simulator) {
      has_sim = true;
      files.push_back(sim_params_path);
    }
    std::map<std::string, std::string> overrides;
    if (svc.name == scenario.estimator) {
      char b[64];
      std::snprintf(b, sizeof b, "%.9g", scenario.start_x);
      overrides["start.x"] = b;
      std::snprintf(b, sizeof b, "%.9g", scenario.start_y);
      overrides["start.y"] = b;
      std::snprintf(b, sizeof b, "%.9g", scenario.start_yaw * 180.0 / M_PI);
      overrides["start.yaw_deg"] = b;
    }
    auto it = scenario.params.find(svc.name);
    if (it != scenario.params.end()) {
      for (const auto& [k, v] : it->second) overrides[k] = v;
    }
    if (!overrides.empty()) {
      const std::string path = run_dir + "/params/" + svc.name + ".overrides.yaml";
      std::ofstream(path) << ParamsYaml(overrides);
      files.push_back(path);
    }
    std::string joined;
    for (const auto& f : files) joined += (joined.empty() ? "" : ":") + f;
    if (!joined.empty()) svc.environment["ROVER_PARAMS"] = joined;
  }
  if (!has_sim) {
    return InvalidArgument(scenario.file + ": simulator service '" + scenario.simulator +
                           "' is not in " + scenario.compose_path);
  }
  for (const auto& [svc, _] : scenario.params) {
    if (project->Find(svc) == nullptr) {
      return InvalidArgument(scenario.file + ": params." + svc + ": no such service in " +
                             scenario.compose_path);
    }
  }

  SupervisorOptions sup_opts;
  sup_opts.bin_dir = options.bin_dir;
  sup_opts.state_dir = run_dir;
  sup_opts.dds_config_uri = options.dds_config_uri;
  sup_opts.abort = options.abort;
  ROVER_RETURN_IF_ERROR(Preflight(*project, sup_opts));
  return Prepared{run_dir, std::move(*world), std::move(*project), sup_opts};
}
}  // namespace

Status PreflightScenario(const Scenario& scenario, std::uint32_t seed, const RunOptions& options) {
  auto p = Prepare(scenario, seed, options);
  if (!p.ok()) return p.status();
  std::error_code ec;
  fs::remove_all(p->run_dir, ec);
  return Status::Ok();
}

Result<RunResult> RunScenario(const Scenario& scenario, std::uint32_t seed, const RunOptions& options) {
  const Time wall_start = MonotonicNow();
  RunResult result;
  result.scenario = scenario.name;
  result.seed = seed;
  auto note = [&](const std::string& n, double t) {
    if (options.progress) options.progress(n, t);
  };
  auto prepared = Prepare(scenario, seed, options);
  if (!prepared.ok()) return prepared.status();
  const std::string run_dir = prepared->run_dir;
  result.run_dir = run_dir;
  const sim::World* world = &prepared->world;
  result.terrain_digest = TerrainDigest(world->terrain);
  ComposeProject* project = &prepared->project;
  note("starting", 0);
  auto sup = Supervisor::Create(*project, prepared->sup_opts);
  if (!sup.ok()) return sup.status();
  result.domain = (*sup)->domain();
  const Status started = (*sup)->Start();
  result.startup_s = ToSeconds(MonotonicNow() - wall_start);
  auto finish = [&](const std::string& failure) -> Result<RunResult> {
    const Time t0 = MonotonicNow();
    (*sup)->Stop();
    result.teardown_s = ToSeconds(MonotonicNow() - t0);
    result.wall_time_s = ToSeconds(MonotonicNow() - wall_start);
    if (!failure.empty() && result.failure.empty()) result.failure = failure;
    result.pass = result.failure.empty();
    std::ofstream(run_dir + "/result.json") << ToJson(result).dump(2) << "\n";
    (void)WriteTrackMap(world->terrain, result, PlannedPath(scenario), run_dir + "/map.png");
    (void)WriteErrorPlot(result, run_dir + "/estimate_error.png");
    return result;
  };
  if (!started.ok()) return finish("service set did not start: " + started.message());

  // The operator's participant on the run's domain.
  auto participant = dds::Participant::Create(result.domain);
  if (!participant.ok()) return finish(participant.status().message());
  auto clock_r = dds::Reader<rover_sim_Clock>::Create(*participant, "sim/clock");
  auto truth_r = dds::Reader<rover_sim_Truth>::Create(*participant, "sim/truth");
  auto pose_r = dds::Reader<rover_dl_PoseEstimate>::Create(*participant, "dl/pose");
  auto odo_r = dds::Reader<rover_dl_PoseEstimate>::Create(*participant, "dl/pose_odometry");
  auto status_r = dds::Reader<rover_dl_DriveStatus>::Create(*participant, "dl/drive_status");
  auto cmd_w = dds::Writer<rover_dl_DriveCommand>::Create(*participant, "dl/drive_command");
  auto control_w = dds::Writer<rover_sim_Control>::Create(*participant, "sim/control");
  if (!clock_r.ok() || !truth_r.ok() || !pose_r.ok() || !odo_r.ok() || !status_r.ok() || !cmd_w.ok() ||
      !control_w.ok()) {
    return finish("cannot create the runner's DDS endpoints");
  }

  std::vector<sim::JudgeRock> rocks;
  for (const auto& r : world->terrain.rocks) {
    rocks.push_back({r.id, r.position.head<2>(), r.diameter, r.height});
  }
  auto judge = sim::Judge::Create(scenario.criteria, rocks);
  if (!judge.ok()) return finish(judge.status().message());

  double sim_now = 0;
  double last_truth_track = -1, last_est_track = -1, last_odo_track = -1;
  std::optional<double> rejected_measurements;  // dl/pose's count, last sample
  std::set<dds_instance_handle_t> truth_writers;
  auto pump = [&] {
    for (auto& c : clock_r->Take()) sim_now = std::max(sim_now, Time{c->sim_time_ns}.seconds());
    truth_r->TakeEach([&](const dds::Sample<rover_sim_Truth>& s) {
      truth_writers.insert(s.info().publication_handle);
      result.truth_publishers = static_cast<int>(truth_writers.size());
      const Time t{s->header.stamp_ns};
      judge->AddTruth(t, ToIsometry(s->pose));
      if (t.seconds() - last_truth_track >= 0.2) {
        result.truth_track.push_back({t.seconds(), s->pose.position.x, s->pose.position.y});
        last_truth_track = t.seconds();
      }
    });
    pose_r->TakeEach([&](const dds::Sample<rover_dl_PoseEstimate>& s) {
      const Time t{s->header.stamp_ns};
      judge->AddEstimate(t, ToIsometry(s->pose));
      rejected_measurements = static_cast<double>(s->rejected_measurements);
      if (t.seconds() - last_est_track >= 0.2) {
        result.estimate_track.push_back({t.seconds(), s->pose.position.x, s->pose.position.y});
        last_est_track = t.seconds();
      }
    });
    odo_r->TakeEach([&](const dds::Sample<rover_dl_PoseEstimate>& s) {
      const Time t{s->header.stamp_ns};
      judge->AddOdometryOnlyEstimate(t, ToIsometry(s->pose));
      if (t.seconds() - last_odo_track >= 0.2) {
        result.odometry_only_track.push_back(
            {t.seconds(), s->pose.position.x, s->pose.position.y});
        last_odo_track = t.seconds();
      }
    });
  };
  // Returns a failure line, or "" while all is well.
  auto check = [&]() -> std::string {
    (*sup)->Poll();
    for (const auto& st : (*sup)->Snapshot()) {
      if (st.state == ServiceState::kFailed || st.state == ServiceState::kBackoff ||
          (st.state == ServiceState::kExited && st.restarts == 0 && !st.last_exit.empty())) {
        std::ifstream log(st.log_path);
        std::string line, last;
        while (std::getline(log, line)) {
          if (!line.empty() && line.rfind("---- roverctl:", 0) != 0) last = line;
        }
        result.crashes.push_back(st.name + ": " + st.last_exit + (last.empty() ? "" : "; " + last));
        return "service '" + st.name + "' crashed (" + st.last_exit + ")";
      }
    }
    if (options.abort && options.abort->load()) return "interrupted";
    if (truth_writers.size() > 1) {
      return "cross-talk: " + std::to_string(truth_writers.size()) + " simulators heard on domain " +
             std::to_string(result.domain);
    }
    if (sim_now > scenario.time_budget_s) {
      char b[128];
      std::snprintf(b, sizeof b, "time budget of %.0f simulated s exceeded", scenario.time_budget_s);
      return b;
    }
    if (ToSeconds(MonotonicNow() - wall_start) > scenario.wall_budget_s) {
      char b[128];
      std::snprintf(b, sizeof b, "hung: wall budget of %.0f s exceeded at %.1f simulated s",
                    scenario.wall_budget_s, sim_now);
      return b;
    }
    return "";
  };
  auto wait_until = [&](const std::function<bool()>& cond) -> std::string {
    while (true) {
      pump();
      if (cond()) return "";
      const std::string f = check();
      if (!f.empty()) return f;
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
  };

  // Start simulated time once the simulator and the drive service hear us.
  std::string failure = wait_until([&] {
    return control_w->MatchedReaders() > 0 && cmd_w->MatchedReaders() > 0;
  });
  if (!failure.empty()) return finish(failure);
  {
    rover_sim_Control resume{};
    dds::CopyString(resume.header.frame_id, "sim");
    resume.command_id = 1;
    resume.command = rover_sim_SIM_RESUME;
    if (!control_w->Write(resume).ok()) return finish("cannot resume the simulator");
  }
  note("running", 0);
  // Wait for the simulator's clock and the pose estimate, then half a simulated second more:
  // the runner hearing dl/pose does not mean that the drive service has (it would reject the
  // command for want of an attitude, as MER's would).
  std::optional<double> first_pose_at;
  failure = wait_until([&] {
    if (!first_pose_at && !result.estimate_track.empty()) first_pose_at = sim_now;
    return sim_now > 0 && first_pose_at && sim_now >= *first_pose_at + 0.5 &&
           cmd_w->MatchedReaders() > 0;
  });
  if (!failure.empty()) return finish(failure);

  if (scenario.task.type != TaskType::kDirected) {
    return finish(std::string("task type '") + TaskTypeName(scenario.task.type) +
                  "' needs the autonomous-navigation services, which this stack does not have yet");
  }
  for (std::size_t i = 0; i < scenario.task.steps.size() && failure.empty(); ++i) {
    const DriveStep& step = scenario.task.steps[i];
    rover_dl_DriveCommand c{};
    c.header.stamp_ns = Time::FromSeconds(sim_now).ns;
    dds::CopyString(c.header.frame_id, "rover");
    c.command_id = static_cast<uint32_t>(i + 1);
    c.primitive = ToIdl(step.primitive);
    c.curvature = step.primitive == Primitive::kStraight ? 0.0 : step.curvature;
    c.distance = step.distance;
    c.angle = step.angle;
    c.speed = step.speed;
    c.timeout_s = step.timeout_s;
    StepResult sr;
    sr.primitive = PrimitiveName(step.primitive);
    sr.command_id = c.command_id;
    sr.sim_start_s = sim_now;
    note("step " + std::to_string(i + 1) + "/" + std::to_string(scenario.task.steps.size()) + " " +
             sr.primitive, sim_now);
    if (!cmd_w->Write(c).ok()) {
      failure = "cannot send the drive command";
      break;
    }
    bool terminal = false;
    bool stop_sent = false;
    failure = wait_until([&] {
      if (step.stop_after_s > 0 && !stop_sent && sim_now - sr.sim_start_s >= step.stop_after_s) {
        rover_dl_DriveCommand stop{};
        stop.header.stamp_ns = Time::FromSeconds(sim_now).ns;
        stop.command_id = c.command_id + 1000;
        stop.primitive = rover_dl_PRIMITIVE_STOP;
        stop_sent = cmd_w->Write(stop).ok();
      }
      status_r->TakeEach([&](const dds::Sample<rover_dl_DriveStatus>& s) {
        if (s->command_id != c.command_id) return;
        if (s->state == rover_dl_DRIVE_DONE || s->state == rover_dl_DRIVE_FAILED ||
            s->state == rover_dl_DRIVE_REJECTED) {
          terminal = true;
          sr.state = s->state == rover_dl_DRIVE_DONE     ? "done"
                     : s->state == rover_dl_DRIVE_FAILED ? "failed"
                                                         : "rejected";
          sr.termination = TerminationName(s->termination);
          sr.message = s->message;
        }
      });
      return terminal;
    });
    sr.sim_end_s = sim_now;
    if (!failure.empty()) sr.state = "interrupted";
    result.steps.push_back(sr);
    if (failure.empty() && sr.termination != step.expect) {
      failure = "step " + std::to_string(i + 1) + " (" + sr.primitive + ") ended " + sr.state +
                " (" + sr.termination + ")" + (step.expect == "nominal" ? "" : ", expected " + step.expect) +
                (sr.message.empty() ? "" : ": " + sr.message);
    }
    if (failure.empty() && step.expect != "nominal") {
      // An expected fault ends the sequence: the rover is safe and stopped, as on MER.
      break;
    }
  }
  // Let the last truth and estimate samples arrive (half a simulated second).
  if (failure.empty()) {
    const double until = sim_now + 0.5;
    failure = wait_until([&] { return sim_now >= until; });
  }
  pump();
  result.sim_time_s = sim_now;
  const sim::Verdict v = judge->Evaluate();
  result.criteria = v.criteria;
  result.distance_driven = v.distance_driven;
  result.estimate_error = v.estimate_error;
  result.odometry_only_error = v.odometry_only_error;
  result.figures = v.figures;
  if (rejected_measurements) {
    result.figures.push_back({"estimator_rejected_measurements", *rejected_measurements,
                              std::numeric_limits<double>::quiet_NaN(), "count", true,
                              "measurements dl-pose gated out or refused (dl/pose)"});
  }
  if (failure.empty() && !v.pass) {
    std::string first = v.FailureSummary();
    failure = first.substr(0, first.find('\n'));
  }
  return finish(failure);
}

}  // namespace rover::deploy
