#pragma once
/// @file
/// dl-vo: binds MER visual odometry (library dl_vo) to topics, with MER's image cadence.
///
///   in:  dl/pose            the rover's pose, odometer, velocity: drives the cadence
///                           (VoCadence: a pair every step_distance of odometer or step_angle
///                           of turn or max_interval_s while driving, one at the end of each
///                           drive, the first as soon as poses arrive) and gives the wheel-
///                           odometry prior (OdometryPrior from the poses at the two capture
///                           times, in the rover frame)
///        ddl/stereo_frame   the camera driver's answer to this service's ddl/camera_request
///                           (matched by request_id; other frames are ignored)
///   out: ddl/camera_request request_id = request_id_prefix << 24 | counter, the configured
///                           camera and processing width, exposure_us
///        dl/relative_pose   one per processed pair after the first: source VISUAL_ODOMETRY,
///                           t_from/t_to = the capture stamps of the two pairs, delta = rover at
///                           t_to in the rover at t_from (ToBodyFrame with the rectified left
///                           camera's pose in the rover frame), 6x6 covariance over
///                           [dx dy dz droll dpitch dyaw], features (inliers when converged,
///                           else features tracked) and status. Only RELPOSE_CONVERGED samples
///                           are measurements; the others carry the odometry prior and their
///                           reason so that operators see failures (the EKF ignores them).
///
/// Per frame: models converted and rectified once per model pair (StereoSetupCache), the raw
/// pair remapped (dl_stereo Rectify) into the rectified pinhole pair VisualOdometry works on.
/// Every processed pair becomes the reference of the next step (as on MER). If the rectified
/// intrinsics change, VisualOdometry is recreated; if the camera moved on the rover between two
/// pairs (mast pointing), the new pair only becomes the reference (no step across it).
///
/// Failures never crash the service: a bad frame (camera, size, bytes, missing/corrupt/singular
/// models, FAILED/STALE health, capture stamp before the request or not after the previous
/// pair) or a pair the library rejects is dropped with a warning and, when a reference exists,
/// published as RELPOSE_BAD_INPUT; the next request follows after retry_delay_s. A request the
/// driver does not answer within request_timeout_s (run clock) is dropped with a warning. Stale
/// dl/pose (older than pose_max_age_s) pauses the cadence. Each sets the heartbeat health to
/// DEGRADED with its reason until the next converged step. A run-clock reset restarts
/// everything (the reference is dropped).

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "rover/base/log.hpp"
#include "rover/dl/stereo/pose_history.hpp"
#include "rover/dl/stereo/setup_cache.hpp"
#include "rover/dl/vo/cadence.hpp"
#include "rover/dl/vo/odometry_prior.hpp"
#include "rover/dl/vo/visual_odometry.hpp"
#include "rover/runtime/service.hpp"

namespace rover::dl::vo {

/// The dl/relative_pose status of a library status (kNoReference has none: maps to BAD_INPUT).
rover_dl_RelativePoseStatus RelativePoseStatusOf(MotionStatus status);

class VoService final : public Service {
 public:
  VoService() : Service("dl-vo") {}

  void DeclareParameters(ParamSet& params) override;
  /// Rules across parameters (the cadence, prior and VO options' own checks; a step below
  /// vo.max_translation).
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
  };
  const Stats& stats() const { return stats_; }
  const std::string& last_problem() const { return last_problem_; }
  const VoCadence* cadence() const { return cadence_.get(); }

 private:
  struct Outstanding {
    std::uint32_t id = 0;
    Time sent;
    VoCadence::Reason reason = VoCadence::Reason::kNone;
  };
  struct Reference {
    Time stamp;
    std::optional<msg::PoseSample> pose;  // rover pose at capture, if known
    Eigen::Isometry3d rover_from_camera;  // rectified left camera
  };

  void OnPose(const rover_dl_PoseEstimate& m);
  void OnStereoFrame(const rover_ddl_StereoFrame& m);
  void OnTimer();
  void MaybeRequest(Time now);
  /// Processes an answered frame; an error is a bad frame.
  Status Process(const Outstanding& o, const rover_ddl_StereoFrame& m);
  void PublishBadInput(Time t_to, const std::string& why);
  void Publish(const MotionEstimate& body, rover_dl_RelativePoseStatus status,
               std::uint32_t features);
  void Problem(const std::string& problem, std::initializer_list<log::Field> fields);
  void UpdateHealth();
  void ResetAll(const std::string& why);
  MotionPrior PriorTo(const std::optional<msg::PoseSample>& to) const;

  ServiceContext* ctx_ = nullptr;
  // Parameters.
  rover_CameraId camera_ = rover_CAMERA_FRONT_HAZCAM;
  std::uint16_t width_ = 512;
  std::uint32_t exposure_us_ = 0;
  double request_timeout_s_ = 10.0;
  double retry_delay_s_ = 1.0;
  double pose_max_age_s_ = 1.0;
  std::uint32_t request_prefix_ = 2;
  Options vo_options_;
  OdometryPriorOptions prior_options_;
  CadenceOptions cadence_options_;

  std::unique_ptr<VoCadence> cadence_;
  std::unique_ptr<stereo::StereoSetupCache> cache_;
  stereo::PoseHistory poses_;
  std::optional<VisualOdometry> vo_;
  std::optional<Reference> reference_;
  std::optional<Outstanding> outstanding_;
  std::optional<Time> last_frame_stamp_;
  Time hold_until_{0};
  Time last_now_{0};
  std::uint32_t counter_ = 0;
  cv::Mat rect_left_, rect_right_;
  Stats stats_;
  std::string last_problem_;
  dds::Writer<rover_ddl_StereoRequest> request_writer_;
  dds::Writer<rover_dl_RelativePose> relpose_writer_;
};

}  // namespace rover::dl::vo
