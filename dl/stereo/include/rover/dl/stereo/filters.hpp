#pragma once
/// @file
/// Filters that remove unreliable disparities after correlation (JPL/MER stereo: border, blob,
/// overhang, vehicle and wheel masks). Each one sets the status of the pixels it rejects (see
/// disparity_image.hpp); the correlator already applied the tests that need the cost curve
/// (range edge, flat valley, uniqueness, left-right line of sight).
///
/// Border:   pixels closer than `margin` px to an image edge.
/// Blob:     4-connected regions of valid pixels in which neighbours differ by at most
///           `max_step` px of disparity; regions smaller than `min_area` px are removed
///           (small isolated patches are almost always mismatches).
/// Overhang: natural terrain seen from a rover recedes up the image: along a column, from the
///           bottom row upwards, disparity should not grow. A pixel whose disparity exceeds by
///           more than max(tolerance_px, ratio * d_ref) the largest accepted disparity d_ref in
///           the `search_rows` rows below it (same column) looms toward the cameras above
///           nearer-looking terrain and is rejected. The scan goes bottom-up and compares only
///           with pixels already accepted, so a run of bad pixels is removed as a whole.
/// Masks:    a fixed vehicle mask (image; non-zero = rover body) and a moving-wheel mask
///           (polygons in image pixels, drawn per frame from the current wheel/steering pose).
///           Masked pixels get kVehicle / kWheel whatever their previous status.

#include <opencv2/core.hpp>
#include <vector>

#include "rover/base/status.hpp"
#include "rover/dl/stereo/disparity_image.hpp"

namespace rover::dl::stereo {

struct FilterOptions {
  int border_px = 0;           ///< extra margin [px] beyond the correlation half-window
  int blob_min_area = 40;      ///< [px] at the processing level; 0 disables
  double blob_max_step = 1.0;  ///< [px] disparity step that still joins neighbours, > 0
  bool overhang = true;
  double overhang_tolerance_px = 2.0;  ///< [px] >= 0
  double overhang_ratio = 0.1;         ///< fraction of d_ref, [0, 1]
  int overhang_search_rows = 8;        ///< [1, 256]

  Status Validate() const;
};

/// Rejects (kBorder) pixels within `margin` px of an edge. Errors: margin < 0.
Status ApplyBorderFilter(int margin, DisparityImage* disparity);

/// Removes small regions (kBlob). Errors: min_area < 0, max_step <= 0, empty image.
Status ApplyBlobFilter(int min_area, double max_step, DisparityImage* disparity);

/// Rejects looming pixels (kOverhang). Errors: bad parameters, empty image.
Status ApplyOverhangFilter(double tolerance_px, double ratio, int search_rows,
                           DisparityImage* disparity);

/// Sets `reason` wherever `mask` (CV_8UC1, same size) is non-zero. Errors: wrong size or type.
Status ApplyMask(const cv::Mat& mask, PixelStatus reason, DisparityImage* disparity);

/// Draws filled polygons given in full-resolution pixels (u, v) into a CV_8UC1 mask of `size`
/// (255 inside) at pyramid level `levels`: a vertex maps to ((u + 0.5) / 2^L - 0.5, same for v).
/// Errors: a polygon with fewer than 3 vertices, non-finite vertices, levels < 0, empty size.
Result<cv::Mat> RasterizePolygons(const std::vector<std::vector<cv::Point2f>>& polygons,
                                  cv::Size size, int levels);

/// Shrinks a mask by an integer factor 2^levels: a low-resolution pixel is masked if any of
/// the full-resolution pixels it covers is (conservative). Errors: wrong type, levels < 0.
Result<cv::Mat> DownsampleMask(const cv::Mat& mask, int levels);

}  // namespace rover::dl::stereo
