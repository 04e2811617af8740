#pragma once
/// @file
/// Software downsampling of a stereo pair (the camera driver's job on MER: 1024 x 1024 frames
/// sent as 256 x 256 for navigation) and the camera models that stay valid for the result.
///
/// Area ("box") filter. With pixel (i, j) covering [i, i+1) x [j, j+1) in pixel-EDGE
/// coordinates, output pixel (u, v) of an out_w x out_h image covers
///   [u W / out_w, (u+1) W / out_w) x [v H / out_h, (v+1) H / out_h)
/// and gets the area-weighted mean of the input pixels it overlaps (separable: rows, then
/// columns), rounded to the nearest integer. For an integer factor n this is the plain mean of
/// each n x n block (JPL's on-board binning); it equals cv::resize with INTER_AREA.
/// The models: geometry::Scale(model, sx, sy) with sx = out_w / W, sy = out_h / H maps pixel
/// centres x_new = sx (x_old + 0.5) - 0.5 (outer edges aligned), exactly the mapping of the
/// filter, so a 3D point projects onto the same scene detail in both images.
/// out_h = max(1, round(H out_w / W)) keeps the aspect ratio.

#include <cstdint>
#include <vector>

#include "rover/base/status.hpp"
#include "rover/geometry/camera_model.hpp"

namespace rover::ddl::camera {

/// 8-bit monochrome image, row-major.
struct GrayImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> pixels;  ///< width * height bytes
};

/// Area-filter downsampling. Errors (InvalidArgument): empty or inconsistent input, output size
/// < 1 or larger than the input (no upsampling).
Result<GrayImage> AreaDownsample(const GrayImage& in, int out_width, int out_height);

struct DownsampledStereo {
  GrayImage left;
  GrayImage right;
  geometry::CameraModel left_model;   ///< valid for `left`
  geometry::CameraModel right_model;  ///< valid for `right`
  double scale_x = 1.0;               ///< out_w / W
  double scale_y = 1.0;               ///< out_h / H
};

/// Downsamples both images to `out_width` (0 = keep the full size) and scales the models.
/// Errors: images of different sizes, a model whose size differs from its image, bad sizes.
Result<DownsampledStereo> DownsampleStereo(const GrayImage& left, const GrayImage& right,
                                           const geometry::CameraModel& left_model,
                                           const geometry::CameraModel& right_model, int out_width);

}  // namespace rover::ddl::camera
