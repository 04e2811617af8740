#include "rover/dl/pose/pose_ekf.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "rover/base/units.hpp"
#include "rover/dl/pose/chi_square.hpp"
#include "rover/geometry/transforms.hpp"

namespace rover::dl::pose {

using locomotion::OdometryIncrement;

namespace {

using geometry::ExpSo3;
using geometry::LogSo3;
using geometry::RotationFromRpy;
using geometry::RpyFromRotation;
Eigen::Matrix3d RotZ(double a) {
  return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ()).toRotationMatrix();
}

struct Segment {
  double duration;  // [s]
  double speed;     // [m/s] along rover x
  double yaw_rate;  // [rad/s] about rover z
};

// Noise and error sources of a simulated run. The filter gets the matching options (consistent
// models), except where a test injects an unmodelled error.
struct SimConfig {
  double dt = 0.02;        // gyro period
  int odo_every = 5;       // 10 Hz odometry
  int sun_every = 50;      // 1 Hz sun sensor (0: none)
  int accel_every = 25;    // 2 Hz accelerometer when at rest
  double sun_start_s = 0;  // no sun before this time
  Eigen::Matrix3d plane = RotationFromRpy(4 * kDegree, -3 * kDegree, 0.0);  // terrain tilt
  double initial_yaw = 30 * kDegree;
  Eigen::Vector3d sun_site =
      Eigen::Vector3d(std::cos(35 * kDegree) * std::cos(120 * kDegree),
                      std::cos(35 * kDegree) * std::sin(120 * kDegree), std::sin(35 * kDegree));
  // Odometry noise model (WheelOdometry's), per metre of mean wheel path.
  double along = 1e-3, cross = 1e-3, yaw = 3e-4;
  double turn_radius = 0.7;     // mean wheel radius of a turn in place [m]
  double odometry_scale = 1.0;  // true distance / odometry distance (unmodelled slip if != 1)
  // Visual odometry.
  double vo_every_s = 0.0;  // 0: none
  double vo_delay_s = 0.5;  // delivered this long after t_to
  double vo_sigma_p = 0.01, vo_sigma_th = 0.5 * kDegree;
  // Truth initialisation.
  bool draw_initial_errors = true;
  Eigen::Vector3d true_bias = Eigen::Vector3d::Constant(std::nan(""));  // NaN: drawn from prior
};

struct Truth {
  double t;
  Eigen::Vector3d p;
  Eigen::Matrix3d R;
  Eigen::Vector3d b;
};

class Simulation {
 public:
  Simulation(std::uint64_t seed, const EkfOptions& options, const SimConfig& config,
             const EkfInitialState& init_sigmas = EkfInitialState())
      : rng_(seed), opt_(options), cfg_(config), ekf_(PoseEkf::Create(options).value()) {
    truth_.t = 0.0;
    truth_.p.setZero();
    truth_.R = cfg_.plane * RotZ(cfg_.initial_yaw);
    if (cfg_.true_bias.allFinite()) {
      truth_.b = cfg_.true_bias;
    } else {
      truth_.b = init_sigmas.gyro_bias_sigma * Normal3();
    }
    EkfInitialState init = init_sigmas;
    init.stamp = Time{0};
    init.position = truth_.p;
    Eigen::Matrix3d r_est = truth_.R;
    if (cfg_.draw_initial_errors) {
      init.position += init_sigmas.position_sigma.cwiseProduct(Normal3());
      // Attitude error drawn with the same rpy-sigma model the filter is given.
      const Eigen::Vector3d rpy = RpyFromRotation(truth_.R);
      const Eigen::Vector3d drpy = init_sigmas.rpy_sigma.cwiseProduct(Normal3());
      r_est = RotationFromRpy(rpy + drpy);
    }
    init.attitude = Eigen::Quaterniond(r_est);
    init.gyro_bias.setZero();
    EXPECT_TRUE(ekf_.Initialize(init).ok());
    history_.push_back(truth_);
    last_odo_ = truth_;
    last_vo_ = truth_;
  }

  PoseEkf& ekf() { return ekf_; }
  const PoseEkf& ekf() const { return ekf_; }
  const Truth& truth() const { return truth_; }

  // Error state (dp, dth, db) of the filter with respect to the truth.
  Eigen::Matrix<double, 9, 1> Error() const {
    Eigen::Matrix<double, 9, 1> e;
    e.segment<3>(0) = truth_.p - ekf_.position();
    e.segment<3>(3) = LogSo3(truth_.R * ekf_.rotation().transpose());
    e.segment<3>(6) = truth_.b - ekf_.gyro_bias();
    return e;
  }
  double Nees() const {
    const Eigen::Matrix<double, 9, 1> e = Error();
    return e.dot(ekf_.covariance().ldlt().solve(e));
  }
  double HeadingError() const {
    return std::remainder(RpyFromRotation(truth_.R).z() - RpyFromRotation(ekf_.rotation()).z(),
                          2 * std::numbers::pi);
  }

  // Runs the segments; calls `check(*this)` after every step.
  template <class F>
  void Run(const std::vector<Segment>& segments, F&& check) {
    for (const Segment& seg : segments) {
      const int steps = static_cast<int>(std::lround(seg.duration / cfg_.dt));
      for (int n = 0; n < steps; ++n) {
        StepOnce(seg);
        check(*this);
      }
    }
  }
  void Run(const std::vector<Segment>& segments) {
    Run(segments, [](const Simulation&) {});
  }

  int vo_sent = 0;
  std::vector<EstimatorEvent> events;

 private:
  Eigen::Vector3d Normal3() { return Eigen::Vector3d(n01_(rng_), n01_(rng_), n01_(rng_)); }

  void StepOnce(const Segment& seg) {
    const double dt = cfg_.dt;
    ++k_;
    // Truth: constant body twist (v, 0, 0; 0, 0, w) over the step, on the tilted plane.
    const double w = seg.yaw_rate;
    const double a = w * dt;
    const double sinc = std::abs(a) < 1e-9 ? 1.0 : std::sin(a) / a;
    const double cosc = std::abs(a) < 1e-9 ? 0.0 : (1 - std::cos(a)) / a;
    const Eigen::Vector3d d_body(seg.speed * dt * sinc, seg.speed * dt * cosc, 0.0);
    const Eigen::Vector3d gyro =
        Eigen::Vector3d(0, 0, w) + truth_.b + opt_.gyro_noise_density / std::sqrt(dt) * Normal3();
    truth_.p += truth_.R * d_body;
    truth_.R = truth_.R * RotZ(a);
    truth_.b += opt_.gyro_bias_walk * std::sqrt(dt) * Normal3();
    truth_.t = k_ * dt;
    history_.push_back(truth_);
    const Time now = Time::FromSeconds(truth_.t);
    EXPECT_TRUE(ekf_.PropagateGyro(now, gyro).ok());

    path_ += (std::abs(seg.speed) + cfg_.turn_radius * std::abs(w)) * dt;
    if (k_ % cfg_.odo_every == 0) {
      OdometryIncrement inc;
      inc.t_from = Time::FromSeconds(last_odo_.t);
      inc.t_to = now;
      const Eigen::Vector3d d = last_odo_.R.transpose() * (truth_.p - last_odo_.p);
      const Eigen::Matrix3d dr = last_odo_.R.transpose() * truth_.R;
      const double s = path_ / cfg_.odometry_scale;
      Eigen::Vector2d e(d.x(), d.y());
      e = e.norm() > 1e-9 ? Eigen::Vector2d(e.normalized()) : Eigen::Vector2d::UnitX();
      const Eigen::Vector2d ep(-e.y(), e.x());
      inc.covariance.setZero();
      inc.covariance.topLeftCorner<2, 2>() =
          s * (cfg_.along * e * e.transpose() + cfg_.cross * ep * ep.transpose());
      inc.covariance(2, 2) = s * cfg_.yaw;
      const Eigen::Vector2d nxy =
          std::sqrt(s * cfg_.along) * n01_(rng_) * e + std::sqrt(s * cfg_.cross) * n01_(rng_) * ep;
      inc.dx = d.x() / cfg_.odometry_scale + nxy.x();
      inc.dy = d.y() / cfg_.odometry_scale + nxy.y();
      inc.dyaw = std::atan2(dr(1, 0), dr(0, 0)) + std::sqrt(s * cfg_.yaw) * n01_(rng_);
      inc.path_length = s;
      EXPECT_TRUE(ekf_.AddWheelOdometry(inc).ok());
      last_odo_ = truth_;
      path_ = 0.0;
    }
    if (cfg_.sun_every > 0 && k_ % cfg_.sun_every == 0 && truth_.t >= cfg_.sun_start_s) {
      const Eigen::Vector3d s = truth_.R.transpose() * cfg_.sun_site;
      const Eigen::Vector3d e1 = s.cross(Eigen::Vector3d::UnitX()).normalized();
      const Eigen::Vector3d e2 = s.cross(e1);
      const Eigen::Vector3d meas =
          (s + opt_.sun_noise * (n01_(rng_) * e1 + n01_(rng_) * e2)).normalized();
      EXPECT_TRUE(ekf_.UpdateSunSensor(now, meas, cfg_.sun_site).ok());
    }
    if (k_ % cfg_.accel_every == 0 && seg.speed == 0.0 && seg.yaw_rate == 0.0) {
      const Eigen::Vector3d f =
          truth_.R.transpose() * Eigen::Vector3d(0, 0, opt_.gravity) + opt_.accel_noise * Normal3();
      EXPECT_TRUE(ekf_.UpdateAccelerometer(now, f).ok());
    }
    if (cfg_.vo_every_s > 0.0) {
      // A VO step from the previous image (t_from) to an image taken vo_delay_s ago (t_to).
      const double t_to = truth_.t - cfg_.vo_delay_s;
      if (t_to - last_vo_.t >= cfg_.vo_every_s - 1e-9) {
        const Truth& to = history_[static_cast<std::size_t>(std::lround(t_to / dt))];
        msg::RelativePose m;
        m.t_from = Time::FromSeconds(last_vo_.t);
        m.t_to = Time::FromSeconds(to.t);
        const Eigen::Vector3d dp = last_vo_.R.transpose() * (to.p - last_vo_.p);
        const Eigen::Matrix3d dr = last_vo_.R.transpose() * to.R;
        // Left perturbation in the t_from frame: R_true = Exp(n) R_meas, t_true = t_meas + n_p.
        const Eigen::Vector3d np = cfg_.vo_sigma_p * Normal3();
        const Eigen::Vector3d nth = cfg_.vo_sigma_th * Normal3();
        m.delta.linear() = ExpSo3(-nth) * dr;
        m.delta.translation() = dp - np;
        m.covariance.setZero();
        m.covariance.diagonal() << Eigen::Vector3d::Constant(cfg_.vo_sigma_p * cfg_.vo_sigma_p),
            Eigen::Vector3d::Constant(cfg_.vo_sigma_th * cfg_.vo_sigma_th);
        EXPECT_TRUE(ekf_.AddRelativePose(m).ok());
        ++vo_sent;
        last_vo_ = to;
      }
    }
    for (EstimatorEvent& e : ekf_.TakeEvents()) events.push_back(std::move(e));
  }

  std::mt19937_64 rng_;
  std::normal_distribution<double> n01_{0.0, 1.0};
  EkfOptions opt_;
  SimConfig cfg_;
  PoseEkf ekf_;
  Truth truth_;
  Truth last_odo_;
  Truth last_vo_;
  std::vector<Truth> history_;
  double path_ = 0.0;
  long k_ = 0;
};

// 200 s: rest, straight, turn in place, arc, rest, straight, turn right, rest.
std::vector<Segment> Trajectory() {
  return {{20, 0, 0}, {40, 0.05, 0}, {30, 0, 0.05},  {40, 0.05, 0.02},
          {15, 0, 0}, {30, 0.05, 0}, {20, 0, -0.04}, {5, 0, 0}};
}

EkfOptions TestOptions() {
  EkfOptions o;
  o.gyro_noise_density = 2e-4;
  o.gyro_bias_walk = 2e-6;
  o.clone_interval_s = 1.0;
  o.clone_window_s = 30.0;
  return o;
}

EkfInitialState TestInit() {
  EkfInitialState init;
  init.position_sigma = Eigen::Vector3d::Constant(0.02);
  init.rpy_sigma = Eigen::Vector3d(1.5 * kDegree, 1.5 * kDegree, 5 * kDegree);
  init.gyro_bias_sigma = 5e-4;
  return init;
}

// ---- consistency ------------------------------------------------------------------------------

TEST(PoseEkf, NeesWithinChiSquareBoundsOverMonteCarloRuns) {
  constexpr int kRuns = 25;
  constexpr int kDim = 9;
  const int every = 250;  // checkpoint every 5 s
  const EkfOptions options = TestOptions();
  SimConfig cfg;
  cfg.vo_every_s = 8.0;  // relative poses too, so the clones take part
  std::vector<double> sum;
  int vo_accepted = 0, vo_total = 0;
  for (int run = 0; run < kRuns; ++run) {
    Simulation sim(1000 + static_cast<std::uint64_t>(run), options, cfg, TestInit());
    std::size_t idx = 0;
    int step = 0;
    sim.Run(Trajectory(), [&](const Simulation& s) {
      if (++step % every != 0) return;
      if (sum.size() <= idx) sum.push_back(0.0);
      sum[idx++] += s.Nees();
    });
    for (const auto& e : sim.events) {
      if (e.source == MotionSource::kVisualOdometry) {
        ++vo_total;
        vo_accepted += e.accepted ? 1 : 0;
      }
    }
  }
  // Per checkpoint, N * ANEES ~ chi2(N * dim) for a consistent filter.
  const double lo95 = ChiSquareQuantile(0.025, kRuns * kDim) / kRuns;
  const double hi95 = ChiSquareQuantile(0.975, kRuns * kDim) / kRuns;
  const double lo99 = ChiSquareQuantile(0.005, kRuns * kDim) / kRuns;
  const double hi99 = ChiSquareQuantile(0.995, kRuns * kDim) / kRuns;
  int inside = 0;
  double mean = 0.0;
  for (double s : sum) {
    const double anees = s / kRuns;
    inside += (anees >= lo95 && anees <= hi95) ? 1 : 0;
    mean += anees / static_cast<double>(sum.size());
  }
  RecordProperty("mean_anees", std::to_string(mean));
  EXPECT_GE(inside, static_cast<int>(0.8 * static_cast<double>(sum.size())))
      << "checkpoints inside [" << lo95 << ", " << hi95 << "]: " << inside << "/" << sum.size()
      << ", mean ANEES " << mean;
  EXPECT_GT(mean, lo99);
  EXPECT_LT(mean, hi99);
  // The relative poses were used, and nearly all accepted at a 99.9 % gate.
  EXPECT_GT(vo_total, 20 * kRuns - 5);
  EXPECT_GE(vo_accepted, vo_total - 3);
}

TEST(PoseEkf, SameSeedSameEstimate) {
  SimConfig cfg;
  cfg.vo_every_s = 8.0;
  Simulation a(7, TestOptions(), cfg, TestInit());
  Simulation b(7, TestOptions(), cfg, TestInit());
  a.Run({{30, 0.05, 0.01}});
  b.Run({{30, 0.05, 0.01}});
  EXPECT_EQ(a.ekf().position(), b.ekf().position());
  EXPECT_EQ(a.ekf().rotation(), b.ekf().rotation());
}

// ---- sun sensor -------------------------------------------------------------------------------

TEST(PoseEkf, SunSensorRemovesAnInjectedHeadingDrift) {
  // A z gyro bias the filter starts without (it only knows its prior) drifts the heading while
  // the sun is not seen; once sun vectors arrive the heading and the bias are corrected.
  SimConfig cfg;
  cfg.sun_start_s = 400.5;  // first sun vector at t = 401 s
  cfg.true_bias = Eigen::Vector3d(0.0, 0.0, 6e-4);
  cfg.draw_initial_errors = false;
  // Level ground: on a slope, turning between stops changes the gravity direction in the rover
  // frame, which makes the z bias (and so the heading drift) observable by the accelerometer.
  cfg.plane = Eigen::Matrix3d::Identity();
  EkfInitialState init = TestInit();
  init.gyro_bias_sigma = 1e-3;
  Simulation sim(42, TestOptions(), cfg, init);
  // Stops between legs give accelerometer updates that keep roll and pitch known (one sun vector
  // cannot tell a rotation about itself).
  std::vector<Segment> drive;
  for (int i = 0; i < 4; ++i) {
    drive.push_back({50, 0.05, 0.0});
    drive.push_back({10, 0.0, 0.0});
    drive.push_back({30, 0.0, 0.05});
    drive.push_back({10, 0.0, 0.0});
  }
  sim.Run(drive);  // 400 s without sun
  const double drift = sim.HeadingError();
  EXPECT_GT(std::abs(drift), 10 * kDegree) << "drift " << drift / kDegree << " deg";
  const HeadingEstimate before = sim.ekf().Heading();
  EXPECT_GT(std::sqrt(before.variance), std::abs(drift) / 3) << "filter should know it drifted";
  sim.Run({{60, 0.05, 0.0}});  // sun at 1 Hz
  EXPECT_LT(std::abs(sim.HeadingError()), 0.5 * kDegree);
  EXPECT_NEAR(sim.ekf().gyro_bias().z(), sim.truth().b.z(), 1e-4);
  const HeadingEstimate after = sim.ekf().Heading();
  EXPECT_LT(std::sqrt(after.variance), 0.5 * kDegree);
  int sun_events = 0, sun_accepted = 0;
  for (const auto& e : sim.events) {
    if (e.source != MotionSource::kSunSensor) continue;
    ++sun_events;
    sun_accepted += e.accepted ? 1 : 0;
    EXPECT_EQ(e.dof, 2);
  }
  EXPECT_EQ(sun_events, 60);  // t = 401, ..., 460 s
  EXPECT_GE(sun_accepted, 58);
}

TEST(PoseEkf, CorruptedSunVectorIsGatedOut) {
  SimConfig cfg;
  Simulation sim(3, TestOptions(), cfg, TestInit());
  sim.Run({{20, 0, 0}});
  const Eigen::Matrix3d r = sim.ekf().rotation();
  const Eigen::Vector3d wrong = RotZ(30 * kDegree) * (sim.truth().R.transpose() * cfg.sun_site);
  ASSERT_TRUE(sim.ekf().UpdateSunSensor(Time::FromSeconds(20), wrong, cfg.sun_site).ok());
  const auto events = sim.ekf().TakeEvents();
  ASSERT_EQ(events.size(), 1u);
  EXPECT_FALSE(events[0].accepted);
  EXPECT_EQ(events[0].source, MotionSource::kSunSensor);
  EXPECT_GT(events[0].mahalanobis_sq, events[0].gate);
  EXPECT_EQ(sim.ekf().rotation(), r);  // untouched
  EXPECT_EQ(sim.ekf().Estimate().rejected_measurements, 1u);
}

// ---- accelerometer ----------------------------------------------------------------------------

TEST(PoseEkf, AccelerometerLevelsRollAndPitchAtRestButNotHeading) {
  EkfOptions o = TestOptions();
  PoseEkf ekf = PoseEkf::Create(o).value();
  const Eigen::Matrix3d truth = RotationFromRpy(5 * kDegree, -7 * kDegree, 40 * kDegree);
  EkfInitialState init;
  init.attitude = Eigen::Quaterniond(RotationFromRpy(2 * kDegree, -4 * kDegree, 40 * kDegree));
  init.rpy_sigma = Eigen::Vector3d(4 * kDegree, 4 * kDegree, 10 * kDegree);
  ASSERT_TRUE(ekf.Initialize(init).ok());
  const double yaw_var0 = ekf.Heading().variance;
  std::mt19937_64 rng(5);
  std::normal_distribution<double> n01;
  for (int k = 1; k <= 1000; ++k) {  // 20 s at rest
    const Time t = Time::FromSeconds(k * 0.02);
    ASSERT_TRUE(ekf.PropagateGyro(t, Eigen::Vector3d(n01(rng), n01(rng), n01(rng)) * 1e-3).ok());
    const Eigen::Vector3d f = truth.transpose() * Eigen::Vector3d(0, 0, o.gravity) +
                              o.accel_noise * Eigen::Vector3d(n01(rng), n01(rng), n01(rng));
    ASSERT_TRUE(ekf.UpdateAccelerometer(t, f).ok());
  }
  EXPECT_TRUE(ekf.stationary());
  const Eigen::Vector3d rpy = ekf.Estimate().rpy;
  EXPECT_NEAR(rpy.x(), 5 * kDegree, 0.2 * kDegree);
  EXPECT_NEAR(rpy.y(), -7 * kDegree, 0.2 * kDegree);
  EXPECT_NEAR(rpy.z(), 40 * kDegree, 0.5 * kDegree);  // heading not observed: stays where it was
  EXPECT_GT(ekf.Heading().variance, 0.9 * yaw_var0);
  const auto events = ekf.TakeEvents();
  // One update per accel_update_interval_s (0.5 s) after the 0.5 s stationary delay.
  EXPECT_NEAR(static_cast<double>(events.size()), 39.0, 1.0);
  for (const auto& e : events) EXPECT_EQ(e.source, MotionSource::kAccelerometer);
}

TEST(PoseEkf, AccelerometerIsIgnoredWhileDriving) {
  PoseEkf ekf = PoseEkf::Create(TestOptions()).value();
  ASSERT_TRUE(ekf.Initialize(EkfInitialState()).ok());
  for (int k = 1; k <= 200; ++k) {
    const Time t = Time::FromSeconds(k * 0.02);
    ASSERT_TRUE(ekf.PropagateGyro(t, Eigen::Vector3d::Zero()).ok());
    if (k % 5 == 0 && k <= 100) {
      OdometryIncrement inc;
      inc.t_from = Time::FromSeconds((k - 5) * 0.02);
      inc.t_to = t;
      inc.dx = 0.005;
      inc.path_length = 0.005;
      inc.covariance.diagonal() << 5e-6, 5e-6, 1e-6;
      ASSERT_TRUE(ekf.AddWheelOdometry(inc).ok());
    }
    if (k <= 100) {
      EXPECT_FALSE(ekf.stationary()) << k;
    }
    if (k >= 5 && k <= 100) {
      EXPECT_NEAR(ekf.Estimate().velocity.x(), 0.05, 1e-12);
    }
    ASSERT_TRUE(ekf.UpdateAccelerometer(t, Eigen::Vector3d(0, 0, 9.81)).ok());
  }
  EXPECT_TRUE(ekf.stationary());
  EXPECT_EQ(ekf.Estimate().velocity, Eigen::Vector3d::Zero());
  // Driving for 2 s, then updates only after the 0.5 s delay.
  const auto events = ekf.TakeEvents();
  ASSERT_FALSE(events.empty());
  EXPECT_GE(events.front().stamp.seconds(), 2.5 - 1e-9);
  EXPECT_NEAR(ekf.Estimate().odometer, 0.1, TestOptions().odometer_step);
  // A non-gravity magnitude (a bump) is not used either.
  ASSERT_TRUE(ekf.PropagateGyro(Time::FromSeconds(10), Eigen::Vector3d::Zero()).ok());
  ASSERT_TRUE(ekf.UpdateAccelerometer(Time::FromSeconds(10), Eigen::Vector3d(0, 0, 12)).ok());
  EXPECT_TRUE(ekf.TakeEvents().empty());
}

// The odometer is path length, not the sum of increment lengths: at rest, wheel-encoder jitter
// gives increments of either sign that cancel (the rover has not moved), and those must not add
// up into distance (dl/pose's odometer grew 0.024 m/s at rest before).
TEST(PoseEkf, OdometerDoesNotGrowFromJitterAtRestButCountsADrive) {
  PoseEkf ekf = PoseEkf::Create(TestOptions()).value();
  ASSERT_TRUE(ekf.Initialize(EkfInitialState()).ok());
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> sign(0, 1);
  int k = 0;
  auto step = [&](double dx, double dy) {
    ++k;
    OdometryIncrement inc;
    inc.t_from = Time::FromSeconds((k - 1) * 0.02);
    inc.t_to = Time::FromSeconds(k * 0.02);
    inc.dx = dx;
    inc.dy = dy;
    inc.path_length = std::hypot(dx, dy);
    inc.covariance.diagonal() << 1e-8, 1e-8, 1e-9;
    ASSERT_TRUE(ekf.PropagateGyro(inc.t_to, Eigen::Vector3d::Zero()).ok());
    ASSERT_TRUE(ekf.AddWheelOdometry(inc).ok());
  };
  // 100 s at 50 Hz of +-0.5 mm jitter that returns to where it was (a count up, a count down).
  for (int i = 0; i < 2500; ++i) {
    const double j = sign(rng) ? 5e-4 : -5e-4;
    step(j, -j);
    step(-j, j);
  }
  EXPECT_LT(ekf.Estimate().odometer, TestOptions().odometer_step);
  // Then a 2 m drive along x: counted to within one step.
  for (int i = 0; i < 400; ++i) step(0.005, 0.0);
  EXPECT_NEAR(ekf.Estimate().odometer, 2.0, TestOptions().odometer_step);
  // A resumed estimator starts from the odometer it is given.
  EkfInitialState resumed;
  resumed.stamp = Time::FromSeconds(k * 0.02);
  resumed.odometer = 12.5;
  ASSERT_TRUE(ekf.Initialize(resumed).ok());
  EXPECT_DOUBLE_EQ(ekf.Estimate().odometer, 12.5);
}

// ---- relative poses ---------------------------------------------------------------------------

TEST(PoseEkf, GatingRejectsACorruptedRelativePoseAndAcceptsGoodOnes) {
  SimConfig cfg;
  cfg.vo_every_s = 5.0;
  Simulation sim(11, TestOptions(), cfg, TestInit());
  sim.Run({{60, 0.05, 0.01}});
  int accepted = 0;
  for (const auto& e : sim.events) {
    if (e.source == MotionSource::kVisualOdometry) {
      EXPECT_TRUE(e.accepted) << e.message;
      EXPECT_EQ(e.dof, 6);
      accepted += e.accepted ? 1 : 0;
    }
  }
  EXPECT_GE(accepted, 10);
  // A VO step with a 1 m jump along x over the last 5 s.
  PoseEkf& ekf = sim.ekf();
  const Eigen::Vector3d p_before = ekf.position();
  const Matrix9d p9_before = ekf.covariance();
  msg::RelativePose bad;
  bad.t_from = Time::FromSeconds(54.0);
  bad.t_to = Time::FromSeconds(59.0);
  bad.delta.translation() = Eigen::Vector3d(0.25 + 1.0, 0.0, 0.0);
  bad.covariance = Matrix6d::Identity() * 1e-4;
  ASSERT_TRUE(ekf.AddRelativePose(bad).ok());
  auto events = ekf.TakeEvents();
  ASSERT_EQ(events.size(), 1u);
  EXPECT_FALSE(events[0].accepted);
  EXPECT_EQ(events[0].source, MotionSource::kVisualOdometry);
  EXPECT_GT(events[0].mahalanobis_sq, events[0].gate);
  EXPECT_NEAR(events[0].gate, ChiSquareQuantile(0.999, 6), 1e-9);
  EXPECT_NE(events[0].message.find("rejected"), std::string::npos);
  EXPECT_EQ(ekf.position(), p_before);
  EXPECT_EQ(ekf.covariance(), p9_before);
  EXPECT_EQ(ekf.Estimate().rejected_measurements, 1u);
  // The same step without the jump is accepted.
  sim.Run({{10, 0.05, 0.01}});
  int late_accepted = 0;
  for (const auto& e : sim.events) {
    if (e.source == MotionSource::kVisualOdometry && e.stamp.seconds() > 60) {
      late_accepted += e.accepted ? 1 : 0;
    }
  }
  EXPECT_GE(late_accepted, 1);
}

TEST(PoseEkf, RelativePosesReduceOdometryDrift) {
  // Wheels slip: the rover travels 15 % further than odometry says (unmodelled), so dead
  // reckoning drifts; visual odometry every 4 s bounds the drift.
  SimConfig cfg;
  cfg.odometry_scale = 1.15;
  cfg.draw_initial_errors = false;
  cfg.vo_sigma_p = 0.005;
  cfg.vo_sigma_th = 0.2 * kDegree;
  const std::vector<Segment> drive = {
      {60, 0.05, 0.0}, {20, 0.0, 0.05}, {60, 0.05, 0.01}, {20, 0.0, -0.05}, {60, 0.05, 0.0}};
  Simulation dead(21, TestOptions(), cfg, TestInit());
  dead.Run(drive);
  cfg.vo_every_s = 4.0;
  Simulation vo(21, TestOptions(), cfg, TestInit());
  vo.Run(drive);
  const double err_dead = dead.Error().head<2>().norm();
  const double err_vo = vo.Error().head<2>().norm();
  EXPECT_GT(err_dead, 0.8);  // ~15 % of 9 m
  EXPECT_LT(err_vo, 0.25 * err_dead) << "dead reckoning " << err_dead << " m, with VO " << err_vo;
  int accepted = 0;
  for (const auto& e : vo.events) {
    accepted += (e.source == MotionSource::kVisualOdometry && e.accepted) ? 1 : 0;
  }
  EXPECT_GT(accepted, vo.vo_sent / 2);
}

TEST(PoseEkf, RelativePoseWaitsForTheFilterAndChecksTheWindow) {
  EkfOptions o = TestOptions();
  o.clone_interval_s = 0.5;
  o.clone_window_s = 5.0;
  PoseEkf ekf = PoseEkf::Create(o).value();
  ASSERT_TRUE(ekf.Initialize(EkfInitialState()).ok());
  auto propagate_to = [&](double t_end) {
    for (double t = ekf.time().seconds() + 0.02; t <= t_end + 1e-9; t += 0.02) {
      ASSERT_TRUE(ekf.PropagateGyro(Time::FromSeconds(t), Eigen::Vector3d::Zero()).ok());
    }
  };
  propagate_to(2.0);
  EXPECT_EQ(ekf.num_clones(), 5u);  // t = 0 (first sample), 0.5, ..., 2.0
  msg::RelativePose m;
  m.t_from = Time::FromSeconds(1.3);  // between clones
  m.t_to = Time::FromSeconds(3.01);   // ahead of the filter
  m.covariance = Matrix6d::Identity() * 1e-4;
  ASSERT_TRUE(ekf.AddRelativePose(m).ok());
  EXPECT_EQ(ekf.pending_relative_poses(), 1u);
  EXPECT_TRUE(ekf.TakeEvents().empty());
  propagate_to(3.0);
  EXPECT_EQ(ekf.pending_relative_poses(), 1u);
  propagate_to(3.1);
  EXPECT_EQ(ekf.pending_relative_poses(), 0u);
  auto events = ekf.TakeEvents();
  ASSERT_EQ(events.size(), 1u);
  EXPECT_TRUE(events[0].accepted) << events[0].message;
  // Clones older than the window are dropped; a measurement from before them is rejected.
  propagate_to(12.0);
  EXPECT_LE(ekf.num_clones(), 11u);
  m.t_from = Time::FromSeconds(2.0);
  m.t_to = Time::FromSeconds(11.0);
  ASSERT_TRUE(ekf.AddRelativePose(m).ok());
  events = ekf.TakeEvents();
  ASSERT_EQ(events.size(), 1u);
  EXPECT_FALSE(events[0].accepted);
  EXPECT_TRUE(std::isnan(events[0].mahalanobis_sq));
  EXPECT_NE(events[0].message.find("clone window"), std::string::npos);
  EXPECT_EQ(ekf.rejected_measurements(), 0u);  // not a gating rejection
  // Bad inputs.
  msg::RelativePose bad = m;
  bad.t_from = Time::FromSeconds(11.5);
  EXPECT_EQ(ekf.AddRelativePose(bad).code(), StatusCode::kInvalidArgument);
  bad = m;
  bad.covariance(0, 1) = 1.0;  // not symmetric
  EXPECT_EQ(ekf.AddRelativePose(bad).code(), StatusCode::kInvalidArgument);
  bad = m;
  bad.covariance(2, 2) = -1.0;
  EXPECT_EQ(ekf.AddRelativePose(bad).code(), StatusCode::kInvalidArgument);
  bad = m;
  bad.delta.linear() *= 2.0;
  EXPECT_EQ(ekf.AddRelativePose(bad).code(), StatusCode::kInvalidArgument);
  bad = m;
  bad.delta.translation().x() = std::nan("");
  EXPECT_EQ(ekf.AddRelativePose(bad).code(), StatusCode::kInvalidArgument);
  bad = m;
  bad.t_to = Time::FromSeconds(100.0);
  EXPECT_EQ(ekf.AddRelativePose(bad).code(), StatusCode::kOutOfRange);
}

// ---- outputs and input checks -----------------------------------------------------------------

TEST(PoseEkf, OutputCovarianceIsOverRollPitchYaw) {
  PoseEkf ekf = PoseEkf::Create(EkfOptions()).value();
  EkfInitialState init;
  init.attitude = Eigen::Quaterniond(RotationFromRpy(10 * kDegree, -20 * kDegree, 135 * kDegree));
  init.position = Eigen::Vector3d(1, 2, 3);
  init.position_sigma = Eigen::Vector3d(0.1, 0.2, 0.3);
  init.rpy_sigma = Eigen::Vector3d(0.01, 0.02, 0.3);
  ASSERT_TRUE(ekf.Initialize(init).ok());
  const PoseEstimate e = ekf.Estimate();
  EXPECT_TRUE(e.position.isApprox(init.position));
  EXPECT_NEAR(e.rpy.x(), 10 * kDegree, 1e-12);
  EXPECT_NEAR(e.rpy.y(), -20 * kDegree, 1e-12);
  EXPECT_NEAR(e.rpy.z(), 135 * kDegree, 1e-12);
  EXPECT_GE(e.orientation.w(), 0.0);
  Eigen::Matrix<double, 6, 1> var;
  var << 0.01, 0.04, 0.09, 1e-4, 4e-4, 0.09;
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(e.covariance(i, i), var(i), 1e-12) << i;
  EXPECT_NEAR(e.covariance(3, 5), 0.0, 1e-12);
  const HeadingEstimate h = ekf.Heading();
  EXPECT_NEAR(h.yaw, 135 * kDegree, 1e-12);
  EXPECT_NEAR(h.variance, 0.09, 1e-12);

  // Numerical check of the angle Jacobian: a small site-frame rotation of the state and the
  // change of the ZYX angles it causes agree with the covariance mapping.
  const Eigen::Matrix3d r0 = ekf.rotation();
  const Eigen::Vector3d dth(1e-6, -2e-6, 3e-6);
  const Eigen::Vector3d drpy = RpyFromRotation(ExpSo3(dth) * r0) - RpyFromRotation(r0);
  // Covariance of the site rotation error from the filter's internal 9x9 block.
  const Eigen::Matrix3d p_th = ekf.covariance().block<3, 3>(3, 3);
  // Map drpy back: E drpy = dth  ->  Var(drpy) = E^-1 P E^-T; compare via the 1-D projection.
  const Eigen::Matrix3d e_inv_num = [&] {
    Eigen::Matrix3d m;
    for (int i = 0; i < 3; ++i) {
      Eigen::Vector3d d = Eigen::Vector3d::Zero();
      d(i) = 1e-7;
      m.col(i) = (RpyFromRotation(ExpSo3(d) * r0) - RpyFromRotation(r0)) / 1e-7;
    }
    return m;
  }();
  EXPECT_LT((e_inv_num * dth - drpy).norm(), 1e-10);
  const Eigen::Matrix3d cov_num = e_inv_num * p_th * e_inv_num.transpose();
  EXPECT_LT((cov_num - e.covariance.block<3, 3>(3, 3)).cwiseAbs().maxCoeff(), 1e-6);
}

TEST(PoseEkf, RejectsBadInputsAndKeepsTheState) {
  PoseEkf ekf = PoseEkf::Create(EkfOptions()).value();
  EXPECT_EQ(ekf.PropagateGyro(Time::FromSeconds(1), Eigen::Vector3d::Zero()).code(),
            StatusCode::kFailedPrecondition);
  EkfInitialState init;
  init.stamp = Time::FromSeconds(1);
  EkfInitialState bad_init = init;
  bad_init.rpy_sigma.x() = -1;
  EXPECT_FALSE(ekf.Initialize(bad_init).ok());
  bad_init = init;
  bad_init.position.x() = std::nan("");
  EXPECT_FALSE(ekf.Initialize(bad_init).ok());
  ASSERT_TRUE(ekf.Initialize(init).ok());
  ASSERT_TRUE(ekf.PropagateGyro(Time::FromSeconds(2), Eigen::Vector3d(0, 0, 0.1)).ok());
  const Eigen::Matrix3d r = ekf.rotation();
  EXPECT_EQ(ekf.PropagateGyro(Time::FromSeconds(1.5), Eigen::Vector3d::Zero()).code(),
            StatusCode::kOutOfRange);
  EXPECT_EQ(ekf.PropagateGyro(Time::FromSeconds(3), Eigen::Vector3d(0, std::nan(""), 0)).code(),
            StatusCode::kInvalidArgument);
  EXPECT_EQ(ekf.rotation(), r);
  EXPECT_EQ(ekf.time(), Time::FromSeconds(2));
  EXPECT_EQ(
      ekf.UpdateSunSensor(Time::FromSeconds(2), Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ())
          .code(),
      StatusCode::kInvalidArgument);
  EXPECT_EQ(ekf.UpdateAccelerometer(Time::FromSeconds(2), Eigen::Vector3d(0, 0, INFINITY)).code(),
            StatusCode::kInvalidArgument);
  OdometryIncrement inc;
  inc.t_from = Time::FromSeconds(1.9);
  inc.t_to = Time::FromSeconds(2.0);
  inc.dx = 0.01;
  ASSERT_TRUE(ekf.AddWheelOdometry(inc).ok());
  EXPECT_EQ(ekf.AddWheelOdometry(inc).code(), StatusCode::kOutOfRange);  // same t_to again
  inc.t_to = Time::FromSeconds(2.1);
  inc.dy = std::nan("");
  EXPECT_EQ(ekf.AddWheelOdometry(inc).code(), StatusCode::kInvalidArgument);
  inc.dy = 0;
  inc.covariance(1, 1) = -1;
  EXPECT_EQ(ekf.AddWheelOdometry(inc).code(), StatusCode::kInvalidArgument);
  // Odometry moves along the current heading (0.1 rad: 0.1 rad/s from t = 1 s to 2 s).
  EXPECT_NEAR(ekf.position().x(), 0.01 * std::cos(0.1), 1e-12);
  EXPECT_NEAR(ekf.position().y(), 0.01 * std::sin(0.1), 1e-12);
}

TEST(PoseEkf, OptionsAndParams) {
  EkfOptions o;
  EXPECT_TRUE(o.Validate().ok());
  o.gate_probability = 1.0;
  EXPECT_NE(o.Validate().message().find("gate_probability"), std::string::npos);
  o = EkfOptions();
  o.sun_noise = 0.0;
  EXPECT_FALSE(o.Validate().ok());
  EXPECT_FALSE(PoseEkf::Create(o).ok());
  o = EkfOptions();
  o.clone_window_s = 0.5;
  EXPECT_FALSE(o.Validate().ok());

  ParamSet p("pose");
  DeclareEkfParams(p);
  Result<EkfOptions> d = EkfOptionsFromParams(p);
  ASSERT_TRUE(d.ok()) << d.status().ToString();
  EXPECT_DOUBLE_EQ(d->gate_probability, EkfOptions().gate_probability);
  ASSERT_TRUE(p.LoadYamlString("ekf:\n  gravity: 3.71\n  clone_window_s: 0.1\n", "pose.yaml").ok());
  d = EkfOptionsFromParams(p);
  ASSERT_FALSE(d.ok());
  EXPECT_EQ(d.status().message().rfind("pose.yaml:3: key 'ekf.clone_window_s'", 0), 0u)
      << d.status().message();
  ParamSet q("pose");
  DeclareEkfParams(q);
  ASSERT_TRUE(q.LoadYamlString("ekf:\n  gate_probability: 2\n", "pose.yaml").ok());
  EXPECT_NE(EkfOptionsFromParams(q).status().message().find("pose.yaml:2: key "
                                                            "'ekf.gate_probability'"),
            std::string::npos);
}

}  // namespace
}  // namespace rover::dl::pose
