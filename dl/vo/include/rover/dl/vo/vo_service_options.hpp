#pragma once
/// @file
/// Every parameter of the dl-vo service, declared once (ParamBinder), with the cross-parameter
/// rule: keys camera, width, retry_delay_s, pose_max_age_s, poll_rate_hz, the camera client's
/// (request_id_prefix default 2, request_timeout_s, exposure_us), the cadence's
/// (step_distance, ...) and the pipeline's (vo.*, prior.*, rectification_cache_size).

#include <string>

#include "rover/base/param_binder.hpp"
#include "rover/base/status.hpp"
#include "rover/dl/camera_client/camera_request_client.hpp"
#include "rover/dl/vo/cadence.hpp"
#include "rover/dl/vo/vo_pipeline.hpp"
#include "rover/msg/camera.hpp"

namespace rover::dl::vo {

struct VoServiceOptions {
  msg::CameraId camera = msg::CameraId::kFrontHazcam;
  int width = 512;              ///< [px] processing width asked of the driver; 0 = full size
  double retry_delay_s = 1.0;   ///< [s] run-clock wait after a bad frame
  double pose_max_age_s = 1.0;  ///< [s] dl/pose this close to a capture time and to now
  double poll_rate_hz = 10.0;   ///< [Hz] cadence, timeout and health checks
  /// "on_request": pairs only while a client asks on dl/vo_command (MER ran VO only in its
  /// VisOdom modes); "always": pairs whenever the cadence says so (the vision set's VO runs).
  std::string imaging = "on_request";
  camera_client::CameraClientOptions client = DefaultClient();
  CadenceOptions cadence;
  VoPipelineOptions pipeline;

  /// The client's options with the retry delay.
  camera_client::CameraClientOptions Client() const;
  /// The parts' checks, and a step below vo.max_translation.
  Status Validate() const;
  static void BindParams(ParamBinder<VoServiceOptions>& b);

 private:
  static camera_client::CameraClientOptions DefaultClient();
};

}  // namespace rover::dl::vo
