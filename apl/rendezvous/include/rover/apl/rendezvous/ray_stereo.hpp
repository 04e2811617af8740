#pragma once
/// @file
/// Range of one left-image pixel of a stereo pair by correlation along its ray, for any camera
/// model (CAHV/CAHVOR/CAHVORE/pinhole; no rectification): the left patch about `pixel` is
/// compared, by normalised cross-correlation, with right-image patches at the projections of
/// points stepped along the pixel's left ray, and the best hypothesis is refined by a parabola
/// through its neighbours. The science-target tracker ranges its features and the designated
/// target with it (target_tracker.hpp).
///
/// Frames: both models in one reference frame (e.g. the rover frame R at capture); the point
/// returned is in that frame. Units: metres, pixels.

#include <Eigen/Core>
#include <string>

#include "rover/base/status.hpp"
#include "rover/geometry/camera_model.hpp"

namespace cv {
class Mat;
}  // namespace cv

namespace rover::apl::rendezvous {

struct RayMatchOptions {
  int half_window = 7;        ///< [px] the patch is (2 half_window + 1)^2
  double t_min = 0.3;         ///< [m] nearest distance along the ray searched
  double t_max = 40.0;        ///< [m] farthest
  double step_px = 0.25;      ///< [px] motion of the right patch between hypotheses
  double min_ncc = 0.7;       ///< lowest correlation that counts as a match
  double min_texture = 2.0;   ///< lowest grey standard deviation of the left patch
  double sigma_px = 0.3;      ///< [px] 1-sigma of the matched disparity (for `sigma_t`)
  /// Ok, or InvalidArgument naming the field (prefix "ray_match.").
  Status Validate() const;
};

struct RayMatch {
  bool found = false;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  ///< [m] in the models' frame
  double t = 0.0;        ///< [m] distance along the left ray
  double sigma_t = 0.0;  ///< [m] 1-sigma of t
  double ncc = -1.0;     ///< best correlation
  std::string why;       ///< when not found: "no texture (std 0.8)", "ncc 0.42 < 0.7", ...
};

/// The range of left-image `pixel`. Errors (InvalidArgument): empty or non-8-bit images, image
/// sizes that differ from the models', options.Validate() failing, `pixel` outside the left
/// image (named with its value). A pixel that does not match (no texture, best correlation too
/// low, best at either end of [t_min, t_max], the ray leaving the right image) is a RayMatch with
/// found = false and the reason.
Result<RayMatch> MatchAlongRay(const cv::Mat& left, const geometry::CameraModel& left_model,
                               const cv::Mat& right, const geometry::CameraModel& right_model,
                               const Eigen::Vector2d& pixel, const RayMatchOptions& options = {});

}  // namespace rover::apl::rendezvous
