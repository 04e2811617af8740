#include "rover/dl/stereo/rectification.hpp"

#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <string>

#include "describe.hpp"

namespace rover::dl::stereo {

using internal::Describe;
using internal::SizeText;
namespace {

std::string Num(double x) {
  std::string s = std::to_string(x);
  return s;
}

Status CheckMapPair(const char* name, const cv::Mat& x, const cv::Mat& y, cv::Size size) {
  const std::string n(name);
  if (x.empty() || y.empty()) return InvalidArgument("rectification map " + n + " is empty");
  const bool floats = x.type() == CV_32FC1 && y.type() == CV_32FC1;
  const bool fixed = x.type() == CV_16SC2 && y.type() == CV_16UC1;
  if (!floats && !fixed) {
    return InvalidArgument("rectification map " + n + " is " + Describe(x) + " + " + Describe(y) +
                           "; expected CV_32FC1 + CV_32FC1 or CV_16SC2 + CV_16UC1");
  }
  if (x.size() != size || y.size() != size) {
    return InvalidArgument("rectification map " + n + " is " + SizeText(x.size()) + " / " +
                           SizeText(y.size()) + "; expected " + SizeText(size) + " like left_x");
  }
  return Status::Ok();
}

}  // namespace

Status RectifiedStereoModel::Validate() const {
  if (!(std::isfinite(focal_px) && focal_px > 0.0)) {
    return InvalidArgument("stereo model focal_px " + Num(focal_px) + " must be > 0");
  }
  if (!(std::isfinite(baseline_m) && baseline_m > 0.0)) {
    return InvalidArgument("stereo model baseline_m " + Num(baseline_m) + " must be > 0");
  }
  if (!std::isfinite(cx) || !std::isfinite(cy) || !std::isfinite(doffs_px)) {
    return InvalidArgument("stereo model cx, cy or doffs_px is not finite");
  }
  return Status::Ok();
}

double RectifiedStereoModel::DepthFromDisparity(double d) const {
  const double den = d + doffs_px;
  if (!(den > 0.0)) return std::numeric_limits<double>::infinity();
  return focal_px * baseline_m / den;
}

double RectifiedStereoModel::DisparityFromDepth(double z) const {
  return focal_px * baseline_m / z - doffs_px;
}

RectifiedStereoModel RectifiedStereoModel::Downsampled(int levels) const {
  RectifiedStereoModel m = *this;
  for (int i = 0; i < levels; ++i) {
    m.focal_px *= 0.5;
    m.doffs_px *= 0.5;
    m.cx = (m.cx - 0.5) * 0.5;
    m.cy = (m.cy - 0.5) * 0.5;
  }
  return m;
}

cv::Matx44d RectifiedStereoModel::ToQ() const {
  return cv::Matx44d(1, 0, 0, -cx,       //
                     0, 1, 0, -cy,       //
                     0, 0, 0, focal_px,  //
                     0, 0, 1.0 / baseline_m, doffs_px / baseline_m);
}

Result<RectifiedStereoModel> RectifiedStereoModel::FromQ(const cv::Matx44d& q) {
  const double tol = 1e-9;
  const bool shape = std::abs(q(0, 0) - 1) < tol && std::abs(q(1, 1) - 1) < tol &&
                     std::abs(q(0, 1)) < tol && std::abs(q(0, 2)) < tol &&
                     std::abs(q(1, 0)) < tol && std::abs(q(1, 2)) < tol &&
                     std::abs(q(2, 0)) < tol && std::abs(q(2, 1)) < tol &&
                     std::abs(q(2, 2)) < tol && std::abs(q(3, 0)) < tol && std::abs(q(3, 1)) < tol;
  if (!shape) {
    return InvalidArgument(
        "Q is not a rectified-stereo reprojection matrix [1 0 0 -cx; 0 1 0 -cy; 0 0 0 f; "
        "0 0 1/B doffs/B]");
  }
  if (!(q(3, 2) > 0.0)) {
    return InvalidArgument("Q(3,2) = 1/baseline is " + Num(q(3, 2)) +
                           "; must be > 0 (right camera to the right of the left one)");
  }
  RectifiedStereoModel m;
  m.focal_px = q(2, 3);
  m.cx = -q(0, 3);
  m.cy = -q(1, 3);
  m.baseline_m = 1.0 / q(3, 2);
  m.doffs_px = q(3, 3) * m.baseline_m;
  ROVER_RETURN_IF_ERROR(m.Validate());
  return m;
}

Status RectificationMaps::Validate() const {
  if (raw_size.width <= 0 || raw_size.height <= 0) {
    return InvalidArgument("rectification raw_size " + SizeText(raw_size) + " is empty");
  }
  if (left_x.empty()) return InvalidArgument("rectification map left is empty");
  ROVER_RETURN_IF_ERROR(CheckMapPair("left", left_x, left_y, left_x.size()));
  ROVER_RETURN_IF_ERROR(CheckMapPair("right", right_x, right_y, left_x.size()));
  return Status::Ok();
}

Status Rectify(const RectificationMaps& maps, const cv::Mat& raw_left, const cv::Mat& raw_right,
               cv::Mat* rect_left, cv::Mat* rect_right) {
  ROVER_RETURN_IF_ERROR(maps.Validate());
  const std::pair<const char*, const cv::Mat*> images[] = {{"left", &raw_left},
                                                           {"right", &raw_right}};
  for (const auto& [name, img] : images) {
    if (img->empty()) return InvalidArgument(std::string(name) + " raw image is empty");
    if (img->type() != CV_8UC1 && img->type() != CV_16UC1) {
      return InvalidArgument(std::string(name) + " raw image is " + Describe(*img) +
                             "; expected CV_8UC1 or CV_16UC1");
    }
    if (img->size() != maps.raw_size) {
      return InvalidArgument(std::string(name) + " raw image is " + SizeText(img->size()) +
                             " but the rectification maps expect " + SizeText(maps.raw_size));
    }
  }
  cv::remap(raw_left, *rect_left, maps.left_x, maps.left_y, cv::INTER_LINEAR, cv::BORDER_CONSTANT,
            cv::Scalar(0));
  cv::remap(raw_right, *rect_right, maps.right_x, maps.right_y, cv::INTER_LINEAR,
            cv::BORDER_CONSTANT, cv::Scalar(0));
  return Status::Ok();
}

}  // namespace rover::dl::stereo
