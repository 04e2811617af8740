// autonav-kinematic: a scenario's mobility task over many seeds in seconds, for tuning autonomy
// before a campaign in the simulator (which takes minutes per seed).
//
// What runs is the real decision-making: the MobilityManager with GESTALT, configured exactly
// as the scenario's apl-mobility service would be (the rover description, the compose file's
// --set arguments, then the scenario's params.apl-mobility, then this tool's --set). What is
// simplified is everything below it:
//  - the world is the scenario's own (sim/world's BuildWorld for each seed: the same rocks,
//    hills and start disc the simulator would build);
//  - locomotion is kinematic (tests' FakeWorld: each primitive driven exactly at --speed /
//    --turn-rate, no slip, no steering time);
//  - stereo is tests/support's ray-cast pinhole HAZCAM (core/hwconfig's mounts, 256 x 256,
//    120 deg) with range noise sigma = --noise * r^2, captured at the request's pose and
//    delivered --latency s later;
//  - the pose is exact (origin on the bare ground, roll and pitch from it under the wheels).
// The outcome, the distance, the steps and the judge's hazard contacts (sim/judge, the scenario's
// criteria) are printed per seed; --verbose adds every drive and status. It says nothing about
// stereo artefacts, slip or the services' timing: the campaign in the simulator does.
// --known-field hands the planner the whole field (exact heights, from truth) before the run:
// a failure then is the planner's, not perception's.
//
//   autonav-kinematic deploy/scenarios/autonav_vl2.yaml --seeds 1..20
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <optional>
#include <memory>
#include <string>
#include <vector>

#include "decision_picture.hpp"
#include "fake_world.hpp"
#include "rover/apl/enav/enav_planner.hpp"
#include "rover/apl/mobility/mobility_manager.hpp"
#include "rover/apl/mobility/mobility_options.hpp"
#include "rover/apl/mobility/navigation.hpp"
#include "rover/base/param_binder.hpp"
#include "rover/deploy/compose.hpp"
#include "rover/deploy/runner.hpp"
#include "rover/deploy/runner/judging.hpp"
#include "rover/deploy/runner/service_set.hpp"
#include "rover/deploy/runner/task.hpp"
#include "rover/deploy/runner/tasks/mobility_task.hpp"
#include "rover/hwconfig/rover_description.hpp"
#include "rover/msg/mobility_idl.hpp"
#include "rover/sim/judge/passability.hpp"
#include "rover/testing/fakes/range_synth.hpp"

namespace {

using namespace rover;               // NOLINT(google-build-using-namespace): a tool's main file
using namespace rover::apl::mobility;  // NOLINT(google-build-using-namespace)
namespace mt = rover::apl::mobility::testing;
namespace rt = rover::testing;

constexpr char kService[] = "apl-mobility";

// A sim/terrain world seen by ray-cast HAZCAMs; the rover's origin on the bare ground.
class TerrainScene : public mt::Scene {
 public:
  TerrainScene(const sim::terrain::Terrain& terrain, const hwconfig::RoverDescription& rover,
               double noise_at_1m, std::uint64_t seed, double traversable_height,
               bool frozen = false)
      : terrain_(terrain), rover_(rover), noise_(noise_at_1m), seed_(seed), frozen_(frozen) {
    for (const auto& r : terrain.rocks) {
      if (r.height > traversable_height) hazards_.push_back(&r);
    }
  }

  Eigen::Isometry3d SiteFromRover(const Pose2& p) const override {
    const sim::terrain::HeightField& g = terrain_.bare;
    const double c = std::cos(p.heading), s = std::sin(p.heading);
    const double half_base = 0.5 * (rover_.front_wheel_x - rover_.rear_wheel_x);
    const double half_track = rover_.half_track;
    auto h = [&](double fx, double fy) { return g.Height(p.x + c * fx - s * fy, p.y + s * fx + c * fy); };
    const double pitch = std::atan2(h(-half_base, 0) - h(half_base, 0), 2.0 * half_base);
    const double roll = std::atan2(h(0, -half_track) - h(0, half_track), 2.0 * half_track);
    Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
    t.linear() = (Eigen::AngleAxisd(p.heading, Eigen::Vector3d::UnitZ()) *
                  Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
                  Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
                     .toRotationMatrix();
    t.translation() = Eigen::Vector3d(p.x, p.y, g.Height(p.x, p.y));
    return t;
  }

  apl::nav_core::RangeScan Capture(const Pose2& pose, CameraId camera) const override {
    const bool rear = camera == CameraId::kRearHazcam;
    if (!rear && camera != CameraId::kFrontHazcam) {
      ++unsupported_;
      return {};  // no NAVCAM here: an empty scan (the manager reads it as all invalid)
    }
    const hwconfig::StereoMount& m = rear ? rover_.rear_hazcam : rover_.front_hazcam;
    rt::PinholeCamera cam = rt::FrontHazcam();
    cam.position = m.position;
    cam.yaw = m.yaw;
    cam.depression = m.depression;
    cam.noise_at_1m = noise_;
    cam.seed = seed_ * 100003u + static_cast<std::uint64_t>(images_++);
    apl::nav_core::RangeScan scan = rt::SynthesizeScan(terrain_.ground, cam, SiteFromRover(pose));
    // --frozen-map: the image is taken (the manager's cycle is unchanged) but its one valid
    // point lies far beyond the planner's reach (a wholly invalid image is an IMG fault), so
    // the planner's map stays the known field.
    if (frozen_ && !scan.valid.empty()) {
      std::fill(scan.valid.begin(), scan.valid.end(), std::uint8_t{0});
      scan.valid[0] = 1;
      scan.xyz[0] = 1.0e4F;
      scan.xyz[1] = 0.0F;
      scan.xyz[2] = 0.0F;
    }
    return scan;
  }

  double Clearance(double x, double y) const override {
    double c = 1e9;
    for (const auto* r : hazards_) {
      c = std::min(c, std::hypot(x - r->position.x(), y - r->position.y()) -
                          sim::terrain::RockBoundingRadius(*r));
    }
    return c;
  }
  int unsupported() const { return unsupported_; }

 private:
  const sim::terrain::Terrain& terrain_;
  const hwconfig::RoverDescription& rover_;
  double noise_;
  std::uint64_t seed_;
  bool frozen_ = false;
  std::vector<const sim::terrain::Rock*> hazards_;
  mutable int images_ = 0;
  mutable int unsupported_ = 0;
};

// Is the field passable at all for the judge? sim/judge passability.hpp over the whole terrain
// (the judge's contact parts, or with `rectangle` the whole ground footprint, `margin` around
// them): the shortest contact-free path's length, or a negative number when there is none.
double FeasiblePathLength(const sim::world::World& world, const sim::judge::RoverFootprint& fp,
                          double traversable_height, Eigen::Vector2d goal, double tolerance,
                          double margin, bool rectangle) {
  const sim::terrain::HeightField& g = world.terrain.bare;
  sim::judge::PassabilityQuery q;
  q.start = {world.start_x, world.start_y};
  q.start_yaw = world.start_yaw;
  q.goal = goal;
  q.tolerance = tolerance;
  q.area_min = {g.min_x(), g.min_y()};
  q.area_max = {g.max_x(), g.max_y()};
  q.margin = margin;
  q.rectangle = rectangle;
  q.traversable_height = traversable_height;
  const auto len = sim::judge::ContactFreePathLength(deploy::runner::JudgeRocks(world), fp, q);
  if (!len.ok()) {
    std::fprintf(stderr, "passability: %s\n", len.status().message().c_str());
    return -1.0;
  }
  return len->has_value() ? **len : -1.0;
}

// apl-mobility's parameters as the scenario's set would give them.
Result<ParamSet> ServiceParams(const deploy::Scenario& scenario,
                               const std::vector<std::string>& extra) {
  ParamSet params(kService);
  DeclareNavigationParams(params);
  ROVER_ASSIGN_OR_RETURN(const deploy::ComposeProject project,
                         deploy::LoadComposeFile(scenario.compose_path));
  const deploy::ServiceSpec* svc = project.Find(kService);
  if (svc == nullptr) {
    return InvalidArgument(scenario.compose_path + ": no service '" + kService + "'");
  }
  for (std::size_t i = 0; i + 1 < svc->command.size(); ++i) {
    if (svc->command[i] == "--set") {
      ROVER_RETURN_IF_ERROR(params.SetFromString(svc->command[i + 1], scenario.compose_path));
    }
  }
  if (auto it = scenario.params.find(kService); it != scenario.params.end()) {
    for (const auto& [key, value] : it->second) {
      ROVER_RETURN_IF_ERROR(params.SetFromString(key + "=" + value, scenario.file));
    }
  }
  for (const std::string& a : extra) ROVER_RETURN_IF_ERROR(params.SetFromString(a, "--set"));
  ROVER_RETURN_IF_ERROR(params.Validate());
  return params;
}

// --known-field: the whole terrain as exact range points (heights every 5 cm, rocks included),
// in scans all taken from the field's centre so the planner's scrolling map keeps them (main
// widens the map to hold them). Truth: a diagnostic that judges the planner apart from what the
// cameras see, never the stack's input.
constexpr double kKnownFieldSpacing = 0.05;  // [m]
std::vector<apl::nav_core::RangeScan> KnownFieldScans(const sim::terrain::Terrain& terrain) {
  const sim::terrain::HeightField& g = terrain.ground;
  const Eigen::Vector2d lo(g.min_x(), g.min_y());
  const Eigen::Vector2d hi(g.max_x(), g.max_y());
  const Eigen::Vector2d centre = 0.5 * (lo + hi);
  const double z0 = g.Height(centre.x(), centre.y());
  std::vector<apl::nav_core::RangeScan> scans;
  constexpr int kRows = 100;  // one scan per 5 m strip of x
  for (double x0 = lo.x(); x0 < hi.x(); x0 += kRows * kKnownFieldSpacing) {
    apl::nav_core::RangeScan sc;
    sc.width = static_cast<int>(std::floor((hi.y() - lo.y()) / kKnownFieldSpacing));
    sc.height = kRows;
    sc.camera = "known_field";
    sc.site_from_rover.translation() = Eigen::Vector3d(centre.x(), centre.y(), z0);
    for (int v = 0; v < sc.height; ++v) {
      for (int u = 0; u < sc.width; ++u) {
        const double x = x0 + (v + 0.5) * kKnownFieldSpacing;
        const double y = lo.y() + (u + 0.5) * kKnownFieldSpacing;
        const bool inside = x < hi.x();
        sc.xyz.push_back(static_cast<float>(x - centre.x()));
        sc.xyz.push_back(static_cast<float>(y - centre.y()));
        sc.xyz.push_back(static_cast<float>(inside ? g.Height(x, y) - z0 : 0.0));
        sc.valid.push_back(inside ? 1 : 0);
      }
    }
    scans.push_back(std::move(sc));
  }
  return scans;
}

struct SeedResult {
  std::string outcome;
  bool pass = false;
  int hazard_contacts = 0;
  int footprint_overlaps = 0;
  double distance = 0, sim_s = 0, to_goal = -1, clearance = 0;
  std::uint32_t steps = 0, images = 0;
  int decisions = 0;                   // arc-vote snapshots (path selections)
  double decide_ms = 0.0;              // manager CPU per decision [ms]
  double ranked = 0.0, checks = 0.0;   // per decision (path planners)
  double free_path = std::numeric_limits<double>::quiet_NaN();  // [m] FeasiblePathLength
  std::string message;
};

const char* PrimitiveName(PrimitiveKind k) {
  switch (k) {
    case PrimitiveKind::kArc: return "arc";
    case PrimitiveKind::kStraight: return "straight";
    case PrimitiveKind::kTurnInPlace: return "turn";
    case PrimitiveKind::kStop: return "stop";
    default: return "?";
  }
}

Result<SeedResult> RunSeed(const deploy::Scenario& scenario,
                           const deploy::runner::MobilityTaskSpec& spec, const ParamSet& params,
                           std::uint32_t seed, const mt::WorldOptions& wo, double noise,
                           bool verbose, bool votes, std::optional<double> passability_margin,
                           bool passability_rectangle, int map_step,
                           const std::vector<int>& picture_steps, bool known_field,
                           bool frozen_map) {
  ROVER_ASSIGN_OR_RETURN(const sim::world::World world,
                         deploy::runner::BuildRunWorld(scenario, seed, scenario.file));
  ROVER_ASSIGN_OR_RETURN(const hwconfig::RoverDescription rover,
                         ReadParams<hwconfig::RoverDescription>(params, "geometry."));
  ROVER_ASSIGN_OR_RETURN(
      MobilityManager manager,
      MakeMobilityManager(params, known_field ? KnownFieldScans(world.terrain) :
                                                std::vector<apl::nav_core::RangeScan>{}));
  ROVER_ASSIGN_OR_RETURN(sim::judge::Judge judge, deploy::runner::MakeJudge(scenario, world));
  const TerrainScene scene(world.terrain, rover, noise, seed, scenario.criteria.traversable_height,
                           frozen_map);
  mt::FakeWorld w(&manager, wo, &scene);
  w.pose() = {world.start_x, world.start_y, world.start_yaw};
  if (map_step >= 0) {
    // The height map's hazard classes around the rover at one decision (planners with heights).
    w.on_arc_votes = [&manager, map_step](const ArcVotesSnapshot& snap) {
      if (static_cast<int>(snap.step) != map_step) return;
      const apl::nav_core::HeightMap* m = manager.assessor().height_map();
      if (m == nullptr) {
        std::printf("    (the planner keeps no height map)\n");
        return;
      }
      const Eigen::Vector3d at = snap.site_from_rover.translation();
      const Eigen::Vector3d fwd = snap.site_from_rover.linear().col(0);
      std::printf("    step %u at (%.2f, %.2f) heading %.0f deg; x up, y left; '.' seen, 'w' "
                  "wheel, 'r' rocker, 'B' body hazard, 'o' rover footprint, '>' heading\n",
                  snap.step, at.x(), at.y(), std::atan2(fwd.y(), fwd.x()) * 180 / M_PI);
      const double half = 4.0;
      int listed = 0;
      for (int j = 0; j < m->height && listed < 40; ++j) {
        for (int i = 0; i < m->width && listed < 40; ++i) {
          const std::size_t k = m->Index(i, j);
          const Eigen::Vector2d c = m->CellCenter(i, j);
          if (m->hazard[k] == 0 || (c - at.head<2>()).norm() > 3.0) continue;
          std::printf("    hazard %d at (%.2f, %.2f) step %.3f count %d range %.2f\n", m->hazard[k],
                      c.x(), c.y(), m->step[k], m->count[k], m->range[k]);
          ++listed;
        }
      }
      for (double x = at.x() + half; x >= at.x() - half; x -= m->resolution) {
        std::printf("    ");
        for (double y = at.y() + half; y >= at.y() - half; y -= m->resolution) {
          int i = 0, j = 0;
          m->CellOf(x, y, &i, &j);
          char c = ' ';
          if (m->Contains(i, j)) {
            const std::size_t k = m->Index(i, j);
            const std::uint8_t h = m->hazard[k];
            c = m->count[k] == 0 ? ' '
                : (h & apl::nav_core::kHazardBody) != 0   ? 'B'
                : (h & apl::nav_core::kHazardRocker) != 0 ? 'r'
                : (h & apl::nav_core::kHazardWheel) != 0  ? 'w'
                                                          : '.';
          }
          const Eigen::Vector3d rel = snap.site_from_rover.inverse() * Eigen::Vector3d(x, y, at.z());
          if (std::abs(rel.x()) <= 0.78 && std::abs(rel.y()) <= 0.58 && c == '.') c = 'o';
          if (rel.x() > 0.8 && rel.x() < 1.0 && std::abs(rel.y()) < 0.06) c = '>';
          std::putchar(c);
        }
        std::printf("\n");
      }
    };
  } else if (votes) {
    // One line per decision: the chosen candidate, then each candidate as
    // kind(k or angle):hazard/waypoint/merged, forbidden ones as kind:X.
    w.on_arc_votes = [](const ArcVotesSnapshot& snap) {
      const apl::nav_core::ArcEvaluation& e = snap.evaluation;
      std::printf("    votes step %u chosen %d", snap.step, e.chosen);
      if (!e.path.empty()) {
        std::printf(" path");
        for (const apl::nav_core::Candidate& c : e.path) {
          if (c.kind == apl::nav_core::MotionKind::kPointTurn) {
            std::printf(" t%.0f", c.turn_angle * 180 / M_PI);
          } else {
            std::printf(" %c%.2f/%.1fm", c.direction > 0 ? 'f' : 'b', c.curvature, c.length);
          }
        }
        std::printf(" (ranked %d, checked %d)", e.candidates_ranked, e.clearance_checks);
      }
      std::printf(":");
      for (std::size_t k = 0; k < e.candidates.size(); ++k) {
        const apl::nav_core::Candidate& c = e.candidates[k];
        if (c.kind == apl::nav_core::MotionKind::kPointTurn) {
          std::printf(" t%.0f", c.turn_angle * 180 / M_PI);
        } else {
          std::printf(" %c%.2f", c.direction > 0 ? 'f' : 'b', c.curvature);
        }
        if (e.hazard[k].goodness == 0) {
          std::printf(":X");
          if (k < e.why.size() && !e.why[k].empty()) std::printf("(%s)", e.why[k].c_str());
        } else {
          std::printf(":%d/%d/%d", e.hazard[k].goodness, e.waypoint[k].goodness,
                      e.merged[k].goodness);
        }
      }
      std::printf("\n");
    };
  }

  deploy::runner::MobilityCommandStorage storage;
  const rover_apl_MobilityCommand idl = deploy::runner::MakeMobilityCommand(spec, 1, 0.0, &storage);
  const MobilityCommand command = msg::MobilityCommandFromIdl(idl);
  const double budget = spec.time_budget_s > 0 ? spec.time_budget_s + 60.0 : 3600.0;

  w.Absorb(manager.OnPose(w.PoseNow(), w.now()));
  double ranked_sum = 0.0, checks_sum = 0.0;
  std::vector<Eigen::Vector2d> trail;
  if (!picture_steps.empty()) {
    // A picture of the ENav decision at each listed step (hazards, tree, checks, cost-to-go).
    auto print = w.on_arc_votes;
    w.on_arc_votes = [print, &manager, &trail, &picture_steps, &world, &rover, seed,
                      &scenario](const ArcVotesSnapshot& snap) {
      trail.push_back(snap.site_from_rover.translation().head<2>());
      if (print) print(snap);
      if (std::find(picture_steps.begin(), picture_steps.end(), static_cast<int>(snap.step)) ==
          picture_steps.end()) {
        return;
      }
      const auto* planner = dynamic_cast<const apl::enav::EnavPlanner*>(&manager.selector());
      const apl::nav_core::HeightMap* m = manager.assessor().height_map();
      if (planner == nullptr || m == nullptr) {
        std::printf("    (no picture: the planner is not ENav)\n");
        return;
      }
      std::vector<apl::enav::PictureRock> rocks;
      for (const auto& rock : world.terrain.rocks) {
        if (rock.height > scenario.criteria.traversable_height) {
          rocks.push_back({rock.position.head<2>(), 0.5 * rock.diameter});
        }
      }
      const std::string file = "enav_seed" + std::to_string(seed) + "_step" +
                               std::to_string(snap.step) + ".png";
      const cv::Mat img = apl::enav::DrawDecision(*planner, *m, rover, trail, rocks);
      std::printf("    step %u: %s %s\n", snap.step, cv::imwrite(file, img) ? "wrote" : "could not write",
                  file.c_str());
    };
  }
  {
    auto print = w.on_arc_votes;
    w.on_arc_votes = [print, &ranked_sum, &checks_sum](const ArcVotesSnapshot& snap) {
      const apl::nav_core::ArcEvaluation& e = snap.evaluation;
      ranked_sum += e.candidates_ranked > 0 ? e.candidates_ranked
                                            : static_cast<double>(e.candidates.size());
      checks_sum += e.clearance_checks;
      if (print) print(snap);
    };
  }
  w.Absorb(manager.OnCommand(command, w.now()));
  judge.AddTruth(w.now(), scene.SiteFromRover(w.pose()));
  std::size_t seen_status = 0, seen_drive = 0;
  std::string last_message;
  MobilityStatus last;
  last.state = State::kRunning;
  bool done = false;
  while (!done && w.now().seconds() < budget) {
    w.Tick();
    judge.AddTruth(w.now(), scene.SiteFromRover(w.pose()));
    for (; seen_drive < w.drives().size(); ++seen_drive) {
      const DriveCommand& d = w.drives()[seen_drive];
      if (verbose) {
        std::printf("  %7.1f s (%6.2f, %6.2f, %6.1f deg) %s k=%.3f s=%.2f a=%.1f\n",
                    w.now().seconds(), w.pose().x, w.pose().y, w.pose().heading * 180 / M_PI,
                    PrimitiveName(d.primitive), d.curvature, d.distance, d.angle * 180 / M_PI);
      }
    }
    for (; seen_status < w.statuses().size(); ++seen_status) {
      const MobilityStatus& s = w.statuses()[seen_status];
      if (s.command_id != command.command_id) continue;
      last = s;
      if (verbose && s.message != last_message) {
        std::printf("  %7.1f s status %s: %s\n", w.now().seconds(),
                    msg::MobilityStateName(s.state), s.message.c_str());
      }
      last_message = s.message;
      if (s.state != State::kRunning) done = true;
    }
  }
  const sim::judge::Verdict v = judge.Evaluate();
  SeedResult r;
  if (passability_margin && spec.goal) {
    r.free_path = FeasiblePathLength(
        world, sim::judge::RoverFootprint::MerDefault(), scenario.criteria.traversable_height,
        spec.goal->xy, spec.goal->tolerance, *passability_margin, passability_rectangle);
  }
  r.outcome = !done                              ? std::string("UNFINISHED")
              : last.state == State::kSucceeded ? std::string("reached")
                                                : std::string(msg::MobilityFaultName(last.fault));
  r.hazard_contacts = static_cast<int>(v.rocks_hit.size());
  r.footprint_overlaps = static_cast<int>(v.footprint_overlaps.size());
  if (verbose) {
    for (const int id : v.rocks_hit) {
      for (const auto& rock : world.terrain.rocks) {
        if (rock.id != id) continue;
        std::printf("  hazard contact: rock %d at (%.2f, %.2f), diameter %.2f m, height %.2f m\n",
                    id, rock.position.x(), rock.position.y(), rock.diameter, rock.height);
        for (const auto& c : v.contacts) {
          if (c.rock_id == id) std::printf("    first touched by %s at %.1f s\n", c.part.c_str(), c.t_s);
        }
        // What the planner's height map (if any) says under the rock's outline.
        if (const apl::nav_core::HeightMap* m = manager.assessor().height_map()) {
          int cells = 0, known = 0, hazard = 0;
          double top = -1.0, top_range = 0.0;
          for (int j = 0; j < m->height; ++j) {
            for (int i = 0; i < m->width; ++i) {
              const Eigen::Vector2d c = m->CellCenter(i, j);
              if ((c - rock.position.head<2>()).norm() > 0.5 * rock.diameter) continue;
              const std::size_t k = m->Index(i, j);
              ++cells;
              if (m->count[k] == 0) continue;
              ++known;
              if (m->hazard[k] & apl::nav_core::kHazardWheel) ++hazard;
              if (m->step[k] > top) {
                top = m->step[k];
                top_range = m->range[k];
              }
            }
          }
          std::printf("    in the height map: %d cells under it, %d seen, %d wheel hazards; highest "
                      "step %.3f m (seen from %.2f m)\n",
                      cells, known, hazard, top, top_range);
        }
      }
    }
  }
  r.pass = deploy::runner::OutcomeNameMatches(spec.expect, r.outcome) && r.hazard_contacts == 0;
  r.decisions = w.arc_vote_snapshots();
  if (r.decisions > 0) {
    r.decide_ms = 1e3 * w.manager_cpu_s() / r.decisions;
    r.ranked = ranked_sum / r.decisions;
    r.checks = checks_sum / r.decisions;
  }
  r.distance = last.distance_driven;
  r.steps = last.steps;
  r.images = last.images;
  r.sim_s = w.now().seconds();
  r.to_goal = last.distance_to_goal;
  r.clearance = w.min_rock_clearance();
  r.message = last.message;
  if (scene.unsupported() > 0) {
    r.message += " [" + std::to_string(scene.unsupported()) + " NAVCAM requests unanswered]";
  }
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"A scenario's mobility task over seeds with a kinematic rover and ray-cast HAZCAMs"};
  std::string path, seeds_text = "1";
  std::vector<std::string> sets;
  mt::WorldOptions wo;
  wo.speed = 0.05;
  wo.turn_rate = 0.1;
  wo.image_latency_s = 2.0;
  double noise = 0.005;
  bool verbose = false;
  std::optional<double> passability_margin;
  app.add_option("scenario", path, "scenario file with a mobility task")->required();
  app.add_option("--seeds", seeds_text, "run seeds, A..B or A");
  app.add_option("--set", sets, "apl-mobility parameter, key=value (after the scenario's)");
  app.add_option("--speed", wo.speed, "[m/s] drive speed")->check(CLI::PositiveNumber);
  app.add_option("--turn-rate", wo.turn_rate, "[rad/s] turn-in-place rate")->check(CLI::PositiveNumber);
  app.add_option("--latency", wo.image_latency_s, "[s] range request to range image")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--noise", noise, "[m] range noise sigma at 1 m (grows with r^2)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--passability", passability_margin,
                 "[m] also search each field for a path free of the judge's hazard contacts with "
                 "this margin around the contact parts (column free_path; - when there is none)")
      ->check(CLI::NonNegativeNumber);
  bool passability_rectangle = false;
  app.add_flag("--passability-rectangle", passability_rectangle,
               "search for a path of the whole ground-footprint rectangle instead (the judge's "
               "footprint_overlaps, which also counts straddled rocks)");
  app.add_flag("--verbose", verbose, "print every drive and status message");
  bool votes = false;
  bool expect_safe = false, expect_typed = false;
  app.add_flag("--expect-safe", expect_safe,
               "exit 0 when no run touched a hazard and every run reached the goal or ended in a "
               "goal error (NOPROGRESS, NOPATH)");
  app.add_flag("--expect-typed", expect_typed,
               "exit 0 when every run reached the goal or ended in a goal error (NOPROGRESS, "
               "NOPATH): no motion error, bad command or time-out; contacts are reported only");
  int map_step = -1;
  app.add_option("--map-at-step", map_step,
                 "print the height map's hazards around the rover at this decision (enav)");
  std::vector<int> picture_steps;
  app.add_option("--picture-at-step", picture_steps,
                 "write enav_seed<S>_step<N>.png: the ENav decision at these steps (the height "
                 "map's hazards, the path tree, the refused and chosen paths, the cost-to-go)");
  app.add_flag("--votes", votes, "print every decision's votes (hazard/waypoint/merged)");
  bool known_field = false;
  app.add_flag("--known-field", known_field,
               "the planner's map holds the whole field exactly before the run (truth: judges "
               "the planner apart from perception; ENav's map is widened to hold it)");
  bool frozen_map = false;
  app.add_flag("--frozen-map", frozen_map,
               "with --known-field: the HAZCAM images add nothing to the planner's map, and its "
               "noise allowance is 0 (the field is exact): the planner's search on a true, "
               "unchanging map");
  CLI11_PARSE(app, argc, argv);
  if (frozen_map && !known_field) {
    std::fprintf(stderr, "autonav-kinematic: --frozen-map needs --known-field (the map it keeps)\n");
    return 2;
  }
  if (frozen_map) sets.insert(sets.begin(), "enav.stereo_noise_coeff=0");
  if (known_field) {
    // ENav's map must hold the field seen from its centre (keys before the user's --set).
    sets.insert(sets.begin(), {"enav.map_size_m=100", "enav.max_point_distance_m=30",
                               "enav.recentre_distance_m=15", "enav.drop_self_points=false"});
  }

  auto fail = [](const Status& s) {
    std::fprintf(stderr, "autonav-kinematic: %s\n", s.message().c_str());
    return 2;
  };
  auto scenario = deploy::LoadScenario(path);
  if (!scenario.ok()) return fail(scenario.status());
  auto seeds = deploy::ParseSeedRange(seeds_text);
  if (!seeds.ok()) return fail(seeds.status());
  auto task = deploy::runner::TaskRegistry::Builtin().Make(*scenario);
  if (!task.ok()) return fail(task.status());
  const auto* mobility = dynamic_cast<const deploy::runner::MobilityTask*>(task->get());
  if (mobility == nullptr) {
    return fail(InvalidArgument(path + ": task.type '" + scenario->task.type +
                                "' is not a mobility task (autonav, goto_waypoint, guarded, "
                                "guarded_arc)"));
  }
  auto params = ServiceParams(*scenario, sets);
  if (!params.ok()) return fail(params.status());

  std::printf("%s: expect %s; speed %.3g m/s, latency %.3g s, noise %.3g m at 1 m\n",
              scenario->name.c_str(), mobility->spec().expect.c_str(), wo.speed,
              wo.image_latency_s, noise);
  if (known_field && PlannerName(*params) != "enav") {
    // GESTALT's grid scrolls with the rover over a few metres: a whole field cannot be held.
    return fail(InvalidArgument("--known-field: nav.planner is '" + PlannerName(*params) +
                                "'; only enav keeps a map the size of a field"));
  }
  std::printf("planner %s\n", PlannerName(*params).c_str());
  std::printf("%5s %-12s %4s %8s %6s %6s %8s %8s %9s %9s %9s %9s %7s %6s  %s\n", "seed",
              "outcome", "pass", "driven", "steps", "images", "sim_s", "to_goal", "contacts",
              "overlaps", "free_path", "decide_ms", "ranked", "checks", "message");
  int passed = 0, runs_decided = 0, unsafe = 0, untyped = 0;
  double decide_sum = 0.0, ranked_all = 0.0, checks_all = 0.0;
  std::map<std::string, int> outcomes;
  for (const std::uint32_t seed : *seeds) {
    auto r = RunSeed(*scenario, mobility->spec(), *params, seed, wo, noise, verbose, votes,
                     passability_margin, passability_rectangle, map_step, picture_steps,
                     known_field, frozen_map);
    if (!r.ok()) return fail(r.status());
    passed += r->pass ? 1 : 0;
    char free_path[16] = "n/a";
    if (!std::isnan(r->free_path)) {
      std::snprintf(free_path, sizeof free_path, r->free_path < 0 ? "-" : "%.1fm", r->free_path);
    }
    std::printf("%5u %-12s %4s %7.1fm %6u %6u %8.0f %7.2fm %9d %9d %9s %9.2f %7.0f %6.1f  %s\n",
                seed, r->outcome.c_str(), r->pass ? "yes" : "no", r->distance, r->steps,
                r->images, r->sim_s, r->to_goal, r->hazard_contacts, r->footprint_overlaps,
                free_path, r->decide_ms, r->ranked, r->checks, r->message.c_str());
    outcomes[r->outcome + (r->hazard_contacts > 0 ? " (contact)" : "")] += 1;
    const bool typed =
        r->outcome == "reached" || r->outcome == "NOPROGRESS" || r->outcome == "NOPATH";
    untyped += typed ? 0 : 1;
    if (r->hazard_contacts > 0 || !typed) unsafe += 1;
    if (r->decisions > 0) {
      runs_decided += 1;
      decide_sum += r->decide_ms;
      ranked_all += r->ranked;
      checks_all += r->checks;
    }
    std::fflush(stdout);
  }
  std::printf("passed %d of %zu (outcome %s, no hazard contact)\n", passed, seeds->size(),
              mobility->spec().expect.c_str());
  std::printf("outcomes:");
  for (const auto& [name, n] : outcomes) std::printf(" %s %d;", name.c_str(), n);
  std::printf("\n");
  if (runs_decided > 0) {
    std::printf("decision (mean over runs): %.2f ms manager CPU per step, %.0f paths ranked, "
                "%.1f clearance checks\n",
                decide_sum / runs_decided, ranked_all / runs_decided, checks_all / runs_decided);
  }
  if (expect_typed) {
    std::printf("%d run(s) ended other than reached / NOPROGRESS / NOPATH\n", untyped);
    return untyped == 0 ? 0 : 1;
  }
  if (expect_safe) {
    std::printf("%d run(s) touched a hazard or ended other than reached / NOPROGRESS / NOPATH\n",
                unsafe);
    return unsafe == 0 ? 0 : 1;
  }
  return passed == static_cast<int>(seeds->size()) ? 0 : 1;
}
