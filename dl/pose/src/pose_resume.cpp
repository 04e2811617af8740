#include "rover/dl/pose/pose_resume.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <vector>

namespace rover::dl::pose {
namespace {

constexpr int kSigmas = 6;

std::string Exact(const double* v, int n) {
  std::string out;
  for (int i = 0; i < n; ++i) {
    char b[40];
    std::snprintf(b, sizeof b, "%.17g", v[i]);
    if (i > 0) out += ' ';
    out += b;
  }
  return out;
}

// `n` finite numbers from the field `key`, or an error naming it.
Result<std::vector<double>> Numbers(const std::map<std::string, std::string>& fields,
                                    const std::string& key, int n) {
  const auto it = fields.find(key);
  if (it == fields.end()) return InvalidArgument("checkpoint: missing key '" + key + "'");
  std::istringstream in(it->second);
  std::vector<double> v;
  double x = 0;
  while (in >> x) v.push_back(x);
  const bool finite = std::all_of(v.begin(), v.end(), [](double d) { return std::isfinite(d); });
  if (!in.eof() || static_cast<int>(v.size()) != n || !finite) {
    return InvalidArgument("checkpoint: key '" + key + "' = '" + it->second +
                                   "': expected " + std::to_string(n) + " finite numbers");
  }
  return v;
}

void Add(const SavedFilter& s, const std::string& prefix, std::map<std::string, std::string>* out) {
  const double q[4] = {s.attitude.w(), s.attitude.x(), s.attitude.y(), s.attitude.z()};
  double sigma[kSigmas];
  for (int i = 0; i < 3; ++i) {
    sigma[i] = s.position_sigma[i];
    sigma[3 + i] = s.rpy_sigma[i];
  }
  (*out)[prefix + "stamp_ns"] = std::to_string(s.stamp.ns);
  (*out)[prefix + "position"] = Exact(s.position.data(), 3);
  (*out)[prefix + "attitude_wxyz"] = Exact(q, 4);
  (*out)[prefix + "sigma_xyz_rpy"] = Exact(sigma, kSigmas);
  (*out)[prefix + "gyro_bias"] = Exact(s.gyro_bias.data(), 3);
  (*out)[prefix + "odometer"] = Exact(&s.odometer, 1);
}

Result<SavedFilter> Read(const std::map<std::string, std::string>& f, const std::string& prefix) {
  ROVER_ASSIGN_OR_RETURN(const auto stamp, Numbers(f, prefix + "stamp_ns", 1));
  ROVER_ASSIGN_OR_RETURN(const auto pos, Numbers(f, prefix + "position", 3));
  ROVER_ASSIGN_OR_RETURN(const auto q, Numbers(f, prefix + "attitude_wxyz", 4));
  ROVER_ASSIGN_OR_RETURN(const auto sigma, Numbers(f, prefix + "sigma_xyz_rpy", kSigmas));
  ROVER_ASSIGN_OR_RETURN(const auto bias, Numbers(f, prefix + "gyro_bias", 3));
  ROVER_ASSIGN_OR_RETURN(const auto odo, Numbers(f, prefix + "odometer", 1));
  SavedFilter s;
  s.stamp = Time{static_cast<std::int64_t>(stamp[0])};
  s.position = {pos[0], pos[1], pos[2]};
  s.attitude = Eigen::Quaterniond(q[0], q[1], q[2], q[3]);
  if (!(std::abs(s.attitude.norm() - 1.0) < 1e-6)) {
    return InvalidArgument("checkpoint: key '" + prefix +
                                   "attitude_wxyz' is not a unit quaternion");
  }
  s.attitude.normalize();
  s.position_sigma = {sigma[0], sigma[1], sigma[2]};
  s.rpy_sigma = {sigma[3], sigma[4], sigma[5]};
  s.gyro_bias = {bias[0], bias[1], bias[2]};
  s.odometer = odo[0];
  return s;
}

}  // namespace

void PoseResumeOptions::BindParams(ParamBinder<PoseResumeOptions>& b) {
  b.Bind("enabled", &PoseResumeOptions::enabled,
         "in a supervised set, keep a checkpoint and resume from it after a restart (else a "
         "restarted dl-pose starts over at start.*)");
  b.Bind("checkpoint_period_s", &PoseResumeOptions::checkpoint_period_s, "s",
         "run time between checkpoints of the published estimate")
      .Range(0.01, 3600.0);
  b.Bind("max_age_s", &PoseResumeOptions::max_age_s, "s",
         "run time from the last checkpoint beyond which a restarted dl-pose does not resume but "
         "declares the pose unknown")
      .Range(0.0, 86400.0);
  b.Bind("max_speed", &PoseResumeOptions::max_speed, "m/s",
         "how fast the rover may have moved while dl-pose was down (position sigma inflation per "
         "second of the gap)")
      .Range(0.0, 10.0);
  b.BindScaled("max_yaw_rate_deg_s", &PoseResumeOptions::max_yaw_rate,
               3.14159265358979323846 / 180.0, "deg/s",
               "how fast it may have turned while dl-pose was down (heading sigma inflation)")
      .Range(0.0, 90.0);
}

SavedFilter SavedFilterOf(const PoseEstimate& e) {
  SavedFilter s;
  s.stamp = e.stamp;
  s.position = e.position;
  s.attitude = e.orientation;
  for (int i = 0; i < 3; ++i) {
    s.position_sigma[i] = std::sqrt(std::max(e.covariance(i, i), 0.0));
    s.rpy_sigma[i] = std::sqrt(std::max(e.covariance(3 + i, 3 + i), 0.0));
  }
  s.gyro_bias = e.gyro_bias;
  s.odometer = e.odometer;
  return s;
}

std::map<std::string, std::string> CheckpointFields(const PoseCheckpoint& c) {
  std::map<std::string, std::string> out;
  Add(c.main, "", &out);
  if (c.odometry_only) Add(*c.odometry_only, "odometry_only.", &out);
  return out;
}

Result<PoseCheckpoint> PoseCheckpointFromFields(const std::map<std::string, std::string>& f) {
  PoseCheckpoint c;
  ROVER_ASSIGN_OR_RETURN(c.main, Read(f, ""));
  auto odometry_only = Read(f, "odometry_only.");
  if (odometry_only.ok()) c.odometry_only = *odometry_only;
  return c;
}

EkfInitialState ResumedInitialState(const SavedFilter& s, Time t, const PoseResumeOptions& o,
                                    double gyro_bias_sigma) {
  const double gap = std::max(ToSeconds(t - s.stamp), 0.0);
  EkfInitialState init;
  init.stamp = t;
  init.position = s.position;
  init.attitude = s.attitude;
  init.gyro_bias = s.gyro_bias;
  init.odometer = s.odometer;
  const double grow_p = o.max_speed * gap;
  for (int i = 0; i < 3; ++i) init.position_sigma[i] = std::hypot(s.position_sigma[i], grow_p);
  init.rpy_sigma = s.rpy_sigma;
  init.rpy_sigma.z() = std::hypot(s.rpy_sigma.z(), o.max_yaw_rate * gap);
  init.gyro_bias_sigma = gyro_bias_sigma;
  return init;
}

}  // namespace rover::dl::pose
