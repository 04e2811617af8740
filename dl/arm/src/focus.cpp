#include "rover/dl/arm/focus.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <opencv2/core.hpp>
#include <string>
#include <utility>
#include <vector>

#include "rover/base/format.hpp"
#include "rover/base/range_check.hpp"

namespace rover::dl::arm {
namespace {

constexpr int kFocusMaxLevels = 6;

// One Haar level on a w x h approximation (row-major in `approx`): writes the next
// approximation ((w/2) x (h/2), odd last row/column dropped) into `next` and returns the mean
// square of the level's detail coefficients (LH, HL, HH together).
double FocusHaarLevel(const std::vector<double>& approx, int w, int h, std::vector<double>& next) {
  const int nw = w / 2;
  const int nh = h / 2;
  next.assign(static_cast<std::size_t>(nw) * static_cast<std::size_t>(nh), 0.0);
  double sum_sq = 0.0;
  for (int r = 0; r < nh; ++r) {
    const double* row0 =
        approx.data() + static_cast<std::size_t>(2 * r) * static_cast<std::size_t>(w);
    const double* row1 = row0 + w;
    double* out = next.data() + static_cast<std::size_t>(r) * static_cast<std::size_t>(nw);
    for (int c = 0; c < nw; ++c) {
      const double a = row0[2 * c];
      const double b = row0[2 * c + 1];
      const double cc = row1[2 * c];
      const double d = row1[2 * c + 1];
      out[c] = 0.25 * (a + b + cc + d);
      const double lh = 0.25 * (a + b - cc - d);
      const double hl = 0.25 * (a - b + cc - d);
      const double hh = 0.25 * (a - b - cc + d);
      sum_sq += lh * lh + hl * hl + hh * hh;
    }
  }
  return sum_sq / (3.0 * static_cast<double>(nw) * static_cast<double>(nh));
}

std::string FocusSampleName(std::size_t i, const char* field) {
  return "samples[" + std::to_string(i) + "]." + field;
}

}  // namespace

Status FocusMeasureOptions::Validate() const {
  ROVER_RETURN_IF_ERROR(CheckIntRange("focus.levels", levels, 1, kFocusMaxLevels));
  return CheckIntRange("focus.first_level", first_level, 1, levels);
}

Result<double> WaveletFocusMeasure(const cv::Mat& image, const FocusMeasureOptions& options) {
  ROVER_RETURN_IF_ERROR(options.Validate());
  if (image.empty()) return InvalidArgument("focus image is empty");
  if (image.type() != CV_8UC1) {
    return InvalidArgument("focus image has type " + cv::typeToString(image.type()) +
                           "; need CV_8UC1 (8-bit mono)");
  }
  const int min_side = 1 << options.levels;
  if (image.cols < min_side || image.rows < min_side) {
    return InvalidArgument("focus image of " + FormatSize(image.cols, image.rows) +
                           " px is too small for " + std::to_string(options.levels) +
                           " levels: need at least " + std::to_string(min_side) + " px on a side");
  }

  // Mean over all pixels (before any cropping) and the level-0 approximation: the image cropped
  // to even size.
  const int w = image.cols - image.cols % 2;
  const int h = image.rows - image.rows % 2;
  std::vector<double> approx(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
  double sum = 0.0;
  for (int r = 0; r < image.rows; ++r) {
    const std::uint8_t* p = image.ptr<std::uint8_t>(r);
    for (int c = 0; c < image.cols; ++c) {
      sum += p[c];
      if (r < h && c < w) {
        approx[static_cast<std::size_t>(r) * static_cast<std::size_t>(w) +
               static_cast<std::size_t>(c)] = p[c];
      }
    }
  }
  const double mean = sum / (static_cast<double>(image.cols) * static_cast<double>(image.rows));
  if (mean <= 0.0) return 0.0;  // all black: no texture, and nothing to normalise by

  double energy = 0.0;
  int lw = w;
  int lh = h;
  std::vector<double> next;
  for (int level = 1; level <= options.levels; ++level) {
    // lw, lh >= 2 here: the image is at least 2^levels px on a side.
    const double e = FocusHaarLevel(approx, lw, lh, next);
    if (level >= options.first_level) energy += e;
    approx.swap(next);
    lw /= 2;
    lh /= 2;
  }
  return energy / (mean * mean);
}

Result<FocusPeak> FindFocusPeak(std::span<const FocusSample> samples) {
  const std::size_t n = samples.size();
  if (n < 3) {
    return InvalidArgument("focus sweep has " + std::to_string(n) + " samples; need at least 3");
  }
  for (std::size_t i = 0; i < n; ++i) {
    ROVER_RETURN_IF_ERROR(CheckFinite(FocusSampleName(i, "height"), samples[i].height));
    ROVER_RETURN_IF_ERROR(CheckNonNegative(FocusSampleName(i, "measure"), samples[i].measure));
  }
  // The first step sets the direction; every step must go the same way.
  const bool ascending = samples[1].height > samples[0].height;
  for (std::size_t i = 1; i < n; ++i) {
    const double step = samples[i].height - samples[i - 1].height;
    if (!(ascending ? step > 0.0 : step < 0.0)) {
      std::string m =
          "focus sweep heights are not strictly monotone: " + FocusSampleName(i, "height") + " = " +
          FormatNumber(samples[i].height) + " after " + FocusSampleName(i - 1, "height") + " = " +
          FormatNumber(samples[i - 1].height);
      if (i > 1) m += ascending ? " (the sweep ascends)" : " (the sweep descends)";
      return InvalidArgument(std::move(m));
    }
  }

  std::size_t p = 0;
  double min_m = samples[0].measure;
  for (std::size_t i = 1; i < n; ++i) {
    if (samples[i].measure > samples[p].measure) p = i;
    min_m = std::min(min_m, samples[i].measure);
  }
  const double max_m = samples[p].measure;

  FocusPeak peak{};
  peak.peak_index = static_cast<int>(p);
  peak.bracketed = p > 0 && p + 1 < n;
  peak.best_height = samples[p].height;
  if (max_m <= 0.0) {
    peak.contrast = 1.0;
  } else if (min_m * kMaxFocusContrast >= max_m) {
    peak.contrast = max_m / min_m;
  } else {
    peak.contrast = kMaxFocusContrast;
  }

  if (peak.bracketed) {
    const FocusSample& s0 = samples[p - 1];
    const FocusSample& s1 = samples[p];
    const FocusSample& s2 = samples[p + 1];
    if (s0.measure > 0.0 && s2.measure > 0.0) {
      const double y0 = std::log(s0.measure);
      const double y1 = std::log(s1.measure);
      const double y2 = std::log(s2.measure);
      const double d1 = (y1 - y0) / (s1.height - s0.height);
      const double d2 = (y2 - y1) / (s2.height - s1.height);
      const double a = (d2 - d1) / (s2.height - s0.height);
      if (a < 0.0) {
        const double vertex = 0.5 * (s0.height + s1.height) - d1 / (2.0 * a);
        const double lo = std::min(s0.height, s2.height);
        const double hi = std::max(s0.height, s2.height);
        if (std::isfinite(vertex)) peak.best_height = std::clamp(vertex, lo, hi);
      }
    }
  }
  return peak;
}

}  // namespace rover::dl::arm
