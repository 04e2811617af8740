#pragma once
/// @file
/// What a lander-return run is judged on, from sim/truth and the simulator's lander (never seen
/// by the stack): the rendezvous's distance estimates against the true distance at 15, 25, 35
/// and 45 m (seed 004's checkpoints), the placement at the ramp base in the ramp's frame at the
/// moment apl-rendezvous reports AT_RAMP_BASE, and whether the rover ended on the deck.
///
/// Placement frame: the chosen ramp's foot B (the middle of its bottom edge), its horizontal
/// up-axis a and left normal n = z x a; the rover's goal is G = B - standoff a, heading along a.
///   lateral = (p - G) . n,   longitudinal = (p - G) . a,   heading = wrap(yaw - atan2(a))
/// with p and yaw the true rover origin and heading. Units: cm and degrees in the figures.

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "rover/deploy/run_report.hpp"
#include "rover/sim/judge/judge.hpp"
#include "rover/sim/terrain/lander.hpp"
#include "rover/sim/terrain/terrain.hpp"

namespace rover::deploy::runner {

/// One apl/rendezvous_status as the task heard it.
struct RendezvousSample {
  double t = 0.0;  ///< [s] sim time of the status stamp
  int phase = 0;   ///< msg::RendezvousPhase ordinal
  double range = 0.0;        ///< [m] the rendezvous's estimate (0: none yet)
  double range_sigma = 0.0;  ///< [m]
  /// The status carries a new distance estimate (a sighting), not one repeated from an earlier
  /// status while the rover moved on: only these are judged against the truth.
  bool new_range = false;
  std::string features;
  Eigen::Vector2d target = Eigen::Vector2d::Zero();  ///< [m] the lander estimate, site frame
};

/// What the lander-return task records for the judge.
struct RendezvousLog {
  double standoff = 1.0;  ///< [m] as commanded (or the service default)
  int ramp = -1;          ///< ramp the rendezvous approached (from its statuses)
  bool expect_on_deck = false;  ///< the task expects the run to end on the deck
  bool expect_acquired = false;  ///< phase 1 only: the run ends at the hand-over to mid range
  std::vector<RendezvousSample> samples;
  std::optional<double> at_base_t;  ///< [s] first AT_RAMP_BASE
  std::string end_phase = "none";   ///< "DONE", "FAILED", ... of the terminal status
  std::string fault = "NONE";
  std::string message;
};

/// The rendezvous figures (measured; never pass/fail here): range_error_<d>m [%] for d in 15,
/// 25, 35, 45 when a sighting's true distance came within 3 m of d; placement_lateral,
/// placement_longitudinal [cm], placement_heading [deg] when AT_RAMP_BASE was reported;
/// on_deck (1/0) from the last truth point inside the deck hexagon; acquired_at_m, the true
/// distance when the first estimate from a sighting was reported; toward_distractor, the
/// sightings after which the estimate (what the next leg drives to) pointed, from the rover's
/// true position, within a layered outcrop's (a rock with layers > 0) angular radius + 0.5 m and
/// outside the lander's (apothem + ramp length): a range error on the right bearing does not count.
std::vector<sim::judge::Criterion> RendezvousFigures(const RendezvousLog& log,
                                                     const sim::terrain::Lander& lander,
                                                     const std::vector<sim::terrain::Rock>& rocks,
                                                     const RunResult& result);

/// The true distance [m] from the rover origin at track point (x, y) to the deck centre.
double TrueLanderDistance(const sim::terrain::Lander& lander, double x, double y);

}  // namespace rover::deploy::runner
