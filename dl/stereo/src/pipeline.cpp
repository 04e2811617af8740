#include "rover/dl/stereo/pipeline.hpp"

#include <chrono>
#include <string>

#include "describe.hpp"
#include "filters_internal.hpp"
#include "worker_pool.hpp"

namespace rover::dl::stereo {

using internal::Describe;
using internal::SizeText;
namespace {

using Clock = std::chrono::steady_clock;

double Ms(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

}  // namespace

Status StereoOptions::Validate() const {
  if (pyramid_levels < 0 || pyramid_levels > 4) {
    return InvalidArgument("pyramid_levels " + std::to_string(pyramid_levels) +
                           " is outside [0, 4]");
  }
  if (!(white_level > 0.0 && white_level <= 65535.0)) {
    return InvalidArgument("white_level " + std::to_string(white_level) + " is outside (0, 65535]");
  }
  if (!(gamma >= 0.1 && gamma <= 10.0)) {
    return InvalidArgument("gamma " + std::to_string(gamma) + " is outside [0.1, 10]");
  }
  ROVER_RETURN_IF_ERROR(prefilter.Validate());
  ROVER_RETURN_IF_ERROR(correlator.Validate());
  ROVER_RETURN_IF_ERROR(filters.Validate());
  ROVER_RETURN_IF_ERROR(reprojection.Validate());
  if (prefilter.kind != PrefilterKind::kNone &&
      2 * prefilter.cap * correlator.window * correlator.window >= 0x7FFF) {
    return InvalidArgument("prefilter.cap " + std::to_string(prefilter.cap) + " with a " +
                           std::to_string(correlator.window) +
                           " px window overflows 16-bit costs; lower the cap");
  }
  if (prefilter.kind == PrefilterKind::kNone &&
      255 * correlator.window * correlator.window >= 0x7FFF) {
    return InvalidArgument("correlator.window " + std::to_string(correlator.window) +
                           " is too large for unfiltered 8-bit images (max 11)");
  }
  return Status::Ok();
}

StereoPipeline::StereoPipeline(const StereoOptions& options, std::optional<StereoCamera> camera,
                               Correlator correlator)
    : options_(options), camera_(std::move(camera)), correlator_(std::move(correlator)) {}

Result<StereoPipeline> StereoPipeline::Create(const StereoOptions& options,
                                              std::optional<StereoCamera> camera) {
  ROVER_RETURN_IF_ERROR(options.Validate());
  if (camera.has_value()) ROVER_RETURN_IF_ERROR(camera->Validate().WithPrefix("camera"));
  auto correlator = Correlator::Create(options.correlator);
  if (!correlator.ok()) return correlator.status();
  return StereoPipeline(options, std::move(camera), std::move(*correlator));
}

Status StereoPipeline::Process(const StereoInput& input, StereoOutput* output) {
  if (output == nullptr) return InvalidArgument("stereo output is null");
  const auto t0 = Clock::now();
  // ---- checks ----
  const std::pair<const char*, const cv::Mat*> images[] = {{"left", &input.left},
                                                           {"right", &input.right}};
  for (const auto& [name, img] : images) {
    if (img->empty()) return InvalidArgument(std::string(name) + " image is empty");
    if (img->type() != CV_8UC1 && img->type() != CV_16UC1) {
      return InvalidArgument(std::string(name) + " image is " + Describe(*img) +
                             "; expected CV_8UC1 or CV_16UC1 (single channel)");
    }
  }
  if (input.left.size() != input.right.size()) {
    return InvalidArgument("left image is " + SizeText(input.left.size()) + " but right image is " +
                           SizeText(input.right.size()) + "; the pair must have equal sizes");
  }
  if (input.left.type() != input.right.type()) {
    return InvalidArgument("left image is " + Describe(input.left) + " but right image is " +
                           Describe(input.right) + "; the pair must have equal types");
  }
  cv::Size full_size = input.left.size();
  if (input.rectification != nullptr) {
    ROVER_RETURN_IF_ERROR(input.rectification->Validate());
    full_size = input.rectification->rectified_size();
  }
  const int levels = options_.pyramid_levels;
  const cv::Size level_size(full_size.width >> levels, full_size.height >> levels);
  const int win = options_.correlator.window;
  if (level_size.width < win || level_size.height < win) {
    return InvalidArgument("image " + SizeText(full_size) + " at pyramid level " +
                           std::to_string(levels) + " is " + SizeText(level_size) +
                           ", smaller than the " + std::to_string(win) + " px window");
  }
  if (!input.vehicle_mask.empty() &&
      (input.vehicle_mask.type() != CV_8UC1 || input.vehicle_mask.size() != full_size)) {
    return InvalidArgument("vehicle mask is " + Describe(input.vehicle_mask) + "; expected " +
                           SizeText(full_size) + " CV_8UC1 (the rectified full-resolution size)");
  }
  cv::Mat wheel_mask;
  if (!input.wheel_polygons.empty()) {
    auto m = RasterizePolygons(input.wheel_polygons, level_size, levels);
    if (!m.ok()) return m.status();
    wheel_mask = std::move(*m);
  }
  cv::Mat vehicle_mask;
  if (!input.vehicle_mask.empty()) {
    auto m = DownsampleMask(input.vehicle_mask, levels);
    if (!m.ok()) return m.status();
    vehicle_mask = std::move(*m);
  }

  // ---- rectify ----
  const cv::Mat* src[2] = {&input.left, &input.right};
  if (input.rectification != nullptr) {
    ROVER_RETURN_IF_ERROR(
        Rectify(*input.rectification, input.left, input.right, &rect_[0], &rect_[1]));
    src[0] = &rect_[0];
    src[1] = &rect_[1];
  }
  const auto t1 = Clock::now();

  // ---- 8-bit, gamma, pyramid, prefilter: left and right in parallel ----
  Status side_status[2];
  double prefilter_ms[2] = {0, 0};
  correlator_.pool_->Run(2, [&](int i, int /*worker*/) {
    Status st = Status::Ok();
    if (src[i]->type() == CV_8UC1 && options_.white_level == 255.0 && options_.gamma == 1.0) {
      work_[i] = *src[i];  // already 8-bit: no copy (Downsample2x and Prefilter write elsewhere)
    } else {
      st = ConvertTo8Bit(*src[i], options_.white_level, options_.gamma, &work_[i]);
    }
    for (int l = 0; st.ok() && l < levels; ++l) st = Downsample2x(work_[i], &work_[i]);
    const auto a = Clock::now();
    if (st.ok()) st = Prefilter(work_[i], options_.prefilter, &filtered_[i]);
    prefilter_ms[i] = Ms(a, Clock::now());
    side_status[i] = st;
  });
  for (int i = 0; i < 2; ++i) {
    if (!side_status[i].ok()) return side_status[i].WithPrefix(i == 0 ? "left" : "right");
  }
  const auto t2 = Clock::now();

  // ---- correlate ----
  StereoOutput& out = *output;  // buffers are reused from call to call
  out.model.reset();
  ROVER_RETURN_IF_ERROR(correlator_.Compute(filtered_[0], filtered_[1], &out.disparity));
  const auto t3 = Clock::now();

  // ---- filters ----
  const FilterOptions& f = options_.filters;
  if (f.border_px > 0) {
    ROVER_RETURN_IF_ERROR(ApplyBorderFilter(win / 2 + f.border_px, &out.disparity));
  }
  ROVER_RETURN_IF_ERROR(ApplyMask(vehicle_mask, PixelStatus::kVehicle, &out.disparity));
  ROVER_RETURN_IF_ERROR(ApplyMask(wheel_mask, PixelStatus::kWheel, &out.disparity));
  if (f.blob_min_area > 1) {
    ROVER_RETURN_IF_ERROR(ApplyBlobFilter(f.blob_min_area, f.blob_max_step, &out.disparity));
  }
  if (f.overhang) {
    // Columns are independent: split them over the workers (ranges aligned to 4 columns).
    const int w = out.disparity.disparity.cols;
    const int parts = std::min(correlator_.pool_->workers(), std::max(1, w / 64));
    correlator_.pool_->Run(parts, [&](int i, int /*worker*/) {
      const int u0 = (w * i / parts) & ~3;
      const int u1 = i + 1 == parts ? w : (w * (i + 1) / parts) & ~3;
      internal::OverhangColumns(f.overhang_tolerance_px, f.overhang_ratio, f.overhang_search_rows,
                                u0, u1, &out.disparity);
    });
  }
  const auto t4 = Clock::now();

  // ---- range and points ----
  out.level = levels;
  if (camera_.has_value()) {
    const RectifiedStereoModel model = camera_->model.Downsampled(levels);
    ROVER_RETURN_IF_ERROR(Reproject(model, camera_->rover_from_camera, options_.reprojection,
                                    &out.disparity, &out.range, &out.xyz_rover));
    out.model = model;
  } else {
    out.range.release();
    out.xyz_rover.release();
  }
  const auto t5 = Clock::now();
  out.valid = out.disparity.ValidMask();
  out.counts = out.disparity.CountStatus();
  out.timings.rectify_ms = Ms(t0, t1);
  out.timings.prefilter_ms = std::max(prefilter_ms[0], prefilter_ms[1]);
  out.timings.prepare_ms = Ms(t1, t2) - out.timings.prefilter_ms;
  out.timings.correlate_ms = Ms(t2, t3);
  out.timings.filter_ms = Ms(t3, t4);
  out.timings.reproject_ms = Ms(t4, t5);
  out.timings.total_ms = Ms(t0, Clock::now());
  return Status::Ok();
}

}  // namespace rover::dl::stereo
