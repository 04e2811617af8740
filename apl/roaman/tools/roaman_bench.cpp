// roaman-bench: ROAMAN against the A* baseline on the same traversability map, in one run.
//   Scene: FIDO's Figure 3 (seed 004 §6.1): a rock field of medium density (15 % rock cover)
//   seen by a synthetic mast NAVCAM panorama from 1.5 m; the planning grid is 6 m x 12 m at
//   5 cm (120 x 240 cells: 1.5 m behind the rover to 10.5 m ahead), the goal 9 m ahead (or
//   the nearest of a few points around it that a safe path reaches), tolerance 1 m.
//   (a) Time: map binning and the seven steps (shared), then planning: ROAMAN (road map, DFS,
//       least-squares fit) vs A* (search, string pulling) vs Dijkstra (the reference); medians
//       of interleaved repeats; the ratio ROAMAN / A*. FIDO's 250 ms on a 266 MHz Pentium for
//       context only.
//   (b) Path length of ROAMAN and of A* relative to the shortest safe path (Dijkstra with
//       length costs on the same graph, string-pulled the same way).
//   --pictures DIR writes the PNGs of README.md (seed 1's map, the cul-de-sac, a replan).
// Usage: roaman-bench [--seeds N] [--repeats N] [--cover K] [--pictures DIR]
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "mast_synth.hpp"
#include "render.hpp"
#include "rover/apl/roaman/planner.hpp"
#include "rover/base/format.hpp"
#include "scenes.hpp"

namespace ro = rover::apl::roaman;
namespace rt = rover::apl::roaman::testing;
using Clock = std::chrono::steady_clock;

namespace {

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

double Ms(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

ro::RoamanOptions FigureThreeOptions() {
  ro::RoamanOptions o;
  o.plan_width = 6.0;  // FIDO's Figure 3: 6 m wide ...
  o.plan_back = 1.5;   // ... 12 m high: 1.5 m behind the rover to 10.5 m ahead
  o.plan_length = 10.5;
  o.goal_margin = 1.5;
  return o;
}

// The mast panorama: 5 pans over +-40° at three tilts (FIDO took 37 NAVCAM pairs for its map).
std::vector<rt::MastCamera> Pointings() {
  rt::MastCamera cam;
  cam.width = 512;  // 1.5 mrad pixels (MER's NAVCAMs: 0.8 mrad)
  cam.height = 384;
  cam.noise_at_10m = 0.02;
  return rt::PanoramaPointings(
      cam, 40.0 * rover::kDegree, 5,
      {-4.0 * rover::kDegree, -18.0 * rover::kDegree, -34.0 * rover::kDegree});
}

struct SeedResult {
  int seed = 0;
  bool comparable = false;
  double bin_ms = 0, map_ms = 0, prepare_ms = 0, roaman_ms = 0, astar_ms = 0, dijkstra_ms = 0;
  double roaman_len = 0, astar_len = 0, shortest_len = 0;
  int roaman_legs = 0, astar_legs = 0, nodes = 0, dropped = 0;
  std::string note;
};

void WritePictures(const std::string& dir, const ro::PlanProblem& problem, const ro::RoadMap& road,
                   const ro::RoamanPlan* roaman, const ro::RoamanPlan* astar,
                   const ro::RoamanPlan* shortest, const std::string& name) {
  const int scale = 3;
  cv::Mat img = rt::RenderPlanningGrid(problem.grid, scale);
  rt::DrawRoadMap(&img, problem.grid, road, scale);
  if (shortest) {
    std::vector<Eigen::Vector2d> p{problem.request.start};
    p.insert(p.end(), shortest->waypoints.begin(), shortest->waypoints.end());
    rt::DrawPath(&img, problem.grid, p, {60, 170, 60}, 1, false, scale);
  }
  if (astar) {
    std::vector<Eigen::Vector2d> p{problem.request.start};
    p.insert(p.end(), astar->waypoints.begin(), astar->waypoints.end());
    rt::DrawPath(&img, problem.grid, p, {220, 80, 0}, 2, true, scale);
  }
  if (roaman) {
    std::vector<Eigen::Vector2d> p{problem.request.start};
    p.insert(p.end(), roaman->waypoints.begin(), roaman->waypoints.end());
    rt::DrawPath(&img, problem.grid, p, {20, 20, 230}, 2, true, scale);
  }
  const std::string path = dir + "/" + name + ".png";
  const rover::Status s = rt::WritePng(path, img);
  std::printf("  wrote %s (%s)\n", path.c_str(), s.ok() ? "ok" : s.message().c_str());
}

SeedResult RunSeed(int seed, double cover, int repeats, const std::string& pictures) {
  SeedResult r;
  r.seed = seed;
  ro::RoamanOptions o = FigureThreeOptions();
  const rover::sim::terrain::Terrain field =
      rt::RockField(cover, static_cast<std::uint64_t>(seed), 30.0);
  const auto scans =
      rt::SynthesizePanorama(field.natural, Pointings(), rt::RoverPose(field.natural, 0, 0, 0));
  std::vector<double> bin, map, prep, rm, as, dj;
  ro::RoamanPlan roaman, astar, shortest;
  std::optional<ro::PlanProblem> problem;
  ro::RoadMap road;
  for (int rep = 0; rep < repeats; ++rep) {
    ro::SiteMap site(o);
    const auto t0 = Clock::now();
    for (const auto& s : scans) {
      if (!site.AddScan(s).ok()) r.note = "a scan was rejected";
    }
    const auto t1 = Clock::now();
    const ro::TraversabilityMap t = ro::ComputeTraversability(site, o);
    const auto t2 = Clock::now();
    // The goal 9 m ahead, or the first of a few points near it that is on the map and that the
    // shortest safe path reaches (so that all three plans end at the same point). The grid
    // always runs to 10.5 m: goal_margin = 10.5 m - goal distance.
    ro::PlanFailure failure = ro::PlanFailure::kNone;
    rover::Result<ro::PlanProblem> p = rover::NotFound("no goal");
    std::string why;
    for (const double d : {9.0, 8.5, 8.0, 7.5, 7.0}) {
      for (const double deg : {0.0, 4.0, -4.0, 8.0, -8.0, 12.0, -12.0}) {
        rover::apl::nav_core::PlanRequest req;
        req.goal =
            d * Eigen::Vector2d(std::cos(deg * rover::kDegree), std::sin(deg * rover::kDegree));
        req.goal_tolerance = 1.0;
        o.goal_margin = o.plan_length - d;
        p = ro::PreparePlan(t, req, o, &failure);
        if (p.ok() && p->goal_on_grid && ro::ShortestSafePath(*p, o).ok()) break;
        why = p.ok() ? "no safe path to " + ro::FormatPoint(req.goal) : p.status().message();
        p = rover::NotFound("no goal near 9 m ahead has a safe path (last: " + why + ")");
      }
      if (p.ok()) break;
    }
    const auto t3 = Clock::now();
    if (!p.ok()) {
      r.note = p.status().message();
      if (!pictures.empty() && rep == 0) {
        // What the rover could do: a partial plan toward the goal 9 m ahead.
        rover::apl::nav_core::PlanRequest req;
        req.goal = {9.0, 0.0};
        req.allow_partial = true;
        o.goal_margin = 1.5;
        auto q = ro::PreparePlan(t, req, o, &failure);
        if (q.ok()) {
          auto a = ro::PlanWithAStar(*q, o);
          auto b = ro::PlanWithRoadMap(*q, o, &road);
          WritePictures(pictures, *q, road, b.ok() ? &*b : nullptr, a.ok() ? &*a : nullptr, nullptr,
                        "rock_field_seed" + std::to_string(seed) + "_partial");
        }
      }
      break;
    }
    problem = std::move(p).value();
    // Interleave the planners' order between repeats.
    auto run_roaman = [&] {
      const auto a = Clock::now();
      auto x = ro::PlanWithRoadMap(*problem, o, &road);
      rm.push_back(Ms(a, Clock::now()));
      if (x.ok()) roaman = *x;
      return x.ok();
    };
    auto run_astar = [&] {
      const auto a = Clock::now();
      auto x = ro::PlanWithAStar(*problem, o);
      as.push_back(Ms(a, Clock::now()));
      if (x.ok()) astar = *x;
      return x.ok();
    };
    bool ok_r = false, ok_a = false;
    if (rep % 2 == 0) {
      ok_r = run_roaman();
      ok_a = run_astar();
    } else {
      ok_a = run_astar();
      ok_r = run_roaman();
    }
    const auto d0 = Clock::now();
    auto ref = ro::ShortestSafePath(*problem, o);
    dj.push_back(Ms(d0, Clock::now()));
    if (ref.ok()) shortest = *ref;
    bin.push_back(Ms(t0, t1));
    map.push_back(Ms(t1, t2));
    prep.push_back(Ms(t2, t3));
    r.comparable = ok_r && ok_a && ref.ok() && roaman.reaches_goal && astar.reaches_goal;
    if (!ok_r) r.note = "roaman: no route";
    if (!ok_a) r.note = "astar: no route";
  }
  r.bin_ms = Median(bin);
  r.map_ms = Median(map);
  r.prepare_ms = Median(prep);
  r.roaman_ms = Median(rm);
  r.astar_ms = Median(as);
  r.dijkstra_ms = Median(dj);
  r.roaman_len = roaman.length;
  r.astar_len = astar.length;
  r.shortest_len = shortest.length;
  r.roaman_legs = static_cast<int>(roaman.legs.size());
  r.astar_legs = static_cast<int>(astar.legs.size());
  r.nodes = roaman.road_nodes;
  r.dropped = roaman.road_dropped;
  if (!pictures.empty() && seed == 1) {
    if (problem)
      WritePictures(pictures, *problem, road, r.comparable ? &roaman : nullptr,
                    r.comparable ? &astar : nullptr, r.comparable ? &shortest : nullptr,
                    "rock_field_seed1");
    ro::SiteMap site(o);
    for (const auto& s : scans) (void)site.AddScan(s);
    const ro::TraversabilityMap t = ro::ComputeTraversability(site, o);
    const std::string path = pictures + "/rock_field_seed1_site.png";
    const rover::Status s = rt::WritePng(path, rt::RenderTraversability(t, 1));
    std::printf("  wrote %s (%s)\n", path.c_str(), s.ok() ? "ok" : s.message().c_str());
  }
  return r;
}

// The pictures of the cul-de-sac and of a replan around a blocked corridor.
void ScenarioPictures(const std::string& dir) {
  ro::RoamanOptions o;
  o.plan_width = 10.0;
  {
    rover::sim::terrain::HeightField g = rt::FlatGround(-3, -7, 14, 7, 0.04);
    rt::AddCulDeSac(&g, {6.0, 0.0}, {-1.0, 0.0}, 3.0, 3.0, 0.3, 0.8);
    ro::RoamanPlanner p(o);
    for (const auto& s : rt::SynthesizePanorama(
             g,
             rt::PanoramaPointings(rt::MastCamera{}, 60.0 * rover::kDegree, 5,
                                   {-6.0 * rover::kDegree, -26.0 * rover::kDegree}),
             rt::RoverPose(g, 0, 0, 0))) {
      (void)p.AddScan(s);
    }
    rover::apl::nav_core::PlanRequest req;
    req.goal = {10.0, 0.0};
    req.allow_partial = true;
    auto a = p.Plan(req, ro::Algorithm::kAStar);
    auto r = p.Plan(req, ro::Algorithm::kRoaman);
    if (p.last_problem() && p.last_road_map()) {
      WritePictures(dir, *p.last_problem(), *p.last_road_map(), r.ok() ? &*r : nullptr,
                    a.ok() ? &*a : nullptr, nullptr, "cul_de_sac");
    }
    std::printf("  cul-de-sac from the mast: roaman %s, astar %s\n",
                r.ok() ? "planned" : r.status().message().c_str(),
                a.ok() ? "planned" : a.status().message().c_str());
  }
  {
    rover::sim::terrain::HeightField g = rt::FlatGround(-3, -5, 14, 5, 0.04);
    rt::AddWall(&g, {2.0, 0.0}, {8.0, 0.0}, 0.25, 0.6);
    rt::AddWall(&g, {-3.0, 3.75}, {14.0, 3.75}, 0.25, 0.6);
    rt::AddWall(&g, {-3.0, -3.75}, {14.0, -3.75}, 0.25, 0.6);
    ro::RoamanOptions w;
    w.plan_width = 8.0;
    ro::RoamanPlanner p(w);
    (void)p.AddScan(rt::OverheadScan(g, -2, -4.5, 12, 4.5, 0.04, rt::RoverPose(g, 0, 0, 0)));
    rover::apl::nav_core::PlanRequest req;
    req.goal = {10.0, 0.0};
    auto first = p.Plan(req);
    if (!first.ok()) return;
    double side = 0.0;
    for (const ro::Leg& l : first->legs) {
      const Eigen::Vector2d m = 0.5 * (l.from + l.to);
      if (m.x() > 3.0 && m.x() < 7.0) side = m.y();
    }
    const double y = side > 0 ? 1.9 : -1.9;
    (void)p.ReportBlocked({4.0, y}, {6.0, y}, 1.6);
    auto second = p.Plan(req);
    if (second.ok() && p.last_problem() && p.last_road_map()) {
      WritePictures(dir, *p.last_problem(), *p.last_road_map(), &*second, nullptr, &*first,
                    "replan");
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"roaman-bench: ROAMAN vs A* on FIDO's 6 x 12 m map at 5 cm"};
  int seeds = 5, repeats = 9;
  double cover = 0.15;
  std::string pictures;
  app.add_option("--seeds", seeds, "rock fields 1..N")->check(CLI::Range(1, 1000));
  app.add_option("--repeats", repeats, "timed runs per seed (medians)")->check(CLI::Range(1, 1000));
  app.add_option("--cover", cover, "rock area fraction k (FIDO's medium field: 0.15)")
      ->check(CLI::Range(0.0, 0.4));
  app.add_option("--pictures", pictures, "folder for the README pictures");
  CLI11_PARSE(app, argc, argv);
  if (!pictures.empty()) std::filesystem::create_directories(pictures);

  std::printf(
      "roaman-bench: rock fields k = %.2f, seeds 1..%d, %d repeats; grid 6 x 12 m at 5 cm "
      "(120 x 240 cells), goal 9 m ahead\n",
      cover, seeds, repeats);
  std::printf("%5s %8s %8s %8s | %9s %8s %9s %7s | %7s %7s %5s/%-5s %s\n", "seed", "bin ms",
              "map ms", "prep ms", "roaman ms", "A* ms", "dijkst ms", "R/A*", "R/short", "A*/shrt",
              "legs", "A*", "road nodes (dropped)");
  std::vector<double> ratio, rlen, alen, rms, ams, mapms;
  for (int seed = 1; seed <= seeds; ++seed) {
    const SeedResult r = RunSeed(seed, cover, repeats, pictures);
    if (!r.comparable) {
      std::printf("%5d  not comparable: %s\n", seed, r.note.c_str());
      continue;
    }
    const double q = r.roaman_ms / r.astar_ms;
    std::printf("%5d %8.1f %8.1f %8.2f | %9.2f %8.2f %9.2f %7.2f | %7.3f %7.3f %5d/%-5d %d (%d)\n",
                r.seed, r.bin_ms, r.map_ms, r.prepare_ms, r.roaman_ms, r.astar_ms, r.dijkstra_ms, q,
                r.roaman_len / r.shortest_len, r.astar_len / r.shortest_len, r.roaman_legs,
                r.astar_legs, r.nodes, r.dropped);
    ratio.push_back(q);
    rlen.push_back(r.roaman_len / r.shortest_len);
    alen.push_back(r.astar_len / r.shortest_len);
    rms.push_back(r.roaman_ms);
    ams.push_back(r.astar_ms);
    mapms.push_back(r.map_ms);
  }
  if (!ratio.empty()) {
    std::printf(
        "median over %zu seeds: seven-step map %.1f ms; planning roaman %.2f ms, A* %.2f ms, "
        "roaman / A* = %.2f\n",
        ratio.size(), Median(mapms), Median(rms), Median(ams), Median(ratio));
    std::printf(
        "path length / shortest safe path: roaman median %.3f (max %.3f), A* median %.3f "
        "(max %.3f)\n",
        Median(rlen), *std::max_element(rlen.begin(), rlen.end()), Median(alen),
        *std::max_element(alen.begin(), alen.end()));
  }
  std::printf(
      "context: FIDO planned its 6 x 12 m, 5 cm map in 250 ms on a 266 MHz Pentium "
      "(seed 004 §6.1); not comparable hardware, shown for scale only\n");
  if (!pictures.empty()) ScenarioPictures(pictures);
  return 0;
}
