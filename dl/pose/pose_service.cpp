// dl-pose: binds PoseEkf and WheelOdometry to ddl/imu, ddl/joint_state, ddl/sun_sensor and
// dl/relative_pose; publishes dl/pose and dl/estimator_event. See pose_service.hpp and
// docs/services/dl-pose.md.
#include "pose_service.hpp"

#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

#include "rover/base/check.hpp"
#include "rover/base/log.hpp"
#include "rover/geometry/transforms.hpp"
#include "rover/msg/pose_idl.hpp"
#include "rover/msg/sensors_idl.hpp"

namespace rover::dl {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
// [m/s^2] default of ekf.gravity: Mars, as the simulator's rover model (sim/physics).
constexpr double kMarsGravity = 3.711;
// A sample this much older than the filter means the run clock went back (simulator reset).
constexpr double kClockResetS = 1.0;

std::string Num(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

}  // namespace

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
  ctx.SetHealth(rover_HEALTH_DEGRADED, "levelling: waiting for stationary ddl/imu samples");
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
  const auto imu = msg::ImuFromIdl(m);
  if (!imu.ok() || !msg::IsUsable(imu->health)) {
    WarnCounted("ddl/imu sample dropped: health FAILED or STALE", "");
    return;
  }
  const Time t = imu->stamp;
  const Eigen::Vector3d& w = imu->angular_velocity;
  const Eigen::Vector3d& f = imu->linear_acceleration;
  if (!w.allFinite() || !f.allFinite()) {
    WarnCounted("ddl/imu sample dropped: non-finite value", "");
    return;
  }
  if (ekf_->initialized() && ToSeconds(ekf_->time() - t) > kClockResetS) {
    Restart("ddl/imu stamp " + Num(t.seconds()) + " s is before the filter time " +
            Num(ekf_->time().seconds()) + " s (run clock reset)");
  }
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
  const auto j = msg::JointStateFromIdl(m);
  if (!j.ok() || !msg::IsUsable(j->health)) {
    WarnCounted("ddl/joint_state sample dropped: health FAILED or STALE", "");
    return;
  }
  auto inc = odometry_->Add(*j);
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
  const auto sample = msg::SunSensorFromIdl(m);
  if (!sun_enabled_ || !sample.ok() || !sample->valid || !msg::IsUsable(sample->health) ||
      !ekf_->initialized()) {
    return;
  }
  const Time t = sample->stamp;
  const geometry::SunState sun = ephemeris_->At(t.seconds() - run_start_s_);
  if (sun.elevation_rad < sun_min_elevation_) return;
  if (last_rate_ > sun_max_rate_) return;  // turning: wait for a steadier sample
  const Status s = ekf_->UpdateSunSensor(t, sample->sun_vector, sun.direction_site);
  if (!s.ok()) {
    WarnCounted("ddl/sun_sensor sample rejected", s.message());
    return;
  }
  PublishEvents();
}

void PoseService::OnRelativePose(const rover_dl_RelativePose& m) {
  if (m.status != rover_dl_RELPOSE_CONVERGED) return;  // not a measurement
  auto r = msg::RelativePoseFromIdl(m);
  if (!r.ok()) {
    const auto source = msg::MotionSourceFromIdl(m.source);
    PublishRejectedInput(source.ok() ? *source : MotionSource::kExternal, Time{m.t_to_ns},
                         r.status().message());
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
    rover_dl_EstimatorEvent m{};
    ctx_->Stamp(m.header, "site");
    msg::EstimatorEventToIdl(e, &m);
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
  rover_dl_EstimatorEvent m{};
  ctx_->Stamp(m.header, "site");
  msg::EstimatorEventToIdl(e, &m);
  const Status s = event_writer_.Write(m);
  if (!s.ok()) WarnCounted("dl/estimator_event write failed", s.message());
}

void PoseService::OnTimer() {
  if (!ekf_->initialized()) {
    ctx_->SetHealth(rover_HEALTH_DEGRADED, "levelling: waiting for stationary ddl/imu samples");
    return;
  }
  rover_dl_PoseEstimate m{};
  ctx_->Stamp(m.header, "site");
  msg::PoseEstimateToIdl(ekf_->Estimate(), &m);  // stamp = the filter's time of validity
  const Status s = pose_writer_.Write(m);
  if (!s.ok()) WarnCounted("dl/pose write failed", s.message());
  if (odometry_only_ && odometry_only_->initialized()) {
    rover_dl_PoseEstimate o{};
    ctx_->Stamp(o.header, "site");
    msg::PoseEstimateToIdl(odometry_only_->Estimate(), &o);
    const Status w = odometry_only_writer_.Write(o);
    if (!w.ok()) WarnCounted("dl/pose_odometry write failed", w.message());
  }
  const double age = ToSeconds(ctx_->Now() - ekf_->time());
  if (age > imu_stale_s_) {
    ctx_->SetHealth(rover_HEALTH_DEGRADED, "no ddl/imu for " + Num(age) + " s");
  } else {
    ctx_->SetHealth(rover_HEALTH_OK, "");
  }
}

}  // namespace rover::dl
