#include "rover/dl/vo/stereo_camera.hpp"

#include <cmath>
#include <string>

namespace rover::dl::vo {
namespace {

bool Finite(double v) { return std::isfinite(v); }

}  // namespace

Status StereoCamera::Validate() const {
  if (width <= 0 || height <= 0) {
    return InvalidArgument("StereoCamera: image size " + std::to_string(width) + "x" +
                           std::to_string(height) + " must be positive");
  }
  if (!Finite(fx) || !Finite(fy) || fx <= 0.0 || fy <= 0.0) {
    return InvalidArgument("StereoCamera: focal lengths fx=" + std::to_string(fx) +
                           ", fy=" + std::to_string(fy) +
                           " must be finite and > 0 (singular "
                           "or missing camera)");
  }
  if (!Finite(cx) || !Finite(cy)) {
    return InvalidArgument("StereoCamera: principal point (cx, cy) must be finite");
  }
  if (!Finite(baseline) || baseline <= 0.0) {
    return InvalidArgument("StereoCamera: baseline=" + std::to_string(baseline) +
                           " m must be finite and > 0 (right camera at +x of the left)");
  }
  return Status::Ok();
}

Result<StereoCamera> StereoCamera::FromProjectionMatrices(
    const Eigen::Matrix<double, 3, 4>& p_left, const Eigen::Matrix<double, 3, 4>& p_right,
    int width, int height) {
  if (!p_left.allFinite() || !p_right.allFinite()) {
    return InvalidArgument("projection matrices contain non-finite values");
  }
  const double tol = 1e-6 * std::max(1.0, std::abs(p_left(0, 0)));
  auto same = [tol](double a, double b) { return std::abs(a - b) <= tol; };
  if (!same(p_left(0, 1), 0.0) || !same(p_left(1, 0), 0.0) || !same(p_left(2, 0), 0.0) ||
      !same(p_left(2, 1), 0.0) || !same(p_left(2, 2), 1.0)) {
    return InvalidArgument(
        "left projection matrix is not of the form K [I | 0] (skew or "
        "rotation present)");
  }
  if (!same(p_left(0, 3), 0.0) || !same(p_left(1, 3), 0.0) || !same(p_left(2, 3), 0.0)) {
    return InvalidArgument("left projection matrix has a non-zero translation column");
  }
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      if (!same(p_left(r, c), p_right(r, c))) {
        return InvalidArgument("left and right projection matrices differ in K at (" +
                               std::to_string(r) + "," + std::to_string(c) +
                               "): not a rectified pair");
      }
    }
  }
  if (!same(p_right(1, 3), 0.0) || !same(p_right(2, 3), 0.0)) {
    return InvalidArgument(
        "right projection matrix has a vertical or depth offset: not a "
        "horizontally rectified pair");
  }
  StereoCamera cam;
  cam.width = width;
  cam.height = height;
  cam.fx = p_left(0, 0);
  cam.fy = p_left(1, 1);
  cam.cx = p_left(0, 2);
  cam.cy = p_left(1, 2);
  cam.baseline = cam.fx != 0.0 ? -p_right(0, 3) / cam.fx : 0.0;
  if (Status s = cam.Validate(); !s.ok()) return s;
  return cam;
}

Eigen::Matrix<double, 2, 3> StereoCamera::ProjectLeftJacobian(const Eigen::Vector3d& p) const {
  const double iz = 1.0 / p.z();
  Eigen::Matrix<double, 2, 3> j;
  j << fx * iz, 0.0, -fx * p.x() * iz * iz,  //
      0.0, fy * iz, -fy * p.y() * iz * iz;
  return j;
}

}  // namespace rover::dl::vo
