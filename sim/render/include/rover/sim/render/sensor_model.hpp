#pragma once
/// @file
/// Camera sensor model: scene radiance -> 8-bit digital numbers (DN), with vignetting, exposure,
/// shot noise, read noise, gain, bias and quantisation. Used by the Renderer after the optical
/// image is formed; public so that tests and tools can apply it to any radiance image.
///
/// Radiance is in "reflectance units": a Lambertian surface of albedo a facing the sun with unit
/// irradiance has radiance a (times the lighting terms of RenderOptions). For pixel (x, y):
///   v      = 1 - vignetting * (r / r_corner)^2,       r = distance from the image centre
///   S      = radiance * v * exposure * full_well_e    [electrons], exposure 1 fills the well
///                                                     at radiance 1
///   S'     = S + sqrt(S + read_noise_e^2) * n,        n ~ N(0, 1) approximately (below)
///   DN     = round(bias_dn + S' * gain * 255 / full_well_e), clamped to [0, 255]
/// i.e. shot noise (Poisson, Gaussian approximation) and read noise add in quadrature.
/// A binned readout (`binning` b > 1: each image pixel is b x b sensor pixels whose charge is
/// summed on the chip before one read, as MER's HAZCAMs were read out) collects b^2 S electrons
/// per image pixel with one read noise and reports their mean:
///   DN     = round(bias_dn + (b^2 S + sqrt(b^2 S + read_noise_e^2) n) * gain * 255 / (b^2 full_well_e))
/// so the brightness is the unbinned one and the noise falls by b (shot) and b^2 (read), not
/// the full per-pixel noise on a b-times-coarser image (which made a 256-px readout of the
/// 1024-px HAZCAM four times noisier than the full frame area-averaged, and dl-stereo's ranges
/// 2-5 times worse).
/// Noise: n is the sum of four 16-bit uniforms from one std::mt19937_64 draw, centred and scaled
/// to unit variance (Irwin-Hall; truncated at +-3.46 sigma), seeded per frame: the same seed
/// gives the same image bit for bit.
///
/// Auto-exposure (AutoExposure): the exposure e_p that puts the `auto_percentile` radiance at
/// `auto_target` of full scale (MER cameras auto-exposed on a histogram percentile as well),
/// raised towards the exposure e_m that puts the median at `auto_median_target`, but by at most
/// `auto_max_overexposure` x e_p: exposure = max(e_p, min(e_m, auto_max_overexposure e_p)).
/// So a small very bright object (the white lander ramps) may clip instead of darkening the
/// whole terrain.

#include <cstdint>
#include <opencv2/core.hpp>

#include "rover/base/status.hpp"

namespace rover::sim::render {

struct SensorOptions {
  bool auto_exposure = true;          ///< exposure from AutoExposure (per stereo pair, left image)
  double exposure = 2.5;              ///< used when !auto_exposure; 1 = radiance 1 fills the well
  double auto_percentile = 0.995;     ///< radiance percentile that auto-exposure places ...
  double auto_target = 0.80;          ///< ... at this fraction of full scale
  double auto_median_target = 0.30;   ///< median radiance wanted at this fraction of full scale
  double auto_max_overexposure = 2.0; ///< limit of the median rule relative to the percentile rule
  double full_well_e = 20000.0;       ///< [e-] electrons at full scale (gain 1)
  double read_noise_e = 25.0;         ///< [e-] RMS read noise
  bool shot_noise = true;             ///< Poisson shot noise (Gaussian approximation)
  bool noise = true;                  ///< false: no shot or read noise (geometry tests)
  double gain = 1.0;                  ///< analog gain multiplier (DN per electron x 255/full well)
  double bias_dn = 2.0;               ///< [DN] dark offset
  double vignetting = 0.15;           ///< light lost at the image corners, [0, 1)
  /// b x b sensor pixels summed per image pixel (a binned readout; set per shot by whoever
  /// renders the readout, not a parameter), [1, 64]
  int binning = 1;

  /// Checks ranges; the message names the field ("sensor.read_noise_e: ...").
  Status Validate() const;
};

/// Exposure for `radiance` (CV_32FC1; pixels <= 0 are ignored): auto_target / (percentile
/// radiance * vignetting-free full well), clamped to [1e-3, 1e3]. Returns options.exposure if
/// no pixel is positive.
double AutoExposure(const cv::Mat& radiance, const SensorOptions& options);

/// Applies the sensor model (see the file comment) to `radiance` (CV_32FC1) with `exposure`;
/// returns CV_8UC1 of the same size. Preconditions: options.Validate().ok(), radiance CV_32FC1.
cv::Mat ApplySensorModel(const cv::Mat& radiance, const SensorOptions& options, double exposure,
                         std::uint64_t seed);

}  // namespace rover::sim::render
