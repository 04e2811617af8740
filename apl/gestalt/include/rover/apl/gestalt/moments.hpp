#pragma once
/// @file
/// First and second moments of a set of 3-D points and the plane fitted to them (GESTALT's cell
/// statistics, seed 002: no matter how many points fall in a cell only ten numbers are kept).
///
/// Moments: n, Σx, Σy, Σz, Σx², Σy², Σz², Σxy, Σxz, Σyz. They add: the moments of a union of
/// point sets are the sums of their moments, so a disc of cells is fitted from the sum of its
/// cells' moments without revisiting a point.
///
/// Plane fit (total least squares): mean m = Σp / n, covariance C = Σ p pᵀ / n - m mᵀ with
/// eigenvalues λ0 <= λ1 <= λ2 and unit eigenvectors v0, v1, v2. The plane passes through m with
/// normal v0 (sign chosen so that v0.z >= 0, i.e. pointing up); it minimises the sum of squared
/// distances along the normal, whose RMS is the residual r = sqrt(λ0). Tilt = acos(v0.z) is the
/// angle between the normal and the site frame's up axis. The fit is planar when
/// λ1 >= ratio · λ0 (seed 002's eigen-ratio test: the points spread in two directions more than
/// across the plane).
///
/// Coordinates are whatever frame the points were added in (GESTALT: site frame minus a fixed
/// origin near the rover, metres); doubles keep the sums exact enough for thousands of points
/// tens of metres from that origin.

#include <Eigen/Core>

namespace rover::apl::gestalt {

struct Moments {
  double n = 0.0;
  double sx = 0.0, sy = 0.0, sz = 0.0;
  double sxx = 0.0, syy = 0.0, szz = 0.0;
  double sxy = 0.0, sxz = 0.0, syz = 0.0;

  void Add(double x, double y, double z) {
    n += 1.0;
    sx += x;
    sy += y;
    sz += z;
    sxx += x * x;
    syy += y * y;
    szz += z * z;
    sxy += x * y;
    sxz += x * z;
    syz += y * z;
  }
  void Add(const Eigen::Vector3d& p) { Add(p.x(), p.y(), p.z()); }
  Moments& operator+=(const Moments& o);
  Moments& operator-=(const Moments& o);
  friend Moments operator+(Moments a, const Moments& b) { return a += b; }
  friend Moments operator-(Moments a, const Moments& b) { return a -= b; }

  bool empty() const { return n <= 0.0; }
  /// Preconditions: !empty().
  Eigen::Vector3d Mean() const { return Eigen::Vector3d(sx, sy, sz) / n; }
  /// Population covariance Σ p pᵀ / n - m mᵀ. Preconditions: !empty().
  Eigen::Matrix3d Covariance() const;
  /// [m] standard deviation of z, sqrt(max(0, Σz²/n - (Σz/n)²)). Preconditions: !empty().
  double StdDevZ() const;
};

struct PlaneFit {
  bool ok = false;      ///< at least 3 points and a well-defined smallest eigenvector
  bool planar = false;  ///< λ1 >= eigen_ratio · λ0
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();      ///< unit, normal.z >= 0
  Eigen::Vector3d eigenvalues = Eigen::Vector3d::Zero();  ///< λ0 <= λ1 <= λ2 [m²]
  double residual = 0.0;  ///< [m] sqrt(λ0), RMS distance of the points to the plane
  double tilt = 0.0;      ///< [rad] acos(normal.z)

  /// [m] z of the plane above (x, y). Preconditions: ok and normal.z > 0.
  double HeightAt(double x, double y) const {
    return centroid.z() -
           (normal.x() * (x - centroid.x()) + normal.y() * (y - centroid.y())) / normal.z();
  }
};

/// Fits a plane to the points summarised by `m` (see the file comment).
PlaneFit FitPlane(const Moments& m, double eigen_ratio);

}  // namespace rover::apl::gestalt
