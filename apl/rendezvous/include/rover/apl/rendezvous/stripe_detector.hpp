#pragma once
/// @file
/// Close-range lander vision, step 1: the six coded dark stripes across each lander ramp
/// (hwconfig/lander_description.hpp) found in one 8-bit camera image, identified (ramp and
/// stripe index) and measured to sub-pixel corners.
///
/// Method.
///  1. Segmentation. A pixel is dark when it is below `dark_ratio` times the local bright level
///     (a max filter of `bright_window_px`, computed at quarter resolution) and that bright level
///     is at least `min_bright_dn`. Stripes are albedo 0.05 on a 0.85 ramp (ratio ~0.06); a
///     shadow on soil next to sunlit soil is ~0.3.
///  2. Candidates. 8-connected dark components of at least `min_area_px` pixels that are
///     elongated (length / thickness >= `min_elongation`) and fill their minimum-area rectangle
///     (>= `min_fill`).
///  3. Sub-pixel edges. Across each candidate, every ~2 px along its long axis, the intensity
///     profile is sampled (bilinear) and each long edge is placed where the profile crosses
///     halfway between the dark level inside and the bright level on that side (unbiased for
///     a symmetric blur). Both flanks must be at least `min_contrast` times the dark level
///     (stripes lie on a light ramp; the ramp's own edge against dark soil does not). A line is
///     fitted to each long edge (least squares, two rounds of outlier rejection).
///  4. Neighbours and codes. Candidates pair with their nearest compatible neighbour towards
///     the top of the image (parallel within `max_neighbour_angle_deg`, overlapping along their
///     length). In a chain, the gap between neighbours (`stripe_gap` = 5 stripe units on the
///     default lander) gives the local image scale, so each stripe's width measures its code:
///     code = width / gap * gap_units. The chain (or its best contiguous part, at least two
///     stripes) is matched to every placement in kRampStripeCodes, bottom of the ramp at the
///     bottom of the image; the best placement must fit within `max_code_error` per stripe and
///     beat every other placement clearly. Each ordered neighbour pair is unique over both
///     ramps, so two neighbours already name the ramp and the indices.
///  5. Ends. The stripes' ends on one side all lie on one line of the ramp (v = +-length/2),
///     so end points (the half-level crossing along the long axis) of all identified stripes
///     are fitted with one line per side; a stripe's corners are its long-edge lines cut by the
///     two end lines. An end that touches the image border is marked not valid.
///
/// Corner order (ramp-surface frame G of hwconfig::LanderDescription, u up the slope, v to the
/// left facing up the ramp): corners[0] = (u-, v+), [1] = (u-, v-), [2] = (u+, v-),
/// [3] = (u+, v+). Seen from in front of the ramp (upright camera) that is lower-left,
/// lower-right, upper-right, upper-left in the image. Pixel convention: core/geometry (centre of
/// the top-left pixel = (0, 0)); the corners are in the raw (distorted) image.
///
/// Assumptions: the camera is roughly upright (roll within ~30 deg), the ramp is seen from its
/// front half-space (the bottom of the ramp nearer than the top).

#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "rover/base/status.hpp"

namespace rover {
template <class Options>
class ParamBinder;
}  // namespace rover

namespace rover::apl::rendezvous {

struct StripeDetectorOptions {
  double dark_ratio = 0.45;       ///< dark: pixel < dark_ratio * local bright level, (0, 1)
  int bright_window_px = 81;      ///< [px] side of the local bright-level window, odd, >= 9
  double min_bright_dn = 40.0;    ///< [DN] local bright level a stripe needs around it
  int min_area_px = 12;           ///< [px] smallest candidate component
  double min_elongation = 3.0;    ///< length / thickness of a candidate
  double min_fill = 0.6;          ///< component area / minimum-area-rectangle area
  double min_contrast = 2.5;      ///< bright flank / dark level, both sides
  double max_neighbour_angle_deg = 12.0;  ///< [deg] neighbours' long axes within this angle
  double max_code_error = 0.75;   ///< [code units] worst stripe of an accepted placement
  double min_code_margin = 0.35;  ///< [code units^2] mean squared cost margin to the runner-up
  int gap_units = 5;              ///< stripe_gap / stripe_unit of the lander (0.15 / 0.03)

  /// Checks every field; messages start with "<prefix><field>: " and name the value.
  Status Validate(const char* prefix = "stripes.") const;
  static void BindParams(ParamBinder<StripeDetectorOptions>& b);
};

/// One identified stripe in the image.
struct DetectedStripe {
  int ramp = 0;   ///< 0 or 1
  int index = 0;  ///< 0 = lowest on the ramp
  /// [px] corners in the order (u-, v+), (u-, v-), (u+, v-), (u+, v+) (see the file comment).
  std::array<Eigen::Vector2d, 4> corners;
  /// corners[k] is measured (false: its end is cut by the image border or not found; the
  /// corner is then an extrapolation and must not be used for pose).
  std::array<bool, 4> corner_valid = {false, false, false, false};
  double code_measured = 0.0;  ///< width / local gap scale [stripe units]
  double edge_rms_px = 0.0;    ///< rms residual of the long-edge line fits [px]
};

/// What DetectStripes found in one image.
struct StripeDetection {
  /// Identified stripes, ramp then index ascending. Stripes of both ramps may appear (never
  /// expected at close range; a caller uses the ramp it wants).
  std::vector<DetectedStripe> stripes;
  int candidates = 0;  ///< dark elongated components examined
  /// Why nothing (or less than a whole ramp) was identified; empty when six stripes of a ramp
  /// were found.
  std::string why;
  double elapsed_ms = 0.0;  ///< processing time (diagnostics only)
  /// Stripes of `ramp` only.
  std::vector<DetectedStripe> OfRamp(int ramp) const;
  /// The ramp with most identified stripes (-1 if none).
  int BestRamp() const;
};

/// Detects and identifies the ramp stripes in `gray8` (CV_8UC1, at least 32 x 32).
/// Errors: InvalidArgument naming "gray8" for an empty, too small or non-8-bit-gray image, or
/// invalid options. No stripe is not an error: an empty list with `why`.
Result<StripeDetection> DetectStripes(const cv::Mat& gray8, const StripeDetectorOptions& options = {});

/// Draws a detection onto `bgr` (CV_8UC3, the image size the detection came from): each
/// stripe's outline (ramp 0 green, ramp 1 orange), its valid corners (circles) and a label
/// "r<ramp>s<index> c<code>". Precondition: bgr != nullptr and CV_8UC3.
void DrawStripeDetection(cv::Mat* bgr, const StripeDetection& detection);

}  // namespace rover::apl::rendezvous
