#pragma once
/// @file
/// FIDO's science-target tracking (seed 004, section 5, steps 3-13) for the single-command
/// approach: the target is designated by a pixel of a NAVCAM left image; after each drive the
/// tracker finds the target and the features about it in the new pair and measures where the
/// target now is relative to the rover, so wheel slip does not enter the approach.
///
/// One step, from the last pair (ref) to a new one (cur), both with camera models in their own
/// rover frame R and the dl/pose at capture:
///  1. Predicted motion M = R_cur from R_ref from the two poses (wheel odometry, slip and all).
///  2. Features: Förstner points (interest_points.hpp) in a window `window_m` wide about the
///     target in the ref left image, each ranged in the ref pair (ray_stereo.hpp) to X_i in R_ref;
///     the target itself is one more point, always kept.
///  3. For each point, its epipolar segment in the cur left image: the ref ray through it at
///     distances t/(1+range_slack) .. t(1+range_slack), moved by M and projected.
///  4. A patch of the ref image is projected into the cur image about the segment: every pixel
///     of a (2 template_half + 1)^2 window in cur is traced back through the local ground plane
///     (R_ref's x-y plane through X_i) into the ref image (a homography for a pinhole camera).
///  5. Coarse cross-correlation of that patch over a band `band_px` wide along the segment
///     (cross-track error of M), the best peak refined by a parabola in x and y.
///  6. The rover motion from all points' new ranges (10) by RANSAC over 3-point rigid fits and
///     a least-squares fit over the inliers (11), an inlier within an ellipsoid about its ray
///     that is as long as its range error (inlier_range_sigma; EstimateMotion); the patches are
///     projected again with the measured motion and matched again within +-refine_px (8-9, the
///     homography refinement), and re-ranged at full resolution (10), and the motion fitted
///     again.
///  7. The target: its own patch's match re-ranged in the cur pair when it agrees with the
///     motion (within gate_sigma sigma + gate_floor_m), else carried by the motion (12).
///  8. The cur pair becomes ref; its features are taken about the new target position.
/// The target's range error falls with its distance (~1 cm at 2 m for the NAVCAM), so the fix
/// at the standoff is measured from there, not carried from the designation at 10 m.
///
/// Frames: R (x forward, y left, z up, at each pair's capture), the site frame S of dl/pose.
/// Units: metres, pixels, radians.

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "rover/apl/rendezvous/interest_points.hpp"
#include "rover/apl/rendezvous/ray_stereo.hpp"
#include "rover/apl/rendezvous/sightings.hpp"
#include "rover/base/status.hpp"
#include "rover/geometry/camera_model.hpp"

namespace rover {
template <class Options>
class ParamBinder;
}  // namespace rover

namespace rover::apl::rendezvous {

struct TrackerOptions {
  double window_m = 1.2;       ///< [m] side of the square about the target where features are taken
  int min_window_px = 96;      ///< [px] least side of that window in the image
  int max_window_px = 360;     ///< [px] largest side
  int max_features = 50;       ///< Förstner points kept (strongest first)
  double min_roundness = 0.4;  ///< Förstner roundness threshold (interest_points.hpp)
  double min_weight_ratio = 0.2;  ///< Förstner weight threshold, times the window's mean
  double max_feature_offset_m = 2.0;  ///< [m] features farther than this from the target dropped
  int template_half = 10;      ///< [px] the projected patch is (2 h + 1)^2
  double range_slack = 0.4;    ///< relative: the epipolar segment spans t / (1 + s) .. t (1 + s)
  int band_px = 40;            ///< [px] searched across the segment (heading error of the pose)
  int refine_px = 3;           ///< [px] search of the refinement with the measured motion
  double min_ncc = 0.7;        ///< lowest patch correlation of a match
  int min_inliers = 5;         ///< fewer features consistent with one motion: the target is lost
  double min_inlier_ratio = 0.4;  ///< ... or fewer than this share of those found again
  double inlier_m = 0.02;      ///< [m] RANSAC threshold floor ...
  double inlier_range_ratio = 0.015;  ///< ... or this fraction of the feature's range
  /// A feature's stereo range is far worse along its ray than across it (sigma ~ t^2: 7-9 cm at
  /// 9 m with the NAVCAM's 0.20 m baseline, millimetres across), so at long range the sphere
  /// above rejects correct features and lets wrong motions gather as many. With this > 0 a
  /// feature is an inlier within an ellipsoid about its ref ray (moved by the motion): the
  /// sphere's radius across the ray and, along it, the larger of that and this many sigma of the
  /// feature's two ranges combined; hypotheses come also from one feature each with dl/pose's
  /// rotation, and the motion is fitted weighting each feature by the covariance of its ranges
  /// (along) and across_sigma_px (across). Where this many sigma are under the sphere's radius
  /// (within ~3 m) the test is the sphere. 0: the sphere and a plain least-squares fit.
  double inlier_range_sigma = 3.0;
  /// [px] 1-sigma of a feature's position across its ray (both images): its weight across the
  /// ray in the motion fit (inlier_range_sigma > 0)
  double across_sigma_px = 0.5;
  double gate_sigma = 3.0;     ///< target measurement within this many sigma ...
  double gate_floor_m = 0.005; ///< ... + this [m] of where the features' motion carries it
  /// Too few features agree on a motion: the target's own match (this correlation or better,
  /// within max_target_alone_jump_m of where the pose puts it) keeps the track alone.
  double min_target_alone_ncc = 0.9;
  double max_target_alone_jump_m = 0.5;
  int ransac_iterations = 300;
  int stereo_half_window = 7;  ///< [px] patch of the range correlation
  double min_stereo_ncc = 0.7; ///< lowest correlation of a range
  /// Ok, or InvalidArgument naming the field (prefix "tracker.").
  Status Validate() const;
  /// Keys `tracker.<field>` of apl-rendezvous.
  static void BindParams(ParamBinder<TrackerOptions>& b);
};

/// One feature of the last step, for drawings and tests.
struct FeatureTrack {
  Eigen::Vector2d ref_pixel = Eigen::Vector2d::Zero();  ///< in the ref left image
  Eigen::Vector2d pixel = Eigen::Vector2d::Zero();      ///< in the cur left image
  double ncc = 0.0;
  bool matched = false;  ///< found and re-ranged in cur
  bool inlier = false;   ///< consistent with the measured motion
  Eigen::Vector3d ref_point = Eigen::Vector3d::Zero();  ///< [m] ranged in the ref pair, R_ref
  Eigen::Vector3d point = Eigen::Vector3d::Zero();      ///< [m] re-ranged in cur, R_cur (matched)
  double ref_sigma = 0.0;  ///< [m] 1-sigma of ref_point along its ref ray
  double sigma = 0.0;      ///< [m] 1-sigma of point along its cur ray (matched)
};

/// Rigid motion B = T A (least squares over the pairs, Kabsch/Umeyama without scale).
/// Precondition: a.size() == b.size() >= 3.
Eigen::Isometry3d FitRigid(const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b);

/// One feature ranged in the ref pair and found and re-ranged in the cur pair (step 6's input).
struct RangedFeature {
  Eigen::Vector3d ref = Eigen::Vector3d::Zero();  ///< [m] in R_ref
  Eigen::Vector3d cur = Eigen::Vector3d::Zero();  ///< [m] in R_cur
  Eigen::Vector3d ref_ray =
      Eigen::Vector3d::UnitX();  ///< unit direction of its ref left ray, R_ref
  double ref_t = 0.0;            ///< [m] its distance along that ray
  double ref_sigma = 0.0;        ///< [m] 1-sigma of the ref range along the ref ray
  double cur_sigma = 0.0;        ///< [m] 1-sigma of the cur range along the cur ray
  double across_sigma = 0.0;     ///< [m] 1-sigma across the rays (the pixel precision at its range)
};

/// The rover's motion from the features (step 6).
struct MotionEstimate {
  Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();  ///< R_cur from R_ref
  std::vector<bool> inlier;                                  ///< per feature
  int inliers = 0;                                           ///< 0 when no motion was found
  double rms = 0.0;                                          ///< [m] residual over the inliers, 3-D
};

/// Step 6: RANSAC and a least-squares fit over the inliers, two rounds. With
/// options.inlier_range_sigma = 0 a 3-point rigid fit per hypothesis, an inlier within
/// max(inlier_m, inlier_range_ratio ref_t) of where the motion carries it, and a plain (Kabsch)
/// fit; with > 0 also one hypothesis per feature with `predicted`'s rotation, the ellipsoids about
/// the rays and the covariance-weighted fit (TrackerOptions::inlier_range_sigma). `seed`: the
/// RANSAC's. inliers = 0 when fewer than 3 features or no motion with 3 inliers.
MotionEstimate EstimateMotion(const std::vector<RangedFeature>& features,
                              const Eigen::Isometry3d& predicted, const TrackerOptions& options,
                              unsigned seed);

class TargetTracker final : public TargetVision {
 public:
  /// Precondition: options.Validate() is ok.
  explicit TargetTracker(const TrackerOptions& options = {});

  Result<TargetFix> Designate(const NavcamPair& pair, const Eigen::Isometry3d& site_from_rover,
                              const Eigen::Vector2d& pixel) override;
  Result<TargetFix> Track(const NavcamPair& pair, const Eigen::Isometry3d& site_from_rover) override;
  DetectionImage LastDrawing() override { return drawing_; }

  /// The features of the last step (empty after Designate).
  const std::vector<FeatureTrack>& tracks() const { return tracks_; }
  /// The target pixel in the last pair's left image.
  const Eigen::Vector2d& target_pixel() const { return target_pixel_; }
  bool started() const { return started_; }

 private:
  struct Frame {
    cv::Mat left, right;  // owned copies
    geometry::CameraModel left_model, right_model;
    Eigen::Isometry3d site_from_rover;
  };
  struct Point {
    Eigen::Vector2d pixel;
    Eigen::Vector3d xyz;  // R of the frame
    double t = 0.0;       // along the left ray
    double sigma = 0.0;   // [m] 1-sigma of t
    Eigen::Vector3d ray = Eigen::Vector3d::UnitX();  // unit direction of the left ray
    double rad_per_px = 0.0;  // [rad] angle of one pixel of the left image there
  };
  static Result<Frame> CopyFrame(const NavcamPair& pair, const Eigen::Isometry3d& site_from_rover);
  // Features about the target in `f` (ranged), the target first. False: too few.
  bool TakeFeatures(const Frame& f, const Eigen::Vector3d& target, const Eigen::Vector2d& target_px,
                    std::vector<Point>* points, std::string* why) const;
  // The ref patch about p projected into cur with motion m (R_cur from R_ref), matched within
  // `band` px of the segment, or within `band` px of `near` when given.
  bool MatchPoint(const Frame& ref, const Point& p, const Frame& cur, const Eigen::Isometry3d& m,
                  const Eigen::Vector2d* near, int band, Eigen::Vector2d* pixel, double* ncc) const;
  void Draw(const Frame& cur, const std::string& name, const TargetFix& fix);
  // `cur` becomes the reference, with features taken about the target (why they are too few,
  // if they are, appended to fix->why).
  void Rereference(Frame cur, const Eigen::Vector3d& target, const Eigen::Vector2d& target_px,
                   TargetFix* fix);

  TrackerOptions options_;
  bool started_ = false;
  std::optional<Frame> ref_;
  std::vector<Point> points_;  // [0] the target
  Eigen::Vector2d target_pixel_ = Eigen::Vector2d::Zero();
  double ref_sigma_ = 0.0;  // [m] of the target in the reference pair
  std::vector<FeatureTrack> tracks_;
  DetectionImage drawing_;
  int steps_ = 0;
};

}  // namespace rover::apl::rendezvous
