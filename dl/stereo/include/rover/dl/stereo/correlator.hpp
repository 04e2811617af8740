#pragma once
/// @file
/// Area correlation along scanlines: sum of absolute differences (SAD) over a w x w window,
/// winner-take-all over a disparity range, the per-pixel acceptance tests that need the cost
/// curve (range edge, flat valley, secondary minimum, left-right line of sight) and the
/// sub-pixel peak.
///
/// For a left pixel (u, v) and disparity d in [d_min, d_min + D):
///     C(u, v, d) = sum_{|i|,|j| <= h} | L(u + i, v + j) - R(u + i - d, v + j) |,  h = (w-1)/2,
/// computed with sliding sums: per disparity, column sums over w rows are updated by one row
/// add and one row subtract, then summed over w columns (cost O(W H D), independent of w^2
/// apart from the w-column sum). A disparity is a candidate only if the whole window lies in
/// both images, so near the left border the search range is truncated (see
/// `full_search_only`).
///
/// Best disparity k* = argmin_d C (smallest d on ties), with C- = C(k*-1), C0 = C(k*),
/// C+ = C(k*+1). Tests, in this order (first failure is the pixel's status):
///   range edge:  k* at an end of its search range (C- or C+ missing)        -> kRangeEdge
///   flat:        C- + C+ - 2 C0 < min_curvature * w^2                       -> kFlat
///   uniqueness:  min_{|d-k*|>1} C(d) <= (1 + uniqueness_ratio) C0          -> kNotUnique
///   left-right:  |k*_R(u - k*) - k*| > lr_max_diff, where k*_R is the best disparity of the
///                right pixel found over the same cost volume (C(u_R + d, v, d) over d)
///                                                                            -> kLeftRight
/// Sub-pixel peak (parabola through the three costs):
///     d = k* + (C- - C+) / (2 (C- + C+ - 2 C0))
/// or the equiangular (symmetric V) fit  d = k* + (C- - C+) / (2 (max(C-, C+) - C0)).
///
/// Inputs are 8-bit prefiltered images (image_prep.hpp); costs are 16-bit, so
/// w^2 * max(input) must stay below 32768 (checked). The SAD kernel uses AVX2 or SSE2 when the
/// CPU has them (runtime dispatch) and a scalar loop otherwise; all give identical results.
/// Rows are split into bands processed by `num_threads` std::threads.

#include <cstdint>
#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "rover/base/status.hpp"
#include "rover/dl/stereo/disparity_image.hpp"

namespace rover::dl::stereo {

namespace internal {
class WorkerPool;
}  // namespace internal

enum class SubpixelMethod { kNone, kParabola, kEquiangular };
enum class SimdLevel { kAuto, kScalar, kSse2, kAvx2 };

/// "scalar", "sse2", "avx2" (kAuto resolves to the best the CPU supports).
const char* SimdLevelName(SimdLevel s);
/// The best level this CPU supports.
SimdLevel DetectSimdLevel();

struct CorrelatorOptions {
  int window = 7;            ///< w, odd, [3, 15]
  int min_disparity = 0;     ///< d_min [px], [-1024, 1024]
  int num_disparities = 64;  ///< D, [2, 512]
  SubpixelMethod subpixel = SubpixelMethod::kEquiangular;
  double uniqueness_ratio = 0.05;  ///< [0, 2]; 0 disables the secondary-minimum test
  double min_curvature = 0.5;      ///< per window pixel, [0, 255]; 0 disables the flat test
  int lr_max_diff = 1;             ///< [px], [0, 64]; -1 disables the left-right check
  bool reject_range_edge = true;   ///< reject minima at the ends of the search range
  bool full_search_only = false;   ///< reject pixels whose search range is truncated
  int num_threads = 2;             ///< [1, 64]
  SimdLevel simd = SimdLevel::kAuto;

  Status Validate() const;
};

/// Holds per-thread scratch buffers and num_threads - 1 persistent helper threads; reuse one
/// instance for a stream of pairs. Not thread-safe: one Compute at a time per instance.
class Correlator {
 public:
  /// Errors: invalid options, or a SIMD level the CPU does not support.
  static Result<Correlator> Create(const CorrelatorOptions& options);

  Correlator(Correlator&&) noexcept;
  Correlator& operator=(Correlator&&) noexcept;
  ~Correlator();

  /// Correlates a rectified, prefiltered pair (CV_8UC1, equal sizes) into `out` (same size).
  /// Errors: empty or mismatched images, wrong types, a disparity range that leaves no pixel
  /// to match, or input values that overflow 16-bit window costs.
  Status Compute(const cv::Mat& left, const cv::Mat& right, DisparityImage* out);

  const CorrelatorOptions& options() const { return options_; }
  /// The SIMD level actually used.
  SimdLevel simd() const { return simd_; }

 private:
  friend class StereoPipeline;  // shares the worker pool
  struct Scratch;
  explicit Correlator(const CorrelatorOptions& options, SimdLevel simd);

  CorrelatorOptions options_;
  SimdLevel simd_ = SimdLevel::kScalar;
  std::unique_ptr<internal::WorkerPool> pool_;
  std::vector<std::unique_ptr<Scratch>> scratch_;
  std::vector<std::uint8_t> left_buf_, right_buf_;
};

}  // namespace rover::dl::stereo
