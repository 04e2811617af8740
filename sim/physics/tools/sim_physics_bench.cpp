// sim-physics-bench: real-time factor of the rover physics (sim seconds per wall second) for
// driving a distance on flat firm ground, up a firm slope and across a rough bumpy field, and
// the peak RSS. Ratios are printed against the flat-ground run (baseline, same process) and
// against the 10x goal.

#include <sys/resource.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <memory>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "rover/sim/heightfield.hpp"
#include "rover/sim/physics/rover_simulation.hpp"

namespace {

using rover::sim::physics::MotorMode;
using rover::sim::physics::RoverModelParams;
using rover::sim::physics::RoverSimulation;
using rover::sim::terrain::HeightField;

std::shared_ptr<HeightField> MakeSlope(double length, double width, double slope_deg) {
  const double res = 0.1;
  auto h = std::make_shared<HeightField>(static_cast<int>(length / res) + 1,
                                         static_cast<int>(width / res) + 1, res,
                                         Eigen::Vector2d(-3.0, -width / 2));
  const double t = std::tan(slope_deg * std::numbers::pi / 180.0);
  for (int j = 0; j < h->ny(); ++j) {
    for (int i = 0; i < h->nx(); ++i) h->at(i, j) = static_cast<float>((h->min_x() + i * res) * t);
  }
  return h;
}

std::shared_ptr<HeightField> MakeRough(double length, double width, std::uint64_t seed) {
  const double res = 0.05;
  auto h = std::make_shared<HeightField>(static_cast<int>(length / res) + 1,
                                         static_cast<int>(width / res) + 1, res,
                                         Eigen::Vector2d(-3.0, -width / 2));
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> ux(h->min_x(), h->max_x()), uy(h->min_y(), h->max_y());
  std::uniform_real_distribution<double> amp(-0.12, 0.15), sig(0.12, 0.5);
  const int bumps = static_cast<int>(length * width * 1.5);
  std::vector<double> z(static_cast<std::size_t>(h->nx()) * h->ny(), 0.0);
  for (int b = 0; b < bumps; ++b) {
    const double cx = ux(rng), cy = uy(rng), a = amp(rng), s = sig(rng);
    const int r = static_cast<int>(3 * s / res) + 1;
    const int ci = static_cast<int>((cx - h->min_x()) / res),
              cj = static_cast<int>((cy - h->min_y()) / res);
    for (int j = std::max(0, cj - r); j <= std::min(h->ny() - 1, cj + r); ++j) {
      for (int i = std::max(0, ci - r); i <= std::min(h->nx() - 1, ci + r); ++i) {
        const double dx = h->min_x() + i * res - cx, dy = h->min_y() + j * res - cy;
        z[static_cast<std::size_t>(j) * h->nx() + i] +=
            a * std::exp(-(dx * dx + dy * dy) / (2 * s * s));
      }
    }
  }
  for (int j = 0; j < h->ny(); ++j) {
    for (int i = 0; i < h->nx(); ++i)
      h->at(i, j) = static_cast<float>(z[static_cast<std::size_t>(j) * h->nx() + i]);
  }
  return h;
}

double CpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

struct RunResult {
  bool ok = false;
  double sim_s = 0.0, wall_s = 0.0, cpu_s = 0.0, distance = 0.0, odometry = 0.0;
  long long steps = 0;
};

RunResult Drive(const RoverModelParams& params, std::shared_ptr<HeightField> terrain,
                double distance, double speed) {
  RunResult res;
  auto sim_or = RoverSimulation::Create(params, terrain, {0.0, 0.0, 0.0});
  if (!sim_or.ok()) {
    std::fprintf(stderr, "create failed: %s\n", sim_or.status().ToString().c_str());
    return res;
  }
  RoverSimulation& sim = **sim_or;
  const double r = params.geometry.wheel_radius;
  for (int m = 0; m < 6; ++m) {
    const double cpr = params.motors[m].CountsPerRad();
    if (!sim.SetMotorGoal(m, MotorMode::kVelocity, 0.0, speed / r * cpr, 1.2).ok()) return res;
  }
  const Eigen::Vector3d start = sim.Readings().chassis.pose_site.translation();
  const double limit = 3.0 * distance / speed;
  const auto t0 = std::chrono::steady_clock::now();
  const double c0 = CpuSeconds();
  double travelled = 0.0;
  while (travelled < distance && sim.time() < limit) {
    const rover::Status st = sim.Advance(0.1);
    if (!st.ok()) {
      std::fprintf(stderr, "advance failed: %s\n", st.ToString().c_str());
      return res;
    }
    const Eigen::Vector3d p = sim.Readings().chassis.pose_site.translation();
    travelled = (p - start).norm();
  }
  const auto t1 = std::chrono::steady_clock::now();
  res.cpu_s = CpuSeconds() - c0;
  res.ok = true;
  res.sim_s = sim.time();
  res.wall_s = std::chrono::duration<double>(t1 - t0).count();
  res.distance = travelled;
  double wheel = 0.0;
  for (int m = 0; m < 6; ++m)
    wheel += sim.Motor(m).position_counts / params.motors[m].CountsPerRad();
  res.odometry = wheel / 6.0 * r;
  res.steps = sim.stats().integrator_steps;
  return res;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Real-time factor of the rover physics (sim-physics-bench)"};
  double distance = 20.0, speed = 0.05, slope = 15.0, accuracy = 1e-3;
  int slices = 3;
  std::string method = "see2";
  std::uint64_t seed = 7;
  double rate_hz = 1000.0;
  app.add_option("--distance", distance, "metres to drive per scenario")
      ->check(CLI::Range(0.1, 1000.0));
  app.add_option("--speed", speed, "drive speed [m/s]")->check(CLI::Range(0.005, 0.11));
  app.add_option("--slope", slope, "slope of the slope scenario [deg]")
      ->check(CLI::Range(0.0, 25.0));
  app.add_option("--accuracy", accuracy, "integrator accuracy")->check(CLI::Range(1e-6, 1e-1));
  app.add_option("--slices", slices, "contact slices per wheel")->check(CLI::Range(1, 5));
  app.add_option("--seed", seed, "seed of the rough field");
  app.add_option("--rate", rate_hz, "control rate (and see1 step) [Hz]")
      ->check(CLI::Range(100.0, 5000.0));
  app.add_option("--integrator", method, "see2 (error-controlled) or see1 (fixed 1 ms)")
      ->check(CLI::IsMember({"see2", "see1"}));
  CLI11_PARSE(app, argc, argv);

  RoverModelParams params;
  params.integrator.accuracy = accuracy;
  params.contact.slices = slices;
  params.integrator.control_rate_hz = rate_hz;
  if (method == "see1") {
    params.integrator.method = rover::sim::physics::IntegratorMethod::kSemiExplicitEulerFixed;
  }
  const double len = distance + 8.0;
  struct Scenario {
    const char* name;
    std::shared_ptr<HeightField> terrain;
  };
  std::vector<Scenario> scenarios = {{"flat firm", MakeSlope(len, 8.0, 0.0)},
                                     {"slope firm", MakeSlope(len, 8.0, slope)},
                                     {"rough field", MakeRough(len, 8.0, seed)}};
  std::printf("sim-physics-bench: %.1f m at %.3f m/s, %s, accuracy %.0e, %d slices, %.0f Hz\n",
              distance, speed, method.c_str(), accuracy, slices, rate_hz);
  std::printf("RTF = sim s / wall s; cpuRTF = sim s / process CPU s (robust on a loaded box)\n");
  std::printf("%-12s %7s %8s %7s %7s %8s %9s %8s %8s %9s\n", "scenario", "sim[s]", "wall[s]",
              "RTF", "cpuRTF", "vs flat", "vs 10x", "steps/s", "slip[%]", "dist[m]");
  double base = 0.0;
  for (const Scenario& sc : scenarios) {
    const RunResult r = Drive(params, sc.terrain, distance, speed);
    if (!r.ok) {
      std::printf("%-12s FAILED\n", sc.name);
      return 1;
    }
    const double rtf = r.sim_s / r.wall_s;
    const double cpu_rtf = r.sim_s / r.cpu_s;
    if (base == 0.0) base = cpu_rtf;
    const double slip = r.odometry > 0.0 ? 100.0 * (1.0 - r.distance / r.odometry) : 0.0;
    std::printf("%-12s %7.1f %8.2f %7.1f %7.1f %8.2f %9.2f %8.0f %8.2f %9.5f\n", sc.name, r.sim_s,
                r.wall_s, rtf, cpu_rtf, cpu_rtf / base, cpu_rtf / 10.0,
                static_cast<double>(r.steps) / r.sim_s, slip, r.distance);
  }
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  std::printf("peak RSS: %.1f MB\n", static_cast<double>(ru.ru_maxrss) / 1024.0);
  return 0;
}
