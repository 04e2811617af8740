#pragma once
/// @file
/// Integrates a yaw rate into a heading: the smoke set's stand-in for pose estimation.
///
///   psi(t_k) = wrap(psi(t_{k-1}) + omega_z(t_k) * (t_k - t_{k-1}))
///
/// Samples must arrive in time order; an older or equal stamp, a gap longer than `max_gap`, or a
/// non-finite rate is rejected (the heading is kept) and reported.

#include "rover/base/status.hpp"
#include "rover/base/time.hpp"

namespace rover::dl::smoke {

class HeadingIntegrator {
 public:
  explicit HeadingIntegrator(Duration max_gap = std::chrono::seconds(1)) : max_gap_(max_gap) {}

  /// Adds one yaw-rate sample [rad/s] stamped `t`. The first sample only sets the time origin.
  Status Add(Time t, double yaw_rate);

  /// [rad] in (-pi, pi].
  double heading() const { return heading_; }
  int samples() const { return samples_; }
  Time last_stamp() const { return last_; }

 private:
  Duration max_gap_;
  double heading_ = 0.0;
  Time last_{0};
  int samples_ = 0;
};

}  // namespace rover::dl::smoke
