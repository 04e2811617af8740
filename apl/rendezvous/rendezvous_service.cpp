#include "rendezvous_service.hpp"

#include <filesystem>
#include <memory>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>

#include "rover/apl/rendezvous/target_tracker.hpp"
#include "rover/apl/rendezvous/vision_pipeline.hpp"
#include "rover/base/log.hpp"
#include "rover/base/param_binder.hpp"
#include "rover/msg/camera_idl.hpp"
#include "rover/msg/arm_idl.hpp"
#include "rover/msg/mast_idl.hpp"
#include "rover/msg/mobility_idl.hpp"
#include "rover/msg/pose_idl.hpp"
#include "rover/msg/rendezvous_idl.hpp"

namespace rover::apl::rendezvous {
namespace {

constexpr double kStepRateHz = 5.0;
constexpr int kMaxDetectionImages = 40;
const char* const kDetectionDirKey = "rendezvous.detection_dir";

void Check(const Status& s, const char* topic) {
  if (!s.ok()) log::Error(std::string(topic) + " write failed", {{"error", s.message()}});
}

}  // namespace

void RendezvousService::DeclareParameters(ParamSet& params) {
  DeclareParams<RendezvousOptions>(params, "rendezvous.");
  DeclareParams<hwconfig::LanderDescription>(params, "lander.");
  DeclareParams<LanderDetectorOptions>(params, "lander_detector.");
  DeclareParams<LongRangeOptions>(params, "long_range.");
  DeclareParams<StripeDetectorOptions>(params, "stripes.");
  DeclareParams<RampPoseOptions>(params, "ramp_pose.");
  DeclareParams<TrackerOptions>(params, "tracker.");
  params.Declare(kDetectionDirKey, std::string(),
                 "folder for the drawn sightings (PNG); empty: none");
}

Status RendezvousService::ValidateParameters(const ParamSet& params) const {
  ROVER_RETURN_IF_ERROR(ReadParams<RendezvousOptions>(params, "rendezvous.").status());
  ROVER_RETURN_IF_ERROR(ReadParams<hwconfig::LanderDescription>(params, "lander.").status());
  ROVER_RETURN_IF_ERROR(ReadParams<LanderDetectorOptions>(params, "lander_detector.").status());
  ROVER_RETURN_IF_ERROR(ReadParams<LongRangeOptions>(params, "long_range.").status());
  ROVER_RETURN_IF_ERROR(ReadParams<StripeDetectorOptions>(params, "stripes.").status());
  ROVER_RETURN_IF_ERROR(ReadParams<TrackerOptions>(params, "tracker.").status());
  return ReadParams<RampPoseOptions>(params, "ramp_pose.").status();
}

Status RendezvousService::OnConfigure(ServiceContext& ctx, const ParamSet& params) {
  ctx_ = &ctx;
  ROVER_ASSIGN_OR_RETURN(const RendezvousOptions options,
                         ReadParams<RendezvousOptions>(params, "rendezvous."));
  ROVER_ASSIGN_OR_RETURN(const hwconfig::LanderDescription lander,
                         ReadParams<hwconfig::LanderDescription>(params, "lander."));
  VisionOptions vision;
  vision.prior_gate = options.prior_gate;
  ROVER_ASSIGN_OR_RETURN(vision.lander, ReadParams<LanderDetectorOptions>(params, "lander_detector."));
  ROVER_ASSIGN_OR_RETURN(vision.far, ReadParams<LongRangeOptions>(params, "long_range."));
  // The long-range detector where the mid-range one cannot reach.
  vision.far_range = std::max(options.sight_range, vision.lander.max_range);
  ROVER_ASSIGN_OR_RETURN(vision.stripes, ReadParams<StripeDetectorOptions>(params, "stripes."));
  ROVER_ASSIGN_OR_RETURN(vision.pose, ReadParams<RampPoseOptions>(params, "ramp_pose."));
  detection_dir_ = params.GetString(kDetectionDirKey);
  if (!detection_dir_.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(detection_dir_, ec);
    if (ec) {
      return InvalidArgument(std::string(kDetectionDirKey) + ": cannot create '" +
                             detection_dir_ + "': " + ec.message());
    }
  }
  ROVER_ASSIGN_OR_RETURN(const TrackerOptions tracker, ReadParams<TrackerOptions>(params, "tracker."));
  executor_.emplace(options, lander, std::make_shared<VisionPipeline>(lander, vision));
  approach_.emplace(options, std::make_shared<TargetTracker>(tracker));
  held_max_ = static_cast<std::size_t>(options.target_images_kept);

  ROVER_ASSIGN_OR_RETURN(mobility_writer_,
                         ctx.MakeWriter<rover_apl_MobilityCommand>("apl/mobility_command"));
  ROVER_ASSIGN_OR_RETURN(mast_writer_, ctx.MakeWriter<rover_dl_MastCommand>("dl/mast_command"));
  ROVER_ASSIGN_OR_RETURN(arm_writer_, ctx.MakeWriter<rover_dl_ArmCommand>("dl/arm_command"));
  ROVER_ASSIGN_OR_RETURN(camera_writer_,
                         ctx.MakeWriter<rover_ddl_StereoRequest>("ddl/camera_request"));
  ROVER_ASSIGN_OR_RETURN(status_writer_,
                         ctx.MakeWriter<rover_apl_RendezvousStatus>("apl/rendezvous_status"));

  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_apl_RendezvousCommand>(
      "apl/rendezvous_command", [this](const dds::Sample<rover_apl_RendezvousCommand>& s) {
        const msg::RendezvousCommand c = msg::RendezvousCommandFromIdl(s.data());
        log::Info("rendezvous command", {{"command_id", c.command_id},
                                         {"target", msg::RendezvousTargetName(c.target)}});
        OnCommand(c);
      }));
  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_dl_PoseEstimate>(
      "dl/pose", [this](const dds::Sample<rover_dl_PoseEstimate>& s) {
        const Result<msg::PoseSample> pose = msg::PoseSampleFromIdl(s.data());
        if (!pose.ok()) return pose.status();
        last_pose_ = pose->site_from_rover;
        Publish(executor_->OnPose(*pose, ctx_->Now()));
        Publish(approach_->OnPose(*pose, ctx_->Now()));
        return Status::Ok();
      }));
  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_apl_MobilityStatus>(
      "apl/mobility_status", [this](const dds::Sample<rover_apl_MobilityStatus>& s) {
        const Result<msg::MobilityStatus> st = msg::MobilityStatusFromIdl(s.data());
        if (!st.ok()) return st.status();
        Publish(executor_->OnMobilityStatus(*st, ctx_->Now()));
        Publish(approach_->OnMobilityStatus(*st, ctx_->Now()));
        return Status::Ok();
      }));
  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_dl_MastStatus>(
      "dl/mast_status", [this](const dds::Sample<rover_dl_MastStatus>& s) {
        const Result<msg::MastStatus> st = msg::MastStatusFromIdl(s.data());
        if (!st.ok()) return st.status();
        Publish(executor_->OnMastStatus(*st, ctx_->Now()));
        Publish(approach_->OnMastStatus(*st, ctx_->Now()));
        return Status::Ok();
      }));
  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_dl_ArmStatus>(
      "dl/arm_status", [this](const dds::Sample<rover_dl_ArmStatus>& s) {
        const Result<msg::ArmStatus> st = msg::ArmStatusFromIdl(s.data());
        if (!st.ok()) return st.status();
        Publish(approach_->OnArmStatus(*st, ctx_->Now()));
        return Status::Ok();
      }));
  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_ddl_StereoFrame>(
      "ddl/stereo_frame", [this](const dds::Sample<rover_ddl_StereoFrame>& s) {
        const rover_ddl_StereoFrame& m = s.data();
        const bool ours = (m.request_id >> 24) == kCameraRequestPrefix;
        if (!ours && m.camera != rover_CAMERA_NAVCAM) return Status::Ok();
        ROVER_ASSIGN_OR_RETURN(const msg::StereoFrame frame, msg::StereoFrameFromIdl(m));
        ROVER_ASSIGN_OR_RETURN(const geometry::CameraModel left_model,
                               msg::CameraModelFromFields(frame.left_model));
        ROVER_ASSIGN_OR_RETURN(const geometry::CameraModel right_model,
                               msg::CameraModelFromFields(frame.right_model));
        // Views of the sample's buffers, valid during this callback.
        const cv::Mat left(frame.height, frame.width, CV_8UC1,
                           const_cast<std::uint8_t*>(frame.left.data()));
        const cv::Mat right(frame.height, frame.width, CV_8UC1,
                            const_cast<std::uint8_t*>(frame.right.data()));
        if (frame.camera == msg::CameraId::kNavcam && last_pose_) {
          // Kept for science commands that name it (a copy: the sample is gone after this).
          held_.push_back({frame.request_id, left.clone(), right.clone(), left_model, right_model,
                           *last_pose_});
          while (held_.size() > held_max_) held_.pop_front();
        }
        if (!ours) return Status::Ok();
        NavcamPair pair;
        pair.stamp = frame.stamp;
        pair.request_id = frame.request_id;
        pair.left = &left;
        pair.right = &right;
        pair.left_model = &left_model;
        pair.right_model = &right_model;
        ExecutorOutput out;
        {
          runtime::ScopedActivity busy(ctx_->activities(), "vision");
          out = executor_->OnStereoPair(pair, ctx_->Now());
          Publish(out);
          out = approach_->OnStereoPair(pair, ctx_->Now());
        }
        Publish(out);
        return Status::Ok();
      }));
  ctx.executor().AddTimer(Seconds(1.0 / kStepRateHz), [this] {
    Publish(executor_->Step(ctx_->Now()));
    Publish(approach_->Step(ctx_->Now()));
  });
  ctx.SetHealth(rover_HEALTH_OK, "");
  return Status::Ok();
}

void RendezvousService::OnCommand(const msg::RendezvousCommand& c) {
  const Time now = ctx_->Now();
  if (c.target == msg::RendezvousTarget::kStop) {
    ExecutorOutput out;
    if (approach_->Stop(c.command_id, &out)) {
      Publish(out);
    } else {
      Publish(executor_->OnCommand(c, now));
    }
    return;
  }
  // One command at a time across both: the other one's running command makes this one BUSY.
  const bool science = c.target == msg::RendezvousTarget::kScience;
  const msg::RendezvousStatus* running = science && executor_->busy()    ? &executor_->status()
                                         : !science && approach_->busy() ? &approach_->status()
                                                                        : nullptr;
  if (running != nullptr) {
    ExecutorOutput out;
    msg::RendezvousStatus s = *running;
    s.command_id = c.command_id;
    s.phase = msg::RendezvousPhase::kFailed;
    s.fault = msg::RendezvousFault::kBusy;
    s.message = "command " + std::to_string(running->command_id) + " is running (phase " +
                msg::RendezvousPhaseName(running->phase) + ")";
    out.statuses.push_back(s);
    out.statuses.push_back(*running);
    Publish(out);
    return;
  }
  if (!science) {
    Publish(executor_->OnCommand(c, now));
    return;
  }
  const HeldPair* held = nullptr;
  for (const HeldPair& h : held_) {
    if (h.id == c.image_id) held = &h;
  }
  NavcamPair pair;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  if (held != nullptr) {
    pair.request_id = held->id;
    pair.left = &held->left;
    pair.right = &held->right;
    pair.left_model = &held->left_model;
    pair.right_model = &held->right_model;
    pose = held->site_from_rover;
  }
  runtime::ScopedActivity busy(ctx_->activities(), "vision");
  Publish(approach_->OnCommand(c, held != nullptr ? &pair : nullptr, pose, now));
}

Status RendezvousService::OnDeactivate(ServiceContext& ctx) {
  msg::RendezvousCommand stop;
  stop.target = msg::RendezvousTarget::kStop;
  if (approach_) {
    ExecutorOutput out;
    if (approach_->Stop(0, &out)) Publish(out);
  }
  if (executor_ && executor_->busy()) Publish(executor_->OnCommand(stop, ctx.Now()));
  return Status::Ok();
}

void RendezvousService::Publish(const ExecutorOutput& out) {
  for (const msg::MobilityCommand& c : out.mobility) {
    msg::MobilityCommandMessage m;
    msg::MobilityCommandToIdl(c, &m);
    ctx_->Stamp(m.msg.header, "site");
    Check(mobility_writer_.Write(m.msg), "apl/mobility_command");
  }
  for (const msg::MastCommand& c : out.mast) {
    rover_dl_MastCommand m{};
    msg::MastCommandToIdl(c, &m);
    ctx_->Stamp(m.header, "site");
    Check(mast_writer_.Write(m), "dl/mast_command");
  }
  for (const msg::ArmCommand& c : out.arm) {
    rover_dl_ArmCommand m{};
    msg::ArmCommandToIdl(c, &m);
    ctx_->Stamp(m.header, "rover");
    Check(arm_writer_.Write(m), "dl/arm_command");
  }
  for (const msg::StereoRequest& r : out.camera) {
    rover_ddl_StereoRequest m{};
    msg::StereoRequestToIdl(r, &m);
    ctx_->Stamp(m.header, "rover");
    Check(camera_writer_.Write(m), "ddl/camera_request");
  }
  for (const msg::RendezvousStatus& st : out.statuses) {
    rover_apl_RendezvousStatus m{};
    msg::RendezvousStatusToIdl(st, &m);
    ctx_->Stamp(m.header, "site");
    Check(status_writer_.Write(m), "apl/rendezvous_status");
    if (st.phase == msg::RendezvousPhase::kFailed) {
      log::Warn("rendezvous ended", {{"command_id", st.command_id},
                                     {"fault", msg::RendezvousFaultName(st.fault)},
                                     {"message", st.message}});
    } else {
      log::Info("rendezvous", {{"phase", msg::RendezvousPhaseName(st.phase)},
                               {"range", st.range},
                               {"target_x", st.target_position.x()},
                               {"target_y", st.target_position.y()},
                               {"target_sigma", st.target_sigma},
                               {"message", st.message}});
    }
  }
  for (const DetectionImage& d : out.images) {
    if (detection_dir_.empty() || !d.bgr || detections_written_ >= kMaxDetectionImages) continue;
    const std::string path = detection_dir_ + "/" + d.name + ".png";
    if (cv::imwrite(path, *d.bgr)) {
      ++detections_written_;
    } else {
      log::Warn("cannot write a detection image", {{"path", path}});
    }
  }
}

}  // namespace rover::apl::rendezvous
