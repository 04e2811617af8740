#include "rover/dl/vo/vo_service_options.hpp"

#include "rover/base/format.hpp"

namespace rover::dl::vo {

camera_client::CameraClientOptions VoServiceOptions::DefaultClient() {
  camera_client::CameraClientOptions c;
  c.request_id_prefix = 2;  // dl-stereo has 1
  return c;
}

camera_client::CameraClientOptions VoServiceOptions::Client() const {
  camera_client::CameraClientOptions c = client;
  c.retry_delay_s = retry_delay_s;
  return c;
}

Status VoServiceOptions::Validate() const {
  ROVER_RETURN_IF_ERROR(Client().Validate());
  ROVER_RETURN_IF_ERROR(cadence.Validate());
  ROVER_RETURN_IF_ERROR(pipeline.Validate());
  if (imaging != "on_request" && imaging != "always") {
    return InvalidArgument("imaging: '" + imaging + "' is not one of: on_request, always");
  }
  if (cadence.step_distance >= pipeline.vo.max_translation) {
    return InvalidArgument("step_distance " + FormatNumber(cadence.step_distance) +
                           " m must be below vo.max_translation " +
                           FormatNumber(pipeline.vo.max_translation) + " m");
  }
  return Status::Ok();
}

void VoServiceOptions::BindParams(ParamBinder<VoServiceOptions>& b) {
  using O = VoServiceOptions;
  b.BindEnum("camera", &O::camera,
             {{"front_hazcam", msg::CameraId::kFrontHazcam},
              {"navcam", msg::CameraId::kNavcam},
              {"rear_hazcam", msg::CameraId::kRearHazcam}},
             "stereo pair used: front_hazcam (fixed, 45 deg down), navcam (mast; keep it still "
             "while driving, MER pointed it ~45 deg down) or rear_hazcam");
  b.Bind("width", &O::width, "px",
         "processing width asked of the camera driver; 0 = full size. MER processed 256x256 "
         "NAVCAM images; the 120 deg HAZCAM needs 512 for enough tracked features")
      .Range(0, 4096);
  b.Nest("", &O::client);
  b.Nest("", &O::cadence);
  b.Nest("", &O::pipeline);
  b.Bind("retry_delay_s", &O::retry_delay_s, "s",
         "run-clock wait after a bad frame before the next request")
      .Range(0.0, 600.0);
  b.Bind("pose_max_age_s", &O::pose_max_age_s, "s",
         "dl/pose must lie within this of a capture time (for the prior) and of now (else the "
         "cadence pauses)")
      .Range(0.01, 60.0);
  b.Bind("poll_rate_hz", &O::poll_rate_hz, "Hz",
         "run-clock rate of the cadence, timeout and health checks")
      .Range(1.0, 100.0);
  b.Bind("imaging", &O::imaging,
         "on_request: take pairs only while a client asks on dl/vo_command (apl-mobility in its "
         "VisOdom modes); always: whenever the cadence says so")
      .OneOf({"on_request", "always"});
}

}  // namespace rover::dl::vo
