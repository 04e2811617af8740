#include "rover/dl/stereo/stereo_ranger.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <string>
#include <utility>

#include "rover/base/check.hpp"
#include "rover/base/format.hpp"
#include "rover/base/log.hpp"
#include "rover/dl/stereo/frame_images.hpp"

namespace rover::dl::stereo {

void StereoRangerOptions::BindParams(ParamBinder<StereoRangerOptions>& b) {
  using O = StereoRangerOptions;
  b.Bind("stereo.pyramid_levels", &O::pyramid_levels, "",
         "2x2 block-mean levels before correlation (the driver already downsampled to the "
         "processing width)")
      .Range(0, 4);
  b.Bind("stereo.window", &O::window, "px", "SAD window, odd").Range(3, 15);
  b.Bind("stereo.num_disparities", &O::num_disparities, "px",
         "disparity search range; 0 = derived from stereo.min_range_m")
      .Range(0, 512);
  b.Bind("stereo.max_disparities", &O::max_disparities, "px", "cap of the derived search range")
      .Range(16, 512);
  b.Bind("stereo.min_range_m", &O::min_range_m, "m",
         "nearest range of interest: sets the derived search range and drops nearer points")
      .Range(0.05, 100.0);
  b.Bind("stereo.max_range_m", &O::max_range_m, "m", "farther points are invalid (range_limit)")
      .Range(0.1, 10000.0);
  b.BindEnum("stereo.prefilter", &O::prefilter,
             {{"log", PrefilterKind::kLaplacianOfGaussian},
              {"dog", PrefilterKind::kDifferenceOfGaussians},
              {"none", PrefilterKind::kNone}},
             "band-pass prefilter: log, dog or none");
  b.Bind("stereo.uniqueness_ratio", &O::uniqueness_ratio, "", "secondary-minimum margin; 0 = off")
      .Range(0.0, 2.0);
  b.Bind("stereo.min_curvature", &O::min_curvature, "",
         "flat-valley threshold per window pixel (low texture); 0 = off")
      .Range(0.0, 255.0);
  b.Bind("stereo.lr_max_diff", &O::lr_max_diff, "px", "left/right consistency tolerance; -1 = off")
      .Range(-1, 64);
  b.Bind("stereo.blob_min_area", &O::blob_min_area, "px",
         "smaller disparity regions are removed; 0 = off")
      .Range(0, 1000000);
  b.Bind("stereo.overhang", &O::overhang, "remove ranges that loom over nearer terrain");
  b.Bind("stereo.num_threads", &O::num_threads, "", "correlation threads").Range(1, 16);
  b.Bind("rectification_cache_size", &O::rectification_cache_size, "",
         "camera-model pairs whose remap tables are kept")
      .Range(1, 32);
}

StereoOptions StereoRangerOptions::Pipeline(int disparities) const {
  StereoOptions o;
  o.pyramid_levels = pyramid_levels;
  o.correlator.window = window;
  o.correlator.num_disparities = disparities;
  o.correlator.uniqueness_ratio = uniqueness_ratio;
  o.correlator.min_curvature = min_curvature;
  o.correlator.lr_max_diff = lr_max_diff;
  o.correlator.num_threads = num_threads;
  o.filters.blob_min_area = blob_min_area;
  o.filters.overhang = overhang;
  o.reprojection.min_range_m = min_range_m;
  o.reprojection.max_range_m = max_range_m;
  o.prefilter.kind = prefilter;
  return o;
}

Status StereoRangerOptions::Validate() const {
  if (max_range_m <= min_range_m) {
    return InvalidArgument("stereo.max_range_m " + FormatNumber(max_range_m) +
                           " must be larger than stereo.min_range_m " + FormatNumber(min_range_m));
  }
  // The correlator's num_disparities is a placeholder when stereo.num_disparities is 0
  // (derived per camera).
  return Pipeline(num_disparities > 0 ? num_disparities : 64)
      .Validate()
      .WithPrefix("stereo parameters");
}

StereoRanger::StereoRanger(const StereoRangerOptions& options, std::optional<VehicleMask> mask)
    : options_(options),
      cache_(static_cast<std::size_t>(options.rectification_cache_size)),
      mask_(std::move(mask)) {
  ROVER_DEMAND(options_.Validate().ok());
}

Result<StereoPipeline*> StereoRanger::PipelineFor(const StereoSetup& setup) {
  int d = options_.num_disparities;
  if (d == 0) {
    const RectifiedStereoModel level = setup.camera.model.Downsampled(options_.pyramid_levels);
    const double nearest = level.DisparityFromDepth(options_.min_range_m);
    const double wanted =
        std::isfinite(nearest) ? std::ceil(nearest) + 2.0 : options_.max_disparities;
    d = static_cast<int>(std::clamp(wanted, 16.0, static_cast<double>(options_.max_disparities)));
  }
  auto it = pipelines_.find(d);
  if (it == pipelines_.end()) {
    auto pipe = StereoPipeline::Create(options_.Pipeline(d));
    if (!pipe.ok()) return pipe.status().WithPrefix("stereo pipeline");
    it = pipelines_.emplace(d, std::move(*pipe)).first;
    log::Info("stereo pipeline created", {{"num_disparities", d}});
  }
  return &it->second;
}

Status StereoRanger::SetPixelMask(msg::CameraId camera, cv::Mat mask) {
  if (!msg::IsKnownCamera(camera)) {
    return InvalidArgument("pixel mask for unknown camera " +
                           std::to_string(static_cast<int>(camera)));
  }
  if (!mask.empty() && mask.type() != CV_8UC1) {
    return InvalidArgument(std::string("pixel mask of ") + msg::CameraName(camera) +
                           " must be CV_8UC1");
  }
  pixel_masks_[static_cast<std::size_t>(camera)] = std::move(mask);
  return Status::Ok();
}

Result<msg::RangeImage> StereoRanger::Range(const msg::StereoFrame& frame, std::uint32_t request_id,
                                            const PoseLookup& lookup) {
  auto setup = cache_.Get(frame.left_model, frame.right_model);
  if (!setup.ok()) return setup.status();
  const StereoSetup& st = **setup;

  msg::RangeImage out;
  out.stamp = frame.stamp;  // capture time
  out.request_id = request_id;
  out.camera = frame.camera;
  auto pose = lookup.poses != nullptr ? lookup.poses->At(frame.stamp, lookup.max_age)
                                      : Result<msg::PoseSample>(NotFound("no pose history"));
  if (pose.ok()) {
    out.rover_pose = pose->site_from_rover;
  } else if (lookup.required) {
    return pose.status().WithPrefix("rover pose at capture");
  } else {
    log::Warn("range image sent with an identity rover_pose",
              {{"reason", pose.status().message()}});
  }

  ROVER_ASSIGN_OR_RETURN(StereoPipeline* const pipe, PipelineFor(st));
  const FrameImages images = ViewFrameImages(frame);
  StereoInput in;
  in.left = images.left;
  in.right = images.right;
  in.rectification = &st.maps;
  const cv::Mat fixed = msg::IsKnownCamera(frame.camera)
                            ? pixel_masks_[static_cast<std::size_t>(frame.camera)]
                            : cv::Mat();
  if (!fixed.empty()) {
    cv::resize(fixed, scaled_pixel_mask_, st.maps.rectified_size(), 0.0, 0.0, cv::INTER_NEAREST);
    in.vehicle_mask = scaled_pixel_mask_;
  }
  ROVER_RETURN_IF_ERROR(pipe->Process(in, &output_));
  const RectifiedStereoModel level_model = st.camera.model.Downsampled(output_.level);
  cv::Mat range, xyz;
  ROVER_RETURN_IF_ERROR(Reproject(level_model, st.camera.rover_from_camera,
                                  options_.Pipeline(0).reprojection, &output_.disparity, &range,
                                  &xyz));
  if (mask_) {
    ROVER_RETURN_IF_ERROR(mask_->Apply(st.camera.rover_from_camera.translation(), &xyz,
                                       &output_.disparity.status)
                              .status());
    output_.counts = output_.disparity.CountStatus();
  }
  last_masked_ = output_.counts[static_cast<std::size_t>(PixelStatus::kVehicle)] +
                 output_.counts[static_cast<std::size_t>(PixelStatus::kWheel)];

  const int w = output_.disparity.disparity.cols;
  const int h = output_.disparity.disparity.rows;
  const auto n = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
  out.width = w;
  out.height = h;
  out.xyz.resize(3 * n);
  out.valid.resize(n);
  out.disparity.resize(n);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (int v = 0; v < h; ++v) {
    const auto* st_row = output_.disparity.status.ptr<std::uint8_t>(v);
    const auto* d_row = output_.disparity.disparity.ptr<float>(v);
    const auto* p_row = xyz.ptr<cv::Vec3f>(v);
    for (int u = 0; u < w; ++u) {
      const std::size_t i =
          static_cast<std::size_t>(v) * static_cast<std::size_t>(w) + static_cast<std::size_t>(u);
      const bool ok = st_row[u] == static_cast<std::uint8_t>(PixelStatus::kValid);
      out.valid[i] = ok ? 1 : 0;
      out.disparity[i] = ok ? d_row[u] : -1.0F;
      for (std::size_t k = 0; k < 3; ++k) {
        out.xyz[3 * i + k] = ok ? p_row[u][static_cast<int>(k)] : nan;
      }
    }
  }
  return out;
}

}  // namespace rover::dl::stereo
