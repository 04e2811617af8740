// dl-pose: binds PoseEkf and WheelOdometry to ddl/imu, ddl/joint_state, ddl/sun_sensor and
// dl/relative_pose; publishes dl/pose and dl/estimator_event. See pose_service.hpp and
// docs/services/dl-pose.md.
#include "pose_service.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <sstream>
#include <vector>

#include "rover/base/check.hpp"
#include "rover/base/log.hpp"
#include "rover/geometry/transforms.hpp"

namespace rover::dl {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
// [m/s^2] default of ekf.gravity: Mars, as the simulator's rover model (sim/physics).
constexpr double kMarsGravity = 3.711;
// A sample this much older than the filter means the run clock went back (simulator reset).
constexpr double kClockResetS = 1.0;

bool UsableHealth(rover_SensorHealth h) {
  return h == rover_HEALTH_OK || h == rover_HEALTH_DEGRADED;
}

Eigen::Vector3d Vec(const rover_Vector3& v) { return {v.x, v.y, v.z}; }
rover_Vector3 Vec(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

template <class A, std::size_t N>
void CopyArray(const double (&src)[N], A& dst) {
  for (std::size_t i = 0; i < N && i < dst.size(); ++i) dst[i] = src[i];
}

JointSample JointFromIdl(const rover_ddl_JointState& m) {
  JointSample j;
  j.stamp = Time{m.header.stamp_ns};
  CopyArray(m.wheel_angle, j.wheel_angle);
  CopyArray(m.wheel_rate, j.wheel_rate);
  CopyArray(m.steer_angle, j.steer_angle);
  CopyArray(m.rocker_angle, j.rocker_angle);
  CopyArray(m.bogie_angle, j.bogie_angle);
  j.healthy = UsableHealth(m.health);
  return j;
}

std::string Num(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

// Checkpoint values: exact round trip of doubles.
std::string Exact(double v) {
  char b[40];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}
std::string Exact(const double* v, int n) {
  std::string out;
  for (int i = 0; i < n; ++i) out += (i ? " " : "") + Exact(v[i]);
  return out;
}
// `n` finite numbers from `text`, or nullopt.
std::optional<std::vector<double>> Numbers(const std::string& text, int n) {
  std::istringstream in(text);
  std::vector<double> v;
  double x = 0;
  while (in >> x) v.push_back(x);
  if (!in.eof() || static_cast<int>(v.size()) != n) return std::nullopt;
  for (double d : v) {
    if (!std::isfinite(d)) return std::nullopt;
  }
  return v;
}

}  // namespace

// ---- conversions ------------------------------------------------------------------------------

rover_dl_PoseEstimate PoseEstimateToIdl(const PoseEstimate& e) {
  rover_dl_PoseEstimate m{};
  m.header.stamp_ns = e.stamp.ns;
  m.pose.position = Vec(e.position);
  m.pose.orientation = {e.orientation.w(), e.orientation.x(), e.orientation.y(), e.orientation.z()};
  for (int r = 0; r < 6; ++r) {
    for (int c = 0; c < 6; ++c) m.covariance[r * 6 + c] = e.covariance(r, c);
  }
  m.velocity = Vec(e.velocity);
  m.gyro_bias = Vec(e.gyro_bias);
  m.stationary = e.stationary;
  m.rejected_measurements = e.rejected_measurements;
  m.odometer = e.odometer;
  return m;
}

rover_dl_EstimatorEvent EstimatorEventToIdl(const EstimatorEvent& e) {
  rover_dl_EstimatorEvent m{};
  m.header.stamp_ns = e.stamp.ns;
  m.source = static_cast<rover_dl_MotionSource>(static_cast<std::int32_t>(e.source));
  m.accepted = e.accepted;
  m.mahalanobis_sq = e.mahalanobis_sq;
  m.gate = e.gate;
  dds::CopyString(m.message, e.message);
  return m;
}

Result<RelativePoseMeasurement> RelativePoseFromIdl(const rover_dl_RelativePose& m) {
  const auto source = static_cast<std::int32_t>(m.source);
  if (source < static_cast<std::int32_t>(MotionSource::kWheelOdometry) ||
      source > static_cast<std::int32_t>(MotionSource::kExternal)) {
    return InvalidArgument("dl/relative_pose: unknown source " + std::to_string(source));
  }
  RelativePoseMeasurement r;
  r.source = static_cast<MotionSource>(source);
  r.t_from = Time{m.t_from_ns};
  r.t_to = Time{m.t_to_ns};
  const rover_Quaternion& q = m.delta.orientation;
  Eigen::Quaterniond quat(q.w, q.x, q.y, q.z);
  const double norm = quat.norm();
  if (!(std::abs(norm - 1.0) <= 1e-6)) {  // also NaN
    return InvalidArgument("dl/relative_pose: delta orientation quaternion has norm " + Num(norm) +
                           " (must be 1)");
  }
  quat.normalize();  // rounding only
  r.delta = Eigen::Isometry3d::Identity();
  r.delta.linear() = quat.toRotationMatrix();
  r.delta.translation() = Vec(m.delta.position);
  r.covariance = Eigen::Map<const Eigen::Matrix<double, 6, 6, Eigen::RowMajor>>(m.covariance);
  return r;
}

Eigen::Vector2d LevelFromSpecificForce(const Eigen::Vector3d& f) {
  // At rest f = R^T (0, 0, g) = g (-sin pitch, sin roll cos pitch, cos roll cos pitch) for
  // R = Rz(yaw) Ry(pitch) Rx(roll) (rover/geometry/transforms.hpp).
  return {std::atan2(f.y(), f.z()), std::atan2(-f.x(), std::hypot(f.y(), f.z()))};
}

// ---- service ----------------------------------------------------------------------------------

void PoseService::DeclareParameters(ParamSet& p) {
  EkfOptions ekf_defaults;
  ekf_defaults.gravity = kMarsGravity;  // the rover is on Mars (and so is the simulated one)
  DeclareEkfParams(p, "ekf.", ekf_defaults);
  DeclareRoverGeometryParams(p, "geometry.");
  DeclareWheelOdometryParams(p, "odometry.");
  p.Declare("publish_rate_hz", 10.0, "[Hz] dl/pose rate (run clock)").Range(8.0, 200.0);
  p.Declare("imu_stale_s", 0.5, "[s] without ddl/imu before the heartbeat reports DEGRADED")
      .Range(0.01, 60.0);
  const StartOptions s;
  p.Declare("start.x", 0.0, "[m] start position, site x (north); the site origin is the start")
      .Range(-1e6, 1e6);
  p.Declare("start.y", 0.0, "[m] start position, site y (west)").Range(-1e6, 1e6);
  p.Declare("start.z", 0.0, "[m] start position, site z (up)").Range(-1e6, 1e6);
  p.Declare("start.yaw_deg", 0.0, "[deg] start heading, from site x (north) towards y (west)")
      .Range(-360.0, 360.0);
  p.Declare("start.position_sigma", s.position_sigma, "[m] initial 1-sigma of x, y, z")
      .Range(0.0, 1e4);
  p.Declare("start.tilt_sigma_deg", s.tilt_sigma / kDeg,
            "[deg] initial 1-sigma of the levelled roll and pitch")
      .Range(0.0, 90.0);
  p.Declare("start.yaw_sigma_deg", s.yaw_sigma / kDeg, "[deg] initial 1-sigma of the heading")
      .Range(0.0, 180.0);
  p.Declare("start.gyro_bias_sigma", s.gyro_bias_sigma, "[rad/s] initial 1-sigma of the gyro bias")
      .Range(0.0, 1.0);
  p.Declare("start.level_samples", s.level_samples,
            "stationary accelerometer samples averaged to level roll and pitch")
      .Range(1, 100000);
  p.Declare("start.level_timeout_s", s.level_timeout_s,
            "[s] start anyway (from all plausible samples) if no stationary stretch by then")
      .Range(0.0, 3600.0);
  p.Declare("start.estimate_gyro_bias", s.estimate_gyro_bias,
            "initial gyro bias = mean gyro rate over the levelling stretch (else 0)");
  // Same keys and defaults as the simulator's sensors.ephemeris.* (sim/sensors).
  const geometry::SunEphemerisOptions e;
  p.Declare("ephemeris.mode", "season",
            "'season': Ls and local true solar time at run start; 'date': J2000 TT days")
      .OneOf({"season", "date"});
  p.Declare("ephemeris.latitude_deg", e.latitude_deg, "[deg] landing-site latitude (+ north)")
      .Range(-90.0, 90.0);
  p.Declare("ephemeris.east_longitude_deg", e.east_longitude_deg,
            "[deg] landing-site east longitude (mode 'date')")
      .Range(-360.0, 360.0);
  p.Declare("ephemeris.ls_deg", e.ls_deg, "[deg] areocentric solar longitude at run start")
      .Range(0.0, 359.999999);
  p.Declare("ephemeris.ltst_hours", e.ltst_hours, "[h] local true solar time at run start")
      .Range(0.0, 23.999999);
  p.Declare("ephemeris.j2000_tt_days", e.j2000_tt_days,
            "[days] TT days since J2000 at run start (mode 'date')")
      .Range(-1.0e6, 1.0e6);
  p.Declare("ephemeris.run_start_s", 0.0,
            "[s] run-clock time of the run start (0 = sim/clock zero, as the simulator)")
      .Range(-1e11, 1e11);
  const ResumeOptions r;
  p.Declare("resume.enabled", r.enabled,
            "in a supervised set, keep a checkpoint and resume from it after a restart (else a "
            "restarted dl-pose starts over at start.*)");
  p.Declare("resume.checkpoint_period_s", r.checkpoint_period_s,
            "[s] run time between checkpoints of the published estimate")
      .Range(0.01, 3600.0);
  p.Declare("resume.max_age_s", r.max_age_s,
            "[s] run time from the last checkpoint beyond which a restarted dl-pose does not "
            "resume but declares the pose unknown")
      .Range(0.0, 86400.0);
  p.Declare("resume.max_speed", r.max_speed,
            "[m/s] how fast the rover may have moved while dl-pose was down (position sigma "
            "inflation per second of the gap)")
      .Range(0.0, 10.0);
  p.Declare("resume.max_yaw_rate_deg_s", r.max_yaw_rate / kDeg,
            "[deg/s] how fast it may have turned while dl-pose was down (heading sigma inflation)")
      .Range(0.0, 90.0);
  p.Declare("sun.enabled", true, "apply ddl/sun_sensor heading updates");
  p.Declare("odometry_only.enabled", true,
            "also run an IMU + wheel odometry filter (no sun, no visual odometry) and publish "
            "it on dl/pose_odometry, the dead-reckoning baseline");
  p.Declare("sun.min_elevation_deg", 0.0,
            "[deg] ignore sun samples when the ephemeris sun is lower than this")
      .Range(-90.0, 90.0);
  p.Declare("sun.max_rate_deg_s", 0.2,
            "[deg/s] ignore sun samples while the rover turns faster than this (a sample's "
            "latency times the turn rate would be a heading error; MER took sun images at rest)")
      .Range(0.0, 100.0);
}

Status PoseService::ValidateParameters(const ParamSet& p) const {
  auto ekf_options = EkfOptionsFromParams(p, "ekf.");
  if (!ekf_options.ok()) return ekf_options.status();
  auto geometry = RoverGeometryFromParams(p, "geometry.");
  if (!geometry.ok()) return geometry.status();
  auto odo_options = WheelOdometryOptionsFromParams(p, "odometry.");
  return odo_options.ok() ? Status::Ok() : odo_options.status();
}

Status PoseService::OnConfigure(ServiceContext& ctx, const ParamSet& p) {
  ctx_ = &ctx;
  auto ekf_options = EkfOptionsFromParams(p, "ekf.");
  if (!ekf_options.ok()) return ekf_options.status();
  ekf_options_ = *ekf_options;
  auto geometry = RoverGeometryFromParams(p, "geometry.");
  if (!geometry.ok()) return geometry.status();
  auto odo_options = WheelOdometryOptionsFromParams(p, "odometry.");
  if (!odo_options.ok()) return odo_options.status();
  auto odometry = WheelOdometry::Create(*geometry, *odo_options);
  if (!odometry.ok()) return odometry.status();
  odometry_.emplace(std::move(*odometry));
  auto ekf = PoseEkf::Create(ekf_options_);
  if (!ekf.ok()) return ekf.status();
  ekf_.emplace(std::move(*ekf));
  if (p.GetBool("odometry_only.enabled")) {
    auto reference = PoseEkf::Create(ekf_options_);
    if (!reference.ok()) return reference.status();
    odometry_only_.emplace(std::move(*reference));
  }

  start_.position = {p.GetDouble("start.x"), p.GetDouble("start.y"), p.GetDouble("start.z")};
  start_.yaw = p.GetDouble("start.yaw_deg") * kDeg;
  start_.position_sigma = p.GetDouble("start.position_sigma");
  start_.tilt_sigma = p.GetDouble("start.tilt_sigma_deg") * kDeg;
  start_.yaw_sigma = p.GetDouble("start.yaw_sigma_deg") * kDeg;
  start_.gyro_bias_sigma = p.GetDouble("start.gyro_bias_sigma");
  start_.level_samples = static_cast<int>(p.GetInt("start.level_samples"));
  start_.level_timeout_s = p.GetDouble("start.level_timeout_s");
  start_.estimate_gyro_bias = p.GetBool("start.estimate_gyro_bias");

  ephemeris_options_.mode = p.GetString("ephemeris.mode") == "date"
                                ? geometry::SunEphemerisOptions::Mode::kDate
                                : geometry::SunEphemerisOptions::Mode::kSeason;
  ephemeris_options_.latitude_deg = p.GetDouble("ephemeris.latitude_deg");
  ephemeris_options_.east_longitude_deg = p.GetDouble("ephemeris.east_longitude_deg");
  ephemeris_options_.ls_deg = p.GetDouble("ephemeris.ls_deg");
  ephemeris_options_.ltst_hours = p.GetDouble("ephemeris.ltst_hours");
  ephemeris_options_.j2000_tt_days = p.GetDouble("ephemeris.j2000_tt_days");
  ROVER_RETURN_IF_ERROR(ephemeris_options_.Validate());
  ephemeris_.emplace(ephemeris_options_);
  run_start_s_ = p.GetDouble("ephemeris.run_start_s");
  sun_enabled_ = p.GetBool("sun.enabled");
  sun_min_elevation_ = p.GetDouble("sun.min_elevation_deg") * kDeg;
  sun_max_rate_ = p.GetDouble("sun.max_rate_deg_s") * kDeg;
  imu_stale_s_ = p.GetDouble("imu_stale_s");
  resume_.enabled = p.GetBool("resume.enabled");
  resume_.checkpoint_period_s = p.GetDouble("resume.checkpoint_period_s");
  resume_.max_age_s = p.GetDouble("resume.max_age_s");
  resume_.max_speed = p.GetDouble("resume.max_speed");
  resume_.max_yaw_rate = p.GetDouble("resume.max_yaw_rate_deg_s") * kDeg;
  if (resume_.enabled) checkpoints_ = CheckpointStore::FromEnvironment(ctx.name());
  LoadCheckpoint();

  auto pw = ctx.MakeWriter<rover_dl_PoseEstimate>("dl/pose");
  if (!pw.ok()) return pw.status();
  pose_writer_ = std::move(*pw);
  auto ew = ctx.MakeWriter<rover_dl_EstimatorEvent>("dl/estimator_event");
  if (!ew.ok()) return ew.status();
  event_writer_ = std::move(*ew);
  if (odometry_only_) {
    auto ow = ctx.MakeWriter<rover_dl_PoseEstimate>("dl/pose_odometry");
    if (!ow.ok()) return ow.status();
    odometry_only_writer_ = std::move(*ow);
  }

  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_ddl_Imu>(
      "ddl/imu", [this](const dds::Sample<rover_ddl_Imu>& s) { OnImu(s.data()); }));
  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_ddl_JointState>(
      "ddl/joint_state",
      [this](const dds::Sample<rover_ddl_JointState>& s) { OnJointState(s.data()); }));
  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_ddl_SunSensor>(
      "ddl/sun_sensor",
      [this](const dds::Sample<rover_ddl_SunSensor>& s) { OnSunSensor(s.data()); }));
  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_dl_RelativePose>(
      "dl/relative_pose",
      [this](const dds::Sample<rover_dl_RelativePose>& s) { OnRelativePose(s.data()); }));
  ctx.executor().AddTimer(Seconds(1.0 / p.GetDouble("publish_rate_hz")), [this] { OnTimer(); });
  if (uninitialised_) {
    ctx.SetHealth(rover_HEALTH_FAILED, *uninitialised_);
  } else {
    ctx.SetHealth(rover_HEALTH_DEGRADED, saved_ ? "restarted: resuming from checkpoint"
                                                : "levelling: waiting for stationary ddl/imu samples");
  }
  return Status::Ok();
}

void PoseService::WarnCounted(const std::string& what, const std::string& detail) {
  const std::uint64_t n = ++warn_counts_[what];
  std::uint64_t p = 1;
  while (p < n) p *= 10;
  if (p == n) log::Warn(what, {{"count", n}, {"detail", detail}});
}

void PoseService::Restart(const std::string& why) {
  log::Info("pose estimator restarted", {{"reason", why}});
  auto ekf = PoseEkf::Create(ekf_options_);
  ROVER_DEMAND(ekf.ok());  // the options were valid at configuration
  ekf_.emplace(std::move(*ekf));
  if (odometry_only_) {
    auto reference = PoseEkf::Create(ekf_options_);
    ROVER_DEMAND(reference.ok());
    odometry_only_.emplace(std::move(*reference));
  }
  odometry_->Reset();
  levelling_ = Levelling{};
}

// ---- inputs -----------------------------------------------------------------------------------

void PoseService::OnImu(const rover_ddl_Imu& m) {
  if (!UsableHealth(m.health)) {
    WarnCounted("ddl/imu sample dropped: health FAILED or STALE", "");
    return;
  }
  const Time t{m.header.stamp_ns};
  const Eigen::Vector3d w = Vec(m.angular_velocity);
  const Eigen::Vector3d f = Vec(m.linear_acceleration);
  if (!w.allFinite() || !f.allFinite()) {
    WarnCounted("ddl/imu sample dropped: non-finite value", "");
    return;
  }
  if (ekf_->initialized() && ToSeconds(ekf_->time() - t) > kClockResetS) {
    Restart("ddl/imu stamp " + Num(t.seconds()) + " s is before the filter time " +
            Num(ekf_->time().seconds()) + " s (run clock reset)");
  }
  if (uninitialised_) return;  // the pose is unknown: nothing to propagate
  if (!ekf_->initialized() && saved_ && !ResumeOrRefuse(t)) return;
  if (!ekf_->initialized()) {
    Level(t, w, f);
    return;
  }
  const Status s = ekf_->PropagateGyro(t, w);
  if (!s.ok()) {
    WarnCounted("ddl/imu sample dropped", s.message());
    return;
  }
  last_rate_ = (w - ekf_->gyro_bias()).norm();
  const Status a = ekf_->UpdateAccelerometer(t, f);
  if (!a.ok()) WarnCounted("accelerometer update failed", a.message());
  if (odometry_only_ && odometry_only_->initialized() && odometry_only_->PropagateGyro(t, w).ok()) {
    (void)odometry_only_->UpdateAccelerometer(t, f);
    (void)odometry_only_->TakeEvents();  // its events are not published
  }
  PublishEvents();
}

void PoseService::Level(Time t, const Eigen::Vector3d& w, const Eigen::Vector3d& f) {
  Levelling& l = levelling_;
  if (!l.first.has_value()) l.first = t;
  const bool plausible =
      std::abs(f.norm() - ekf_options_.gravity) <= ekf_options_.accel_magnitude_tolerance;
  const bool still = plausible && w.norm() <= ekf_options_.stationary_gyro_threshold;
  if (plausible) {
    l.f_all += f;
    ++l.count_all;
  }
  if (still) {
    if (l.count == 0) l.still_since = t;
    l.f_sum += f;
    l.w_sum += w;
    ++l.count;
  } else {
    l.f_sum.setZero();
    l.w_sum.setZero();
    l.count = 0;
  }
  if (l.count >= start_.level_samples) {
    const double n = static_cast<double>(l.count);
    const double span = ToSeconds(t - l.still_since);
    Start(t, l.f_sum / n,
          start_.estimate_gyro_bias ? Eigen::Vector3d(l.w_sum / n) : Eigen::Vector3d::Zero(),
          start_.estimate_gyro_bias ? span : 0.0, "levelled at rest");
  } else if (ToSeconds(t - *l.first) >= start_.level_timeout_s) {
    const Eigen::Vector3d mean = l.count_all > 0
                                     ? Eigen::Vector3d(l.f_all / static_cast<double>(l.count_all))
                                     : Eigen::Vector3d(0.0, 0.0, ekf_options_.gravity);
    log::Warn("no stationary stretch to level on; starting from the mean accelerometer sample",
              {{"samples", l.count_all}, {"waited_s", ToSeconds(t - *l.first)}});
    Start(t, mean, Eigen::Vector3d::Zero(), 0.0, "not levelled at rest");
  }
}

void PoseService::Start(Time t, const Eigen::Vector3d& f_mean, const Eigen::Vector3d& bias,
                        double bias_span_s, const char* how) {
  const Eigen::Vector2d rp = LevelFromSpecificForce(f_mean);
  EkfInitialState init;
  init.stamp = t;
  init.position = start_.position;
  init.attitude = geometry::QuaternionFromRpy(rp.x(), rp.y(), start_.yaw);
  init.gyro_bias = bias;
  init.position_sigma = Eigen::Vector3d::Constant(start_.position_sigma);
  init.rpy_sigma = Eigen::Vector3d(start_.tilt_sigma, start_.tilt_sigma, start_.yaw_sigma);
  init.gyro_bias_sigma = start_.gyro_bias_sigma;
  if (bias_span_s > 0.0) {
    init.gyro_bias_sigma = std::min(
        start_.gyro_bias_sigma,
        std::max(ekf_options_.gyro_noise_density / std::sqrt(bias_span_s), 1e-7));
  }
  const Status s = ekf_->Initialize(init);
  if (!s.ok()) {
    WarnCounted("pose estimator could not start", s.message());
    levelling_ = Levelling{};
    return;
  }
  if (odometry_only_) {
    const Status r = odometry_only_->Initialize(init);
    ROVER_DEMAND(r.ok());  // the same initial state was just accepted by ekf_
  }
  log::Info("pose estimator started", {{"how", how},
                                       {"t_s", t.seconds()},
                                       {"roll_deg", rp.x() / kDeg},
                                       {"pitch_deg", rp.y() / kDeg},
                                       {"yaw_deg", start_.yaw / kDeg},
                                       {"gyro_bias_z", bias.z()},
                                       {"gyro_bias_sigma", init.gyro_bias_sigma}});
  levelling_ = Levelling{};
}

void PoseService::OnJointState(const rover_ddl_JointState& m) {
  const JointSample j = JointFromIdl(m);
  if (!j.healthy) {
    WarnCounted("ddl/joint_state sample dropped: health FAILED or STALE", "");
    return;
  }
  auto inc = odometry_->Add(j);
  if (!inc.ok()) {
    WarnCounted("ddl/joint_state sample rejected by wheel odometry", inc.status().message());
    return;
  }
  if (!ekf_->initialized() || !inc->has_value()) return;
  const Status s = ekf_->AddWheelOdometry(**inc);
  if (!s.ok()) WarnCounted("wheel odometry increment rejected", s.message());
  if (odometry_only_ && odometry_only_->initialized()) {
    (void)odometry_only_->AddWheelOdometry(**inc);
  }
}

void PoseService::OnSunSensor(const rover_ddl_SunSensor& m) {
  if (!sun_enabled_ || !m.valid || !UsableHealth(m.health) || !ekf_->initialized()) return;
  const Time t{m.header.stamp_ns};
  const geometry::SunState sun = ephemeris_->At(t.seconds() - run_start_s_);
  if (sun.elevation_rad < sun_min_elevation_) return;
  if (last_rate_ > sun_max_rate_) return;  // turning: wait for a steadier sample
  const Status s = ekf_->UpdateSunSensor(t, Vec(m.sun_vector), sun.direction_site);
  if (!s.ok()) {
    WarnCounted("ddl/sun_sensor sample rejected", s.message());
    return;
  }
  PublishEvents();
}

void PoseService::OnRelativePose(const rover_dl_RelativePose& m) {
  if (m.status != rover_dl_RELPOSE_CONVERGED) return;  // not a measurement
  auto r = RelativePoseFromIdl(m);
  if (!r.ok()) {
    const auto source = static_cast<std::int32_t>(m.source);
    const bool known = source >= 0 && source <= static_cast<std::int32_t>(MotionSource::kExternal);
    PublishRejectedInput(known ? static_cast<MotionSource>(source) : MotionSource::kExternal,
                         Time{m.t_to_ns}, r.status().message());
    return;
  }
  const Status s = ekf_->AddRelativePose(*r);
  if (!s.ok()) {
    PublishRejectedInput(r->source, r->t_to, s.message());
    return;
  }
  PublishEvents();
}

// ---- outputs ----------------------------------------------------------------------------------

void PoseService::PublishEvents() {
  for (const EstimatorEvent& e : ekf_->TakeEvents()) {
    rover_dl_EstimatorEvent m = EstimatorEventToIdl(e);
    ctx_->Stamp(m.header, "site");
    m.header.stamp_ns = e.stamp.ns;
    const Status s = event_writer_.Write(m);
    if (!s.ok()) WarnCounted("dl/estimator_event write failed", s.message());
  }
}

void PoseService::PublishRejectedInput(MotionSource source, Time t, const std::string& message) {
  WarnCounted("relative pose rejected as bad input", message);
  EstimatorEvent e;
  e.stamp = t;
  e.source = source;
  e.accepted = false;
  e.mahalanobis_sq = std::numeric_limits<double>::quiet_NaN();
  e.gate = 0.0;
  e.message = "relative pose rejected: " + message;
  rover_dl_EstimatorEvent m = EstimatorEventToIdl(e);
  ctx_->Stamp(m.header, "site");
  m.header.stamp_ns = t.ns;
  const Status s = event_writer_.Write(m);
  if (!s.ok()) WarnCounted("dl/estimator_event write failed", s.message());
}

void PoseService::OnTimer() {
  if (uninitialised_) {
    ctx_->SetHealth(rover_HEALTH_FAILED, *uninitialised_);
    return;
  }
  if (!ekf_->initialized()) {
    ctx_->SetHealth(rover_HEALTH_DEGRADED, "levelling: waiting for stationary ddl/imu samples");
    return;
  }
  rover_dl_PoseEstimate m = PoseEstimateToIdl(ekf_->Estimate());
  ctx_->Stamp(m.header, "site");
  m.header.stamp_ns = ekf_->time().ns;  // the filter's time of validity
  const Status s = pose_writer_.Write(m);
  if (!s.ok()) WarnCounted("dl/pose write failed", s.message());
  if (odometry_only_ && odometry_only_->initialized()) {
    rover_dl_PoseEstimate o = PoseEstimateToIdl(odometry_only_->Estimate());
    ctx_->Stamp(o.header, "site");
    o.header.stamp_ns = odometry_only_->time().ns;
    const Status w = odometry_only_writer_.Write(o);
    if (!w.ok()) WarnCounted("dl/pose_odometry write failed", w.message());
  }
  if (!last_checkpoint_ || ekf_->time() < *last_checkpoint_ ||
      ToSeconds(ekf_->time() - *last_checkpoint_) >= resume_.checkpoint_period_s) {
    SaveCheckpoint();
  }
  const double age = ToSeconds(ctx_->Now() - ekf_->time());
  if (age > imu_stale_s_) {
    ctx_->SetHealth(rover_HEALTH_DEGRADED, "no ddl/imu for " + Num(age) + " s");
  } else {
    ctx_->SetHealth(rover_HEALTH_OK, "");
  }
}

// ---- restart: checkpoint, resume or refuse ------------------------------------------------------

namespace {

// Keys of one filter's checkpoint under `prefix` ("" for dl/pose, "odometry_only." for the other).
void AddSaved(const PoseEstimate& e, const std::string& prefix,
              std::map<std::string, std::string>* out) {
  const double q[4] = {e.orientation.w(), e.orientation.x(), e.orientation.y(),
                       e.orientation.z()};
  double sigma[6];
  for (int i = 0; i < 6; ++i) sigma[i] = std::sqrt(std::max(e.covariance(i, i), 0.0));
  (*out)[prefix + "stamp_ns"] = std::to_string(e.stamp.ns);
  (*out)[prefix + "position"] = Exact(e.position.data(), 3);
  (*out)[prefix + "attitude_wxyz"] = Exact(q, 4);
  (*out)[prefix + "sigma_xyz_rpy"] = Exact(sigma, 6);
  (*out)[prefix + "gyro_bias"] = Exact(e.gyro_bias.data(), 3);
  (*out)[prefix + "odometer"] = Exact(e.odometer);
}

}  // namespace

void PoseService::SaveCheckpoint() {
  if (!checkpoints_.enabled()) return;
  std::map<std::string, std::string> fields;
  AddSaved(ekf_->Estimate(), "", &fields);
  if (odometry_only_ && odometry_only_->initialized()) {
    AddSaved(odometry_only_->Estimate(), "odometry_only.", &fields);
  }
  const Status s = checkpoints_.Save(fields);
  if (!s.ok()) WarnCounted("checkpoint not written", s.message());
  last_checkpoint_ = ekf_->time();
}

void PoseService::LoadCheckpoint() {
  saved_.reset();
  saved_odometry_only_.reset();
  uninitialised_.reset();
  auto loaded = checkpoints_.Load();
  if (!loaded.ok()) {
    uninitialised_ = "pose unknown after restart: " + loaded.status().message();
    log::Error("checkpoint unreadable: pose unknown", {{"reason", loaded.status().message()}});
    return;
  }
  if (!loaded->has_value()) return;  // a first start in this set
  const auto& f = **loaded;
  auto read = [&](const std::string& prefix) -> std::optional<Saved> {
    auto get = [&](const char* key, int n) -> std::optional<std::vector<double>> {
      const auto it = f.find(prefix + key);
      return it == f.end() ? std::nullopt : Numbers(it->second, n);
    };
    const auto stamp = get("stamp_ns", 1);
    const auto pos = get("position", 3);
    const auto q = get("attitude_wxyz", 4);
    const auto sigma = get("sigma_xyz_rpy", 6);
    const auto bias = get("gyro_bias", 3);
    const auto odo = get("odometer", 1);
    if (!stamp || !pos || !q || !sigma || !bias || !odo) return std::nullopt;
    Saved s;
    s.stamp = Time{static_cast<std::int64_t>((*stamp)[0])};
    s.position = {(*pos)[0], (*pos)[1], (*pos)[2]};
    s.attitude = Eigen::Quaterniond((*q)[0], (*q)[1], (*q)[2], (*q)[3]);
    if (!(std::abs(s.attitude.norm() - 1.0) < 1e-6)) return std::nullopt;
    s.attitude.normalize();
    s.position_sigma = {(*sigma)[0], (*sigma)[1], (*sigma)[2]};
    s.rpy_sigma = {(*sigma)[3], (*sigma)[4], (*sigma)[5]};
    s.gyro_bias = {(*bias)[0], (*bias)[1], (*bias)[2]};
    s.odometer = (*odo)[0];
    return s;
  };
  saved_ = read("");
  if (!saved_) {
    uninitialised_ = "pose unknown after restart: checkpoint " + checkpoints_.path() +
                     " has no complete estimate";
    log::Error("checkpoint incomplete: pose unknown", {{"path", checkpoints_.path()}});
    return;
  }
  if (odometry_only_) saved_odometry_only_ = read("odometry_only.");
  log::Info("restarted: checkpoint found", {{"path", checkpoints_.path()},
                                            {"t_s", saved_->stamp.seconds()}});
}

bool PoseService::ResumeOrRefuse(Time t) {
  const Saved saved = *saved_;
  saved_.reset();
  const double gap = ToSeconds(t - saved.stamp);
  if (gap < -kClockResetS) {
    // The run clock is behind the checkpoint: a new run (simulator reset), not a restart.
    log::Info("checkpoint is from a later run time: starting afresh",
              {{"checkpoint_t_s", saved.stamp.seconds()}, {"t_s", t.seconds()}});
    saved_odometry_only_.reset();
    return true;
  }
  if (gap > resume_.max_age_s) {
    uninitialised_ = "pose unknown after restart: the last checkpoint (t = " +
                     Num(saved.stamp.seconds()) + " s) is " + Num(gap) +
                     " s old, more than resume.max_age_s " + Num(resume_.max_age_s) + " s";
    log::Error("restarted without a usable checkpoint: pose unknown, dl/pose not published",
               {{"reason", *uninitialised_}});
    ctx_->SetHealth(rover_HEALTH_FAILED, *uninitialised_);
    return false;
  }
  const double g = std::max(gap, 0.0);
  auto init_from = [&](const Saved& s) {
    EkfInitialState init;
    init.stamp = t;
    init.position = s.position;
    init.attitude = s.attitude;
    init.gyro_bias = s.gyro_bias;
    init.odometer = s.odometer;
    const double grow_p = resume_.max_speed * g;
    for (int i = 0; i < 3; ++i) init.position_sigma[i] = std::hypot(s.position_sigma[i], grow_p);
    init.rpy_sigma = s.rpy_sigma;
    init.rpy_sigma.z() = std::hypot(s.rpy_sigma.z(), resume_.max_yaw_rate * g);
    init.gyro_bias_sigma = start_.gyro_bias_sigma;
    return init;
  };
  const Status s = ekf_->Initialize(init_from(saved));
  if (!s.ok()) {
    uninitialised_ = "pose unknown after restart: checkpoint rejected: " + s.message();
    ctx_->SetHealth(rover_HEALTH_FAILED, *uninitialised_);
    return false;
  }
  if (odometry_only_) {
    // Without its own checkpoint the baseline resumes from dl/pose's.
    const Status r = odometry_only_->Initialize(init_from(saved_odometry_only_.value_or(saved)));
    ROVER_DEMAND(r.ok());
  }
  saved_odometry_only_.reset();
  levelling_ = Levelling{};
  log::Info("pose estimator resumed from checkpoint",
            {{"checkpoint_t_s", saved.stamp.seconds()}, {"t_s", t.seconds()}, {"gap_s", gap}});
  ctx_->SetHealth(rover_HEALTH_OK, "");
  return true;
}

}  // namespace rover::dl
