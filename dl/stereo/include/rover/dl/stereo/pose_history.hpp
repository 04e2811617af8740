#pragma once
/// @file
/// A short history of the rover's pose estimates (dl/pose) to look up the pose at an image's
/// capture time: the stereo service stamps each range image with it and visual odometry takes
/// its wheel-odometry prior from the change between two capture times.
///
/// Frames: `site_from_rover` is the rover frame (x forward, y left, z up) in the site frame
/// (x north, y west, z up), metres. At(t) interpolates between the two samples around t
/// (translation and odometer linearly, rotation by slerp); outside the covered span it returns
/// the nearest sample. Either way the nearest sample must lie within `max_gap` of t, otherwise
/// the pose at t is unknown (NotFound): a stale or missing estimate is never passed off as one.

#include <Eigen/Geometry>
#include <cmath>
#include <cstddef>
#include <deque>
#include <optional>
#include <string>

#include "rover/base/status.hpp"
#include "rover/base/time.hpp"

namespace rover::dl::stereo {

struct PoseSample {
  Time stamp;  ///< time of validity on the run clock
  Eigen::Isometry3d site_from_rover = Eigen::Isometry3d::Identity();
  double odometer = 0.0;                               ///< [m] path length driven
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();  ///< [m/s] rover frame
  bool stationary = false;                             ///< the estimator's rest flag
};

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
  std::size_t size() const { return samples_.size(); }
  bool empty() const { return samples_.empty(); }
  void Clear() { samples_.clear(); }

 private:
  std::size_t capacity_;
  std::deque<PoseSample> samples_;  // oldest first
};

/// Reads a dl/pose message (header.stamp_ns, pose {position, orientation w x y z}, odometer,
/// velocity, stationary) into a sample; the quaternion is renormalised. Errors: a quaternion
/// whose norm is not within 1e-3 of 1 (or not finite).
template <class Msg>
Result<PoseSample> PoseSampleFromMessage(const Msg& m) {
  const auto& q = m.pose.orientation;
  const Eigen::Quaterniond quat(q.w, q.x, q.y, q.z);
  if (!(std::abs(quat.norm() - 1.0) <= 1e-3)) {
    return InvalidArgument("dl/pose orientation is not a unit quaternion (norm " +
                           std::to_string(quat.norm()) + ")");
  }
  PoseSample s;
  s.stamp = Time{m.header.stamp_ns};
  s.site_from_rover.linear() = quat.normalized().toRotationMatrix();
  s.site_from_rover.translation() =
      Eigen::Vector3d(m.pose.position.x, m.pose.position.y, m.pose.position.z);
  s.odometer = m.odometer;
  s.velocity = Eigen::Vector3d(m.velocity.x, m.velocity.y, m.velocity.z);
  s.stationary = m.stationary;
  return s;
}

}  // namespace rover::dl::stereo
