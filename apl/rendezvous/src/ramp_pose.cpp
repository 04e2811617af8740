#include "rover/apl/rendezvous/ramp_pose.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Dense>
#include <opencv2/calib3d.hpp>

#include "rover/base/check.hpp"
#include "rover/base/format.hpp"
#include "rover/base/param_binder.hpp"
#include "rover/base/range_check.hpp"

namespace rover::apl::rendezvous {
namespace {

using Mat6 = Eigen::Matrix<double, 6, 6>;
using Vec6 = Eigen::Matrix<double, 6, 1>;

struct Observation {
  int camera = 0;  ///< 0 left, 1 right
  int stripe = 0;
  Eigen::Vector3d p_ramp;  ///< corner in G
  Eigen::Vector2d pixel;
};

Eigen::Matrix3d Hat(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

Eigen::Matrix3d ExpSo3(const Eigen::Vector3d& phi) {
  const double a = phi.norm();
  if (a < 1e-12) return Eigen::Matrix3d::Identity() + Hat(phi);
  return Eigen::AngleAxisd(a, phi / a).toRotationMatrix();
}

/// rover_from_ramp from the left camera's corners by a plane homography (see the file comment).
Result<Eigen::Isometry3d> InitialPose(const std::vector<Observation>& obs,
                                      const geometry::CameraModel& model) {
  std::vector<cv::Point2d> plane, img;
  std::vector<Eigen::Vector3d> dirs;
  Eigen::Vector3d centre = model.Center(), mean_dir = Eigen::Vector3d::Zero();
  for (const auto& o : obs) {
    if (o.camera != 0) continue;
    const auto ray = model.Unproject(o.pixel);
    if (!ray) continue;
    centre = ray->origin;
    dirs.push_back(ray->direction);
    mean_dir += ray->direction;
    plane.emplace_back(o.p_ramp.x(), o.p_ramp.y());
  }
  if (dirs.size() < 4) {
    return FailedPrecondition("ramp pose: " + std::to_string(dirs.size()) +
                              " left-image corners could be unprojected, 4 needed");
  }
  // Virtual pinhole looking along the mean ray.
  const Eigen::Vector3d z = mean_dir.normalized();
  Eigen::Vector3d x = z.unitOrthogonal();
  const Eigen::Vector3d y = z.cross(x);
  x = y.cross(z);
  Eigen::Matrix3d rover_from_cam;
  rover_from_cam << x, y, z;
  for (const auto& d : dirs) {
    const Eigen::Vector3d c = rover_from_cam.transpose() * d;
    img.emplace_back(c.x() / c.z(), c.y() / c.z());
  }
  const cv::Mat h_cv = cv::findHomography(plane, img, 0);
  if (h_cv.empty()) return FailedPrecondition("ramp pose: the corners give no homography");
  Eigen::Matrix3d h;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) h(r, c) = h_cv.at<double>(r, c);
  }
  double lambda = 2.0 / (h.col(0).norm() + h.col(1).norm());
  if (h(2, 2) * lambda < 0) lambda = -lambda;  // the plane origin in front of the camera
  Eigen::Matrix3d r_approx;
  r_approx.col(0) = lambda * h.col(0);
  r_approx.col(1) = lambda * h.col(1);
  r_approx.col(2) = r_approx.col(0).cross(r_approx.col(1));
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(r_approx, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d r = svd.matrixU() * svd.matrixV().transpose();
  if (r.determinant() < 0) {
    Eigen::Matrix3d u = svd.matrixU();
    u.col(2) = -u.col(2);
    r = u * svd.matrixV().transpose();
  }
  const Eigen::Vector3d t = lambda * h.col(2);
  if (!(t.z() > 0) || !r.allFinite()) {
    return FailedPrecondition("ramp pose: the initial pose puts the ramp behind the camera");
  }
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = rover_from_cam * r;
  pose.translation() = centre + rover_from_cam * t;
  return pose;
}

}  // namespace

Status RampPoseOptions::Validate(const char* prefix) const {
  const std::string p(prefix);
  ROVER_RETURN_IF_ERROR(CheckIntRange(p + "min_stripes", min_stripes, 1, hwconfig::kStripesPerRamp));
  ROVER_RETURN_IF_ERROR(CheckIntRange(p + "ramp", ramp, -1, 1));
  ROVER_RETURN_IF_ERROR(CheckIntRange(p + "max_iterations", max_iterations, 1, 1000));
  ROVER_RETURN_IF_ERROR(CheckRange(p + "huber_px", huber_px, Bounds::OpenLow(0.0, 100.0), "px"));
  ROVER_RETURN_IF_ERROR(CheckRange(p + "max_rms_px", max_rms_px, Bounds::OpenLow(0.0, 100.0), "px"));
  ROVER_RETURN_IF_ERROR(CheckRange(p + "stripe_lift", stripe_lift, -0.1, 0.1, "m"));
  return Status::Ok();
}

void RampPoseOptions::BindParams(ParamBinder<RampPoseOptions>& b) {
  using O = RampPoseOptions;
  b.Bind("min_stripes", &O::min_stripes, "", "identified stripes of the ramp needed (left image)");
  b.Bind("ramp", &O::ramp, "", "ramp to estimate (0/1), -1 = the best one seen");
  b.Bind("max_iterations", &O::max_iterations, "", "Levenberg-Marquardt iterations");
  b.Bind("huber_px", &O::huber_px, "px", "Huber threshold on a corner's reprojection error");
  b.Bind("max_rms_px", &O::max_rms_px, "px", "largest accepted rms reprojection error");
  b.Bind("stripe_lift", &O::stripe_lift, "m", "stripes above the ramp surface (paint: 0)");
}

Eigen::Vector3d StripeCornerInRamp(const hwconfig::LanderDescription& lander, int ramp, int index,
                                   int corner, double lift) {
  ROVER_DEMAND(corner >= 0 && corner < 4);
  const hwconfig::StripeLayout s = lander.Stripe(ramp, index);
  const double du = (corner == 0 || corner == 1) ? -0.5 * s.width : 0.5 * s.width;
  const double dv = (corner == 0 || corner == 3) ? 0.5 * s.length : -0.5 * s.length;
  return {s.u + du, dv, lift};
}

Result<RampPose> EstimateRampPose(const hwconfig::LanderDescription& lander,
                                  const StripeDetection& left,
                                  const geometry::CameraModel& left_model,
                                  const StripeDetection* right,
                                  const geometry::CameraModel* right_model,
                                  const RampPoseOptions& options) {
  ROVER_RETURN_IF_ERROR(options.Validate());
  if (right != nullptr && right_model == nullptr) {
    return InvalidArgument("right_model: null with a right detection given");
  }
  const int ramp = options.ramp >= 0 ? options.ramp : left.BestRamp();
  const std::vector<DetectedStripe> left_stripes = ramp >= 0 ? left.OfRamp(ramp) : std::vector<DetectedStripe>{};
  if (static_cast<int>(left_stripes.size()) < options.min_stripes) {
    return FailedPrecondition("ramp pose: " + std::to_string(left_stripes.size()) +
                              " stripes of ramp " + std::to_string(std::max(ramp, 0)) +
                              " identified in the left image, " +
                              std::to_string(options.min_stripes) + " needed" +
                              (left.why.empty() ? "" : " (" + left.why + ")"));
  }
  std::vector<Observation> obs;
  auto add = [&](const std::vector<DetectedStripe>& stripes, int camera) {
    for (const auto& s : stripes) {
      for (int c = 0; c < 4; ++c) {
        if (!s.corner_valid[static_cast<std::size_t>(c)]) continue;
        obs.push_back({camera, s.index, StripeCornerInRamp(lander, ramp, s.index, c, options.stripe_lift),
                       s.corners[static_cast<std::size_t>(c)]});
      }
    }
  };
  add(left_stripes, 0);
  ROVER_ASSIGN_OR_RETURN(Eigen::Isometry3d pose, InitialPose(obs, left_model));
  if (right != nullptr) add(right->OfRamp(ramp), 1);
  const geometry::CameraModel* models[2] = {&left_model, right_model};

  // Levenberg-Marquardt on T <- T Exp(delta).
  auto evaluate = [&](const Eigen::Isometry3d& t, Mat6* jtj, Vec6* jtr, double* rms) {
    double cost = 0.0, sq = 0.0;
    int n = 0;
    if (jtj) jtj->setZero();
    if (jtr) jtr->setZero();
    const Eigen::Matrix3d& r = t.linear();
    for (const auto& o : obs) {
      Eigen::Matrix<double, 2, 3> jp;
      const auto px = models[o.camera]->Project(t * o.p_ramp, &jp);
      if (!px) {
        cost += 1e6;
        continue;
      }
      const Eigen::Vector2d e = *px - o.pixel;
      const double norm = e.norm();
      const double w = norm <= options.huber_px ? 1.0 : options.huber_px / norm;
      cost += norm <= options.huber_px ? norm * norm
                                       : 2.0 * options.huber_px * norm - options.huber_px * options.huber_px;
      sq += e.squaredNorm();
      ++n;
      if (jtj) {
        Eigen::Matrix<double, 3, 6> dp;
        dp.leftCols<3>() = r;
        dp.rightCols<3>() = -r * Hat(o.p_ramp);
        const Eigen::Matrix<double, 2, 6> j = jp * dp;
        *jtj += w * j.transpose() * j;
        *jtr += w * j.transpose() * e;
      }
    }
    if (rms) *rms = n > 0 ? std::sqrt(sq / n) : 0.0;
    return cost;
  };
  double lambda = 1e-3, rms = 0.0;
  Mat6 jtj;
  Vec6 jtr;
  double cost = evaluate(pose, &jtj, &jtr, &rms);
  int it = 0;
  for (; it < options.max_iterations; ++it) {
    Mat6 a = jtj;
    a.diagonal() += lambda * jtj.diagonal().cwiseMax(1e-9);
    const Vec6 delta = -a.ldlt().solve(jtr);
    Eigen::Isometry3d cand = pose;
    cand.translation() += pose.linear() * delta.head<3>();
    cand.linear() = pose.linear() * ExpSo3(delta.tail<3>());
    const double c = evaluate(cand, nullptr, nullptr, nullptr);
    if (c < cost) {
      pose = cand;
      // Re-orthonormalise.
      Eigen::JacobiSVD<Eigen::Matrix3d> svd(pose.linear(), Eigen::ComputeFullU | Eigen::ComputeFullV);
      pose.linear() = svd.matrixU() * svd.matrixV().transpose();
      const double rel = (cost - c) / std::max(cost, 1e-12);
      cost = evaluate(pose, &jtj, &jtr, &rms);
      lambda = std::max(lambda * 0.3, 1e-9);
      if (rel < 1e-10 && delta.norm() < 1e-9) break;
    } else {
      lambda *= 10.0;
      if (lambda > 1e8) break;
    }
  }
  // Covariance from the weighted normal matrix, residual-scaled.
  const int n_res = 2 * static_cast<int>(obs.size());
  double wsq = 0.0;
  for (const auto& o : obs) {
    const auto px = models[o.camera]->Project(pose * o.p_ramp);
    if (!px) continue;
    const double norm = (*px - o.pixel).norm();
    const double w = norm <= options.huber_px ? 1.0 : options.huber_px / norm;
    wsq += w * norm * norm;
  }
  const double sigma2 = n_res > 6 ? wsq / (n_res - 6) : 1.0;
  RampPose out;
  out.ramp = ramp;
  out.rover_from_ramp = pose;
  out.covariance = sigma2 * jtj.inverse();
  out.rms_px = rms;
  out.corners_used = static_cast<int>(obs.size());
  std::set<int> used;
  for (const auto& o : obs) used.insert(o.stripe);
  out.stripes_used = static_cast<int>(used.size());
  out.iterations = it;
  if (!(rms <= options.max_rms_px)) {
    return FailedPrecondition("ramp pose: rms reprojection error " + FormatNumber(rms, 3) +
                              " px over " + std::to_string(obs.size()) + " corners exceeds " +
                              "max_rms_px " + FormatNumber(options.max_rms_px));
  }
  return out;
}

Result<RampBase> RampBaseInRover(const hwconfig::LanderDescription& lander, const RampPose& pose,
                                 const Eigen::Vector3d& up_in_rover) {
  if (!up_in_rover.allFinite() || up_in_rover.norm() < 1e-9) {
    return InvalidArgument("up_in_rover: (" + FormatNumber(up_in_rover.x()) + ", " +
                           FormatNumber(up_in_rover.y()) + ", " + FormatNumber(up_in_rover.z()) +
                           ") is not a direction");
  }
  const Eigen::Vector3d up = up_in_rover.normalized();
  const Eigen::Vector3d u = pose.rover_from_ramp.linear().col(0);
  const double s = std::clamp(u.dot(up), -1.0, 1.0);
  const double incl = std::asin(s);
  if (std::abs(incl) >= 80.0 * M_PI / 180.0) {
    return FailedPrecondition("ramp pose: ramp inclined " + FormatNumber(incl * 180.0 / M_PI, 3) +
                              " deg against up_in_rover");
  }
  RampBase b;
  b.inclination = incl;
  b.slope_length = lander.ramp_length / std::cos(incl);
  b.base_in_rover = pose.rover_from_ramp * Eigen::Vector3d(-0.5 * b.slope_length, 0.0, 0.0);
  b.up_axis_in_rover = (u - s * up).normalized();
  return b;
}

}  // namespace rover::apl::rendezvous
