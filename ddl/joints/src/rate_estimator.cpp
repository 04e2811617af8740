#include "rover/ddl/joints/rate_estimator.hpp"

#include <cmath>

#include "rover/base/check.hpp"

namespace rover::ddl::joints {

RateEstimator::RateEstimator(double window_s, double counts_per_rad)
    : window_ns_(std::llround(window_s * 1e9)), counts_per_rad_(counts_per_rad) {
  ROVER_DEMAND(window_s > 0.0 && counts_per_rad > 0.0);
}

bool RateEstimator::Add(std::int64_t stamp_ns, std::int64_t counts) {
  if (!samples_.empty() && stamp_ns <= samples_.back().first) return false;
  samples_.emplace_back(stamp_ns, counts);
  while (samples_.size() > 2 && stamp_ns - samples_.front().first > window_ns_) {
    samples_.pop_front();
  }
  return true;
}

double RateEstimator::Rate() const {
  const std::size_t n = samples_.size();
  if (n < 2) return 0.0;
  // Centre on the first sample to keep the sums small and exact.
  const std::int64_t t0 = samples_.front().first;
  const std::int64_t c0 = samples_.front().second;
  double st = 0.0, sc = 0.0;
  for (const auto& [t, c] : samples_) {
    st += static_cast<double>(t - t0) * 1e-9;
    sc += static_cast<double>(c - c0);
  }
  const double tm = st / static_cast<double>(n), cm = sc / static_cast<double>(n);
  double stt = 0.0, stc = 0.0;
  for (const auto& [t, c] : samples_) {
    const double dt = static_cast<double>(t - t0) * 1e-9 - tm;
    stt += dt * dt;
    stc += dt * (static_cast<double>(c - c0) - cm);
  }
  if (stt <= 0.0) return 0.0;
  return stc / stt / counts_per_rad_;
}

}  // namespace rover::ddl::joints
