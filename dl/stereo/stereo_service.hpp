#pragma once
/// @file
/// dl-stereo: binds the stereo ranging library (dl_stereo) to topics.
///
///   in:  dl/range_request   (request_id, camera, width): queued (at most max_queue), served one
///                           at a time in arrival order
///        ddl/stereo_frame   the camera driver's answer; only the frame whose request_id is the
///                           outstanding ddl/camera_request's is used, others are ignored
///        dl/pose            kept as a short history (PoseHistory) to look up the rover pose at
///                           the capture time
///   out: ddl/camera_request one per range request: this service's own request_id
///                           (request_id_prefix << 24 | counter), the camera, the processing
///                           width (the request's, or default_width when it says 0), exposure_us
///        dl/range_image     one per good frame: stamp = capture time, frame "rover", the
///                           range request's id and camera, the processed size, rover_pose = the
///                           dl/pose estimate interpolated at the capture time, XYZ [m] in the
///                           rover frame (NaN where invalid), valid (1/0), disparity [px of the
///                           processed image] (-1 where invalid)
///
/// Per frame: the models are converted (msg::CameraModelFromFields) and rectified once per model
/// pair (StereoSetupCache, rectification_cache_size pairs); the raw pair is remapped, correlated
/// and filtered by StereoPipeline; the disparities are reprojected with the rectified left camera's
/// pose in the rover frame. The disparity search range is num_disparities, or with 0 derived
/// from the nearest range of interest: ceil(f B / min_range_m) + 2 at the processing level,
/// clamped to [16, max_disparities].
///
/// Failures never crash the service and never produce a range image with bogus data: a frame
/// with the wrong camera or size, a byte count that is not width x height, missing, corrupt or
/// singular models (no baseline), FAILED/STALE health, a capture stamp before the request or
/// not after the previous frame's, or no dl/pose within pose_max_age_s of the capture
/// (require_pose) is dropped with a warning (sys/event), and no dl/range_image is sent for that
/// request. A request the driver does not answer within request_timeout_s of run-clock time is
/// dropped with a warning. Both set the heartbeat's health to DEGRADED with the reason until the
/// next range image is published. A run-clock reset (simulator reset) clears the pose history and
/// re-sends the outstanding request.

#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "rover/base/log.hpp"
#include "rover/dl/stereo/pipeline.hpp"
#include "rover/dl/stereo/pose_history.hpp"
#include "rover/dl/stereo/setup_cache.hpp"
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
  const std::string& last_problem() const { return last_problem_; }
  const StereoSetupCache* setup_cache() const { return cache_.get(); }

 private:
  struct Request {
    std::uint32_t range_request_id = 0;
    rover_CameraId camera = rover_CAMERA_NAVCAM;
    std::uint16_t width = 0;  // processing width asked of the driver (0 = full size)
  };
  struct Outstanding {
    Request request;
    std::uint32_t camera_request_id = 0;
    Time sent;
  };

  void OnRangeRequest(const rover_dl_RangeRequest& m);
  void OnStereoFrame(const rover_ddl_StereoFrame& m);
  void OnPose(const rover_dl_PoseEstimate& m);
  void OnTimer();
  void SendNext();
  /// Ranges a frame; returns the reason if it is bad (nothing published then).
  Status Process(const Outstanding& o, const rover_ddl_StereoFrame& m);
  Result<StereoPipeline*> PipelineFor(const StereoSetup& setup);
  void Fail(const std::string& problem, std::initializer_list<log::Field> fields);
  void UpdateHealth();

  ServiceContext* ctx_ = nullptr;
  // Parameters.
  int default_width_ = 256;
  std::uint32_t exposure_us_ = 0;
  double request_timeout_s_ = 10.0;
  std::size_t max_queue_ = 4;
  double pose_max_age_s_ = 1.0;
  bool require_pose_ = true;
  std::uint32_t request_prefix_ = 1;
  StereoOptions options_;
  int num_disparities_ = 0;  // 0 = derived from min_range_m_
  int max_disparities_ = 256;
  double min_range_m_ = 0.3;

  std::unique_ptr<StereoSetupCache> cache_;
  std::map<int, StereoPipeline> pipelines_;  // by number of disparities
  StereoOutput output_;
  PoseHistory poses_;
  std::deque<Request> queue_;
  std::optional<Outstanding> outstanding_;
  std::uint32_t counter_ = 0;
  std::optional<Time> last_frame_stamp_;
  Time last_now_{0};
  Stats stats_;
  std::string last_problem_;
  dds::Writer<rover_ddl_StereoRequest> request_writer_;
  dds::Writer<rover_dl_RangeImage> range_writer_;
};

}  // namespace rover::dl::stereo
