#pragma once
/// @file
/// Image preparation before correlation: conversion to 8 bits with optional gamma correction,
/// pyramid downsampling and the band-pass prefilter (Laplacian of Gaussian or difference of
/// Gaussians) that removes the brightness and contrast differences between the two cameras.
///
/// Conversion:   I8 = round(255 * (I / white_level)^(1/gamma)), clipped to [0, 255].
///               gamma = 1 is a plain rescale; gamma > 1 brightens dark regions.
/// Downsampling: one pyramid level averages 2x2 blocks, so level L+1 has floor(W/2) x floor(H/2)
///               pixels and a pixel centre maps as u_L = 2 u_{L+1} + 0.5 (see
///               RectifiedStereoModel::Downsampled).
/// Prefilter:    LoG:  P = -gain * (Laplacian (3x3) of (G_sigma * I))
///               DoG:  P =  gain * (G_sigma * I - G_sigma_outer * I)
///               none: P = I (raw intensities, no clipping)
///               then Q = clamp(round(P), -cap, cap) + cap, an 8-bit image in [0, 2 cap].
/// All images are single-channel.

#include <opencv2/core.hpp>

#include "rover/base/status.hpp"

namespace rover::dl::stereo {

enum class PrefilterKind { kNone, kLaplacianOfGaussian, kDifferenceOfGaussians };

/// "none", "log", "dog".
const char* PrefilterKindName(PrefilterKind k);
/// Parses "none", "log" or "dog".
Result<PrefilterKind> ParsePrefilterKind(const std::string& name);

struct PrefilterOptions {
  PrefilterKind kind = PrefilterKind::kLaplacianOfGaussian;
  double sigma = 0.7;        ///< [px] Gaussian of LoG, or inner Gaussian of DoG; (0, 10]
  double sigma_outer = 2.0;  ///< [px] outer Gaussian of DoG (> sigma); ignored by LoG
  double gain = 2.0;         ///< response multiplier before clipping; (0, 100]
  int cap = 63;              ///< clip level; output in [0, 2 cap]; [1, 63]

  Status Validate() const;
};

/// Converts `in` (CV_8UC1 or CV_16UC1) to CV_8UC1 scaled by 255 / white_level with gamma.
/// Errors: empty image, other types, white_level <= 0 or > 65535, gamma outside [0.1, 10].
Status ConvertTo8Bit(const cv::Mat& in, double white_level, double gamma, cv::Mat* out);

/// One pyramid level down by 2x2 block averaging (CV_8UC1). Errors: empty, wrong type,
/// fewer than 2 rows or columns.
Status Downsample2x(const cv::Mat& in, cv::Mat* out);

/// Applies the prefilter to a CV_8UC1 image, writing CV_8UC1 of the same size into `out`
/// (which may be a view into a larger buffer; it is reallocated only if its size or type
/// differs). Errors: empty, wrong type, invalid options.
Status Prefilter(const cv::Mat& in, const PrefilterOptions& options, cv::Mat* out);

}  // namespace rover::dl::stereo
