#pragma once
/// @file
/// apl-rendezvous: the service that binds the RendezvousExecutor (library apl_rendezvous) to
/// topics, with the VisionPipeline (lander detector, stripe detector, ramp pose) injected.
///
///   in:  apl/rendezvous_command -> OnCommand        dl/pose          -> OnPose
///        apl/mobility_status    -> OnMobilityStatus dl/mast_status   -> OnMastStatus
///        ddl/stereo_frame       -> OnStereoPair (only its own request ids, prefix 3)
///        dl/arm_status          -> TargetApproach::OnArmStatus
///   out: apl/mobility_command (every motion goes through apl-mobility), dl/mast_command,
///        dl/arm_command (stow, placement), ddl/camera_request (full NAVCAM frames),
///        apl/rendezvous_status (latched)
/// TARGET_SCIENCE commands go to the TargetApproach (target_approach.hpp, with the
/// TargetTracker), the others to the RendezvousExecutor; one command runs at a time (BUSY).
/// The service keeps the last `rendezvous.target_images_kept` NAVCAM pairs of any requester,
/// each with the dl/pose at its arrival, so a science command can name the pair its target was
/// picked in (image_id = the frame's request_id).
/// A run-clock timer at 5 Hz calls Step. The NAVCAM frames come from the camera driver itself
/// (as dl-stereo's and dl-vo's do): no DL service makes intensity images for the APL.
///
/// Parameters: rendezvous.* (RendezvousOptions), lander.* (the lander the rover knows,
/// core/hwconfig's LanderDescription), lander_detector.*, stripes.*, ramp_pose.*, and
/// rendezvous.detection_dir: a folder where every sighting's drawing is written as PNG (empty:
/// none; the runner points it into the run folder). A bad sample is rejected with its
/// conversion's message (sys/health) and never reaches the executor.

#include <deque>
#include <optional>
#include <string>

#include <opencv2/core.hpp>

#include "rover/apl/rendezvous/rendezvous_executor.hpp"
#include "rover/apl/rendezvous/target_approach.hpp"
#include "rover/runtime/service.hpp"

namespace rover::apl::rendezvous {

class RendezvousService final : public Service {
 public:
  RendezvousService() : Service("apl-rendezvous") {}

  std::vector<runtime::InputSpec> Inputs() const override {
    return {{"dl/pose", {.max_age_s = 1.0}}};
  }
  void DeclareParameters(ParamSet& params) override;
  Status ValidateParameters(const ParamSet& params) const override;
  Status OnConfigure(ServiceContext& ctx, const ParamSet& params) override;
  Status OnDeactivate(ServiceContext& ctx) override;

 private:
  struct HeldPair {
    std::uint32_t id = 0;
    cv::Mat left, right;
    geometry::CameraModel left_model, right_model;
    Eigen::Isometry3d site_from_rover = Eigen::Isometry3d::Identity();
  };
  void Publish(const ExecutorOutput& out);
  void OnCommand(const msg::RendezvousCommand& c);

  ServiceContext* ctx_ = nullptr;
  std::optional<RendezvousExecutor> executor_;
  std::optional<TargetApproach> approach_;
  std::deque<HeldPair> held_;
  std::size_t held_max_ = 8;
  std::optional<Eigen::Isometry3d> last_pose_;
  std::string detection_dir_;
  int detections_written_ = 0;
  dds::Writer<rover_apl_MobilityCommand> mobility_writer_;
  dds::Writer<rover_dl_MastCommand> mast_writer_;
  dds::Writer<rover_dl_ArmCommand> arm_writer_;
  dds::Writer<rover_ddl_StereoRequest> camera_writer_;
  dds::Writer<rover_apl_RendezvousStatus> status_writer_;
};

}  // namespace rover::apl::rendezvous
