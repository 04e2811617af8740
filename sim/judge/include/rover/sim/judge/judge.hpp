#pragma once
/// @file
/// The judge: scores a run against ground truth. It is the only consumer of simulator truth
/// besides tests; the stack never sees it.
///
/// Inputs, all in the site frame (x north, y west, z up; metres, radians, run-clock time):
///  - truth samples: the rover body pose over time (from sim/truth);
///  - estimate samples: the stack's own pose estimate over time (from dl/pose), optional;
///  - odometry-only samples: the stack's IMU + wheel odometry baseline (dl/pose_odometry),
///    optional, reported beside the fused estimate (never judged);
///  - the terrain's rock list and the rover's contact parts and ground footprint;
///  - pass criteria.
/// Output: one Criterion per check with the measured value, the limit, pass/fail and a detail
/// line, and the overall verdict.
///
/// Hazard contact: a rock taller than `traversable_height` (MER/FIDO's 20 cm obstacle) that a
/// part of the rover touches at any truth sample. The parts are the rover description's
/// (hwconfig::RoverDescription::ContactParts(): wheel discs covering every steering angle, the
/// bogie and rocker bands on the wheel lines, the body box), each with its clearance less
/// `clearance_margin` for articulation and sinkage; a rock counts against a part when it is
/// taller than that part's clearance and its footprint (its outline polygon, elongation and
/// lobes included; JudgeRock) reaches the part's outline. A rock lower than the belly that passes
/// between the wheels is not a contact. Reported as the criterion `hazard_contacts` (limit
/// `max_hazard_contacts`, 0 when unset), its detail naming the first rocks, their heights and the
/// part that touched each.
///
/// Footprint overlaps (a figure, `footprint_overlaps`): the stricter count of such rocks whose
/// footprint reaches the whole ground-footprint rectangle (GroundFootprint(): wheels, body, mast,
/// camera mounts), i.e. also those the rover straddled. Tilt is the angle between the body z
/// axis and the site z axis. Estimate error at an estimate sample is
/// the horizontal distance between the estimated and the (linearly interpolated) true position;
/// heading error is the estimated minus the true yaw, wrapped to (-pi, pi].
///
/// Figures (Verdict::figures) are measurements reported with the verdict but not judged: the
/// final and worst estimate errors (m, % of the distance driven, heading deg) and the same for
/// the odometry-only baseline, so every number printed names the truth comparison behind it.

#include <Eigen/Geometry>
#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include "rover/base/status.hpp"
#include "rover/base/time.hpp"
#include "rover/hwconfig/rover_description.hpp"

namespace rover::sim::judge {

struct JudgeRock {
  int id = 0;
  Eigen::Vector2d xy = Eigen::Vector2d::Zero();  ///< [m] centre
  double diameter = 0.0;                         ///< [m] nominal
  double height = 0.0;                            ///< [m]
  /// [m] the footprint's outline, site frame, a polygon around `xy` (sim/terrain RockOutline:
  /// elongation and lobes included); empty: the disc of the nominal diameter.
  std::vector<Eigen::Vector2d> outline = {};
  /// [m] the largest distance from `xy` to the footprint's edge.
  double Reach() const;
};

/// Whether `rock` reaches within `margin` of `part` of a rover standing at site_from_rover =
/// (rot, t) (2-D). With an outline: a vertex within `margin` of the part, or the part's point
/// nearest the rock's centre inside the outline (exact for convex parts up to the polygon's
/// chords). The height test against the part's clearance is the caller's.
bool RockTouches(const JudgeRock& rock, const Eigen::Matrix2d& rot, const Eigen::Vector2d& t,
                 const hwconfig::ContactPart& part, double margin = 0.0);

/// What of the rover can touch a rock, in the rover frame (x forward, y left, z up).
struct RoverFootprint {
  std::vector<hwconfig::ContactPart> parts;  ///< see the file comment
  double clearance_margin = 0.05;            ///< [m] off every non-zero part clearance
  /// [m] the whole rover's ground footprint (footprint_overlaps)
  Eigen::Vector2d body_min{-0.75, -0.58}, body_max{0.75, 0.58};
  /// The default rover description's contact parts and ground footprint.
  static RoverFootprint MerDefault();
  /// [m] The height a rock must exceed to touch `part`: its clearance less clearance_margin (0
  /// for parts that reach the ground).
  double ClearanceOf(const hwconfig::ContactPart& part) const {
    return part.clearance > 0.0 ? std::max(0.0, part.clearance - clearance_margin) : 0.0;
  }
};

struct JudgeCriteria {
  std::optional<Eigen::Vector2d> target_xy;  ///< [m] final position goal
  double position_tolerance = 0.5;           ///< [m]
  std::optional<double> target_heading;      ///< [rad] final heading goal
  double heading_tolerance = 0.0873;         ///< [rad] (5 deg)
  double max_tilt = 0.5236;                  ///< [rad] (30 deg)
  double traversable_height = 0.20;          ///< [m] taller rocks must not be touched
  std::optional<double> max_estimate_error;  ///< [m] largest |estimate - truth| allowed
  std::optional<double> max_estimate_error_fraction;  ///< of distance driven (e.g. 0.01 = 1%)
  std::optional<double> max_estimate_heading_error;  ///< [rad] largest |heading error| allowed
  std::optional<double> min_distance;        ///< [m] the rover must have driven at least this
  std::optional<int> max_hazard_contacts;    ///< hazard contacts allowed (file comment); unset = 0
  Status Validate() const;
};

struct Criterion {
  std::string name;     ///< e.g. "final_position_error"
  double measured = 0;  ///< in `unit`
  double limit = 0;
  std::string unit;     ///< "m", "deg", "count", "%"
  bool pass = false;
  std::string detail;
};

struct ErrorSample {
  Time t;
  double position_error = 0;  ///< [m] horizontal
  double heading_error = 0;   ///< [rad] signed, estimate - truth
};

/// A rock over the traversable height that a part of the rover touched (its first contact).
struct HazardContact {
  int rock_id = 0;
  Eigen::Vector2d xy = Eigen::Vector2d::Zero();  ///< [m] the rock's centre, site frame
  double height = 0.0;                           ///< [m]
  std::string part;                              ///< core/hwconfig contact part: wheel_lf, body...
  double t_s = 0.0;                              ///< [s] run time of the first contact
};

struct Verdict {
  bool pass = false;
  std::vector<Criterion> criteria;
  double distance_driven = 0;        ///< [m] truth path length (horizontal)
  double max_tilt = 0;               ///< [rad]
  std::vector<int> rocks_hit;        ///< ids of rocks over the traversable height touched
  std::vector<HazardContact> contacts;  ///< the same, where, by which part, when
  std::vector<int> footprint_overlaps;      ///< ids of such rocks under the ground footprint
  std::vector<ErrorSample> estimate_error;  ///< over time
  std::vector<ErrorSample> odometry_only_error;  ///< over time (empty without such samples)
  /// Not judged (limit NaN, pass true): see the file comment.
  std::vector<Criterion> figures;
  const Criterion* Find(const std::string& name) const;
  /// The failed criteria as "name: measured > limit unit" lines.
  std::string FailureSummary() const;
};

class Judge {
 public:
  /// Fails on invalid criteria.
  static Result<Judge> Create(JudgeCriteria criteria, std::vector<JudgeRock> rocks,
                              RoverFootprint footprint = RoverFootprint::MerDefault());

  /// Truth and estimate samples must arrive in time order (older ones are ignored and counted).
  void AddTruth(Time t, const Eigen::Isometry3d& pose);
  void AddEstimate(Time t, const Eigen::Isometry3d& pose);
  void AddOdometryOnlyEstimate(Time t, const Eigen::Isometry3d& pose);
  std::size_t out_of_order() const { return out_of_order_; }

  /// Scores what was added so far. Without any truth sample the verdict fails with a criterion
  /// "truth_received".
  Verdict Evaluate() const;

 private:
  Judge() = default;
  struct Stamped {
    Time t;
    Eigen::Isometry3d pose;
  };
  void CheckRocks(const Eigen::Isometry3d& pose);
  std::optional<Eigen::Isometry3d> TruthAt(Time t) const;

  JudgeCriteria criteria_;
  std::vector<JudgeRock> rocks_;  // only those taller than the traversable height
  RoverFootprint footprint_;
  // Spatial hash over the tall rocks: cell -> indices.
  double cell_ = 1.0;
  std::vector<std::vector<std::size_t>> grid_;
  Eigen::Vector2d grid_min_ = Eigen::Vector2d::Zero();
  int grid_nx_ = 0, grid_ny_ = 0;
  double max_rock_radius_ = 0;
  std::vector<Stamped> truth_;
  std::vector<Stamped> estimates_;
  std::vector<Stamped> odometry_only_;
  std::vector<ErrorSample> ErrorsOf(const std::vector<Stamped>& estimates) const;
  std::vector<bool> hit_;
  std::vector<int> hit_part_;  // index into footprint_.parts of the first contact
  std::vector<double> hit_t_;  // [s] run time of the first contact
  double now_s_ = 0.0;         // run time of the truth sample being checked
  std::vector<bool> overlap_;
  double distance_ = 0;
  double max_tilt_ = 0;
  std::size_t out_of_order_ = 0;
};

}  // namespace rover::sim::judge
