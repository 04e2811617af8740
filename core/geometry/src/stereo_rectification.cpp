// Stereo rectification of a pair of camera models (camera_model.hpp, RectifyStereoPair).

#include <cmath>
#include <numbers>
#include <string>

#include "camera_internal.hpp"
#include "rover/geometry/camera_model.hpp"

namespace rover::geometry {
namespace {

// Fills the remap tables of one camera: rectified pixel -> source pixel, through the ray
// direction (both models share the projection centre).
void FillMaps(const CameraModel& source, const Cahv& rectified, int width, int height,
              std::vector<float>* map_x, std::vector<float>* map_y) {
  const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  map_x->assign(n, kUnmappedPixel);
  map_y->assign(n, kUnmappedPixel);
  const double det = rectified.a.dot(rectified.h.cross(rectified.v));
  for (int y = 0; y < height; ++y) {
    const Eigen::Vector3d vy = rectified.v - y * rectified.a;
    for (int x = 0; x < width; ++x) {
      const Eigen::Vector3d d = (rectified.h - x * rectified.a).cross(vy) / det;
      const auto px = source.ProjectDirection(d);
      if (!px || !(std::abs(px->x()) < 1e7 && std::abs(px->y()) < 1e7)) continue;
      const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                            static_cast<std::size_t>(x);
      (*map_x)[i] = static_cast<float>(px->x());
      (*map_y)[i] = static_cast<float>(px->y());
    }
  }
}

}  // namespace

Status RectifyOptions::Validate() const {
  if (width < 0 || height < 0) {
    return InvalidArgument("RectifyOptions: width = " + std::to_string(width) + ", height = " +
                           std::to_string(height) + " must be >= 0 (0 = input size)");
  }
  if (!std::isfinite(focal_px) || focal_px < 0.0) {
    return InvalidArgument("RectifyOptions: focal_px = " + std::to_string(focal_px) +
                           " must be finite and >= 0 (0 = automatic)");
  }
  return Status::Ok();
}

Result<RectifiedPair> RectifyStereoPair(const CameraModel& left, const CameraModel& right,
                                        const RectifyOptions& options) {
  ROVER_RETURN_IF_ERROR(options.Validate());
  const internal::LinearPart l = internal::LinearPartOf(left);
  const internal::LinearPart r = internal::LinearPartOf(right);
  if (!(l.theta > 0.0) || !(r.theta > 0.0)) {
    return InvalidArgument("RectifyStereoPair: a mirrored input model (H' x V' against A)");
  }
  const Eigen::Vector3d baseline = r.center - l.center;
  const double baseline_norm = baseline.norm();
  if (!(baseline_norm > 1e-9)) {
    return InvalidArgument("RectifyStereoPair: the camera centres coincide (baseline " +
                           std::to_string(baseline_norm) + " m)");
  }
  // x along the baseline, oriented like the inputs' horizontal axes (no mirroring).
  Eigen::Vector3d x = baseline / baseline_norm;
  if (x.dot(l.axes.col(0) + r.axes.col(0)) < 0.0) x = -x;
  // z: the mean pointing axis, made perpendicular to x; y completes x right, y down, z forward.
  const Eigen::Vector3d mean_axis = (l.axes.col(2) + r.axes.col(2)).normalized();
  Eigen::Vector3d z = mean_axis - mean_axis.dot(x) * x;
  if (!(z.norm() > std::sin(std::numbers::pi / 180.0))) {
    return InvalidArgument(
        "RectifyStereoPair: the baseline is within 1 deg of the pointing axis; a pair looking "
        "along its baseline cannot be rectified to rows");
  }
  z.normalize();
  const Eigen::Vector3d y = z.cross(x);

  const int width = options.width > 0 ? options.width : left.width();
  const int height = options.height > 0 ? options.height : left.height();
  const double f = options.focal_px > 0.0 ? options.focal_px : 0.25 * (l.fx + l.fy + r.fx + r.fy);
  const double hc = 0.5 * (width - 1.0);
  const double vc = 0.5 * (height - 1.0);
  const Cahv left_cahv{l.center, z, f * x + hc * z, f * y + vc * z};
  const Cahv right_cahv{r.center, z, f * x + hc * z, f * y + vc * z};
  auto left_model = CameraModel::Create(left_cahv, width, height);
  if (!left_model.ok()) return left_model.status().WithPrefix("RectifyStereoPair");
  auto right_model = CameraModel::Create(right_cahv, width, height);
  if (!right_model.ok()) return right_model.status().WithPrefix("RectifyStereoPair");

  RectifiedPair pair{*left_model, *right_model, baseline.dot(x), f, {}, {}, {}, {}};
  if (options.compute_maps) {
    FillMaps(left, left_cahv, width, height, &pair.left_map_x, &pair.left_map_y);
    FillMaps(right, right_cahv, width, height, &pair.right_map_x, &pair.right_map_y);
  }
  return pair;
}

}  // namespace rover::geometry
