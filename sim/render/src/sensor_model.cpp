#include "rover/sim/render/sensor_model.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "rover/base/check.hpp"

namespace rover::sim::render {
namespace {

Status Bad(const std::string& field, double value, const std::string& what) {
  return InvalidArgument("sensor." + field + ": " + std::to_string(value) + " " + what);
}

}  // namespace

Status SensorOptions::Validate() const {
  if (!(std::isfinite(exposure) && exposure > 0.0 && exposure <= 1e3)) {
    return Bad("exposure", exposure, "is out of range (0, 1000]");
  }
  if (!(auto_percentile > 0.0 && auto_percentile <= 1.0)) {
    return Bad("auto_percentile", auto_percentile, "is out of range (0, 1]");
  }
  if (!(auto_target > 0.0 && auto_target <= 1.0)) {
    return Bad("auto_target", auto_target, "is out of range (0, 1]");
  }
  if (!(std::isfinite(full_well_e) && full_well_e >= 1.0)) {
    return Bad("full_well_e", full_well_e, "must be >= 1");
  }
  if (!(std::isfinite(read_noise_e) && read_noise_e >= 0.0)) {
    return Bad("read_noise_e", read_noise_e, "must be >= 0");
  }
  if (!(std::isfinite(gain) && gain > 0.0 && gain <= 100.0)) {
    return Bad("gain", gain, "is out of range (0, 100]");
  }
  if (!(std::isfinite(bias_dn) && bias_dn >= 0.0 && bias_dn < 255.0)) {
    return Bad("bias_dn", bias_dn, "is out of range [0, 255)");
  }
  if (!(vignetting >= 0.0 && vignetting < 1.0)) {
    return Bad("vignetting", vignetting, "is out of range [0, 1)");
  }
  if (binning < 1 || binning > 64) return Bad("binning", binning, "is out of range [1, 64]");
  return Status::Ok();
}

double AutoExposure(const cv::Mat& radiance, const SensorOptions& options) {
  ROVER_DEMAND(radiance.type() == CV_32FC1);
  std::vector<float> values;
  values.reserve(radiance.total());
  for (int r = 0; r < radiance.rows; ++r) {
    const float* p = radiance.ptr<float>(r);
    for (int c = 0; c < radiance.cols; ++c) {
      if (p[c] > 0.0F && std::isfinite(p[c])) values.push_back(p[c]);
    }
  }
  if (values.empty()) return options.exposure;
  const auto k = static_cast<std::size_t>(
      std::min<double>(static_cast<double>(values.size()) - 1.0,
                       std::floor(options.auto_percentile * static_cast<double>(values.size()))));
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
  const double level = values[k];
  if (!(level > 0.0)) return options.exposure;
  const double e_pct = options.auto_target / (level * options.gain);
  const std::size_t mid = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(mid), values.end());
  const double e_med = values[mid] > 0.0F ? options.auto_median_target / (values[mid] * options.gain)
                                          : e_pct;
  const double e = std::max(e_pct, std::min(e_med, options.auto_max_overexposure * e_pct));
  return std::clamp(e, 1e-3, 1e3);
}

cv::Mat ApplySensorModel(const cv::Mat& radiance, const SensorOptions& options, double exposure,
                         std::uint64_t seed) {
  ROVER_DEMAND(radiance.type() == CV_32FC1);
  ROVER_DEMAND(std::isfinite(exposure) && exposure > 0.0);
  cv::Mat out(radiance.size(), CV_8UC1);
  std::mt19937_64 rng(seed);
  const double cx = 0.5 * (radiance.cols - 1), cy = 0.5 * (radiance.rows - 1);
  const double inv_r2 = 1.0 / std::max(1.0, cx * cx + cy * cy);
  // A binned pixel collects the charge of binning^2 sensor pixels and reports their mean.
  const double pixels = static_cast<double>(options.binning) * options.binning;
  const double electrons_per_unit = exposure * options.full_well_e * pixels;
  const double dn_per_e = options.gain * 255.0 / (options.full_well_e * pixels);
  const double read_var = options.read_noise_e * options.read_noise_e;
  const bool noise = options.noise;
  const bool shot = options.shot_noise;
  // Irwin-Hall(4) of 16-bit uniforms: sum of four U[0,1) has mean 2, variance 1/3.
  constexpr double kU16 = 1.0 / 65536.0;
  const double kScale = std::sqrt(3.0);
  for (int r = 0; r < radiance.rows; ++r) {
    const float* in = radiance.ptr<float>(r);
    std::uint8_t* o = out.ptr<std::uint8_t>(r);
    const double dy = r - cy;
    for (int c = 0; c < radiance.cols; ++c) {
      const double dx = c - cx;
      const double v = 1.0 - options.vignetting * (dx * dx + dy * dy) * inv_r2;
      const double rad = std::isfinite(in[c]) ? std::max(0.0F, in[c]) : 0.0;
      double s = rad * v * electrons_per_unit;
      if (noise) {
        const std::uint64_t bits = rng();
        const double u = static_cast<double>(bits & 0xFFFF) + static_cast<double>((bits >> 16) & 0xFFFF) +
                         static_cast<double>((bits >> 32) & 0xFFFF) + static_cast<double>(bits >> 48);
        const double n = (u * kU16 + 2.0 * kU16 - 2.0) * kScale;
        s += std::sqrt((shot ? s : 0.0) + read_var) * n;
      }
      const double dn = std::round(options.bias_dn + s * dn_per_e);
      o[c] = static_cast<std::uint8_t>(std::clamp(dn, 0.0, 255.0));
    }
  }
  return out;
}

}  // namespace rover::sim::render
