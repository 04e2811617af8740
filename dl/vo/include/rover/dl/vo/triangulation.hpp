#pragma once
/// @file
/// Stereo triangulation with a 3D covariance per point (Matthies & Shafer 1987 error model, as
/// used by MER visual odometry).
///
/// Each matched pixel defines a ray from its camera centre: left c_l = 0, r_l = Ray(u_l);
/// right c_r = (b, 0, 0), r_r = Ray(u_r). The point is the midpoint of the shortest segment
/// between the two rays ("ray gap"): with w = c_l - c_r, a = r_l.r_l, b = r_l.r_r, c = r_r.r_r,
/// d = r_l.w, e = r_r.w,
///   s = (b e - c d) / (a c - b^2),  t = (a e - b d) / (a c - b^2),
///   X = (c_l + s r_l + c_r + t r_r) / 2,   gap = |c_l + s r_l - c_r - t r_r|.
/// The covariance propagates independent pixel noise sigma on (u_l, v_l, u_r, v_r) through the
/// Jacobian J = dX/d(u_l, v_l, u_r, v_r) (central differences): Sigma = sigma^2 J J^T. Its long
/// axis points along the viewing ray and grows with range^2 / (f b).

#include <Eigen/Core>
#include <optional>

#include "rover/dl/vo/stereo_camera.hpp"

namespace rover::dl::vo {

struct StereoPoint {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();    ///< [m] left camera frame
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();  ///< [m^2]
  double ray_gap = 0.0;                                  ///< [m] gap between the two rays
};

/// Midpoint of closest approach of rays c1 + s r1 and c2 + t r2 (s, t > 0). Returns nullopt for
/// parallel or diverging rays or a point behind either camera. `gap` (optional) receives the
/// ray gap [m].
std::optional<Eigen::Vector3d> RayMidpoint(const Eigen::Vector3d& c1, const Eigen::Vector3d& r1,
                                           const Eigen::Vector3d& c2, const Eigen::Vector3d& r2,
                                           double* gap = nullptr);

/// Triangulates a left/right pixel pair of a rectified stereo camera and propagates
/// `pixel_sigma` [px] (1 sigma per image coordinate) into the 3D covariance. Returns nullopt if
/// the disparity is not positive or the geometry is degenerate.
std::optional<StereoPoint> TriangulateStereo(const StereoCamera& camera,
                                             const Eigen::Vector2d& left_px,
                                             const Eigen::Vector2d& right_px, double pixel_sigma);

}  // namespace rover::dl::vo
