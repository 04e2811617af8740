#pragma once
/// @file
/// What the rendezvous executor needs from one NAVCAM pair, whatever detector made it, and the
/// interface the executor asks for it through (RendezvousVision). The service's implementation
/// (vision_pipeline.hpp) runs the lander detector (mid range) and the stripe detector with the
/// ramp pose solver (close range); tests give the executor a fake that sees a known world.
///
/// Frames: R is the rover frame at the pair's capture time (x forward, y left, z up, origin on
/// the ground below the rocker pivots); G the ramp-surface frame of core/hwconfig's
/// lander_description.hpp. Units metres and radians.

#include <algorithm>
#include <cmath>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <string>

#include "rover/base/status.hpp"
#include "rover/base/time.hpp"
#include "rover/geometry/camera_model.hpp"

namespace cv {
class Mat;
}  // namespace cv

namespace rover::apl::rendezvous {

/// One NAVCAM pair as the executor hands it to the vision: 8-bit images (views, valid during the
/// call) and the camera models in R at capture time.
struct NavcamPair {
  Time stamp;
  std::uint32_t request_id = 0;
  const cv::Mat* left = nullptr;
  const cv::Mat* right = nullptr;  ///< may be null: monocular
  const geometry::CameraModel* left_model = nullptr;
  const geometry::CameraModel* right_model = nullptr;
};

/// The lander seen at long or mid range.
struct LanderFix {
  bool found = false;
  bool far = false;  ///< the long-range detector looked (rough range, sharp bearing)
  Eigen::Vector3d center_rover = Eigen::Vector3d::Zero();  ///< deck centre in R [m]
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Identity();  ///< of center_rover [m^2]
  std::string features;  ///< which features carried the fix ("deck lines 3, legs 4, stereo")
  std::string why;       ///< when not found: why
};

/// [rad] Half width of the bearing window the long-range search covers about an estimate
/// `range` m away: atan(max(prior_gate, 0.1 range) / range). The vision searches it and the
/// executor never accepts a far fix outside it.
inline double FarSearchHalfWindow(double range, double prior_gate) {
  return std::atan2(std::max(prior_gate, 0.1 * range), range);
}

/// A ramp's pose from its coded stripes at close range.
struct RampFix {
  bool found = false;
  int ramp = -1;            ///< 0 or 1
  int stripes = 0;          ///< identified stripes used by the pose
  double rms_px = 0.0;      ///< reprojection residual
  Eigen::Isometry3d rover_from_ramp = Eigen::Isometry3d::Identity();  ///< G -> R
  /// 1-sigma of the ramp-base position [m] and of the ramp's yaw [rad] in R.
  double base_sigma = 0.0;
  double yaw_sigma = 0.0;
  std::string features;
  std::string why;
};

/// Why the science-target tracker lost the target (a typed goal error of the approach).
enum class TargetLoss {
  kNone,
  kOutOfView,       ///< the target is outside the new left image
  kTooFewFeatures,  ///< fewer features about the target than the pose needs
};

/// "NONE", "OUT_OF_VIEW", "TOO_FEW_FEATURES".
inline const char* TargetLossName(TargetLoss l) {
  switch (l) {
    case TargetLoss::kNone: return "NONE";
    case TargetLoss::kOutOfView: return "OUT_OF_VIEW";
    case TargetLoss::kTooFewFeatures: return "TOO_FEW_FEATURES";
  }
  return "?";
}

/// The science target in one NAVCAM pair: where it is in R of that pair, and how it was found.
struct TargetFix {
  bool tracked = false;
  TargetLoss loss = TargetLoss::kNone;
  Eigen::Vector3d target_rover = Eigen::Vector3d::Zero();  ///< [m] the target point in R
  double sigma = 0.0;  ///< [m] 1-sigma of target_rover (its stereo range, mostly)
  /// true: the target's own patch was matched and re-ranged in this pair; false: carried from
  /// the last pair by the features' rigid motion.
  bool target_measured = false;
  int features = 0;  ///< features about the target in the last pair
  int matched = 0;   ///< of them, found again in this pair and re-ranged
  int inliers = 0;   ///< of them, consistent with one rigid motion
  double rms = 0.0;  ///< [m] residual of the rigid motion over the inliers
  /// Rover motion measured from the last pair to this one: R_this from R_last (identity at
  /// the designation), and the same from dl/pose (the prediction the search started from).
  Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d predicted_motion = Eigen::Isometry3d::Identity();
  std::string why;  ///< when lost: why, with the numbers
};

/// Detection images the service keeps in the run folder (features drawn on them).
struct DetectionImage {
  std::string name;                  ///< "lander_03", "stripes_07"
  std::shared_ptr<const cv::Mat> bgr;  ///< 8-bit BGR
};

class RendezvousVision {
 public:
  virtual ~RendezvousVision() = default;
  /// The lander in a pair (long or mid range). `prior_rover` is the expected deck centre on the
  /// ground in R (x, y: the search window; z: the ground there); an error only for bad input
  /// (empty image, model size mismatch).
  virtual Result<LanderFix> SightLander(const NavcamPair& pair,
                                        const Eigen::Vector3d& prior_rover) = 0;
  /// A ramp's coded stripes and its pose (close range). Errors only for bad input.
  virtual Result<RampFix> SightRamp(const NavcamPair& pair) = 0;
  /// The image of the last sighting with its features drawn, for the run folder (may be empty).
  virtual DetectionImage LastDrawing() { return {}; }
};

/// The science-target approach's vision (target_tracker.hpp in the service; a fake in tests).
class TargetVision {
 public:
  virtual ~TargetVision() = default;
  /// Starts a track: the target is the surface point seen at left-image `pixel` of `pair`
  /// (ranged in the pair). `site_from_rover`: dl/pose at the pair's capture. Errors
  /// (InvalidArgument, naming the pixel and value): the pixel outside the image, without a
  /// stereo range (sky, no texture), or without features about it; bad images.
  virtual Result<TargetFix> Designate(const NavcamPair& pair, const Eigen::Isometry3d& site_from_rover,
                                      const Eigen::Vector2d& pixel) = 0;
  /// The target in a new pair, from the last one (Designate or Track). A lost target is a fix
  /// with tracked = false and its TargetLoss; errors only for bad input or no track started.
  virtual Result<TargetFix> Track(const NavcamPair& pair, const Eigen::Isometry3d& site_from_rover) = 0;
  /// The last pair's image with the features and the target drawn (may be empty).
  virtual DetectionImage LastDrawing() { return {}; }
};

}  // namespace rover::apl::rendezvous
