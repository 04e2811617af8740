#pragma once
/// @file
/// A short history of the rover's pose estimates (dl/pose, as PoseSample) to look up the pose at
/// a past time: the stereo service stamps each range image with the pose at its capture time,
/// visual odometry takes its wheel-odometry prior from the change between two capture times, and
/// application code can ask where the rover was when a measurement was taken.
///
/// Frames: `site_from_rover` is the rover frame (x forward, y left, z up) in the site frame
/// (x north, y west, z up), metres. At(t) interpolates between the two samples around t
/// (translation and odometer linearly, rotation by slerp); outside the covered span it returns
/// the nearest sample. Either way the nearest sample must lie within `max_gap` of t, otherwise
/// the pose at t is unknown (NotFound): a stale or missing estimate is never passed off as one.

#include <Eigen/Geometry>
#include <cstddef>
#include <deque>
#include <optional>
#include <string>

#include "rover/base/status.hpp"
#include "rover/base/time.hpp"
#include "rover/msg/pose.hpp"

namespace rover::msg {

class PoseHistory {
 public:
  /// Precondition: capacity >= 2.
  explicit PoseHistory(std::size_t capacity = 512);

  /// Appends a sample (the oldest is dropped when full). A sample with the newest stamp
  /// replaces it. Errors (history unchanged): non-finite values, a rotation that is not
  /// orthonormal (1e-6), a stamp older than the newest (out of order).
  Status Add(const PoseSample& sample);

  /// The pose at `t` (see the file comment). Errors: NotFound if empty or if the nearest sample
  /// is more than `max_gap` away, naming both times.
  Result<PoseSample> At(Time t, Duration max_gap) const;

  std::optional<PoseSample> Latest() const;
  /// Whether `t` is more than `by` older than the newest sample: the run clock went back (a
  /// simulator reset) rather than a sample arriving out of order. False when empty.
  bool WentBackBy(Time t, Duration by) const;
  std::size_t size() const { return samples_.size(); }
  bool empty() const { return samples_.empty(); }
  void Clear() { samples_.clear(); }

 private:
  std::size_t capacity_;
  std::deque<PoseSample> samples_;  // oldest first
};

}  // namespace rover::msg
