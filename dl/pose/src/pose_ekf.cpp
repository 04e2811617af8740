#include "rover/dl/pose/pose_ekf.hpp"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "rover/base/check.hpp"
#include "rover/base/format.hpp"
#include "rover/dl/pose/chi_square.hpp"
#include "rover/geometry/transforms.hpp"

namespace rover::dl::pose {

using locomotion::OdometryIncrement;

namespace {

using geometry::ExpSo3;
using geometry::LogSo3;
using geometry::Skew;

constexpr double kSameTimeS = 1e-6;
constexpr std::size_t kMaxPending = 64;

Eigen::Matrix3d RotZ(double a) {
  return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ()).toRotationMatrix();
}

// Maps ZYX angle increments (droll, dpitch, dyaw) to the site-frame rotation they cause.
Eigen::Matrix3d EulerToSiteRotation(const Eigen::Vector3d& rpy) {
  const double cp = std::cos(rpy.y()), sp = std::sin(rpy.y());
  const double cy = std::cos(rpy.z()), sy = std::sin(rpy.z());
  Eigen::Matrix3d e;
  e.col(0) << cy * cp, sy * cp, -sp;
  e.col(1) << -sy, cy, 0.0;
  e.col(2) << 0.0, 0.0, 1.0;
  return e;
}

Eigen::Matrix3d Orthonormalize(const Eigen::Matrix3d& r) {
  return Eigen::Quaterniond(r).normalized().toRotationMatrix();
}

// m = (m + m^T) / 2 without a temporary.
void Symmetrize(Eigen::MatrixXd& m) {
  for (Eigen::Index j = 0; j < m.cols(); ++j) {
    for (Eigen::Index i = 0; i < j; ++i) {
      const double v = 0.5 * (m(i, j) + m(j, i));
      m(i, j) = v;
      m(j, i) = v;
    }
  }
}

bool SymmetricPositiveDefinite(const Eigen::MatrixXd& m) {
  if (!m.allFinite()) return false;
  const double scale = std::max(1.0, m.cwiseAbs().maxCoeff());
  if ((m - m.transpose()).cwiseAbs().maxCoeff() > 1e-9 * scale) return false;
  Eigen::LLT<Eigen::MatrixXd> llt(m);
  return llt.info() == Eigen::Success;
}

}  // namespace

// ---- options ----------------------------------------------------------------------------------

Status EkfOptions::Validate() const {
  struct Field {
    const char* name;
    double value;
    bool strictly_positive;
  };
  const Field fields[] = {
      {"gyro_noise_density", gyro_noise_density, false},
      {"gyro_bias_walk", gyro_bias_walk, false},
      {"odometry_vertical_variance_per_m", odometry_vertical_variance_per_m, false},
      {"gravity", gravity, true},
      {"accel_noise", accel_noise, true},
      {"accel_magnitude_tolerance", accel_magnitude_tolerance, true},
      {"accel_update_interval_s", accel_update_interval_s, false},
      {"stationary_delay_s", stationary_delay_s, false},
      {"stationary_gyro_threshold", stationary_gyro_threshold, true},
      {"wheel_motion_threshold", wheel_motion_threshold, false},
      {"odometer_step", odometer_step, false},
      {"sun_noise", sun_noise, true},
      {"clone_interval_s", clone_interval_s, false},
      {"clone_window_s", clone_window_s, false},
      {"max_pending_s", max_pending_s, false},
  };
  for (const Field& f : fields) {
    if (!std::isfinite(f.value) || f.value < 0.0 || (f.strictly_positive && f.value == 0.0)) {
      return InvalidArgument(std::string("EkfOptions.") + f.name + ": " + FormatNumber(f.value) +
                             (f.strictly_positive ? " must be > 0" : " must be >= 0"));
    }
  }
  if (!(gate_probability > 0.0 && gate_probability < 1.0)) {
    return InvalidArgument("EkfOptions.gate_probability: " + FormatNumber(gate_probability) +
                           " must be in (0, 1)");
  }
  if (clone_interval_s > 0.0 && clone_window_s < clone_interval_s) {
    return InvalidArgument("EkfOptions.clone_window_s: " + FormatNumber(clone_window_s) +
                           " must be >= clone_interval_s " + FormatNumber(clone_interval_s));
  }
  return Status::Ok();
}

// ---- construction -----------------------------------------------------------------------------

PoseEkf::PoseEkf(const EkfOptions& o) : options_(o), P_(Eigen::MatrixXd::Zero(9, 9)) {}

Result<PoseEkf> PoseEkf::Create(const EkfOptions& options) {
  ROVER_RETURN_IF_ERROR(options.Validate());
  return PoseEkf(options);
}

Status PoseEkf::Initialize(const EkfInitialState& init) {
  if (!init.position.allFinite() || !init.attitude.coeffs().allFinite() ||
      !init.gyro_bias.allFinite() || !init.position_sigma.allFinite() ||
      !init.rpy_sigma.allFinite() || !std::isfinite(init.gyro_bias_sigma)) {
    return InvalidArgument("EKF initial state has a non-finite value");
  }
  if (init.attitude.norm() < 0.5) {
    return InvalidArgument("EKF initial attitude is not a unit quaternion (norm " +
                           FormatNumber(init.attitude.norm()) + ")");
  }
  if ((init.position_sigma.array() < 0).any() || (init.rpy_sigma.array() < 0).any() ||
      init.gyro_bias_sigma < 0) {
    return InvalidArgument("EKF initial sigmas must be >= 0");
  }
  time_ = init.stamp;
  p_ = init.position;
  R_ = init.attitude.normalized().toRotationMatrix();
  bg_ = init.gyro_bias;
  P_ = Eigen::MatrixXd::Zero(9, 9);
  P_.block<3, 3>(0, 0) = init.position_sigma.cwiseAbs2().asDiagonal();
  const Eigen::Matrix3d e = EulerToSiteRotation(geometry::RpyFromRotation(R_));
  P_.block<3, 3>(3, 3) = e * init.rpy_sigma.cwiseAbs2().asDiagonal() * e.transpose();
  P_.block<3, 3>(6, 6) = Eigen::Matrix3d::Identity() * init.gyro_bias_sigma * init.gyro_bias_sigma;
  phi_acc_.setIdentity();
  clones_.clear();
  last_clone_.reset();
  pending_.clear();
  events_.clear();
  last_rate_.setZero();
  last_motion_ = init.stamp;
  last_accel_update_.reset();
  last_odometry_.reset();
  velocity_.setZero();
  rejected_ = 0;
  odometer_ = std::isfinite(init.odometer) ? std::max(init.odometer, 0.0) : 0.0;
  odometer_pending_.setZero();
  initialized_ = true;
  if (options_.clone_interval_s > 0.0) AddClone();  // so relative poses may start at t0
  return Status::Ok();
}

// ---- propagation ------------------------------------------------------------------------------

void PoseEkf::PropagateLive(const Matrix9d& phi, const Matrix9d& q) {
  Matrix9d pll = P_.topLeftCorner<9, 9>();
  pll = phi * pll * phi.transpose() + q;
  P_.topLeftCorner<9, 9>() = 0.5 * (pll + pll.transpose());
  phi_acc_ = phi * phi_acc_;
}

void PoseEkf::SyncCross() {
  const Eigen::Index m = P_.rows() - 9;
  if (m > 0 && !phi_acc_.isIdentity(0.0)) {
    const Eigen::MatrixXd cross = phi_acc_ * P_.topRightCorner(9, m);
    P_.topRightCorner(9, m) = cross;
    P_.bottomLeftCorner(m, 9) = cross.transpose();
  }
  phi_acc_.setIdentity();
}

Status PoseEkf::PropagateGyro(Time t, const Eigen::Vector3d& angular_velocity) {
  if (!initialized_) return FailedPrecondition("EKF: gyro sample before Initialize()");
  if (!angular_velocity.allFinite()) return InvalidArgument("EKF: non-finite gyro rate");
  if (t < time_) {
    return OutOfRange("EKF: gyro sample at " + FormatNumber(t.seconds()) +
                      " s is older than the filter (" + FormatNumber(time_.seconds()) + " s)");
  }
  const double dt = ToSeconds(t - time_);
  last_rate_ = angular_velocity - bg_;
  if (dt > 0.0) {
    R_ = Orthonormalize(R_ * ExpSo3(last_rate_ * dt));
    Matrix9d phi = Matrix9d::Identity();
    phi.block<3, 3>(3, 6) = -R_ * dt;
    Matrix9d q = Matrix9d::Zero();
    q.block<3, 3>(3, 3).diagonal().setConstant(options_.gyro_noise_density *
                                               options_.gyro_noise_density * dt);
    q.block<3, 3>(6, 6).diagonal().setConstant(options_.gyro_bias_walk * options_.gyro_bias_walk *
                                               dt);
    PropagateLive(phi, q);
    time_ = t;
  }
  if (options_.clone_interval_s > 0.0 &&
      (!last_clone_.has_value() ||
       ToSeconds(time_ - *last_clone_) >= options_.clone_interval_s - kSameTimeS)) {
    AddClone();
  }
  PruneClones();
  ProcessPending();
  return Status::Ok();
}

Status PoseEkf::AddWheelOdometry(const OdometryIncrement& inc) {
  if (!initialized_) return FailedPrecondition("EKF: odometry before Initialize()");
  if (!std::isfinite(inc.dx) || !std::isfinite(inc.dy) || !std::isfinite(inc.dyaw) ||
      !std::isfinite(inc.path_length) || !inc.covariance.allFinite() ||
      (inc.covariance.diagonal().array() < 0.0).any()) {
    return InvalidArgument(
        "EKF: wheel odometry increment has a non-finite value or a negative "
        "variance");
  }
  if (last_odometry_.has_value() && inc.t_to <= *last_odometry_) {
    return OutOfRange("EKF: wheel odometry increment ending at " +
                      FormatNumber(inc.t_to.seconds()) + " s is not after the previous one (" +
                      FormatNumber(last_odometry_->seconds()) + " s)");
  }
  const Eigen::Matrix3d r_from = R_ * RotZ(inc.dyaw).transpose();
  const Eigen::Vector3d d(inc.dx, inc.dy, 0.0);
  const Eigen::Vector3d dp = r_from * d;
  Eigen::Matrix3d cov_body = Eigen::Matrix3d::Zero();
  cov_body.topLeftCorner<2, 2>() = inc.covariance.topLeftCorner<2, 2>();
  cov_body(2, 2) = options_.odometry_vertical_variance_per_m * std::abs(inc.path_length);
  Matrix9d phi = Matrix9d::Identity();
  phi.block<3, 3>(0, 3) = -Skew(dp);
  Matrix9d q = Matrix9d::Zero();
  q.block<3, 3>(0, 0) = r_from * cov_body * r_from.transpose();
  PropagateLive(phi, q);
  p_ += dp;

  // Path length in steps of odometer_step: the displacement since the last step, not the sum of
  // the increments' lengths (which would rectify zero-mean encoder jitter into distance).
  odometer_pending_ += dp;
  if (odometer_pending_.norm() >= options_.odometer_step) {
    odometer_ += odometer_pending_.norm();
    odometer_pending_.setZero();
  }
  const double dt = ToSeconds(inc.t_to - inc.t_from);
  if (dt > 0.0) velocity_ = d / dt;
  if (std::abs(inc.path_length) > options_.wheel_motion_threshold) {
    last_motion_ = std::max(last_motion_, inc.t_to);
  }
  last_odometry_ = inc.t_to;
  return Status::Ok();
}

// ---- clones -----------------------------------------------------------------------------------

void PoseEkf::AddClone() {
  SyncCross();
  const Eigen::Index n = P_.rows();
  Eigen::MatrixXd pn(n + 6, n + 6);
  pn.topLeftCorner(n, n) = P_;
  pn.block(n, 0, 6, n) = P_.topRows(6);
  pn.block(0, n, n, 6) = P_.leftCols(6);
  pn.block(n, n, 6, 6) = P_.topLeftCorner(6, 6);
  P_ = std::move(pn);
  clones_.push_back({time_, p_, R_});
  last_clone_ = time_;
}

void PoseEkf::PruneClones() {
  std::size_t drop = 0;
  while (drop < clones_.size() &&
         ToSeconds(time_ - clones_[drop].t) > options_.clone_window_s + kSameTimeS) {
    ++drop;
  }
  if (drop == 0) return;
  SyncCross();
  const Eigen::Index n = P_.rows();
  const Eigen::Index removed = static_cast<Eigen::Index>(6 * drop);
  std::vector<Eigen::Index> keep;
  keep.reserve(static_cast<std::size_t>(n - removed));
  for (Eigen::Index i = 0; i < 9; ++i) keep.push_back(i);
  for (Eigen::Index i = 9 + removed; i < n; ++i) keep.push_back(i);
  Eigen::MatrixXd pn = P_(keep, keep);
  P_ = std::move(pn);
  clones_.erase(clones_.begin(), clones_.begin() + static_cast<std::ptrdiff_t>(drop));
}

std::optional<PoseEkf::PoseNode> PoseEkf::Interpolate(Time t) const {
  const double to_live = ToSeconds(time_ - t);
  if (std::abs(to_live) <= kSameTimeS) return PoseNode{p_, R_, 0, 0, 0.0};
  if (to_live < 0.0 || clones_.empty()) return std::nullopt;
  if (ToSeconds(clones_.front().t - t) > kSameTimeS) return std::nullopt;
  for (std::size_t k = 0; k < clones_.size(); ++k) {
    const Clone& a = clones_[k];
    const int block_a = 9 + 6 * static_cast<int>(k);
    if (std::abs(ToSeconds(t - a.t)) <= kSameTimeS)
      return PoseNode{a.p, a.R, block_a, block_a, 0.0};
    const bool last = k + 1 == clones_.size();
    const Time tb = last ? time_ : clones_[k + 1].t;
    if (t > a.t && t < tb) {
      const Eigen::Vector3d& pb = last ? p_ : clones_[k + 1].p;
      const Eigen::Matrix3d& rb = last ? R_ : clones_[k + 1].R;
      const int block_b = last ? 0 : block_a + 6;
      const double w = ToSeconds(t - a.t) / ToSeconds(tb - a.t);
      PoseNode node;
      node.p = (1.0 - w) * a.p + w * pb;
      node.R = a.R * ExpSo3(w * LogSo3(a.R.transpose() * rb));
      node.block_a = block_a;
      node.block_b = block_b;
      node.weight_b = w;
      return node;
    }
  }
  return std::nullopt;
}

// ---- updates ----------------------------------------------------------------------------------

void PoseEkf::Reject(MotionSource source, Time t, std::string message) {
  EstimatorEvent e;
  e.stamp = t;
  e.source = source;
  e.accepted = false;
  e.mahalanobis_sq = std::numeric_limits<double>::quiet_NaN();
  e.gate = 0.0;
  e.message = std::move(message);
  events_.push_back(std::move(e));
}

bool PoseEkf::Update(MotionSource source, Time t, const Eigen::VectorXd& r,
                     const Eigen::MatrixXd& h, const Eigen::MatrixXd& noise,
                     const std::string& what) {
  SyncCross();
  const Eigen::Index m = r.size();
  ROVER_DEMAND(h.rows() == m && h.cols() == P_.rows() && noise.rows() == m);
  const Eigen::MatrixXd pht = P_ * h.transpose();
  Eigen::MatrixXd s = h * pht + noise;
  s = 0.5 * (s + s.transpose());
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(s);
  EstimatorEvent e;
  e.stamp = t;
  e.source = source;
  e.dof = static_cast<int>(m);
  e.gate = ChiSquareQuantile(options_.gate_probability, static_cast<int>(m));
  if (ldlt.info() != Eigen::Success || !ldlt.isPositive() || !r.allFinite()) {
    e.accepted = false;
    e.mahalanobis_sq = std::numeric_limits<double>::quiet_NaN();
    e.message = what + ": innovation covariance not positive definite";
    ++rejected_;
    events_.push_back(std::move(e));
    return false;
  }
  e.mahalanobis_sq = r.dot(ldlt.solve(r));
  e.accepted = std::isfinite(e.mahalanobis_sq) && e.mahalanobis_sq <= e.gate;
  std::ostringstream msg;
  msg << what << (e.accepted ? " accepted" : " rejected") << ": d2 " << e.mahalanobis_sq
      << (e.accepted ? " <= " : " > ") << "gate " << e.gate << " (" << m << " dof)";
  e.message = msg.str();
  const bool accepted = e.accepted;
  events_.push_back(std::move(e));
  if (!accepted) {
    ++rejected_;
    return false;
  }
  const Eigen::MatrixXd k = ldlt.solve(pht.transpose()).transpose();  // n x m
  Inject(k * r);
  // In place: with 60 clones P is 369 x 369 (1 MB), and a temporary of that size per update was
  // most of dl-pose's time (allocation, page faults).
  P_.noalias() -= k * pht.transpose();
  Symmetrize(P_);
  return true;
}

void PoseEkf::Inject(const Eigen::VectorXd& dx) {
  p_ += dx.segment<3>(0);
  R_ = Orthonormalize(ExpSo3(dx.segment<3>(3)) * R_);
  bg_ += dx.segment<3>(6);
  for (std::size_t k = 0; k < clones_.size(); ++k) {
    const Eigen::Index o = 9 + 6 * static_cast<Eigen::Index>(k);
    clones_[k].p += dx.segment<3>(o);
    clones_[k].R = Orthonormalize(ExpSo3(dx.segment<3>(o + 3)) * clones_[k].R);
  }
}

bool PoseEkf::stationary() const {
  return initialized_ && ToSeconds(time_ - last_motion_) >= options_.stationary_delay_s &&
         last_rate_.norm() <= options_.stationary_gyro_threshold;
}

Status PoseEkf::UpdateAccelerometer(Time t, const Eigen::Vector3d& f) {
  if (!initialized_) return FailedPrecondition("EKF: accelerometer sample before Initialize()");
  if (!f.allFinite()) return InvalidArgument("EKF: non-finite accelerometer sample");
  if (!stationary()) return Status::Ok();
  if (std::abs(f.norm() - options_.gravity) > options_.accel_magnitude_tolerance) {
    return Status::Ok();  // accelerating or vibrating: not a gravity measurement
  }
  if (last_accel_update_.has_value() &&
      ToSeconds(t - *last_accel_update_) < options_.accel_update_interval_s) {
    return Status::Ok();
  }
  last_accel_update_ = t;
  const Eigen::Vector3d g(0.0, 0.0, options_.gravity);
  const Eigen::VectorXd r = f - R_.transpose() * g;
  Eigen::MatrixXd h = Eigen::MatrixXd::Zero(3, P_.rows());
  h.block<3, 3>(0, 3) = R_.transpose() * Skew(g);
  const Eigen::MatrixXd noise =
      Eigen::MatrixXd::Identity(3, 3) * options_.accel_noise * options_.accel_noise;
  Update(MotionSource::kAccelerometer, t, r, h, noise, "accelerometer");
  return Status::Ok();
}

Status PoseEkf::UpdateSunSensor(Time t, const Eigen::Vector3d& sun_rover,
                                const Eigen::Vector3d& sun_site) {
  if (!initialized_) return FailedPrecondition("EKF: sun sensor sample before Initialize()");
  if (!sun_rover.allFinite() || !sun_site.allFinite() || sun_rover.norm() < 1e-6 ||
      sun_site.norm() < 1e-6) {
    return InvalidArgument("EKF: sun vectors must be finite and non-zero");
  }
  const Eigen::Vector3d s_site = sun_site.normalized();
  const Eigen::Vector3d s_meas = sun_rover.normalized();
  const Eigen::Vector3d s_pred = R_.transpose() * s_site;
  const Eigen::Vector3d a =
      std::abs(s_pred.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d e1 = s_pred.cross(a).normalized();
  const Eigen::Vector3d e2 = s_pred.cross(e1);
  Eigen::Matrix<double, 2, 3> basis;
  basis.row(0) = e1.transpose();
  basis.row(1) = e2.transpose();
  const Eigen::VectorXd r = basis * (s_meas - s_pred);
  Eigen::MatrixXd h = Eigen::MatrixXd::Zero(2, P_.rows());
  h.block<2, 3>(0, 3) = basis * R_.transpose() * Skew(s_site);
  const Eigen::MatrixXd noise =
      Eigen::MatrixXd::Identity(2, 2) * options_.sun_noise * options_.sun_noise;
  Update(MotionSource::kSunSensor, t, r, h, noise, "sun sensor");
  return Status::Ok();
}

Status PoseEkf::AddRelativePose(const msg::RelativePose& m) {
  if (!initialized_) return FailedPrecondition("EKF: relative pose before Initialize()");
  if (!m.delta.matrix().allFinite() || !m.covariance.allFinite()) {
    return InvalidArgument("EKF: relative pose has a non-finite value");
  }
  if (m.t_to <= m.t_from) {
    return InvalidArgument("EKF: relative pose t_to (" + FormatNumber(m.t_to.seconds()) +
                           " s) must be after t_from (" + FormatNumber(m.t_from.seconds()) + " s)");
  }
  const Eigen::Matrix3d r = m.delta.linear();
  if ((r.transpose() * r - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() > 1e-6 ||
      r.determinant() < 0.0) {
    return InvalidArgument("EKF: relative pose delta rotation is not a rotation matrix");
  }
  if (!SymmetricPositiveDefinite(m.covariance)) {
    return InvalidArgument("EKF: relative pose covariance is not symmetric positive definite");
  }
  const double ahead = ToSeconds(m.t_to - time_);
  if (ahead > options_.max_pending_s) {
    return OutOfRange("EKF: relative pose t_to is " + FormatNumber(ahead) +
                      " s ahead of the filter (max_pending_s " +
                      FormatNumber(options_.max_pending_s) + ")");
  }
  if (ahead > kSameTimeS) {
    if (pending_.size() >= kMaxPending) {
      const msg::RelativePose dropped = pending_.front();
      pending_.pop_front();
      Reject(dropped.source, dropped.t_to,
             std::string(MotionSourceName(dropped.source)) +
                 " relative pose dropped: too many measurements waiting for the filter");
    }
    pending_.push_back(m);
    return Status::Ok();
  }
  ProcessRelativePose(m);
  return Status::Ok();
}

void PoseEkf::ProcessPending() {
  // Measurements are processed in arrival order once the filter has reached their t_to.
  for (auto it = pending_.begin(); it != pending_.end();) {
    if (ToSeconds(it->t_to - time_) <= kSameTimeS) {
      const msg::RelativePose m = *it;
      it = pending_.erase(it);
      ProcessRelativePose(m);
    } else {
      ++it;
    }
  }
}

void PoseEkf::ProcessRelativePose(const msg::RelativePose& m) {
  const std::string what = std::string(MotionSourceName(m.source)) + " relative pose";
  const std::optional<PoseNode> from = Interpolate(m.t_from);
  const std::optional<PoseNode> to = Interpolate(m.t_to);
  if (!from.has_value() || !to.has_value()) {
    Reject(m.source, m.t_to,
           what + " rejected: t_from " + FormatNumber(m.t_from.seconds()) +
               " s is outside the clone window (oldest " +
               (clones_.empty() ? std::string("none") : FormatNumber(clones_.front().t.seconds())) +
               " s, filter at " + FormatNumber(time_.seconds()) + " s)");
    return;
  }
  const Eigen::Matrix3d ri_t = from->R.transpose();
  const Eigen::Vector3d dp_pred = ri_t * (to->p - from->p);
  const Eigen::Matrix3d dr_pred = ri_t * to->R;
  Eigen::VectorXd r(6);
  r.head<3>() = m.delta.translation() - dp_pred;
  r.tail<3>() = LogSo3(m.delta.linear() * dr_pred.transpose());

  // Jacobians with respect to the two pose errors, before distribution over the blocks.
  Eigen::Matrix<double, 6, 6> h_i = Eigen::Matrix<double, 6, 6>::Zero();
  Eigen::Matrix<double, 6, 6> h_j = Eigen::Matrix<double, 6, 6>::Zero();
  h_j.block<3, 3>(0, 0) = ri_t;
  h_i.block<3, 3>(0, 0) = -ri_t;
  h_i.block<3, 3>(0, 3) = ri_t * Skew(to->p - from->p);
  h_j.block<3, 3>(3, 3) = ri_t;
  h_i.block<3, 3>(3, 3) = -ri_t;
  Eigen::MatrixXd h = Eigen::MatrixXd::Zero(6, P_.rows());
  auto add = [&h](const PoseNode& node, const Eigen::Matrix<double, 6, 6>& j) {
    h.middleCols<6>(node.block_a) += (1.0 - node.weight_b) * j;
    if (node.weight_b != 0.0) h.middleCols<6>(node.block_b) += node.weight_b * j;
  };
  add(*from, h_i);
  add(*to, h_j);
  Update(m.source, m.t_to, r, h, m.covariance, what);
}

// ---- outputs ----------------------------------------------------------------------------------

Eigen::Quaterniond PoseEkf::attitude() const {
  Eigen::Quaterniond q(R_);
  q.normalize();
  if (q.w() < 0.0) q.coeffs() *= -1.0;
  return q;
}

PoseEstimate PoseEkf::Estimate() const {
  PoseEstimate e;
  e.stamp = time_;
  e.position = p_;
  e.orientation = attitude();
  e.rpy = geometry::RpyFromRotation(R_);
  Eigen::Matrix3d emap = EulerToSiteRotation(e.rpy);
  if (std::abs(emap.determinant()) < 1e-9) emap.col(0) += Eigen::Vector3d::Constant(1e-9);
  Matrix6d j = Matrix6d::Identity();
  j.block<3, 3>(3, 3) = emap.inverse();
  const Matrix6d pose_cov = P_.topLeftCorner<6, 6>();
  e.covariance = j * pose_cov * j.transpose();
  e.covariance = 0.5 * (e.covariance + e.covariance.transpose()).eval();
  e.stationary = stationary();
  e.velocity = e.stationary ? Eigen::Vector3d::Zero() : velocity_;
  e.gyro_bias = bg_;
  e.rejected_measurements = rejected_;
  e.odometer = odometer_;
  return e;
}

HeadingEstimate PoseEkf::Heading() const {
  const PoseEstimate e = Estimate();
  return {e.stamp, e.rpy.z(), e.covariance(5, 5)};
}

std::vector<EstimatorEvent> PoseEkf::TakeEvents() {
  std::vector<EstimatorEvent> out;
  out.swap(events_);
  return out;
}

// ---- parameters -------------------------------------------------------------------------------

void DeclareEkfParams(ParamSet& params, const std::string& prefix, const EkfOptions& defaults) {
  const EkfOptions& d = defaults;
  auto decl = [&](const char* key, double v, const char* doc, double lo, double hi) {
    params.Declare(prefix + key, v, doc).Range(lo, hi);
  };
  decl("gyro_noise_density", d.gyro_noise_density, "[rad/s/sqrt(Hz)] gyro angle random walk", 0.0,
       1.0);
  decl("gyro_bias_walk", d.gyro_bias_walk, "[rad/s/sqrt(s)] gyro bias random walk", 0.0, 1.0);
  decl("odometry_vertical_variance_per_m", d.odometry_vertical_variance_per_m,
       "[m^2/m] rover-z noise added to wheel odometry steps", 0.0, 1.0);
  decl("gravity", d.gravity, "[m/s^2] local gravity", 0.1, 30.0);
  decl("accel_noise", d.accel_noise, "[m/s^2] accelerometer 1-sigma per axis", 1e-6, 10.0);
  decl("accel_magnitude_tolerance", d.accel_magnitude_tolerance,
       "[m/s^2] allowed | |f| - g | for a gravity update", 1e-4, 10.0);
  decl("accel_update_interval_s", d.accel_update_interval_s,
       "[s] minimum spacing of accelerometer updates", 0.0, 3600.0);
  decl("stationary_delay_s", d.stationary_delay_s,
       "[s] without wheel motion before the rover counts as stationary", 0.0, 3600.0);
  decl("stationary_gyro_threshold", d.stationary_gyro_threshold,
       "[rad/s] bias-corrected rate below which the rover may be at rest", 1e-6, 1.0);
  decl("wheel_motion_threshold", d.wheel_motion_threshold,
       "[m] odometry path per increment that counts as motion", 0.0, 1.0);
  decl("odometer_step", d.odometer_step,
       "[m] the odometer grows in steps of planar displacement of this length (jitter at rest "
       "does not add up)",
       0.0, 10.0);
  decl("sun_noise", d.sun_noise, "[rad] sun vector 1-sigma angular error", 1e-6, 1.0);
  decl("gate_probability", d.gate_probability, "chi-square gate probability", 0.5, 0.999999999);
  decl("clone_interval_s", d.clone_interval_s, "[s] pose clone spacing (0: no clones)", 0.0,
       3600.0);
  decl("clone_window_s", d.clone_window_s, "[s] pose clones kept this long", 0.0, 3600.0);
  decl("max_pending_s", d.max_pending_s, "[s] how far ahead of the filter a relative pose may wait",
       0.0, 3600.0);
}

Result<EkfOptions> EkfOptionsFromParams(const ParamSet& params, const std::string& prefix) {
  ROVER_RETURN_IF_ERROR(params.Validate());
  EkfOptions o;
  auto get = [&](const char* key) { return params.GetDouble(prefix + key); };
  o.gyro_noise_density = get("gyro_noise_density");
  o.gyro_bias_walk = get("gyro_bias_walk");
  o.odometry_vertical_variance_per_m = get("odometry_vertical_variance_per_m");
  o.gravity = get("gravity");
  o.accel_noise = get("accel_noise");
  o.accel_magnitude_tolerance = get("accel_magnitude_tolerance");
  o.accel_update_interval_s = get("accel_update_interval_s");
  o.stationary_delay_s = get("stationary_delay_s");
  o.stationary_gyro_threshold = get("stationary_gyro_threshold");
  o.wheel_motion_threshold = get("wheel_motion_threshold");
  o.odometer_step = get("odometer_step");
  o.sun_noise = get("sun_noise");
  o.gate_probability = get("gate_probability");
  o.clone_interval_s = get("clone_interval_s");
  o.clone_window_s = get("clone_window_s");
  o.max_pending_s = get("max_pending_s");
  if (o.clone_interval_s > 0.0 && o.clone_window_s < o.clone_interval_s) {
    const std::string key = prefix + "clone_window_s";
    return InvalidArgument(params.Origin(key).ToString() + ": key '" + key +
                           "': " + FormatNumber(o.clone_window_s) +
                           " must be >= clone_interval_s " + FormatNumber(o.clone_interval_s));
  }
  ROVER_RETURN_IF_ERROR(o.Validate());
  return o;
}

}  // namespace rover::dl::pose
