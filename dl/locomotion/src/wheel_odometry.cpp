#include "rover/dl/locomotion/wheel_odometry.hpp"

#include <Eigen/QR>
#include <cmath>
#include <sstream>

#include "rover/base/format.hpp"

namespace rover::dl::locomotion {
namespace {

SuspensionAngles Suspension(const msg::JointState& s, bool use) {
  SuspensionAngles a;
  if (use) {
    a.rocker = s.rocker_angle;
    a.bogie = s.bogie_angle;
  }
  return a;
}

double WheelHeading(const msg::JointState& s, int wheel) {
  for (int j = 0; j < kNumSteered; ++j) {
    if (kSteeredWheel[static_cast<std::size_t>(j)] == wheel) {
      return s.steer_angle[static_cast<std::size_t>(j)];
    }
  }
  return 0.0;
}

}  // namespace

Status WheelOdometryOptions::Validate() const {
  auto positive = [](double v, const char* name) -> Status {
    if (!std::isfinite(v) || v < 0.0) {
      return InvalidArgument(std::string("WheelOdometryOptions.") + name + ": " + FormatNumber(v) +
                             " must be finite and >= 0");
    }
    return Status::Ok();
  };
  ROVER_RETURN_IF_ERROR(positive(along_variance_per_m, "along_variance_per_m"));
  ROVER_RETURN_IF_ERROR(positive(cross_variance_per_m, "cross_variance_per_m"));
  ROVER_RETURN_IF_ERROR(positive(yaw_variance_per_m, "yaw_variance_per_m"));
  if (!std::isfinite(max_wheel_step) || max_wheel_step <= 0.0) {
    return InvalidArgument("WheelOdometryOptions.max_wheel_step: " + FormatNumber(max_wheel_step) +
                           " must be > 0");
  }
  if (!std::isfinite(max_wheel_rate) || max_wheel_rate <= 0.0) {
    return InvalidArgument("WheelOdometryOptions.max_wheel_rate: " + FormatNumber(max_wheel_rate) +
                           " must be > 0");
  }
  if (!std::isfinite(slip_ratio) || slip_ratio < 0.0 || slip_ratio >= 0.5) {
    return InvalidArgument("WheelOdometryOptions.slip_ratio: " + FormatNumber(slip_ratio) +
                           " must be in [0, 0.5)");
  }
  if (!std::isfinite(max_interval_s) || max_interval_s <= 0.0) {
    return InvalidArgument("WheelOdometryOptions.max_interval_s: " + FormatNumber(max_interval_s) +
                           " must be > 0");
  }
  return Status::Ok();
}

Result<WheelOdometry> WheelOdometry::Create(const RoverGeometry& geometry,
                                            const WheelOdometryOptions& options) {
  ROVER_RETURN_IF_ERROR(geometry.Validate());
  ROVER_RETURN_IF_ERROR(options.Validate());
  return WheelOdometry(geometry, options);
}

Status CheckWheelJump(const msg::JointState& from, const msg::JointState& to,
                      double max_wheel_rate) {
  if (to.stamp <= from.stamp) return Status::Ok();
  const double dt = ToSeconds(to.stamp - from.stamp);
  const double limit = max_wheel_rate * dt + kWheelJumpSlack;
  for (std::size_t i = 0; i < to.wheel_angle.size(); ++i) {
    const double d = to.wheel_angle[i] - from.wheel_angle[i];
    if (!(std::abs(d) <= limit)) {
      return OutOfRange("wheel " + std::to_string(i) + " angle jumped by " + FormatNumber(d) +
                        " rad in " + FormatNumber(dt, 3) + " s (at most " + FormatNumber(limit, 3) +
                        " rad at " + FormatNumber(max_wheel_rate) + " rad/s): an encoder fault");
    }
  }
  return Status::Ok();
}

Result<OdometryIncrement> WheelOdometry::Compute(const msg::JointState& from,
                                                 const msg::JointState& to) const {
  if (!from.AllFinite() || !to.AllFinite()) {
    return InvalidArgument("wheel odometry: joint sample has a non-finite angle or rate");
  }
  if (to.stamp <= from.stamp) {
    return InvalidArgument("wheel odometry: sample at " + FormatNumber(to.stamp.seconds()) +
                           " s is not after the previous one at " +
                           FormatNumber(from.stamp.seconds()) + " s");
  }
  const double dt = ToSeconds(to.stamp - from.stamp);
  if (dt > options_.max_interval_s) {
    return OutOfRange("wheel odometry: interval " + FormatNumber(dt) +
                      " s exceeds max_interval_s " + FormatNumber(options_.max_interval_s) + " s");
  }
  ROVER_RETURN_IF_ERROR(CheckWheelJump(from, to, options_.max_wheel_rate));
  const SuspensionAngles s0 = Suspension(from, options_.use_suspension);
  const SuspensionAngles s1 = Suspension(to, options_.use_suspension);
  const double r = geometry_.wheel_radius;

  Eigen::Matrix<double, 12, 3> a;
  Eigen::Matrix<double, 12, 1> b;
  double path = 0.0;
  for (int i = 0; i < kNumWheels; ++i) {
    const auto ui = static_cast<std::size_t>(i);
    const double dth = to.wheel_angle[ui] - from.wheel_angle[ui];
    if (std::abs(dth) > options_.max_wheel_step) {
      return OutOfRange("wheel odometry: wheel " + std::to_string(i) + " turned " +
                        FormatNumber(dth) + " rad in one interval (max_wheel_step " +
                        FormatNumber(options_.max_wheel_step) + ")");
    }
    const Eigen::Vector3d c0 = geometry_.WheelCentre(i, s0);
    const Eigen::Vector3d c1 = geometry_.WheelCentre(i, s1);
    const Eigen::Vector2d pbar = 0.5 * (c0 + c1).head<2>();
    const Eigen::Vector2d dp = (c1 - c0).head<2>();
    const double heading = 0.5 * (WheelHeading(from, i) + WheelHeading(to, i));
    const double pitch = 0.5 * (RoverGeometry::LinkPitch(i, s0) + RoverGeometry::LinkPitch(i, s1));
    const Eigen::Vector2d t(std::cos(heading), std::sin(heading));
    const Eigen::Vector2d n(-t.y(), t.x());
    const Eigen::Vector2d jp(-pbar.y(), pbar.x());
    const double rim = (1.0 - options_.slip_ratio) * r * dth * std::cos(pitch);
    path += std::abs(rim);
    a.row(2 * i) << t.x(), t.y(), t.dot(jp);
    b(2 * i) = rim - t.dot(dp);
    a.row(2 * i + 1) << n.x(), n.y(), n.dot(jp);
    b(2 * i + 1) = -n.dot(dp);
  }
  const Eigen::Vector3d twist = a.colPivHouseholderQr().solve(b);

  OdometryIncrement inc;
  inc.t_from = from.stamp;
  inc.t_to = to.stamp;
  const double w = twist.z();
  double sinc, cosc;  // sin(w)/w and (1 - cos w)/w
  if (std::abs(w) < 1e-6) {
    sinc = 1.0 - w * w / 6.0;
    cosc = w / 2.0;
  } else {
    sinc = std::sin(w) / w;
    cosc = (1.0 - std::cos(w)) / w;
  }
  inc.dx = twist.x() * sinc - twist.y() * cosc;
  inc.dy = twist.x() * cosc + twist.y() * sinc;
  inc.dyaw = w;
  inc.path_length = path / kNumWheels;
  inc.residual_rms = std::sqrt((a * twist - b).squaredNorm() / 12.0);

  Eigen::Vector2d e(inc.dx, inc.dy);
  const double norm = e.norm();
  e = norm > 1e-9 ? Eigen::Vector2d(e / norm) : Eigen::Vector2d::UnitX();
  const Eigen::Vector2d ep(-e.y(), e.x());
  const double s = inc.path_length;
  inc.covariance.setZero();
  inc.covariance.topLeftCorner<2, 2>() = s * (options_.along_variance_per_m * e * e.transpose() +
                                              options_.cross_variance_per_m * ep * ep.transpose());
  inc.covariance(2, 2) = s * options_.yaw_variance_per_m;
  return inc;
}

Result<std::optional<OdometryIncrement>> WheelOdometry::Add(const msg::JointState& sample) {
  if (!sample.AllFinite()) {
    return InvalidArgument("wheel odometry: joint sample has a non-finite angle or rate");
  }
  if (!previous_.has_value()) {
    previous_ = sample;
    return std::optional<OdometryIncrement>();
  }
  if (sample.stamp > previous_->stamp &&
      ToSeconds(sample.stamp - previous_->stamp) > options_.max_interval_s) {
    previous_ = sample;  // restart after a gap: the motion over the gap is unknown
    return std::optional<OdometryIncrement>();
  }
  Result<OdometryIncrement> inc = Compute(*previous_, sample);
  if (!inc.ok()) {
    // An implausible jump restarts the stream at the new sample (so one bad encoder reading
    // does not block odometry forever); an out-of-order sample is simply dropped.
    if (sample.stamp > previous_->stamp) previous_ = sample;
    return inc.status();
  }
  previous_ = sample;
  return std::optional<OdometryIncrement>(std::move(inc).value());
}

void DeclareWheelOdometryParams(ParamSet& params, const std::string& prefix) {
  const WheelOdometryOptions d;
  params
      .Declare(prefix + "along_variance_per_m", d.along_variance_per_m,
               "[m^2/m] odometry variance along the motion per metre")
      .Range(0.0, 1.0);
  params
      .Declare(prefix + "cross_variance_per_m", d.cross_variance_per_m,
               "[m^2/m] odometry variance across the motion per metre")
      .Range(0.0, 1.0);
  params
      .Declare(prefix + "yaw_variance_per_m", d.yaw_variance_per_m,
               "[rad^2/m] odometry heading variance per metre")
      .Range(0.0, 1.0);
  params
      .Declare(prefix + "max_wheel_step", d.max_wheel_step,
               "[rad] largest plausible wheel rotation between two samples")
      .Range(1e-3, 100.0);
  params
      .Declare(prefix + "max_wheel_rate", d.max_wheel_rate,
               "[rad/s] fastest plausible wheel; a faster jump between two samples is an encoder "
               "fault and the sample is rejected")
      .Range(1e-3, 1000.0);
  params
      .Declare(prefix + "max_interval_s", d.max_interval_s,
               "[s] largest plausible time between two samples")
      .Range(1e-3, 60.0);
  params.Declare(prefix + "use_suspension", d.use_suspension,
                 "use rocker/bogie angles for the contact geometry");
  params
      .Declare(prefix + "slip_ratio", d.slip_ratio,
               "expected longitudinal wheel slip on the terrain (calibrated there): a rim "
               "distance d counts as (1 - slip_ratio) d on the ground")
      .Range(0.0, 0.49);
}

Result<WheelOdometryOptions> WheelOdometryOptionsFromParams(const ParamSet& params,
                                                            const std::string& prefix) {
  ROVER_RETURN_IF_ERROR(params.Validate());
  WheelOdometryOptions o;
  o.along_variance_per_m = params.GetDouble(prefix + "along_variance_per_m");
  o.cross_variance_per_m = params.GetDouble(prefix + "cross_variance_per_m");
  o.yaw_variance_per_m = params.GetDouble(prefix + "yaw_variance_per_m");
  o.max_wheel_step = params.GetDouble(prefix + "max_wheel_step");
  o.max_interval_s = params.GetDouble(prefix + "max_interval_s");
  o.max_wheel_rate = params.GetDouble(prefix + "max_wheel_rate");
  o.use_suspension = params.GetBool(prefix + "use_suspension");
  o.slip_ratio = params.GetDouble(prefix + "slip_ratio");
  ROVER_RETURN_IF_ERROR(o.Validate());
  return o;
}

}  // namespace rover::dl::locomotion
