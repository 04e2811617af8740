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
///  - the terrain's rock list and the rover's footprint (wheel contact points and belly box);
///  - pass criteria.
/// Output: one Criterion per check with the measured value, the limit, pass/fail and a detail
/// line, and the overall verdict.
///
/// Rock contact: a rock taller than `traversable_height` (MER/FIDO's 20 cm obstacle) counts as
/// hit when, at any truth sample, its footprint disc (diameter D) overlaps a wheel's ground
/// contact disc, or lies under the belly box while taller than the belly clearance. Tilt is the
/// angle between the body z axis and the site z axis.
///
/// Hazard contact (autonomous driving's figure): a rock taller than `traversable_height` whose
/// footprint disc overlaps the rover's ground footprint (the rectangle of
/// hwconfig::RoverDescription::GroundFootprint(): wheels, body, mast, camera mounts) at any
/// truth sample, i.e. the rover drove over or into it with any part. Reported as the criterion
/// `hazard_contacts` when `max_hazard_contacts` is set, else as a figure. Estimate error at an estimate sample is
/// the horizontal distance between the estimated and the (linearly interpolated) true position;
/// heading error is the estimated minus the true yaw, wrapped to (-pi, pi].
///
/// Figures (Verdict::figures) are measurements reported with the verdict but not judged: the
/// final and worst estimate errors (m, % of the distance driven, heading deg) and the same for
/// the odometry-only baseline, so every number printed names the truth comparison behind it.

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

#include "rover/base/status.hpp"
#include "rover/base/time.hpp"

namespace rover::sim::judge {

struct JudgeRock {
  int id = 0;
  Eigen::Vector2d xy = Eigen::Vector2d::Zero();  ///< [m] centre
  double diameter = 0.0;                          ///< [m]
  double height = 0.0;                            ///< [m]
};

/// Where the rover touches the ground, in the rover frame (x forward, y left, z up).
struct RoverFootprint {
  std::vector<Eigen::Vector2d> wheels;  ///< wheel ground-contact points [m]
  double wheel_contact_radius = 0.10;   ///< [m] half the wheel width plus margin
  Eigen::Vector2d belly_min{-0.45, -0.35}, belly_max{0.45, 0.35};  ///< [m] belly box
  double belly_clearance = 0.30;        ///< [m] rocks taller than this hit the belly
  /// [m] the whole rover's ground footprint (hazard contacts)
  Eigen::Vector2d body_min{-0.75, -0.58}, body_max{0.75, 0.58};
  /// The default rover description's wheel centres (wheelbase 1.25 m, track 1.0 m) and ground
  /// footprint; the contact radius, belly box and clearance above are the judge's own (with
  /// margins).
  static RoverFootprint MerDefault();
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
  std::optional<int> max_hazard_contacts;    ///< judge hazard contacts (see the file comment)
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

struct Verdict {
  bool pass = false;
  std::vector<Criterion> criteria;
  double distance_driven = 0;        ///< [m] truth path length (horizontal)
  double max_tilt = 0;               ///< [rad]
  std::vector<int> rocks_hit;        ///< ids of rocks over the traversable height touched
  std::vector<int> hazards_hit;      ///< ids of such rocks under the ground footprint
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
  std::vector<bool> hazard_hit_;
  double distance_ = 0;
  double max_tilt_ = 0;
  std::size_t out_of_order_ = 0;
};

}  // namespace rover::sim::judge
