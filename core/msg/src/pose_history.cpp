#include "rover/msg/pose_history.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "rover/base/check.hpp"

namespace rover::msg {
namespace {

std::string Seconds(Time t) {
  std::ostringstream os;
  os.precision(10);
  os << t.seconds();
  return os.str() + " s";
}

}  // namespace

PoseHistory::PoseHistory(std::size_t capacity) : capacity_(capacity) {
  ROVER_DEMAND(capacity_ >= 2);
}

Status PoseHistory::Add(const PoseSample& s) {
  if (!s.site_from_rover.matrix().allFinite() || !std::isfinite(s.odometer) ||
      !s.velocity.allFinite()) {
    return InvalidArgument("pose sample at " + Seconds(s.stamp) + " has a non-finite value");
  }
  const Eigen::Matrix3d r = s.site_from_rover.linear();
  if (!(r.transpose() * r).isApprox(Eigen::Matrix3d::Identity(), 1e-6) || r.determinant() < 0) {
    return InvalidArgument("pose sample at " + Seconds(s.stamp) +
                           " has a rotation that is not orthonormal");
  }
  if (!samples_.empty()) {
    const Time newest = samples_.back().stamp;
    if (s.stamp < newest) {
      return OutOfRange("pose sample at " + Seconds(s.stamp) + " is older than the newest, " +
                        Seconds(newest));
    }
    if (s.stamp == newest) {
      samples_.back() = s;
      return Status::Ok();
    }
  }
  samples_.push_back(s);
  while (samples_.size() > capacity_) samples_.pop_front();
  return Status::Ok();
}

Result<PoseSample> PoseHistory::At(Time t, Duration max_gap) const {
  if (samples_.empty()) return NotFound("no pose estimate received yet");
  // First sample with stamp >= t.
  const auto after =
      std::lower_bound(samples_.begin(), samples_.end(), t,
                       [](const PoseSample& s, Time value) { return s.stamp < value; });
  const PoseSample* lo = after == samples_.begin() ? nullptr : &*(after - 1);
  const PoseSample* hi = after == samples_.end() ? nullptr : &*after;
  const Duration gap_lo = lo != nullptr ? t - lo->stamp : Duration::max();
  const Duration gap_hi = hi != nullptr ? hi->stamp - t : Duration::max();
  const Duration gap = std::min(gap_lo, gap_hi);
  if (gap > max_gap) {
    const PoseSample* nearest = gap_lo <= gap_hi ? lo : hi;
    return NotFound("no pose estimate within " + std::to_string(ToSeconds(max_gap)) + " s of " +
                    Seconds(t) + " (nearest at " + Seconds(nearest->stamp) + ")");
  }
  if (lo == nullptr) return *hi;
  if (hi == nullptr || hi->stamp == t) return hi != nullptr ? *hi : *lo;
  const double f = ToSeconds(t - lo->stamp) / ToSeconds(hi->stamp - lo->stamp);
  PoseSample out = f < 0.5 ? *lo : *hi;  // flags from the nearer sample
  out.stamp = t;
  const Eigen::Quaterniond qa(lo->site_from_rover.linear());
  const Eigen::Quaterniond qb(hi->site_from_rover.linear());
  out.site_from_rover = Eigen::Isometry3d::Identity();
  out.site_from_rover.linear() = qa.slerp(f, qb).normalized().toRotationMatrix();
  out.site_from_rover.translation() =
      (1.0 - f) * lo->site_from_rover.translation() + f * hi->site_from_rover.translation();
  out.odometer = (1.0 - f) * lo->odometer + f * hi->odometer;
  out.velocity = (1.0 - f) * lo->velocity + f * hi->velocity;
  return out;
}

bool PoseHistory::WentBackBy(Time t, Duration by) const {
  return !samples_.empty() && samples_.back().stamp - t > by;
}

std::optional<PoseSample> PoseHistory::Latest() const {
  if (samples_.empty()) return std::nullopt;
  return samples_.back();
}

}  // namespace rover::msg
