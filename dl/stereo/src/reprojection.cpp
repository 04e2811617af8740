#include "rover/dl/stereo/reprojection.hpp"

#include <cmath>
#include <string>

namespace rover::dl::stereo {
namespace {

Status CheckPose(const Eigen::Isometry3d& t) {
  if (!t.matrix().allFinite()) return InvalidArgument("rover_from_camera has non-finite entries");
  const Eigen::Matrix3d r = t.linear();
  if ((r.transpose() * r - Eigen::Matrix3d::Identity()).norm() > 1e-6 || r.determinant() < 0) {
    return InvalidArgument("rover_from_camera rotation is not a proper rotation");
  }
  return Status::Ok();
}

}  // namespace

Status StereoCamera::Validate() const {
  ROVER_RETURN_IF_ERROR(model.Validate());
  return CheckPose(rover_from_camera);
}

Status ReprojectionOptions::Validate() const {
  if (!(min_range_m >= 0.0) || std::isinf(min_range_m)) {
    return InvalidArgument("reprojection.min_range_m " + std::to_string(min_range_m) +
                           " must be finite and >= 0");
  }
  if (!(max_range_m > min_range_m)) {
    return InvalidArgument("reprojection.max_range_m " + std::to_string(max_range_m) +
                           " must exceed min_range_m " + std::to_string(min_range_m));
  }
  return Status::Ok();
}

Status Reproject(const RectifiedStereoModel& model, const Eigen::Isometry3d& rover_from_camera,
                 const ReprojectionOptions& options, DisparityImage* disparity, cv::Mat* range,
                 cv::Mat* xyz_rover) {
  ROVER_RETURN_IF_ERROR(model.Validate());
  ROVER_RETURN_IF_ERROR(CheckPose(rover_from_camera));
  ROVER_RETURN_IF_ERROR(options.Validate());
  if (disparity == nullptr || disparity->empty()) {
    return InvalidArgument("disparity image to reproject is empty");
  }
  const cv::Size size = disparity->size();
  constexpr float kNan = kInvalidDisparity;
  if (range != nullptr) range->create(size, CV_32FC1);
  if (xyz_rover != nullptr) xyz_rover->create(size, CV_32FC3);
  const Eigen::Matrix3d r = rover_from_camera.linear();
  const Eigen::Vector3d t = rover_from_camera.translation();
  const double fb = model.focal_px * model.baseline_m;
  const double inv_f = 1.0 / model.focal_px;
  for (int v = 0; v < size.height; ++v) {
    const float* d = disparity->disparity.ptr<float>(v);
    std::uint8_t* s = disparity->status.ptr<std::uint8_t>(v);
    float* rg = range != nullptr ? range->ptr<float>(v) : nullptr;
    cv::Vec3f* xyz = xyz_rover != nullptr ? xyz_rover->ptr<cv::Vec3f>(v) : nullptr;
    for (int u = 0; u < size.width; ++u) {
      bool ok = s[u] == static_cast<std::uint8_t>(PixelStatus::kValid);
      Eigen::Vector3d p_c;
      double dist = 0.0;
      if (ok) {
        const double den = d[u] + model.doffs_px;
        ok = den > 0.0;
        if (ok) {
          const double z = fb / den;
          p_c = Eigen::Vector3d((u - model.cx) * z * inv_f, (v - model.cy) * z * inv_f, z);
          dist = p_c.norm();
          ok = dist >= options.min_range_m && dist <= options.max_range_m;
        }
        if (!ok) disparity->Reject(v, u, PixelStatus::kRangeLimit);
      }
      if (ok) {
        if (rg != nullptr) rg[u] = static_cast<float>(dist);
        if (xyz != nullptr) {
          const Eigen::Vector3d p_r = r * p_c + t;
          xyz[u] = cv::Vec3f(static_cast<float>(p_r.x()), static_cast<float>(p_r.y()),
                             static_cast<float>(p_r.z()));
        }
      } else {
        if (rg != nullptr) rg[u] = kNan;
        if (xyz != nullptr) xyz[u] = cv::Vec3f(kNan, kNan, kNan);
      }
    }
  }
  return Status::Ok();
}

}  // namespace rover::dl::stereo
