#pragma once
/// @file
/// Joint rate from encoder counts over time: the least-squares slope of the unwrapped count
/// over the samples of the last `window` seconds,
///   rate = sum (t_i - t_mean)(c_i - c_mean) / sum (t_i - t_mean)^2 / counts_per_rad.
/// A 1-count quantisation error contributes at most ~ 2 sqrt(3) / (window counts_per_rad
/// sqrt(n)) rad/s; a constant rate is recovered exactly (up to count rounding). Samples whose
/// stamp is not newer than the last are ignored (reordered or duplicated telemetry).

#include <cstdint>
#include <deque>
#include <utility>

namespace rover::ddl::joints {

class RateEstimator {
 public:
  /// Preconditions: window_s > 0, counts_per_rad > 0.
  RateEstimator(double window_s, double counts_per_rad);

  /// Adds the unwrapped count at `stamp_ns`. Returns false if ignored (not newer).
  bool Add(std::int64_t stamp_ns, std::int64_t counts);
  /// [rad/s]; 0 with fewer than two samples.
  double Rate() const;
  std::size_t size() const { return samples_.size(); }
  void Clear() { samples_.clear(); }

 private:
  std::int64_t window_ns_;
  double counts_per_rad_;
  std::deque<std::pair<std::int64_t, std::int64_t>> samples_;
};

}  // namespace rover::ddl::joints
