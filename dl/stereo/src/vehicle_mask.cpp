#include "rover/dl/stereo/vehicle_mask.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <utility>

#include "rover/base/check.hpp"
#include "rover/base/range_check.hpp"
#include "rover/dl/stereo/disparity_image.hpp"

namespace rover::dl::stereo {

void VehicleMaskOptions::BindParams(ParamBinder<VehicleMaskOptions>& b) {
  using O = VehicleMaskOptions;
  b.Bind("enabled", &O::enabled,
         "remove range points on the rover's own wheels and body or hidden behind them");
  b.Bind("wheel_margin_m", &O::wheel_margin_m, "m",
         "added to the wheel radius and half width of each wheel volume")
      .Range(0.0, 1.0);
  b.Bind("wheel_lift_m", &O::wheel_lift_m, "m",
         "each wheel volume reaches this far above the wheel's top (suspension lifting it)")
      .Range(0.0, 1.0);
  b.Bind("support_depth_m", &O::support_depth_m, "m",
         "each wheel volume reaches this far below the wheel's ground contact (the ground a "
         "wheel stands on is opaque)")
      .Range(0.0, 10.0);
  b.Bind("body_margin_m", &O::body_margin_m, "m", "added to the body box on every side")
      .Range(0.0, 1.0);
  const char* const pixels_doc =
      "fixed pixel mask of this camera: image file, non-zero = rover, scaled to the rectified "
      "image; empty = none";
  b.Bind("front_hazcam_pixels", &O::front_hazcam_pixels, pixels_doc);
  b.Bind("rear_hazcam_pixels", &O::rear_hazcam_pixels, pixels_doc);
  b.Bind("navcam_pixels", &O::navcam_pixels, pixels_doc);
}

Result<cv::Mat> LoadPixelMask(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    return NotFound("pixel mask file '" + path + "' does not exist");
  }
  cv::Mat img = cv::imread(path, cv::IMREAD_GRAYSCALE);
  if (img.empty()) return InvalidArgument("pixel mask file '" + path + "' is not a readable image");
  cv::Mat mask;
  cv::compare(img, 0, mask, cv::CMP_GT);  // 255 where the rover is
  return mask;
}

Status VehicleMaskOptions::Validate() const {
  const Bounds b = Bounds::Closed(0.0, 1.0);
  ROVER_RETURN_IF_ERROR(CheckRange("wheel_margin_m", wheel_margin_m, b, "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("wheel_lift_m", wheel_lift_m, b, "m"));
  ROVER_RETURN_IF_ERROR(
      CheckRange("support_depth_m", support_depth_m, Bounds::Closed(0.0, 10.0), "m"));
  return CheckRange("body_margin_m", body_margin_m, b, "m");
}

VehicleMask::VehicleMask(const hwconfig::RoverDescription& rover,
                         const VehicleMaskOptions& options)
    : options_(options) {
  ROVER_DEMAND(options_.Validate().ok());
  const double r = rover.wheel_radius;
  const double half_width = 0.5 * rover.wheel_width;
  const double top = r + options_.wheel_margin_m + options_.wheel_lift_m;
  const double bottom = r + options_.wheel_margin_m + options_.support_depth_m;
  for (int i = 0; i < hwconfig::kNumWheels; ++i) {
    const bool steered = std::find(hwconfig::kSteeredWheel.begin(), hwconfig::kSteeredWheel.end(),
                                   i) != hwconfig::kSteeredWheel.end();
    const double steer_sweep = std::hypot(r, half_width) + options_.wheel_margin_m;
    const Eigen::Vector2d half =
        steered ? Eigen::Vector2d(steer_sweep, steer_sweep)
                : Eigen::Vector2d(r + options_.wheel_margin_m, half_width + options_.wheel_margin_m);
    const Eigen::Vector3d c = rover.WheelCentre(i);
    volumes_.push_back(
        {Eigen::AlignedBox3d(Eigen::Vector3d(c.x() - half.x(), c.y() - half.y(), c.z() - bottom),
                             Eigen::Vector3d(c.x() + half.x(), c.y() + half.y(), c.z() + top)),
         VehiclePart::kWheel});
  }
  const Eigen::Vector3d body_half =
      0.5 * rover.body_size + Eigen::Vector3d::Constant(options_.body_margin_m);
  volumes_.push_back({Eigen::AlignedBox3d(rover.body_centre - body_half,
                                          rover.body_centre + body_half),
                      VehiclePart::kBody});
}

bool SegmentMeetsBox(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                     const Eigen::AlignedBox3d& box) {
  // Parameter interval [t0, t1] of a + t (b - a) inside every slab, starting from [0, 1].
  double t0 = 0.0;
  double t1 = 1.0;
  const Eigen::Vector3d d = b - a;
  for (int k = 0; k < 3; ++k) {
    const double lo = box.min()[k];
    const double hi = box.max()[k];
    if (std::abs(d[k]) < 1e-12) {
      if (a[k] < lo || a[k] > hi) return false;
      continue;
    }
    double ta = (lo - a[k]) / d[k];
    double tb = (hi - a[k]) / d[k];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
    if (t0 > t1) return false;
  }
  return true;
}

VehiclePart VehicleMask::Hides(const Eigen::Vector3d& eye, const Eigen::Vector3d& point) const {
  if (!options_.enabled) return VehiclePart::kNone;
  for (const Volume& v : volumes_) {
    if (v.box.contains(point)) return v.part;
    if (!v.box.contains(eye) && SegmentMeetsBox(eye, point, v.box)) return v.part;
  }
  return VehiclePart::kNone;
}

Result<int> VehicleMask::Apply(const Eigen::Vector3d& eye, cv::Mat* xyz, cv::Mat* status) const {
  if (xyz == nullptr || status == nullptr) return InvalidArgument("vehicle mask: null image");
  if (xyz->type() != CV_32FC3 || status->type() != CV_8UC1 || xyz->size() != status->size()) {
    return InvalidArgument("vehicle mask: xyz must be CV_32FC3 and status CV_8UC1 of one size (" +
                           std::to_string(xyz->cols) + "x" + std::to_string(xyz->rows) + " vs " +
                           std::to_string(status->cols) + "x" + std::to_string(status->rows) +
                           ")");
  }
  if (!options_.enabled) return 0;
  const auto valid = static_cast<std::uint8_t>(PixelStatus::kValid);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  int masked = 0;
  for (int v = 0; v < xyz->rows; ++v) {
    auto* p_row = xyz->ptr<cv::Vec3f>(v);
    auto* s_row = status->ptr<std::uint8_t>(v);
    for (int u = 0; u < xyz->cols; ++u) {
      if (s_row[u] != valid) continue;
      const Eigen::Vector3d p(p_row[u][0], p_row[u][1], p_row[u][2]);
      const VehiclePart part = Hides(eye, p);
      if (part == VehiclePart::kNone) continue;
      s_row[u] = static_cast<std::uint8_t>(part == VehiclePart::kWheel ? PixelStatus::kWheel
                                                                       : PixelStatus::kVehicle);
      p_row[u] = cv::Vec3f(nan, nan, nan);
      ++masked;
    }
  }
  return masked;
}

}  // namespace rover::dl::stereo
