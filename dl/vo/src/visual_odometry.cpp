#include "rover/dl/vo/visual_odometry.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "rover/base/check.hpp"
#include "rover/base/format.hpp"
#include "rover/dl/vo/triangulation.hpp"

namespace rover::dl::vo {

const char* MotionStatusName(MotionStatus status) {
  switch (status) {
    case MotionStatus::kConverged:
      return "converged";
    case MotionStatus::kTooFewFeatures:
      return "too_few_features";
    case MotionStatus::kLimitsFailed:
      return "limits_failed";
    case MotionStatus::kNotConverged:
      return "not_converged";
    case MotionStatus::kBadInput:
      return "bad_input";
    case MotionStatus::kNoReference:
      return "no_reference";
  }
  return "unknown";
}

namespace {

bool FinitePositive(double v) { return std::isfinite(v) && v > 0.0; }

}  // namespace

void Options::BindParams(ParamBinder<Options>& b) {
  b.Bind("pixel_sigma", &Options::pixel_sigma, "px", "1-sigma matching noise in the covariance")
      .Range(0.01, 10.0);
  b.Bind("min_range", &Options::min_range, "m", "nearer features are dropped").Range(0.05, 100.0);
  b.Bind("max_range", &Options::max_range, "m", "farther features are dropped").Range(0.1, 1000.0);
  b.Nest("", &Options::interest);
  b.Bind("min_features", &Options::min_features, "", "tracked features needed").Range(3, 10000);
  b.Bind("min_inliers", &Options::min_inliers, "", "RANSAC/ML inliers needed").Range(3, 10000);
  b.Bind("min_inlier_fraction", &Options::min_inlier_fraction, "", "inliers / tracked, at least")
      .Range(0.0, 1.0);
  b.Bind("max_translation", &Options::max_translation, "m", "of one step, at most (sanity limit)")
      .Range(0.01, 10.0);
  b.BindDegrees("max_rotation_deg", &Options::max_rotation, "of one step, at most (sanity limit)")
      .Range(0.1, 90.0);
  b.Bind("max_prior_mahalanobis_sq", &Options::max_prior_mahalanobis_sq, "",
         "gate on the estimate's distance from the odometry prior; 0 = off")
      .Range(0.0, 1e6);
}

Status Options::Validate() const {
  ROVER_RETURN_IF_ERROR(interest.Validate());
  ROVER_RETURN_IF_ERROR(match.Validate());
  ROVER_RETURN_IF_ERROR(ransac.Validate());
  ROVER_RETURN_IF_ERROR(refine.Validate());
  if (!FinitePositive(pixel_sigma)) return InvalidArgument("pixel_sigma must be finite and > 0");
  if (!FinitePositive(min_range) || !FinitePositive(max_range) || max_range <= min_range) {
    return InvalidArgument("range limits [" + FormatNumber(min_range) + ", " +
                           FormatNumber(max_range) + "] m must satisfy 0 < min_range < max_range");
  }
  if (!FinitePositive(window_sigmas)) return InvalidArgument("window_sigmas must be > 0");
  if (!FinitePositive(min_window) || !FinitePositive(max_window) || max_window < min_window) {
    return InvalidArgument("search windows must satisfy 0 < min_window <= max_window");
  }
  if (!FinitePositive(refine_window_threshold)) {
    return InvalidArgument("refine_window_threshold must be > 0");
  }
  if (first_pass_features < 3) return InvalidArgument("first_pass_features must be >= 3");
  if (plane_neighbours < 0 || plane_neighbours == 1 || plane_neighbours == 2) {
    return InvalidArgument("plane_neighbours must be 0 or >= 3");
  }
  if (min_features < 3) return InvalidArgument("min_features must be >= 3");
  if (min_inliers < 3) return InvalidArgument("min_inliers must be >= 3");
  if (!std::isfinite(min_inlier_fraction) || min_inlier_fraction < 0.0 ||
      min_inlier_fraction > 1.0) {
    return InvalidArgument("min_inlier_fraction must be in [0, 1]");
  }
  if (!FinitePositive(max_translation)) return InvalidArgument("max_translation must be > 0");
  if (!FinitePositive(max_rotation) || max_rotation > std::numbers::pi) {
    return InvalidArgument("max_rotation must be in (0, pi] rad");
  }
  if (!std::isfinite(model_translation_fraction) || model_translation_fraction < 0.0 ||
      model_translation_fraction > 1.0) {
    return InvalidArgument("model_translation_fraction must be in [0, 1]");
  }
  if (!std::isfinite(max_prior_mahalanobis_sq) || max_prior_mahalanobis_sq < 0.0) {
    return InvalidArgument("max_prior_mahalanobis_sq must be finite and >= 0");
  }
  return Status::Ok();
}

Options Options::Automotive() {
  Options o;
  o.interest.cell_size = 24;
  o.interest.min_separation = 12;
  o.match.max_disparity = 128;
  o.match.pyramid_levels = 4;
  o.min_range = 1.0;
  o.max_range = 80.0;
  o.max_window = 160.0;
  o.max_translation = 4.0;
  o.max_rotation = 0.35;
  o.model_translation_fraction = 0.008;
  return o;
}

MotionPrior MotionPrior::Stationary(double sigma_translation, double sigma_rotation) {
  MotionPrior p;
  p.covariance.setZero();
  p.covariance.diagonal() << Eigen::Vector3d::Constant(sigma_translation * sigma_translation),
      Eigen::Vector3d::Constant(sigma_rotation * sigma_rotation);
  return p;
}

Result<VisualOdometry> VisualOdometry::Create(const Options& options, const StereoCamera& camera) {
  if (Status s = options.Validate(); !s.ok()) return s.WithPrefix("vo options");
  if (Status s = camera.Validate(); !s.ok()) return s;
  const int min_size = 2 * (options.match.template_radius + options.interest.border) + 8;
  if (camera.width < min_size || camera.height < min_size) {
    return InvalidArgument("StereoCamera: image size " + std::to_string(camera.width) + "x" +
                           std::to_string(camera.height) + " is too small (at least " +
                           std::to_string(min_size) + " px per side)");
  }
  return VisualOdometry(options, camera);
}

MotionEstimate ToBodyFrame(const MotionEstimate& estimate, const Eigen::Isometry3d& t_b_c) {
  MotionEstimate out = estimate;
  ChangeMotionFrame(estimate.delta, estimate.covariance, t_b_c, &out.delta, &out.covariance);
  return out;
}

MotionPrior ToCameraFrame(const MotionPrior& body_prior, const Eigen::Isometry3d& t_b_c) {
  MotionPrior out;
  ChangeMotionFrame(body_prior.delta, body_prior.covariance, t_b_c.inverse(), &out.delta,
                    &out.covariance);
  return out;
}

void VisualOdometry::Reset() {
  steps_ = 0;
  has_reference_ = false;
  reference_ = Reference{};
  last_tracks_.clear();
}

Status VisualOdometry::CheckFrame(const StereoFrame& frame) const {
  for (const auto* side : {"left", "right"}) {
    const cv::Mat& img = side[0] == 'l' ? frame.left : frame.right;
    if (img.empty()) return InvalidArgument(std::string(side) + " image is empty");
    if (img.type() != CV_8UC1) {
      return InvalidArgument(std::string(side) + " image has OpenCV type " +
                             std::to_string(img.type()) + "; expected CV_8UC1 (8-bit grey)");
    }
    if (img.cols != camera_.width || img.rows != camera_.height) {
      return InvalidArgument(std::string(side) + " image is " + FormatSize(img.cols, img.rows) +
                             "; the camera is " + FormatSize(camera_.width, camera_.height));
    }
  }
  if (has_reference_ && frame.stamp <= reference_.stamp) {
    return FailedPrecondition("stereo pair stamped " + FormatNumber(frame.stamp.seconds()) +
                              " s is not after the reference pair (" +
                              FormatNumber(reference_.stamp.seconds()) +
                              " s): pairs out of time order");
  }
  return Status::Ok();
}

namespace {

Status CheckPrior(const MotionPrior& prior) {
  if (!prior.delta.matrix().allFinite()) return InvalidArgument("prior.delta is not finite");
  const Eigen::Matrix3d r = prior.delta.linear();
  if ((r.transpose() * r - Eigen::Matrix3d::Identity()).norm() > 1e-6 || r.determinant() < 0.0) {
    return InvalidArgument("prior.delta rotation is not a rotation matrix");
  }
  if (!prior.covariance.allFinite()) return InvalidArgument("prior.covariance is not finite");
  if ((prior.covariance - prior.covariance.transpose()).norm() >
      1e-9 * std::max(1.0, prior.covariance.norm())) {
    return InvalidArgument("prior.covariance is not symmetric");
  }
  const Eigen::SelfAdjointEigenSolver<Matrix6d> es(prior.covariance);
  if (es.eigenvalues().minCoeff() < -1e-12 * std::max(1.0, es.eigenvalues().maxCoeff())) {
    return InvalidArgument("prior.covariance is not positive semi-definite");
  }
  return Status::Ok();
}

}  // namespace

Result<MotionEstimate> VisualOdometry::Process(const StereoFrame& frame, const MotionPrior& prior) {
  if (Status s = CheckFrame(frame); !s.ok()) return s;
  if (Status s = CheckPrior(prior); !s.ok()) return s;
  ImagePyramid left(frame.left, options_.match.pyramid_levels);
  const CorrelationImage right(frame.right);
  MotionEstimate est;
  est.t_to = frame.stamp;
  if (has_reference_) {
    est = EstimateMotion(reference_, left, right, prior);
    est.t_from = reference_.stamp;
    est.t_to = frame.stamp;
  } else {
    est.status = MotionStatus::kNoReference;
    est.t_from = frame.stamp;
    est.delta = prior.delta;
    est.covariance = prior.covariance;
    est.message = "first stereo pair: stored as the reference";
    last_tracks_.clear();
  }
  reference_ = BuildReference(frame, std::move(left), right);
  has_reference_ = true;
  ++steps_;
  return est;
}

VisualOdometry::Reference VisualOdometry::BuildReference(const StereoFrame& frame,
                                                         ImagePyramid left,
                                                         const CorrelationImage& right) const {
  Reference ref;
  ref.stamp = frame.stamp;
  InterestOptions io = options_.interest;
  io.border = std::max(io.border, options_.match.template_radius + 1);
  const std::vector<InterestPoint> points = DetectInterestPoints(frame.left, io);
  ref.selected = static_cast<int>(points.size());
  for (const InterestPoint& p : points) {
    const Eigen::Vector2d px(p.x, p.y);
    const StereoMatch sm = MatchStereo(left.level(0), right, px, options_.match);
    if (!sm.ok) continue;
    const auto x = TriangulateStereo(camera_, px, sm.right, options_.pixel_sigma);
    if (!x || x->position.z() < options_.min_range || x->position.z() > options_.max_range) {
      continue;
    }
    ref.features.push_back(Feature{px, x->position, x->covariance, p.strength, {0, 0, 1}});
  }
  if (options_.warp_templates && options_.plane_neighbours >= 3) EstimateNormals(&ref.features);
  ref.left = std::move(left);
  return ref;
}

void VisualOdometry::EstimateNormals(std::vector<Feature>* features) const {
  // Local plane through each feature and its nearest neighbours in the image whose range is
  // within 20 % of its own (so that a rock's edge does not borrow the ground behind it).
  const int k = options_.plane_neighbours;
  std::vector<std::pair<double, int>> near;
  for (std::size_t i = 0; i < features->size(); ++i) {
    Feature& f = (*features)[i];
    near.clear();
    for (std::size_t j = 0; j < features->size(); ++j) {
      if (j == i) continue;
      const Feature& g = (*features)[j];
      if (std::abs(g.position.z() - f.position.z()) > 0.2 * f.position.z()) continue;
      near.emplace_back((g.left - f.left).squaredNorm(), static_cast<int>(j));
    }
    if (static_cast<int>(near.size()) < k) continue;
    std::partial_sort(near.begin(), near.begin() + k, near.end());
    Eigen::Vector3d mean = f.position;
    for (int n = 0; n < k; ++n)
      mean += (*features)[static_cast<std::size_t>(near[n].second)].position;
    mean /= k + 1;
    Eigen::Matrix3d scatter = (f.position - mean) * (f.position - mean).transpose();
    for (int n = 0; n < k; ++n) {
      const Eigen::Vector3d d =
          (*features)[static_cast<std::size_t>(near[n].second)].position - mean;
      scatter += d * d.transpose();
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(scatter);
    const Eigen::Vector3d ev = es.eigenvalues();  // ascending
    // Planar (thin along the normal) and spread in two directions; the normal must not be
    // almost perpendicular to the viewing ray.
    if (!(ev(0) < 0.05 * ev(1)) || !(ev(1) > 1e-6)) continue;
    const Eigen::Vector3d n = es.eigenvectors().col(0);
    if (std::abs(n.dot(f.position.normalized())) < 0.2) continue;
    f.normal = n;
  }
}

namespace {

struct Candidate {
  int feature = 0;
  TrackRequest request;
};

struct TrackedSet {
  std::vector<Correspondence> points;
  std::vector<FeatureTrack> tracks;
};

struct Solve {
  bool ok = false;
  MotionStatus status = MotionStatus::kNotConverged;
  std::string message;
  Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
  Matrix6d covariance = Matrix6d::Zero();
  std::vector<int> inliers;
  int ransac_iterations = 0;
  int refine_iterations = 0;
  double cost_per_dof = 0.0;
};

double Median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

}  // namespace

MotionEstimate VisualOdometry::EstimateMotion(const Reference& from, const ImagePyramid& left,
                                              const CorrelationImage& right,
                                              const MotionPrior& prior) {
  MotionEstimate est;
  est.features_selected = from.selected;
  est.features_stereo = static_cast<int>(from.features.size());
  est.delta = prior.delta;
  est.covariance = prior.covariance;
  last_tracks_.clear();
  auto fail = [&est](MotionStatus s, std::string msg) {
    est.status = s;
    est.message = std::move(msg);
    return est;
  };
  const Options& o = options_;
  if (est.features_stereo < o.min_features) {
    return fail(MotionStatus::kTooFewFeatures,
                std::to_string(est.features_stereo) + " of " + std::to_string(from.selected) +
                    " interest points have stereo in the reference pair (need " +
                    std::to_string(o.min_features) + ")");
  }
  const double margin = o.match.template_radius + 1.0;

  // Predicts every feature under motion (t, cov); features outside the image or needing a too
  // large search window are left out.
  auto predict = [&](const Eigen::Isometry3d& t, const Matrix6d& cov) {
    std::vector<Candidate> out;
    const Eigen::Matrix3d rt = t.linear().transpose();
    for (std::size_t i = 0; i < from.features.size(); ++i) {
      const Feature& f = from.features[i];
      const Eigen::Vector3d rel = f.position - t.translation();
      const Eigen::Vector3d q = rt * rel;
      if (q.z() < o.min_range) continue;
      const Eigen::Vector2d u = camera_.ProjectLeft(q);
      if (!camera_.Inside(u, margin)) continue;
      Eigen::Matrix<double, 3, 6> jp;
      jp.leftCols<3>() = -rt;
      jp.rightCols<3>() = rt * Skew(rel);
      const Eigen::Matrix3d s3 = jp * cov * jp.transpose() + rt * f.covariance * rt.transpose();
      const Eigen::Matrix<double, 2, 3> ju = camera_.ProjectLeftJacobian(q);
      const Eigen::Matrix2d su = ju * s3 * ju.transpose();
      Candidate c;
      c.feature = static_cast<int>(i);
      c.request.from = f.left;
      c.request.predicted = u;
      c.request.half_window = Eigen::Vector2d(
          std::clamp(o.window_sigmas * std::sqrt(su(0, 0)), o.min_window, o.max_window),
          std::clamp(o.window_sigmas * std::sqrt(su(1, 1)), o.min_window, o.max_window));
      if (o.warp_templates) {
        // Image motion of the local plane n^T X = n^T P: X(u) = z(u) r(u) with r = Ray(u), so
        //   dX/du = z (I - r n^T / (n^T r)) dr/du,   dr/du = [1/fx 0; 0 1/fy; 0 0],
        //   A = d(u_new)/d(u_old) = J_proj(q) R^T dX/du.
        const Eigen::Vector3d r = f.position / f.position.z();
        Eigen::Matrix<double, 3, 2> dray = Eigen::Matrix<double, 3, 2>::Zero();
        dray(0, 0) = 1.0 / camera_.fx;
        dray(1, 1) = 1.0 / camera_.fy;
        const Eigen::Matrix3d proj =
            Eigen::Matrix3d::Identity() - r * f.normal.transpose() / f.normal.dot(r);
        c.request.warp = ju * rt * (f.position.z() * proj * dray);
      }
      out.push_back(c);
    }
    return out;
  };

  auto track = [&](const std::vector<Candidate>& cands) {
    TrackedSet set;
    for (const Candidate& c : cands) {
      const TrackMatch tm = TrackFeature(from.left, left, c.request, o.match);
      if (!tm.ok || !camera_.Inside(tm.to, margin)) continue;
      const StereoMatch sm = MatchStereo(left.level(0), right, tm.to, o.match);
      if (!sm.ok) continue;
      const auto x = TriangulateStereo(camera_, tm.to, sm.right, o.pixel_sigma);
      if (!x || x->position.z() < o.min_range || x->position.z() > o.max_range) continue;
      const Feature& f = from.features[static_cast<std::size_t>(c.feature)];
      set.points.push_back(Correspondence{f.position, f.covariance, x->position, x->covariance});
      set.tracks.push_back(FeatureTrack{f.left, tm.to, sm.right, false});
    }
    return set;
  };

  const std::uint64_t seed = o.ransac.seed ^ (0x9E3779B97F4A7C15ULL * (steps_ + 1));
  auto solve = [&](const std::vector<Correspondence>& pts, int min_inliers) {
    Solve s;
    RansacOptions ro = o.ransac;
    ro.seed = seed;
    const RansacResult rr = RansacRigidMotion(pts, ro);
    s.ransac_iterations = rr.iterations;
    if (!rr.ok || static_cast<int>(rr.inliers.size()) < min_inliers) {
      s.status = MotionStatus::kTooFewFeatures;
      s.message = "RANSAC found " + std::to_string(rr.inliers.size()) + " inliers among " +
                  std::to_string(pts.size()) + " tracked features (need " +
                  std::to_string(min_inliers) + ")";
      return s;
    }
    if (static_cast<double>(rr.inliers.size()) < o.min_inlier_fraction * pts.size()) {
      s.status = MotionStatus::kNotConverged;
      s.message = "no RANSAC consensus: " + std::to_string(rr.inliers.size()) + " of " +
                  std::to_string(pts.size()) + " features agree";
      return s;
    }
    RefineResult ml = RefineMaximumLikelihood(pts, rr.inliers, rr.motion, o.refine);
    s.refine_iterations = ml.iterations;
    std::vector<int> inliers = rr.inliers;
    if (ml.converged) {
      // Re-select the inliers under the ML motion and refine once more.
      std::vector<int> again;
      for (std::size_t i = 0; i < pts.size(); ++i) {
        if (MahalanobisSq(pts[i], ml.motion) < o.ransac.inlier_chi2) {
          again.push_back(static_cast<int>(i));
        }
      }
      if (static_cast<int>(again.size()) >= min_inliers && again != inliers) {
        RefineResult ml2 = RefineMaximumLikelihood(pts, again, ml.motion, o.refine);
        s.refine_iterations += ml2.iterations;
        if (ml2.converged) {
          ml = ml2;
          inliers = again;
        }
      }
    }
    if (!ml.converged) {
      s.status = MotionStatus::kNotConverged;
      s.message = "maximum-likelihood refinement did not converge in " +
                  std::to_string(o.refine.max_iterations) + " iterations (or is degenerate)";
      return s;
    }
    const double dof = std::max(1.0, 3.0 * static_cast<double>(inliers.size()) - 6.0);
    s.cost_per_dof = ml.cost / dof;
    s.covariance = ml.covariance;
    if (o.scale_covariance_by_residual && s.cost_per_dof > 1.0) s.covariance *= s.cost_per_dof;
    const double model_sigma = o.model_translation_fraction * ml.motion.translation().norm();
    s.covariance.topLeftCorner<3, 3>() += model_sigma * model_sigma * Eigen::Matrix3d::Identity();
    s.ok = true;
    s.status = MotionStatus::kConverged;
    s.motion = ml.motion;
    s.inliers = std::move(inliers);
    return s;
  };

  std::vector<Candidate> cands = predict(prior.delta, prior.covariance);
  if (static_cast<int>(cands.size()) < o.min_features) {
    return fail(MotionStatus::kTooFewFeatures,
                std::to_string(cands.size()) +
                    " features are predicted inside the new image (need " +
                    std::to_string(o.min_features) + ")");
  }
  std::vector<double> windows;
  windows.reserve(cands.size());
  for (const Candidate& c : cands) windows.push_back(c.request.half_window.maxCoeff());
  if (Median(windows) > o.refine_window_threshold) {
    // First pass: a spatially spread subset, the smallest window in each cell of a coarse grid.
    const double aspect = static_cast<double>(camera_.width) / camera_.height;
    const int gx =
        std::max(1, static_cast<int>(std::lround(std::sqrt(o.first_pass_features * aspect))));
    const int gy = std::max(1, (o.first_pass_features + gx - 1) / gx);
    std::vector<int> best(static_cast<std::size_t>(gx * gy), -1);
    for (std::size_t i = 0; i < cands.size(); ++i) {
      const Eigen::Vector2d& u = cands[i].request.from;
      const int cx = std::min(gx - 1, static_cast<int>(u.x() * gx / camera_.width));
      const int cy = std::min(gy - 1, static_cast<int>(u.y() * gy / camera_.height));
      int& b = best[static_cast<std::size_t>(cy * gx + cx)];
      if (b < 0 || windows[i] < windows[static_cast<std::size_t>(b)]) b = static_cast<int>(i);
    }
    std::vector<Candidate> subset;
    for (int b : best) {
      if (b >= 0) subset.push_back(cands[static_cast<std::size_t>(b)]);
    }
    const TrackedSet first = track(subset);
    const Solve s1 = solve(first.points, std::max(5, o.min_inliers / 2));
    if (s1.ok) {
      est.first_pass = true;
      // Inflate the first-pass covariance: it comes from few features.
      cands = predict(s1.motion, 4.0 * s1.covariance);
    }
  }

  const TrackedSet set = track(cands);
  est.features_tracked = static_cast<int>(set.points.size());
  last_tracks_ = set.tracks;
  if (est.features_tracked < o.min_features) {
    return fail(MotionStatus::kTooFewFeatures, std::to_string(est.features_tracked) +
                                                   " features tracked with stereo (need " +
                                                   std::to_string(o.min_features) + ")");
  }
  const Solve s = solve(set.points, o.min_inliers);
  est.ransac_iterations = s.ransac_iterations;
  est.refine_iterations = s.refine_iterations;
  est.inliers = static_cast<int>(s.inliers.size());
  if (!s.ok) return fail(s.status, s.message);
  for (int i : s.inliers) last_tracks_[static_cast<std::size_t>(i)].inlier = true;
  est.cost_per_dof = s.cost_per_dof;

  const double dist = s.motion.translation().norm();
  const double angle = RotationAngle(s.motion.linear());
  if (dist > o.max_translation) {
    return fail(MotionStatus::kLimitsFailed, "translation " + FormatNumber(dist) +
                                                 " m exceeds max_translation " +
                                                 FormatNumber(o.max_translation) + " m");
  }
  if (angle > o.max_rotation) {
    return fail(MotionStatus::kLimitsFailed, "rotation " + FormatNumber(angle) +
                                                 " rad exceeds max_rotation " +
                                                 FormatNumber(o.max_rotation) + " rad");
  }
  if (o.max_prior_mahalanobis_sq > 0.0) {
    const Vector6d e = MotionError(prior.delta, s.motion);
    const Matrix6d c = prior.covariance + s.covariance;
    const Eigen::LDLT<Matrix6d> ldlt(c);
    const double d2 = e.dot(ldlt.solve(e));
    if (!(d2 <= o.max_prior_mahalanobis_sq)) {
      return fail(MotionStatus::kLimitsFailed, "estimate is " + FormatNumber(d2) +
                                                   " (Mahalanobis^2) from the prior; limit " +
                                                   FormatNumber(o.max_prior_mahalanobis_sq));
    }
  }
  est.status = MotionStatus::kConverged;
  est.delta = s.motion;
  est.covariance = s.covariance;
  est.message.clear();
  return est;
}

}  // namespace rover::dl::vo
