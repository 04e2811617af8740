#include "rover/msg/pose_idl.hpp"

#include <cmath>

#include "idl_enum.hpp"
#include "rover/base/check.hpp"
#include "rover/base/format.hpp"
#include "rover/base/range_check.hpp"
#include "rover/geometry/transforms.hpp"

namespace rover::msg {

using internal::Vec;
namespace {

// Every component finite; the message names it ("pose.position.x is nan (must be finite)").
Status CheckVecFinite(const std::string& name, const rover_Vector3& v) {
  ROVER_RETURN_IF_ERROR(CheckFinite(name + ".x", v.x));
  ROVER_RETURN_IF_ERROR(CheckFinite(name + ".y", v.y));
  return CheckFinite(name + ".z", v.z);
}
Eigen::Quaterniond Quat(const rover_Quaternion& q) { return {q.w, q.x, q.y, q.z}; }
rover_Quaternion Quat(const Eigen::Quaterniond& q) { return {q.w(), q.x(), q.y(), q.z()}; }

void CovarianceToIdl(const Matrix6d& c, double (&out)[36]) {
  for (int r = 0; r < 6; ++r) {
    for (int k = 0; k < 6; ++k) out[r * 6 + k] = c(r, k);
  }
}
Matrix6d CovarianceFromIdl(const double (&in)[36]) {
  return Eigen::Map<const Eigen::Matrix<double, 6, 6, Eigen::RowMajor>>(in);
}

// The dl/pose orientation, normalised. Errors: a norm not within 1e-3 of 1 (or NaN).
Result<Eigen::Quaterniond> PoseOrientation(const rover_dl_PoseEstimate& in) {
  const Eigen::Quaterniond q = Quat(in.pose.orientation);
  if (!(std::abs(q.norm() - 1.0) <= 1e-3)) {
    return InvalidArgument("dl/pose orientation is not a unit quaternion (norm " +
                           FormatNumber(q.norm()) + ")");
  }
  return q.normalized();
}

}  // namespace

Eigen::Isometry3d IsometryFromIdl(const rover_Pose3& in) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = Quat(in.orientation).normalized().toRotationMatrix();
  t.translation() = Vec(in.position);
  return t;
}

void IsometryToIdl(const Eigen::Isometry3d& in, rover_Pose3* out) {
  out->position = Vec(Eigen::Vector3d(in.translation()));
  out->orientation = Quat(Eigen::Quaterniond(in.linear()));
}

static_assert(rover_dl_SOURCE_WHEEL_ODOMETRY == static_cast<int>(MotionSource::kWheelOdometry));
static_assert(rover_dl_SOURCE_VISUAL_ODOMETRY == static_cast<int>(MotionSource::kVisualOdometry));
static_assert(rover_dl_SOURCE_SUN_SENSOR == static_cast<int>(MotionSource::kSunSensor));
static_assert(rover_dl_SOURCE_ACCELEROMETER == static_cast<int>(MotionSource::kAccelerometer));
static_assert(rover_dl_SOURCE_EXTERNAL == static_cast<int>(MotionSource::kExternal));
static_assert(rover_dl_RELPOSE_CONVERGED == static_cast<int>(RelativePoseStatus::kConverged));
static_assert(rover_dl_RELPOSE_TOO_FEW_FEATURES ==
              static_cast<int>(RelativePoseStatus::kTooFewFeatures));
static_assert(rover_dl_RELPOSE_LIMITS_FAILED ==
              static_cast<int>(RelativePoseStatus::kLimitsFailed));
static_assert(rover_dl_RELPOSE_NOT_CONVERGED ==
              static_cast<int>(RelativePoseStatus::kNotConverged));
static_assert(rover_dl_RELPOSE_BAD_INPUT == static_cast<int>(RelativePoseStatus::kBadInput));

Result<MotionSource> MotionSourceFromIdl(const rover_dl_MotionSource& s, std::string_view field) {
  return internal::EnumFromIdl<MotionSource>(s, 5, field, "MotionSource");
}

void PoseEstimateToIdl(const PoseEstimate& in, rover_dl_PoseEstimate* out) {
  out->header.stamp_ns = in.stamp.ns;
  out->pose.position = Vec(in.position);
  out->pose.orientation = Quat(in.orientation);
  CovarianceToIdl(in.covariance, out->covariance);
  out->velocity = Vec(in.velocity);
  out->gyro_bias = Vec(in.gyro_bias);
  out->stationary = in.stationary;
  out->rejected_measurements = in.rejected_measurements;
  out->odometer = in.odometer;
}

Result<PoseEstimate> PoseEstimateFromIdl(const rover_dl_PoseEstimate& in) {
  PoseEstimate e;
  e.stamp = Time{in.header.stamp_ns};
  e.position = Vec(in.pose.position);
  ROVER_ASSIGN_OR_RETURN(e.orientation, PoseOrientation(in));
  e.rpy = geometry::RpyFromQuaternion(e.orientation);
  e.covariance = CovarianceFromIdl(in.covariance);
  e.velocity = Vec(in.velocity);
  e.gyro_bias = Vec(in.gyro_bias);
  e.stationary = in.stationary;
  e.rejected_measurements = in.rejected_measurements;
  e.odometer = in.odometer;
  return e;
}

Result<PoseSample> PoseSampleFromIdl(const rover_dl_PoseEstimate& in) {
  ROVER_ASSIGN_OR_RETURN(const Eigen::Quaterniond q, PoseOrientation(in));
  ROVER_RETURN_IF_ERROR(CheckVecFinite("pose.position", in.pose.position));
  ROVER_RETURN_IF_ERROR(CheckVecFinite("velocity", in.velocity));
  ROVER_RETURN_IF_ERROR(CheckFinite("odometer", in.odometer));
  PoseSample s;
  s.stamp = Time{in.header.stamp_ns};
  s.site_from_rover.linear() = q.toRotationMatrix();
  s.site_from_rover.translation() = Vec(in.pose.position);
  s.odometer = in.odometer;
  s.velocity = Vec(in.velocity);
  s.stationary = in.stationary;
  return s;
}

Result<AttitudeSample> AttitudeSampleFromIdl(const rover_dl_PoseEstimate& in) {
  const Eigen::Quaterniond q = Quat(in.pose.orientation);
  const double n = q.norm();
  if (!q.coeffs().allFinite() || !(n >= 0.5 && n <= 2.0)) {
    return InvalidArgument("dl/pose orientation (" + FormatNumber(q.w()) + ", " +
                           FormatNumber(q.x()) + ", " + FormatNumber(q.y()) + ", " +
                           FormatNumber(q.z()) + ") is not a rotation (norm " + FormatNumber(n) +
                           ")");
  }
  const geometry::Rpy rpy = geometry::RpyFromQuaternion(q.normalized());
  AttitudeSample a;
  a.stamp = Time{in.header.stamp_ns};
  a.roll = rpy.x();
  a.pitch = rpy.y();
  a.yaw = rpy.z();
  a.healthy = true;
  return a;
}

void RelativePoseToIdl(const RelativePose& in, rover_dl_RelativePose* out) {
  out->header.stamp_ns = in.stamp.ns;
  out->source = internal::EnumToIdl<rover_dl_MotionSource>(in.source);
  out->t_from_ns = in.t_from.ns;
  out->t_to_ns = in.t_to.ns;
  IsometryToIdl(in.delta, &out->delta);
  CovarianceToIdl(in.covariance, out->covariance);
  out->status = internal::EnumToIdl<rover_dl_RelativePoseStatus>(in.status);
  out->features = in.features;
}

Result<RelativePose> RelativePoseFromIdl(const rover_dl_RelativePose& in) {
  RelativePose r;
  r.stamp = Time{in.header.stamp_ns};
  ROVER_ASSIGN_OR_RETURN(r.source, MotionSourceFromIdl(in.source, "dl/relative_pose: source"));
  ROVER_ASSIGN_OR_RETURN(
      r.status, internal::EnumFromIdl<RelativePoseStatus>(in.status, 5, "dl/relative_pose: status",
                                                          "RelativePoseStatus"));
  r.t_from = Time{in.t_from_ns};
  r.t_to = Time{in.t_to_ns};
  const double norm = Quat(in.delta.orientation).norm();
  if (!(std::abs(norm - 1.0) <= 1e-6)) {  // also NaN
    return InvalidArgument("dl/relative_pose: delta orientation quaternion has norm " +
                           FormatNumber(norm) + " (must be 1)");
  }
  r.delta = IsometryFromIdl(in.delta);  // normalised: rounding only
  r.covariance = CovarianceFromIdl(in.covariance);
  r.features = in.features;
  return r;
}

void EstimatorEventToIdl(const EstimatorEvent& in, rover_dl_EstimatorEvent* out) {
  out->header.stamp_ns = in.stamp.ns;
  out->source = internal::EnumToIdl<rover_dl_MotionSource>(in.source);
  out->accepted = in.accepted;
  out->mahalanobis_sq = in.mahalanobis_sq;
  out->gate = in.gate;
  idl::CopyString(out->message, in.message);
}

Result<EstimatorEvent> EstimatorEventFromIdl(const rover_dl_EstimatorEvent& in) {
  EstimatorEvent e;
  e.stamp = Time{in.header.stamp_ns};
  ROVER_ASSIGN_OR_RETURN(e.source, MotionSourceFromIdl(in.source, "dl/estimator_event: source"));
  e.accepted = in.accepted;
  e.mahalanobis_sq = in.mahalanobis_sq;
  e.gate = in.gate;
  e.message = idl::ReadString(in.message);
  return e;
}

void VoCommandToIdl(const VoCommand& in, rover_dl_VoCommand* out) {
  ROVER_DEMAND(!in.client.empty() && in.client.size() <= 63);
  out->header.stamp_ns = in.stamp.ns;
  idl::CopyString(out->client, in.client);
  out->imaging = in.imaging;
}

Result<VoCommand> VoCommandFromIdl(const rover_dl_VoCommand& in) {
  VoCommand c;
  c.stamp = Time{in.header.stamp_ns};
  c.client = in.client;
  if (c.client.empty()) return InvalidArgument("dl/vo_command: client is empty");
  c.imaging = in.imaging;
  return c;
}

}  // namespace rover::msg
