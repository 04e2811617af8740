#pragma once
/// @file
/// ddl-camera: the stereo camera driver service. Binds the CameraDriver (ddl_camera):
///   in:  ddl/camera_request (command), hw/camera_frame (state, on request),
///        ddl/joint_state (stream, 50 Hz; mast pan/tilt for the NAVCAM models)
///   out: hw/camera_request (command), ddl/stereo_frame (state, one per answered request)
///   and the microscopic imager on the arm: ddl/mi_request -> hw/mi_request, hw/mi_frame ->
///   ddl/mi_frame (checked sizes, the requester's id; no model: its pose follows the arm)
/// A valid request goes to the camera head with the driver's own request id; its frame is
/// downsampled to the requested width (0 = full) and published with the left/right models in
/// the rover frame at capture time (calibration from `camera_file`; NAVCAM models follow the
/// mast) and the frame's health (OK; DEGRADED when the mast sample nearest the capture is
/// older than mast_max_age_s; FAILED when the mast pose was never received).
///
/// Invalid requests (unknown camera, width beyond the camera's calibrated width, exposure above
/// max_exposure_us, too many requests waiting): nothing is sent to the camera head and NO
/// ddl/stereo_frame is published (a frame's health describes sensor data; an empty FAILED
/// frame would be indistinguishable from a camera fault). The rejection is a warning on
/// sys/event naming the request id, the field, the value and the allowed range; the requester
/// sees no frame for that request id and times out. (The IDL has no status topic for camera
/// requests; see docs/services/ddl-camera.md.)
///
/// Health (heartbeat, every 1/watchdog_rate_hz of the run clock): DEGRADED while ddl/joint_state
/// is stale, or since the last request went unanswered (request_timeout_s) or its frame was
/// corrupt, until a frame succeeds; FAILED while writes fail; else OK.

#include <optional>
#include <string>

#include "rover/ddl/camera/camera_driver.hpp"
#include "rover/ddl/driver_support/driver_health.hpp"
#include "rover/runtime/service.hpp"

namespace rover::ddl::camera {

class CameraService final : public Service {
 public:
  CameraService() : Service("ddl-camera") {}

  void DeclareParameters(ParamSet& p) override;
  /// Cross-parameter checks that `--validate` (and so `roverctl up`) reports before start-up.
  Status ValidateParameters(const ParamSet& p) const override;
  Status OnConfigure(ServiceContext& ctx, const ParamSet& p) override;

 private:
  /// The driver from the calibration file and options (`path` gets the resolved file).
  static Result<CameraDriver> MakeDriver(const ParamSet& p, std::string* path);
  Time Now();
  void OnRequest(const rover_ddl_StereoRequest& request);
  Status OnJointState(const rover_ddl_JointState& joints);
  Status OnFrame(const rover_hw_CameraFrame& frame);
  void OnMiRequest(const rover_ddl_MiRequest& request);
  Status OnMiFrame(const rover_hw_MiFrame& frame);
  void OnWatchdog();

  ServiceContext* ctx_ = nullptr;
  std::optional<CameraDriver> driver_;
  std::optional<driver_support::InputMonitor> joints_;
  std::optional<driver_support::InputMonitor> frames_;
  std::optional<driver_support::InputMonitor> mi_frames_;
  driver_support::ClockJumpDetector clock_jump_;
  std::string camera_error_;  // last unanswered request or corrupt frame; cleared by a good frame
  std::string write_error_;
  dds::Writer<rover_hw_CameraRequest> request_writer_;
  dds::Writer<rover_hw_MiRequest> mi_request_writer_;
  dds::Writer<rover_ddl_MiFrame> mi_frame_writer_;
  dds::Writer<rover_ddl_StereoFrame> frame_writer_;
};

}  // namespace rover::ddl::camera
