#pragma once
/// @file
/// MER visual odometry (Cheng, Maimone & Matthies 2005/2006; Maimone, Cheng & Matthies 2007):
/// the 6-DOF motion of a stereo camera between two stereo pairs, with its covariance.
///
/// Per stereo pair (the "reference" for the next step):
///   1. Förstner interest operator on the left image, best feature per grid cell, minimum
///      separation between features (interest_operator.hpp).
///   2. Stereo matching of each feature along its row with pseudo-normalised correlation and a
///      biquadratic sub-pixel fit, left-right checked (matching.hpp).
///   3. Triangulation with a 3D covariance per feature (triangulation.hpp).
/// Per step, from the reference pair (time t_from) to the new pair (t_to):
///   4. Prediction of each feature in the new left image with the prior motion (wheel odometry
///      on the rover), and a search window of +-window_sigmas standard deviations of the
///      predicted pixel (prior covariance and the feature's 3D covariance propagated).
///      If the median window is larger than refine_window_threshold, a first pass tracks a
///      spatially spread subset (at most first_pass_features, coarse-to-fine) and estimates the
///      motion, which then predicts all features in small windows.
///   5. Correlation tracking, then stereo re-matching in the new right image and triangulation.
///      The template is warped by the predicted local image motion of the surface around the
///      feature: a plane fitted to the feature's nearest 3D neighbours (fronto-parallel if the
///      fit is poor), mapped through the prior motion. Without it, the ground's perspective
///      stretch under forward motion biases the tracked positions (0.5 % of the step here).
///   6. RANSAC over closed-form 3-point rigid fits (rigid_motion.hpp), then Gauss-Newton maximum
///      likelihood over the inliers weighted by the 3D covariances; inliers re-selected with the
///      refined motion and the refinement repeated once.
///   7. MER's sanity checks: enough features, enough inliers, convergence, and limits on the
///      translation and rotation of one step (and, optionally, on the distance from the prior).
///   Whatever the outcome of steps 4-7, the new pair becomes the reference for the next step.
///
/// Frames and units: the left camera frame (x right, y down, z forward), metres and radians.
/// The estimate is T_from_to (see rigid_motion.hpp): the left camera at t_to expressed in the
/// left camera at t_from; chain them as T_0_k = T_0_(k-1) * delta. Covariance over
/// [dx, dy, dz, dthx, dthy, dthz] with the perturbation of rigid_motion.hpp. ChangeMotionFrame()
/// converts the estimate (and a prior) between the camera and the rover body frame.
///
/// Errors: bad input (image size or type, invalid camera, out-of-order stamp, non-finite prior)
/// is returned as a Status and leaves the state unchanged. A step that runs but cannot give a
/// trustworthy motion returns an estimate whose status is not kConverged; it is never a
/// measurement. The library is deterministic (RANSAC seeded per step from options and the
/// step count).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "rover/base/status.hpp"
#include "rover/base/time.hpp"
#include "rover/dl/vo/interest_operator.hpp"
#include "rover/dl/vo/matching.hpp"
#include "rover/dl/vo/rigid_motion.hpp"
#include "rover/dl/vo/stereo_camera.hpp"

namespace rover::dl::vo {

struct Options {
  InterestOptions interest;
  MatchOptions match;
  RansacOptions ransac;
  RefineOptions refine;

  double pixel_sigma = 0.3;  ///< [px] 1-sigma matching noise per image coordinate
  double min_range = 0.3;    ///< [m] features nearer than this are dropped
  double max_range = 60.0;   ///< [m] features farther than this are dropped

  // Tracking.
  double window_sigmas = 3.0;             ///< search half window in predicted standard deviations
  double min_window = 3.0;                ///< [px] smallest search half window
  double max_window = 120.0;              ///< [px] largest search half window (larger are clipped)
  double refine_window_threshold = 10.0;  ///< [px] median window above which a first pass runs
  int first_pass_features = 48;           ///< features tracked in the first pass
  bool warp_templates = true;             ///< warp templates by the predicted local image motion
  int plane_neighbours = 6;               ///< 3D neighbours for the local plane of a warp (0: none)

  // Sanity limits (MER 2005 flight software style).
  int min_features = 12;                     ///< tracked features with 3D at both times, at least
  int min_inliers = 10;                      ///< RANSAC/ML inliers, at least
  double min_inlier_fraction = 0.25;         ///< inliers / tracked features, at least
  double max_translation = 1.0;              ///< [m] |t| of one step, at most
  double max_rotation = 0.35;                ///< [rad] rotation angle of one step, at most (20 deg)
  double max_prior_mahalanobis_sq = 0.0;     ///< gate on (estimate - prior); 0 disables
  bool scale_covariance_by_residual = true;  ///< inflate Cov by max(1, cost / dof)
  /// Model error not in the pixel-noise model (calibration, e.g. a baseline or focal error that
  /// scales every step): adds (fraction * |t|)^2 to each translation variance. 0 = pure ML
  /// covariance (MER); KITTI needs ~0.008, measured (see README).
  double model_translation_fraction = 0.0;

  Status Validate() const;

  /// dl-vo's keys vo.* (without the prefix): pixel_sigma, min_range, max_range, cell_size,
  /// min_separation, min_features, min_inliers, min_inlier_fraction, max_translation,
  /// max_rotation_deg, max_prior_mahalanobis_sq.
  static void BindParams(ParamBinder<Options>& b);

  /// Defaults for a rover NAVCAM/HAZCAM pair (MER-like: slow steps of up to ~1 m).
  static Options Rover() { return Options{}; }
  /// Defaults for car-mounted data such as KITTI (1.2 m steps at 10 Hz, wide images).
  static Options Automotive();
};

/// A rectified stereo pair: 8-bit single-channel images of the camera's size.
struct StereoFrame {
  Time stamp;
  cv::Mat left;
  cv::Mat right;
};

/// The predicted motion between the reference pair and the new pair (e.g. wheel odometry),
/// in the same convention as the estimate.
struct MotionPrior {
  Eigen::Isometry3d delta = Eigen::Isometry3d::Identity();  ///< T_from_to, camera frame
  Matrix6d covariance = Matrix6d::Identity() * 1e-2;        ///< over [dt (m); dtheta (rad)]

  /// A prior of zero motion with the given 1-sigma translation [m] and rotation [rad].
  static MotionPrior Stationary(double sigma_translation, double sigma_rotation);
};

enum class MotionStatus {
  kConverged,       ///< a measurement: delta and covariance are valid
  kTooFewFeatures,  ///< too few features selected, matched in stereo or tracked
  kLimitsFailed,    ///< the motion broke a sanity limit (step size, prior gate)
  kNotConverged,    ///< no RANSAC consensus, or ML did not converge / is degenerate
  kBadInput,        ///< for publishers: the step was rejected with a Status (never returned)
  kNoReference,     ///< first pair (or after Reset()): stored as the reference, no motion
};
const char* MotionStatusName(MotionStatus status);

/// Output of one step; the relative-pose measurement for the EKF (dl/relative_pose).
struct MotionEstimate {
  MotionStatus status = MotionStatus::kNoReference;
  Time t_from;  ///< stamp of the reference pair
  Time t_to;    ///< stamp of the new pair
  /// T_from_to in the left camera frame. Not converged: the prior's delta (not a measurement).
  Eigen::Isometry3d delta = Eigen::Isometry3d::Identity();
  /// Cov of [dt; dtheta] (m, rad). Not converged: the prior's covariance.
  Matrix6d covariance = Matrix6d::Zero();
  std::string message;  ///< why the status is not kConverged (empty otherwise)

  // Diagnostics.
  int features_selected = 0;  ///< interest points in the reference left image
  int features_stereo = 0;    ///< of which triangulated in the reference pair
  int features_tracked = 0;   ///< tracked into the new pair and triangulated there
  int inliers = 0;            ///< used by the final ML estimate
  int ransac_iterations = 0;
  int refine_iterations = 0;
  bool first_pass = false;    ///< the coarse first pass ran
  double cost_per_dof = 0.0;  ///< ML cost / (3 inliers - 6)

  bool converged() const { return status == MotionStatus::kConverged; }
};

/// The estimate re-expressed for a frame b rigidly attached to the camera (the rover body),
/// given the extrinsic T_b_c (camera pose in b): delta_b = T_b_c delta T_b_c^-1 and the
/// covariance propagated (ChangeMotionFrame). For the rover frame (x forward, y left, z up) the
/// covariance is then over [dx, dy, dz, droll, dpitch, dyaw], the layout of dl/relative_pose.
MotionEstimate ToBodyFrame(const MotionEstimate& estimate, const Eigen::Isometry3d& t_b_c);

/// A prior given in the body frame b (e.g. wheel odometry) re-expressed in the camera frame.
MotionPrior ToCameraFrame(const MotionPrior& body_prior, const Eigen::Isometry3d& t_b_c);

/// A tracked feature kept for diagnostics and plotting (last step).
struct FeatureTrack {
  Eigen::Vector2d from_left, to_left, to_right;
  bool inlier = false;
};

class VisualOdometry {
 public:
  /// Validates the options and the camera.
  static Result<VisualOdometry> Create(const Options& options, const StereoCamera& camera);

  /// Processes the next stereo pair. The first pair (or the first after Reset()) returns an
  /// estimate with status kNoReference. Returns a Status error (state unchanged) for images of
  /// the wrong size or type, a stamp not later than the reference's, or an invalid prior.
  Result<MotionEstimate> Process(const StereoFrame& frame, const MotionPrior& prior);

  /// Forgets the reference pair.
  void Reset();

  bool has_reference() const { return has_reference_; }
  const Options& options() const { return options_; }
  const StereoCamera& camera() const { return camera_; }
  /// Tracks of the last step (for plots and tests).
  const std::vector<FeatureTrack>& last_tracks() const { return last_tracks_; }

 private:
  struct Feature {
    Eigen::Vector2d left;  // integer pixel of the interest point
    Eigen::Vector3d position;
    Eigen::Matrix3d covariance;
    double strength = 0.0;
    Eigen::Vector3d normal{0.0, 0.0, 1.0};  // local surface normal (fronto-parallel default)
  };
  struct Reference {
    Time stamp;
    ImagePyramid left;
    std::vector<Feature> features;
    int selected = 0;
  };

  VisualOdometry(const Options& options, const StereoCamera& camera)
      : options_(options), camera_(camera) {}
  Status CheckFrame(const StereoFrame& frame) const;
  void EstimateNormals(std::vector<Feature>* features) const;
  Reference BuildReference(const StereoFrame& frame, ImagePyramid left,
                           const CorrelationImage& right) const;
  MotionEstimate EstimateMotion(const Reference& from, const ImagePyramid& left,
                                const CorrelationImage& right, const MotionPrior& prior);

  Options options_;
  StereoCamera camera_;
  bool has_reference_ = false;
  Reference reference_;
  std::uint64_t steps_ = 0;
  std::vector<FeatureTrack> last_tracks_;
};

}  // namespace rover::dl::vo
