#pragma once
/// @file
/// Long-range lander acquisition (FIDO rendezvous, seed 004, first phase: ~25-150 m): finds the
/// lander in one NAVCAM image by fusing two weak cues that each fire on other things, and
/// measures its bearing and a rough range from its angular size.
///
/// Method (doc/long_range.md has the pictures and the measured rates).
///   0. Search band. From the camera model (rover frame), the image box of every point between
///      `min_range` and `max_range` (or the prior's range window) inside the bearing window, from
///      the ground to the deck top: at long range this is a band a few tens of pixels high under
///      the horizon.
///   1. Line cue (Canny). Canny edges in the band, straight segments by the probabilistic Hough
///      transform, kept when within `level_tolerance_deg` of the image of a level line across the
///      view. Segments within the lander's height and overlapping in columns are chained into
///      groups; a group of >= `min_group_lines` segments on distinct rows whose box is as wide and
///      as high as the lander could be at the prior range is a line candidate. Layered outcrops
///      and the far edge of the map are line candidates too.
///   2. Texture cue (Haar wavelets). Two levels of the orthonormal 2-D Haar transform of the
///      band. At level-1 resolution, over a window of about half the deck's image size: the
///      coarse detail energy E2 (level 2), the fine detail energy E1 (level 1) and the brightest
///      level-2 approximation LL2. The signature of the painted lander is (a) strong coarse
///      detail: sqrt(E2 / median E2 of the band) >= `min_contrast`, (b) smooth panels with sharp
///      edges, not rock grain: E1 / E2 <= `max_fine_ratio` (white noise gives ~4, a clean step
///      edge ~1), (c) a bright part: max LL2 / median LL2 >= `min_brightness`. Connected windows
///      with the signature are texture candidates; near rocks, shadows and sunlit soil edges are
///      texture candidates too.
///   3. Fusion. A line candidate whose box overlaps a texture candidate is a lander candidate;
///      the one with most line rows (then strongest texture) nearest the prior bearing wins.
///   4. Bearing from the candidate's column centre; range from the angular size: the width of the
///      group's top line (the deck top, 2 apothem .. 2 deck_radius wide: R = 2.8 m f / w) and the
///      height from the top line to the lowest row of the candidate (deck top to feet: R =
///      deck_height f / h) and the feet put on the ground plane at the prior's ground height,
///      fused by inverse variance; with a right image, stereo replaces both when the lit part's
///      patch correlates (>= 0.7) along its ray (0.3 px of disparity: ~8 % at 100 m). The
///      executor fuses the fix with the a-priori estimate and reacquires every few metres.
///
/// Frames and units as lander_detector.hpp: camera models in the rover frame (x forward, y left,
/// z up, origin on the ground); `center` is the deck top centre in that frame [m]; bearing
/// [rad, + left] and horizontal range [m] from the rover frame origin.
///
/// Preconditions: an 8-bit grey image of its model's size, taken with the mast near level (the
/// lander within a few degrees of the horizon). Cost: a few ms per image (the band is small).

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "rover/apl/rendezvous/lander_detector.hpp"
#include "rover/base/status.hpp"
#include "rover/geometry/camera_model.hpp"
#include "rover/hwconfig/lander_description.hpp"

namespace rover {
template <class Options>
class ParamBinder;
}  // namespace rover

namespace rover::apl::rendezvous {

/// Tuning of DetectLanderFar. Lengths in pixels unless stated.
struct LongRangeOptions {
  double min_range = 20.0;           ///< [m] nearest lander range searched (without a prior)
  double max_range = 160.0;          ///< [m] farthest
  double canny_low = 20.0;           ///< Canny hysteresis thresholds [grey levels]
  double canny_high = 50.0;
  double level_tolerance_deg = 20.0; ///< level segment: angle to the image of a level line
  int min_line_length = 5;           ///< [px] shortest segment (Hough)
  int min_group_lines = 2;           ///< segments on distinct rows in a line candidate
  /// Segment kept when its mean gradient along it is >= this times the band's median segment's.
  double min_line_contrast = 2.0;
  double min_contrast = 2.5;         ///< texture: sqrt(E2 / band median E2)
  double max_fine_ratio = 1.6;       ///< texture: E1 / E2 (smooth panels, sharp edges)
  double min_brightness = 1.3;       ///< texture: max LL2 / band median LL2
  double extent_sigma_px = 1.5;      ///< [px] 1-sigma of a measured width or height

  /// Checks every field; messages start with "<prefix><field>: ".
  Status Validate(const char* prefix = "long_range.") const;
  static void BindParams(ParamBinder<LongRangeOptions>& b);
};

/// A candidate box of one cue (left-image pixels) with its strength.
struct CueBox {
  cv::Rect box;
  double strength = 0.0;  ///< line cue: segments; texture cue: peak contrast
};

/// The result of DetectLanderFar. When `found` is false, `reason`, the cue boxes and the timing
/// are set.
struct FarSighting {
  bool found = false;
  std::string reason;           ///< why not found, or a summary
  double bearing = 0.0;         ///< [rad] of the deck centre from the rover origin, + left
  double bearing_sigma = 0.0;   ///< [rad]
  double range = 0.0;           ///< [m] horizontal, rover origin to deck centre
  double range_sigma = 0.0;     ///< [m]
  Eigen::Vector3d center = Eigen::Vector3d::Zero();  ///< deck top centre, rover frame [m]
  Eigen::Matrix3d center_covariance = Eigen::Matrix3d::Zero();  ///< [m^2]
  cv::Rect box;                 ///< the fused candidate
  cv::Rect band;                ///< the search band
  std::vector<CueBox> line_candidates;     ///< line cue alone
  std::vector<CueBox> texture_candidates;  ///< texture cue alone
  std::vector<CueBox> fused;               ///< both, co-located
  std::vector<LanderLine> lines;           ///< level segments of the chosen candidate
  std::string features;         ///< e.g. "far: lines 4 rows 3, texture 5.2, width 31 px"
  double elapsed_ms = 0.0;
};

/// Finds the lander far away in `left8` (CV_8UC1 of `left_model`'s size); `right8` (may be
/// empty, then `right_model` is ignored) gives the stereo range. Errors
/// (InvalidArgument naming the input): empty image, wrong type or size, options or lander
/// description failing Validate, non-finite or non-positive prior fields. Not finding the lander
/// is not an error.
Result<FarSighting> DetectLanderFar(const cv::Mat& left8, const geometry::CameraModel& left_model,
                                    const cv::Mat& right8, const geometry::CameraModel* right_model,
                                    const hwconfig::LanderDescription& lander,
                                    const LongRangeOptions& options = {},
                                    const std::optional<LanderPrior>& prior = std::nullopt);

/// Draws the search band (grey), line candidates (yellow), texture candidates (magenta) and the
/// fused detection (green, with range and bearing) onto `bgr` (CV_8UC3). No-op when empty.
void DrawFarSighting(cv::Mat* bgr, const FarSighting& sighting);

}  // namespace rover::apl::rendezvous
