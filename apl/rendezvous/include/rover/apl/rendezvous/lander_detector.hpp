#pragma once
/// @file
/// Mid-range lander detection (FIDO rendezvous, seed 004, second phase: ~5-30 m): finds the
/// lander in a NAVCAM image from its straight edges and measures its bearing and range, with
/// stereo when the right image is given.
///
/// Method (lander_lines.md has the details and the measured errors).
///   1. Line segments (OpenCV's LSD) on the left image. A segment is "level" when its image
///      direction is within `level_tolerance_deg` of the image of a horizontal line across the
///      view through its midpoint, and "truss" when within `truss_tolerance_deg` of the image of
///      the local vertical (both found by projecting small 3-D offsets through the model, so
///      mast tilt and roll do not matter).
///   2. Deck hypotheses: level segments chained by vertical and horizontal proximity into bands
///      (the deck top and bottom edges of the slab). A band of width w px implies a range
///      R_w = f 2.8 m / w (the deck's silhouette is 2 apothem .. 2 deck_radius wide).
///   3. Truss check: near-vertical segments in the region below the band, down to
///      1.1 deck_height f / R_w, at least `min_truss_lines` of them. Bands without a truss
///      (horizon, rock shadows) are rejected; the best band by score (level length + truss) wins.
///   4. Range. Monocular: from the elevation angles of the deck top e_t and of the leg feet e_f,
///      R_v = deck_height / (tan e_t - tan e_f) (R_w when the feet give nothing plausible).
///      Stereo (right image given): the two ends of the deck band are matched into the right
///      image by normalised cross-correlation along the epipolar line (sub-pixel by a parabola)
///      and triangulated; the deck centre is their midpoint pushed `end_depth_offset` further
///      along the view (one end only: its depth plus the offset, on the band's bearing). A stereo
///      range more than `max_disagreement` from R_w is dropped. With a right image, a band that
///      stereo does not confirm is reported not found (this is what rejects rock and shadow
///      bands); the two ranges are fused by inverse variance.
///   5. Ramp hypothesis (right image needed; `min_ramp_edges` 0 turns it off). A ramp facing the
///      camera hides the middle of the truss and cuts the deck band, so the ramp itself is lander
///      evidence: a stack of >= min_ramp_edges level edge rows with both polarities, at least
///      three aligned at both ends (two in a stack of five or more rows), flanked by near-vertical
///      ramp side edges and lighter than the ground beside it by `min_ramp_contrast`. Both stripe
///      ends (whole stack and per edge row) are matched in the right image; the ramp middle is at
///      the mean of the inlying horizontal ranges. Stereo must confirm it: matches on both ends,
///      >= 3 inliers, and stripes of at most 1.15x their true length at that range. The deck
///      centre is apothem + ramp_length / 2 further along the ramp axis, which is the view
///      direction when the stripes are foreshortened by less than cos 26 deg ("frontal"), else
///      turned by the foreshortening angle (sign from the two ends' depths). A frontal ramp is
///      preferred over a truss-confirmed band; otherwise a ramp sighting is used only when the
///      band hypothesis finds nothing.
///
/// Frames and units. The camera models are in the rover frame (x forward, y left, z up, origin on
/// the ground). `center` is the deck top centre in the rover frame [m]; range = hypot(center.x,
/// center.y) [m] and bearing = atan2(center.y, center.x) [rad, + left] are both from the rover
/// frame origin; elevation is the deck top's elevation seen from the left camera [rad].
///
/// Preconditions: 8-bit grey images of their models' size; the lander between min_range and
/// max_range and below the horizon. Cost ~40-110 ms per 1024^2 pair (one core), mostly LSD.

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "rover/base/status.hpp"
#include "rover/geometry/camera_model.hpp"
#include "rover/hwconfig/lander_description.hpp"

namespace rover {
template <class Options>
class ParamBinder;
}  // namespace rover

namespace rover::apl::rendezvous {

/// Tuning of DetectLander. Angles in degrees, lengths in pixels unless stated.
struct LanderDetectorOptions {
  double min_range = 4.0;              ///< [m] nearest lander range searched
  double max_range = 35.0;             ///< [m] farthest
  double level_tolerance_deg = 8.0;    ///< level segment: angle to the local horizontal
  double truss_tolerance_deg = 35.0;   ///< truss segment: angle to the local vertical
  double min_level_length = 12.0;      ///< [px] shortest level segment used
  double min_truss_length = 6.0;       ///< [px] shortest truss segment used
  int min_truss_lines = 3;             ///< truss segments needed under a deck band
  int stereo_half_width = 8;           ///< [px] half width of a stereo patch
  double min_correlation = 0.6;        ///< lowest accepted normalised cross-correlation
  double disparity_sigma = 0.25;       ///< [px] 1-sigma of a matched feature's disparity
  double end_depth_offset = 0.3;       ///< [m] deck ends to deck centre along the view
  double monocular_sigma = 0.08;       ///< relative 1-sigma of the monocular range
  double max_disagreement = 0.25;      ///< relative stereo - monocular range gap tolerated
  /// Ramp hypothesis (used when no truss-confirmed deck band is found and a right image is
  /// given): distinct stripe-edge rows needed in a stack; 0 turns the hypothesis off.
  int min_ramp_edges = 4;
  double min_ramp_contrast = 25.0;     ///< [grey levels] light ramp over the ground beside it

  /// Checks every field; messages start with "<prefix><field>: ".
  Status Validate(const char* prefix = "lander_detector.") const;
  static void BindParams(ParamBinder<LanderDetectorOptions>& b);
};

/// Optional search window from an earlier sighting or odometry.
struct LanderPrior {
  double bearing = 0.0;        ///< [rad] rover frame
  double bearing_window = 0.5; ///< [rad] half width accepted around `bearing`
  double range = 15.0;         ///< [m]
  double range_window = 10.0;  ///< [m] half width accepted around `range`
  /// [m] height of the ground at the lander in the rover frame (from the pose estimate; the
  /// long-range detector's search band depends on it when the rover stands tilted or lower).
  double ground_z = 0.0;
};

/// An image line segment the detector used, in left-image pixels.
struct LanderLine {
  Eigen::Vector2d a = Eigen::Vector2d::Zero();
  Eigen::Vector2d b = Eigen::Vector2d::Zero();
  enum class Kind { kDeck, kTruss } kind = Kind::kDeck;
};

/// The result of DetectLander. When `found` is false only `reason` (and the timing) is set.
struct LanderSighting {
  bool found = false;
  std::string reason;           ///< why not found, or a summary of the estimate
  double bearing = 0.0;         ///< [rad] azimuth of the deck centre from the rover origin, + left
  double bearing_sigma = 0.0;   ///< [rad]
  double elevation = 0.0;       ///< [rad] of the deck top centre from the left camera
  double elevation_sigma = 0.0; ///< [rad]
  double range = 0.0;           ///< [m] horizontal, rover frame origin to deck centre
  double range_sigma = 0.0;     ///< [m]
  double range_monocular = 0.0; ///< [m] left camera to deck centre, vertical extent or width
  double range_stereo = 0.0;    ///< [m] left camera to deck centre, stereo (0: not used)
  /// Deck top centre in the rover frame [m] and its covariance [m^2].
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  Eigen::Matrix3d center_covariance = Eigen::Matrix3d::Zero();
  cv::Rect box;                 ///< left-image box of deck and truss
  std::vector<LanderLine> lines;  ///< deck and truss segments used
  std::string features;         ///< e.g. "deck lines 5, truss lines 9, stereo ends 2 (used)"
  double elapsed_ms = 0.0;      ///< processing time (informative)
};

/// Finds the lander in `left8` (CV_8UC1, size of `left_model`). `right8` may be empty (then
/// `right_model` is ignored and may be null): monocular range only. Errors (InvalidArgument,
/// naming the input): empty left image, wrong type, size different from its model, a right
/// image without a model or of the wrong size, non-finite or negative prior fields, options that
/// fail Validate, a description that fails Validate. Not finding the lander is not an error.
Result<LanderSighting> DetectLander(const cv::Mat& left8, const cv::Mat& right8,
                                    const geometry::CameraModel& left_model,
                                    const geometry::CameraModel* right_model,
                                    const hwconfig::LanderDescription& lander,
                                    const LanderDetectorOptions& options = {},
                                    const std::optional<LanderPrior>& prior = std::nullopt);

/// Draws the sighting onto `bgr` (CV_8UC3, the left image converted): deck lines yellow, truss
/// lines cyan, the box green and the bearing/range as text; a not-found sighting draws its
/// reason. No-op for a null or empty image.
void DrawLanderSighting(cv::Mat* bgr, const LanderSighting& sighting);

}  // namespace rover::apl::rendezvous
