#pragma once
/// @file
/// dl-stereo: binds the stereo ranging library (dl_stereo: StereoRanger) and the camera client
/// (dl_camera_client) to topics.
///
///   in:  dl/range_request   (request_id, camera, width): queued (at most max_queue), served one
///                           at a time in arrival order
///        ddl/stereo_frame   the camera driver's answer; only the frame whose request_id is the
///                           outstanding ddl/camera_request's is used, others are ignored
///        dl/pose            kept as a short history (msg::PoseHistory) to look up the rover
///                           pose at the capture time
///   out: ddl/camera_request one per range request: this service's own request_id
///                           (request_id_prefix << 24 | counter), the camera, the processing
///                           width (the request's, or default_width when it says 0), exposure_us
///        dl/range_image     one per good frame (StereoRanger): stamp = capture time, frame
///                           "rover", the range request's id and camera, the processed size,
///                           rover_pose = the dl/pose estimate interpolated at the capture time,
///                           XYZ [m] in the rover frame (NaN where invalid), valid (1/0),
///                           disparity [px of the processed image] (-1 where invalid);
///                           points on or behind the rover's own wheels and body (VehicleMask,
///                           vehicle_mask.*, the rover description geometry.*) are invalid
///
/// Failures never crash the service and never produce a range image with bogus data: a frame
/// with the wrong camera or size, a byte count that is not width x height, missing, corrupt or
/// singular models (no baseline), FAILED/STALE health, a capture stamp before the request or
/// not after the previous frame's, or no dl/pose within pose_max_age_s of the capture
/// (require_pose) is dropped with a warning (sys/event), and no dl/range_image is sent for that
/// request. A request the driver does not answer within request_timeout_s of run-clock time is
/// dropped with a warning. Both set the heartbeat's health to DEGRADED with the reason
/// (msg::HealthLatch) until the next range image is published. A run-clock reset (simulator
/// reset) clears the pose history and re-sends the outstanding request.

#include <cstdint>
#include <deque>
#include <memory>
#include <string>

#include "rover/base/log.hpp"
#include "rover/dl/camera_client/camera_request_client.hpp"
#include "rover/dl/stereo/stereo_ranger.hpp"
#include "rover/msg/health.hpp"
#include "rover/msg/pose_history.hpp"
#include "rover/msg/range.hpp"
#include "rover/runtime/service.hpp"

namespace rover::dl::stereo {

class StereoService final : public Service {
 public:
  StereoService() : Service("dl-stereo") {}

  void DeclareParameters(ParamSet& params) override;
  /// Rules across parameters (range limits, the pipeline's own checks, e.g. an odd window).
  Status ValidateParameters(const ParamSet& params) const override;
  Status OnConfigure(ServiceContext& ctx, const ParamSet& params) override;

  /// Counters for tests and logs.
  struct Stats {
    std::uint64_t range_requests = 0;     ///< dl/range_request samples accepted into the queue
    std::uint64_t rejected_requests = 0;  ///< bad or overflowing range requests
    std::uint64_t camera_requests = 0;    ///< ddl/camera_request samples sent
    std::uint64_t frames = 0;             ///< ddl/stereo_frame samples that answered a request
    std::uint64_t bad_frames = 0;         ///< of which dropped as bad
    std::uint64_t timeouts = 0;           ///< requests the driver did not answer in time
    std::uint64_t published = 0;          ///< dl/range_image samples sent
  };
  const Stats& stats() const { return stats_; }
  /// The last problem reported (empty when the last request succeeded).
  const std::string& last_problem() const { return health_.problem(); }
  const StereoSetupCache* setup_cache() const {
    return ranger_ ? &ranger_->setup_cache() : nullptr;
  }

 private:
  void OnRangeRequest(const rover_dl_RangeRequest& m);
  void OnStereoFrame(const rover_ddl_StereoFrame& m);
  void OnPose(const rover_dl_PoseEstimate& m);
  void OnTimer();
  void SendNext();
  /// Ranges an answered frame; returns the reason if it is bad (nothing published then).
  Status Process(const camera_client::Outstanding& o, const rover_ddl_StereoFrame& m);
  void Fail(const std::string& problem, std::initializer_list<log::Field> fields);
  void UpdateHealth();

  ServiceContext* ctx_ = nullptr;
  // Parameters.
  int default_width_ = 256;
  std::size_t max_queue_ = 4;
  double pose_max_age_s_ = 1.0;
  bool require_pose_ = true;

  std::unique_ptr<StereoRanger> ranger_;
  std::unique_ptr<camera_client::CameraRequestClient> client_;
  msg::PoseHistory poses_;
  std::deque<msg::RangeRequest> queue_;
  msg::HealthLatch health_;
  Stats stats_;
  dds::Writer<rover_ddl_StereoRequest> request_writer_;
  dds::Writer<rover_dl_RangeImage> range_writer_;
};

}  // namespace rover::dl::stereo
