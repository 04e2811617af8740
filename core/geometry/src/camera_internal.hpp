#pragma once
// Private helpers shared by the camera-model sources. Not part of the public API.

#include <optional>
#include <vector>

#include <Eigen/Core>

#include "rover/geometry/camera_model.hpp"

namespace rover::geometry::internal {

/// g(t) = t (c0 + c1 t^2 + c2 t^4 + c3 t^6), the radial map of CAHVOR/CAHVORE (c0 = 1 + r0,
/// c1 = r1, c2 = r2, c3 = 0, t = tangent resp. chi) and of the Brown model (c0 = 1, k1, k2, k3,
/// t = normalised radius). Requires c0 > 0, so g increases from t = 0 up to `fold`, the first
/// t > 0 with g'(t) = 0 (+infinity if none below 1e4).
struct OddPolynomial {
  double c0 = 1.0;
  double c1 = 0.0;
  double c2 = 0.0;
  double c3 = 0.0;
  double fold = 0.0;

  double Value(double t) const;
  double Derivative(double t) const;
  /// The t in [0, fold) with g(t) = target >= 0; nullopt if target >= g(fold) or not finite.
  std::optional<double> Invert(double target) const;
};

OddPolynomial MakeOddPolynomial(double c0, double c1, double c2, double c3);

/// The polynomial of a model's radial distortion (identity for CAHV), computing its fold.
OddPolynomial RadialPolynomialOf(const CameraModel::Variant& model);
/// As above with a known fold (cheap).
OddPolynomial RadialPolynomialOf(const CameraModel::Variant& model, double fold);

/// Direction d of the CAHV ray through `pixel`, scaled so that d.A = 1 (any |A|).
Eigen::Vector3d CahvRayDirection(const Eigen::Vector3d& a, const Eigen::Vector3d& h,
                                 const Eigen::Vector3d& v, const Eigen::Vector2d& pixel);

/// The linear (pinhole) part of any model: centre, orthonormal camera axes in the reference
/// frame (x right, y down, z forward; for JPL models z = A/|A| and x, y = H', V' made orthogonal
/// symmetrically) and fx, fy, cx, cy of the pinhole that best matches the C, A, H, V part
/// (exact if theta = pi/2). `theta` as in Intrinsics (pi/2 for pinholes).
struct LinearPart {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();  // columns x, y, z
  double fx = 0.0;
  double fy = 0.0;
  double cx = 0.0;
  double cy = 0.0;
  double theta = 0.0;
};
LinearPart LinearPartOf(const CameraModel& model);

/// Pixel grid over the image: `cols` x `rows` pixel centres from (0, 0) to (w - 1, h - 1).
std::vector<Eigen::Vector2d> PixelGrid(int width, int height, int cols, int rows);

}  // namespace rover::geometry::internal
