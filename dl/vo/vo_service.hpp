#pragma once
/// @file
/// dl-vo: binds MER visual odometry (library dl_vo: VoPipeline, VoCadence) and the camera client
/// (dl_camera_client) to topics, with MER's image cadence.
///
///   in:  dl/pose            the rover's pose, odometer, velocity: drives the cadence
///                           (VoCadence: a pair every step_distance of odometer or step_angle
///                           of turn or max_interval_s while driving, one at the end of each
///                           drive, the first as soon as poses arrive) and gives the wheel-
///                           odometry prior (kept in a msg::PoseHistory)
///        ddl/stereo_frame   the camera driver's answer to this service's ddl/camera_request
///                           (matched by request_id; other frames are ignored)
///   out: ddl/camera_request request_id = request_id_prefix << 24 | counter, the configured
///                           camera and processing width, exposure_us
///        dl/relative_pose   one per processed pair after the first (VoPipeline): source
///                           VISUAL_ODOMETRY, t_from/t_to = the capture stamps of the two pairs,
///                           delta = rover at t_to in the rover at t_from, 6x6 covariance over
///                           [dx dy dz droll dpitch dyaw], features and status. Only
///                           RELPOSE_CONVERGED samples are measurements; the others carry the
///                           odometry prior and their reason so that operators see failures.
///
/// Failures never crash the service: a bad frame (the client's checks: camera, size, health,
/// capture stamp; or the pipeline's: bytes, missing/corrupt/singular models) is dropped with a
/// warning and, when a reference exists, published as RELPOSE_BAD_INPUT; the next request
/// follows after retry_delay_s. A request the driver does not answer within request_timeout_s
/// (run clock) is dropped with a warning. Stale dl/pose (older than pose_max_age_s) pauses the
/// cadence. Each sets the heartbeat health to DEGRADED with its reason (msg::HealthLatch) until
/// the next converged step. A run-clock reset restarts everything (the reference is dropped).

#include <cstdint>
#include <memory>
#include <optional>
#include <set>
#include <string>

#include "rover/base/log.hpp"
#include "rover/dl/camera_client/camera_request_client.hpp"
#include "rover/dl/vo/cadence.hpp"
#include "rover/dl/vo/vo_pipeline.hpp"
#include "rover/dl/vo/vo_service_options.hpp"
#include "rover/msg/health.hpp"
#include "rover/msg/pose_history.hpp"
#include "rover/runtime/service.hpp"

namespace rover::dl::vo {

class VoService final : public Service {
 public:
  VoService() : Service("dl-vo") {}

  /// Staleness limits of the periodic inputs (parameters inputs.*): the pose (10 Hz) that paces and
  /// seeds the VO steps.
  std::vector<runtime::InputSpec> Inputs() const override {
    return {{"dl/pose", {.max_age_s = 1.0}}};
  }
  void DeclareParameters(ParamSet& params) override;
  /// Rules across parameters (VoServiceOptions::Validate: the cadence, client, prior and VO
  /// options' own checks; a step below vo.max_translation).
  Status ValidateParameters(const ParamSet& params) const override;
  Status OnConfigure(ServiceContext& ctx, const ParamSet& params) override;

  struct Stats {
    std::uint64_t camera_requests = 0;  ///< ddl/camera_request samples sent
    std::uint64_t frames = 0;           ///< ddl/stereo_frame samples that answered a request
    std::uint64_t bad_frames = 0;       ///< of which dropped as bad (service or library)
    std::uint64_t timeouts = 0;         ///< requests the driver did not answer in time
    std::uint64_t references = 0;       ///< pairs that only became the reference
    std::uint64_t published = 0;        ///< dl/relative_pose samples sent
    std::uint64_t converged = 0;        ///< of which RELPOSE_CONVERGED
    std::uint64_t rejected_commands = 0;  ///< dl/vo_command samples refused (bad client name)
  };
  /// Whether pairs are taken now: imaging = always, or a client asks (dl/vo_command).
  bool imaging() const { return options_.imaging == "always" || !clients_.empty(); }
  /// The clients asking for pairs now.
  const std::set<std::string>& clients() const { return clients_; }
  const Stats& stats() const { return stats_; }
  const std::string& last_problem() const { return health_.problem(); }
  const VoCadence* cadence() const { return cadence_.get(); }

 private:
  Status OnPose(const rover_dl_PoseEstimate& m);
  Status OnVoCommand(const rover_dl_VoCommand& m);
  void OnStereoFrame(const rover_ddl_StereoFrame& m);
  void OnTimer();
  void MaybeRequest(Time now);
  /// Processes an answered frame; an error is a bad frame.
  Status Process(const camera_client::Outstanding& o, const rover_ddl_StereoFrame& m);
  void Publish(const msg::RelativePose& r);
  void Problem(const std::string& problem, std::initializer_list<log::Field> fields);
  void UpdateHealth();
  void ResetAll(const std::string& why);

  ServiceContext* ctx_ = nullptr;
  VoServiceOptions options_;

  std::unique_ptr<VoCadence> cadence_;
  std::unique_ptr<camera_client::CameraRequestClient> client_;
  std::unique_ptr<VoPipeline> pipeline_;
  msg::PoseHistory poses_;
  msg::HealthLatch health_;
  Stats stats_;
  std::set<std::string> clients_;
  dds::Writer<rover_ddl_StereoRequest> request_writer_;
  dds::Writer<rover_dl_RelativePose> relpose_writer_;
};

}  // namespace rover::dl::vo
