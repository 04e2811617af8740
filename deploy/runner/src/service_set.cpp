#include "rover/deploy/runner/service_set.hpp"

#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>

#include "rover/base/format.hpp"
#include "rover/deploy/runner/run_loop.hpp"
#include "rover/runtime/security_files.hpp"

namespace rover::deploy::runner {
namespace fs = std::filesystem;
namespace {

constexpr double kRadToDeg = 180.0 / M_PI;


std::string ParamsYaml(const std::map<std::string, std::string>& flat) {
  std::string out;
  for (const auto& [k, v] : flat) out += k + ": " + v + "\n";
  return out;
}

std::string UniqueProject(const Scenario& s, std::uint32_t seed) {
  std::random_device rd;
  char buf[16];
  std::snprintf(buf, sizeof buf, "%04x", static_cast<unsigned>(rd() & 0xffff));
  return s.name + "-seed" + std::to_string(seed) + "-" + std::to_string(getpid()) + buf;
}

const char* const kRendezvousService = "apl-rendezvous";

// The parameter files of one service: the simulator's world file, then its overrides.
Status GiveParameters(const Scenario& scenario, const sim::world::World& world,
                      const std::string& run_dir, const std::string& sim_params_path,
                      ServiceSpec* svc) {
  std::vector<std::string> files;
  if (svc->name == scenario.simulator) files.push_back(sim_params_path);
  std::map<std::string, std::string> overrides;
  if (svc->name == scenario.estimator) {
    overrides["start.x"] = FormatNumber(scenario.start_x, 9);
    overrides["start.y"] = FormatNumber(scenario.start_y, 9);
    overrides["start.yaw_deg"] = FormatNumber(scenario.start_yaw * kRadToDeg, 9);
  }
  if (svc->name == kRendezvousService) {
    // The rendezvous draws its sightings into the run folder, and knows the lander it returns
    // to as the scenario builds it (as the estimator is told its start pose).
    overrides["rendezvous.detection_dir"] = run_dir + "/detections";
    if (world.terrain.lander) {
      const hwconfig::LanderDescription d = world.terrain.lander->params.Description();
      overrides["lander.deck_height"] = FormatNumber(d.deck_height, 9);
      overrides["lander.deck_thickness"] = FormatNumber(d.deck_thickness, 9);
      overrides["lander.deck_radius"] = FormatNumber(d.deck_radius, 9);
      overrides["lander.ramp_length"] = FormatNumber(d.ramp_length, 9);
      overrides["lander.ramp_width"] = FormatNumber(d.ramp_width, 9);
      overrides["lander.stripe_unit"] = FormatNumber(d.stripe_unit, 9);
      overrides["lander.stripe_gap"] = FormatNumber(d.stripe_gap, 9);
    }
  }
  if (auto it = scenario.params.find(svc->name); it != scenario.params.end()) {
    for (const auto& [k, v] : it->second) overrides[k] = v;
  }
  if (!overrides.empty()) {
    const std::string path = run_dir + "/params/" + svc->name + ".overrides.yaml";
    std::ofstream out(path);
    out << ParamsYaml(overrides);
    if (!out) return Unavailable("cannot write " + path);
    files.push_back(path);
  }
  std::string joined;
  for (const auto& f : files) joined += (joined.empty() ? "" : ":") + f;
  if (!joined.empty()) svc->environment["ROVER_PARAMS"] = joined;
  return Status::Ok();
}

}  // namespace

std::string TerrainDigest(const sim::terrain::Terrain& t) {
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

std::string SimParamsYaml(const Scenario& s, std::uint32_t seed,
                          const std::vector<std::string>& lockstep_services) {
  YAML::Node root = YAML::Load(s.text);
  YAML::Node out(YAML::NodeType::Map);
  for (const auto& sec : sim::world::WorldSections()) {
    if (root[sec]) out[sec] = root[sec];
  }
  if (!out["terrain"]) out["terrain"] = YAML::Node(YAML::NodeType::Map);
  // A scenario that fixes terrain.seed keeps its terrain; otherwise each run seed is a new one.
  if (!out["terrain"]["seed"]) out["terrain"]["seed"] = seed;
  out["rover"]["start"]["x"] = s.start_x;
  out["rover"]["start"]["y"] = s.start_y;
  out["rover"]["start"]["yaw_deg"] = s.start_yaw * kRadToDeg;
  out["sim"]["seed"] = seed;
  out["sim"]["real_time_factor"] = s.real_time_factor;
  out["sim"]["lockstep_lead_s"] = s.lockstep == "lead" ? s.lockstep_lead_s : 0.0;
  out["sim"]["lockstep_strict"] = s.lockstep == "strict";
  out["sim"]["lockstep_quantum_s"] = s.lockstep_quantum_s;
  if (s.lockstep == "strict") {
    std::string names;
    for (const auto& n : lockstep_services) names += (names.empty() ? "" : ",") + n;
    out["sim"]["lockstep_services"] = names;
  }
  // Simulated time starts when the runner says so, once every service is up.
  out["sim"]["start_paused"] = true;
  YAML::Emitter e;
  e << out;
  return std::string(e.c_str()) + "\n";
}

Result<sim::world::World> BuildRunWorld(const Scenario& scenario, std::uint32_t seed,
                                        const std::string& source) {
  ParamSet world_params("world");
  sim::world::DeclareWorldParams(world_params);
  ROVER_RETURN_IF_ERROR(world_params.LoadYamlSections(SimParamsYaml(scenario, seed), source,
                                                      sim::world::WorldSections()));
  ROVER_RETURN_IF_ERROR(world_params.Validate());
  return sim::world::BuildWorld(world_params);
}

Result<PreparedRun> PrepareRun(const Scenario& scenario, std::uint32_t seed,
                               const RunOptions& options) {
  const std::string run_dir =
      options.out_dir + "/" + scenario.name + "-seed" + std::to_string(seed);
  std::error_code ec;
  fs::remove_all(run_dir, ec);
  fs::create_directories(run_dir + "/params", ec);
  if (ec) return Unavailable("cannot create " + run_dir + ": " + ec.message());

  // The service set.
  ROVER_ASSIGN_OR_RETURN(ComposeProject project, LoadComposeFile(scenario.compose_path));
  project.rover.project = UniqueProject(scenario, seed);
  project.rover.clock = "sim";
  project.rover.lockstep = scenario.lockstep == "strict" ? "strict" : "lead";
  // Strict lock-step waits for every service but the simulator, and for the runner.
  std::vector<std::string> lockstep_services;
  for (const auto& svc : project.services) {
    if (svc.name != scenario.simulator) lockstep_services.push_back(svc.name);
  }
  lockstep_services.push_back(kRunnerName);

  // The world, exactly as the simulator will build it.
  const std::string sim_yaml = SimParamsYaml(scenario, seed, lockstep_services);
  const std::string sim_params_path = run_dir + "/params/" + scenario.simulator + ".yaml";
  std::ofstream(sim_params_path) << sim_yaml;
  ROVER_ASSIGN_OR_RETURN(sim::world::World world, BuildRunWorld(scenario, seed, sim_params_path));

  project.rover.domain.reset();
  if (project.Find(scenario.simulator) == nullptr) {
    return InvalidArgument(scenario.file + ": simulator service '" + scenario.simulator +
                           "' is not in " + scenario.compose_path);
  }
  for (auto& svc : project.services) {
    ROVER_RETURN_IF_ERROR(GiveParameters(scenario, world, run_dir, sim_params_path, &svc));
  }
  // The scenario's faults join the compose file's x-rover.faults; every service gets them at
  // start (ROVER_FAULTS, windows on simulated time), so the same seed hits the same samples.
  ROVER_RETURN_IF_ERROR(AppendSetFaults(scenario.faults, &project.rover.faults));
  for (const auto& [svc, _] : scenario.params) {
    if (project.Find(svc) == nullptr) {
      return InvalidArgument(scenario.file + ": params." + svc + ": no such service in " +
                             scenario.compose_path);
    }
  }

  SupervisorOptions sup;
  sup.bin_dir = options.bin_dir;
  sup.state_dir = run_dir;
  sup.dds_config_uri = options.dds_config_uri;
  sup.abort = options.abort;
  sup.security_dir = options.security_dir;
  project.rover.security = project.rover.security || options.security;
  ROVER_RETURN_IF_ERROR(Preflight(project, sup));
  if (project.rover.security) {
    // This process's participants (operator, clock, tasks, recorder, the set's heartbeat
    // reader) join as the scenario runner, which may read every topic.
    setenv(dds::kSecurityDirVariable, SecurityDirFor(sup).c_str(), 1);
    setenv(dds::kSecurityIdentityVariable, "scenario-runner", 1);
  }
  return PreparedRun{run_dir, std::move(world), std::move(project), sup};
}

// ---- ServiceSet --------------------------------------------------------------------------------

Result<std::unique_ptr<ServiceSet>> ServiceSet::Create(const PreparedRun& prepared) {
  ROVER_ASSIGN_OR_RETURN(std::unique_ptr<Supervisor> sup,
                         Supervisor::Create(prepared.project, prepared.supervisor));
  return std::unique_ptr<ServiceSet>(new ServiceSet(std::move(sup)));
}

ServiceSet::~ServiceSet() = default;

Status ServiceSet::Start() { return supervisor_->Start(); }

Status ServiceSet::OpenOperator() {
  ROVER_ASSIGN_OR_RETURN(participant_, dds::Participant::Create(domain()));
  ROVER_ASSIGN_OR_RETURN(control_,
                         dds::Writer<rover_sim_Control>::Create(participant_, "sim/control"));
  return Status::Ok();
}

bool ServiceSet::SimulatorHearsUs() const {
  return control_.valid() && control_.MatchedReaders() > 0;
}

Status ServiceSet::ResumeSimulator() {
  rover_sim_Control resume{};
  dds::CopyString(resume.header.frame_id, "sim");
  resume.command_id = 1;
  resume.command = rover_sim_SIM_RESUME;
  if (!control_.Write(resume).ok()) return Unavailable("cannot resume the simulator");
  return Status::Ok();
}

std::string ServiceSet::CheckServices(std::vector<std::string>* crashes) {
  const Time now = MonotonicNow();
  if (now - last_process_poll_ < Seconds(kProcessPollS)) {
    supervisor_->PollHeartbeats();
    return "";
  }
  last_process_poll_ = now;
  supervisor_->Poll();
  for (const auto& st : supervisor_->Snapshot()) {
    // A service killed on purpose is expected to end once and be restarted; waiting for that
    // restart is not a crash (ending again afterwards is).
    if (auto k = killed_.find(st.name); k != killed_.end() &&
                                        st.state == ServiceState::kBackoff &&
                                        st.restarts == k->second) {
      continue;
    }
    if (st.state == ServiceState::kFailed || st.state == ServiceState::kBackoff ||
        (st.state == ServiceState::kExited && st.restarts == 0 && !st.last_exit.empty())) {
      std::ifstream log(st.log_path);
      std::string line, last;
      while (std::getline(log, line)) {
        if (!line.empty() && line.rfind("---- roverctl:", 0) != 0) last = line;
      }
      crashes->push_back(st.name + ": " + st.last_exit + (last.empty() ? "" : "; " + last));
      return "service '" + st.name + "' crashed (" + st.last_exit + ")";
    }
  }
  return "";
}

void ServiceSet::Stop() { supervisor_->Stop(); }

Status ServiceSet::Kill(const std::string& service) {
  int restarts = 0;
  for (const auto& st : supervisor_->Snapshot()) {
    if (st.name == service) restarts = st.restarts;
  }
  ROVER_RETURN_IF_ERROR(supervisor_->Signal(service, SIGKILL));
  killed_[service] = restarts;
  return Status::Ok();
}

bool ServiceSet::RunsAgain(const std::string& service) const {
  auto k = killed_.find(service);
  if (k == killed_.end()) return false;
  for (const auto& st : supervisor_->Snapshot()) {
    if (st.name == service) return st.state == ServiceState::kRunning && st.restarts > k->second;
  }
  return false;
}

}  // namespace rover::deploy::runner
