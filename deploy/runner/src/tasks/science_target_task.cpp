#include "rover/deploy/runner/tasks/science_target_task.hpp"

#include <cmath>
#include <limits>

#include "rover/base/format.hpp"
#include "rover/msg/camera_idl.hpp"
#include "rover/msg/mast_idl.hpp"
#include "rover/msg/pose_idl.hpp"
#include "rover/msg/rendezvous_idl.hpp"

namespace rover::deploy::runner {
namespace {

std::vector<std::string> ScienceExpectChoices() {
  std::vector<std::string> out = {"at_target"};
  for (int f = 1; f < msg::kRendezvousFaultCount; ++f) {
    out.emplace_back(msg::RendezvousFaultName(static_cast<msg::RendezvousFault>(f)));
  }
  return out;
}

Status ParseXy(const YAML::Node& n, const std::string& key, double lo, double hi,
               const yaml::FileErrors& err, Eigen::Vector2d* out) {
  const YAML::Node v = n[key];
  if (!v) return Status::Ok();
  ROVER_RETURN_IF_ERROR(yaml::CheckKeys(v, "task." + key, {"x", "y"}, err));
  ROVER_RETURN_IF_ERROR(yaml::OptionalNumber(v, "x", "task." + key, lo, hi, err, &out->x()));
  return yaml::OptionalNumber(v, "y", "task." + key, lo, hi, err, &out->y());
}

constexpr double kNotJudged = std::numeric_limits<double>::quiet_NaN();

}  // namespace

Result<ScienceTargetSpec> ParseScienceTargetTask(const TaskSource& source) {
  const YAML::Node& n = source.section;
  const yaml::FileErrors& err = source.errors;
  ROVER_RETURN_IF_ERROR(yaml::CheckKeys(
      n, "task",
      {"type", "target", "standoff", "pixel_offset", "look_offset", "time_budget_s", "expect"}, err));
  ScienceTargetSpec spec;
  double target = 0;
  ROVER_RETURN_IF_ERROR(yaml::OptionalNumber(n, "target", "task", 0, 99, err, &target));
  if (target != std::floor(target)) {
    return err.At(n["target"], "task.target: " + yaml::ScalarText(n["target"]) +
                                   " is not an index into science_targets");
  }
  spec.target = static_cast<int>(target);
  ROVER_RETURN_IF_ERROR(yaml::OptionalNumber(n, "standoff", "task", 0.0, 5.0, err, &spec.standoff));
  ROVER_RETURN_IF_ERROR(ParseXy(n, "pixel_offset", -2000, 2000, err, &spec.pixel_offset));
  ROVER_RETURN_IF_ERROR(ParseXy(n, "look_offset", -50, 50, err, &spec.look_offset));
  ROVER_RETURN_IF_ERROR(
      yaml::OptionalNumber(n, "time_budget_s", "task", 0, 1e6, err, &spec.time_budget_s));
  if (const YAML::Node x = n["expect"]) {
    ROVER_ASSIGN_OR_RETURN(spec.expect, ParseTaskExpect(x, ScienceExpectChoices(), err));
  }
  return spec;
}

Status ScienceTargetTask::Open(TaskContext& ctx) {
  if (ctx.world != nullptr) {
    int seen = 0;
    for (const sim::terrain::Rock& r : ctx.world->terrain.rocks) {
      if (r.science_target && seen++ == spec_.target) {
        // Where an operator clicks on the rock: its face towards the rover, 0.4 radius from
        // its centre (the top of a low dome seen from 10 m sits on its silhouette).
        const Eigen::Vector2d c = r.position.head<2>();
        const Eigen::Vector2d to_rover = Eigen::Vector2d(start_x_, start_y_) - c;
        const Eigen::Vector2d p =
            c + 0.2 * r.diameter * (to_rover.norm() > 1e-6 ? to_rover.normalized() : Eigen::Vector2d::UnitX());
        top_ = Eigen::Vector3d(p.x(), p.y(), ctx.world->terrain.natural.Height(p.x(), p.y()));
      }
    }
    if (!top_) {
      return InvalidArgument("task.target: " + std::to_string(spec_.target) +
                             " is not a science target of the scenario (it has " +
                             std::to_string(seen) + ")");
    }
  }
  ROVER_ASSIGN_OR_RETURN(command_,
                         ctx.MakeWriter<rover_apl_RendezvousCommand>("apl/rendezvous_command"));
  ROVER_ASSIGN_OR_RETURN(mast_, ctx.MakeWriter<rover_dl_MastCommand>("dl/mast_command"));
  ROVER_ASSIGN_OR_RETURN(camera_, ctx.MakeWriter<rover_ddl_StereoRequest>("ddl/camera_request"));
  ROVER_ASSIGN_OR_RETURN(status_,
                         ctx.MakeReader<rover_apl_RendezvousStatus>("apl/rendezvous_status"));
  ROVER_ASSIGN_OR_RETURN(mast_status_, ctx.MakeReader<rover_dl_MastStatus>("dl/mast_status"));
  ROVER_ASSIGN_OR_RETURN(frames_, ctx.MakeReader<rover_ddl_StereoFrame>("ddl/stereo_frame"));
  ROVER_ASSIGN_OR_RETURN(truth_, ctx.MakeReader<rover_sim_Truth>("sim/truth"));
  ROVER_ASSIGN_OR_RETURN(odometry_, ctx.MakeReader<rover_dl_PoseEstimate>("dl/pose_odometry"));
  return Status::Ok();
}

bool ScienceTargetTask::Ready() const {
  return command_.valid() && command_.MatchedReaders() > 0 && mast_.MatchedReaders() > 0 &&
         camera_.MatchedReaders() > 0;
}

TaskOutcome ScienceTargetTask::Run(TaskContext& ctx) {
  TaskOutcome out;
  if (!top_) {
    out.failure = "science_target needs the simulated world (truth) to pick the target";
    return out;
  }
  std::optional<Eigen::Isometry3d> truth, odometry;
  auto pump = [&] {
    truth_.TakeEach([&](const dds::Sample<rover_sim_Truth>& s) {
      truth = msg::IsometryFromIdl(s->pose);
    });
    odometry_.TakeEach([&](const dds::Sample<rover_dl_PoseEstimate>& s) {
      if (auto p = msg::PoseSampleFromIdl(s.data()); p.ok()) odometry = p->site_from_rover;
    });
  };
  // 1. Aim the mast at the target and take the designation pair.
  StepResult look;
  look.primitive = "designation_pair";
  look.sim_start_s = ctx.Now();
  ctx.Note("science_target: designation pair");
  msg::MastCommand m;
  m.stamp = Time::FromSeconds(ctx.Now());
  m.command_id = kMastId;
  m.pointing = msg::MastPointing::kLookAt;
  m.look_at = *top_ + Eigen::Vector3d(spec_.look_offset.x(), spec_.look_offset.y(), 0.0);
  rover_dl_MastCommand mw{};
  msg::MastCommandToIdl(m, &mw);
  dds::CopyString(mw.header.frame_id, "site");
  if (!mast_.Write(mw).ok()) {
    out.failure = "cannot send the mast command";
    return out;
  }
  std::string mast_failure;
  bool at_goal = false;
  out.failure = ctx.WaitUntil([&] {
    pump();
    mast_status_.TakeEach([&](const dds::Sample<rover_dl_MastStatus>& s) {
      auto st = msg::MastStatusFromIdl(s.data());
      if (!st.ok() || st->command_id != kMastId) return;
      if (st->state == msg::MastState::kAtGoal) at_goal = true;
      if (st->state == msg::MastState::kFault || st->state == msg::MastState::kRejected) {
        mast_failure = std::string("dl-mast ") + msg::MastStateName(st->state) + ": " + st->message;
      }
    });
    return at_goal || !mast_failure.empty() || ctx.Now() - look.sim_start_s > 60.0;
  });
  if (!out.failure.empty()) return out;
  if (!at_goal) {
    out.failure = mast_failure.empty() ? "dl-mast did not reach the designation pointing in 60 s"
                                       : mast_failure;
    return out;
  }
  const std::uint32_t image_id = (kCameraPrefix << 24) | 1u;
  msg::StereoRequest r;
  r.stamp = Time::FromSeconds(ctx.Now());
  r.request_id = image_id;
  r.camera = msg::CameraId::kNavcam;
  rover_ddl_StereoRequest rw{};
  msg::StereoRequestToIdl(r, &rw);
  dds::CopyString(rw.header.frame_id, "rover");
  if (!camera_.Write(rw).ok()) {
    out.failure = "cannot send the camera request";
    return out;
  }
  std::optional<geometry::CameraModel> left_model;
  int width = 0, height = 0;
  const double asked = ctx.Now();
  out.failure = ctx.WaitUntil([&] {
    pump();
    frames_.TakeEach([&](const dds::Sample<rover_ddl_StereoFrame>& s) {
      if (s->request_id != image_id) return;
      auto f = msg::StereoFrameFromIdl(s.data());
      if (!f.ok()) return;
      auto lm = msg::CameraModelFromFields(f->left_model);
      if (!lm.ok()) return;
      left_model = *lm;
      width = f->width;
      height = f->height;
    });
    return left_model.has_value() || ctx.Now() - asked > 30.0;
  });
  if (!out.failure.empty()) return out;
  if (!left_model || !truth) {
    out.failure = !left_model ? "no NAVCAM pair for the designation within 30 s" : "no sim/truth heard";
    return out;
  }
  // 2. The operator's pick: the target point projected, plus the scenario's offset.
  const Eigen::Isometry3d truth_at_designation = *truth;
  const std::optional<Eigen::Isometry3d> odometry_at_designation = odometry;
  const Eigen::Vector3d top_rover = truth_at_designation.inverse() * *top_;
  const auto px = left_model->Project(top_rover);
  if (!px) {
    out.failure = "the target is behind the designation camera";
    return out;
  }
  const Eigen::Vector2d pixel = *px + spec_.pixel_offset;
  look.sim_end_s = ctx.Now();
  look.state = "succeeded";
  look.message = "target at pixel (" + FormatNumber(pixel.x()) + ", " + FormatNumber(pixel.y()) +
                 ") of " + std::to_string(width) + "x" + std::to_string(height) + ", " +
                 FormatNumber(top_rover.head<2>().norm()) + " m away";
  out.steps.push_back(look);
  ctx.recorder.AddFigure({"designation_range", top_rover.head<2>().norm(), kNotJudged, "m", true,
                          "true horizontal distance to the target at the designation"});

  // 3. The command, and its statuses.
  msg::RendezvousCommand c;
  c.stamp = Time::FromSeconds(ctx.Now());
  c.command_id = kCommandId;
  c.target = msg::RendezvousTarget::kScience;
  c.standoff = spec_.standoff;
  c.time_budget_s = spec_.time_budget_s;
  c.image_id = image_id;
  c.pixel_x = pixel.x();
  c.pixel_y = pixel.y();
  rover_apl_RendezvousCommand cw{};
  msg::RendezvousCommandToIdl(c, &cw);
  dds::CopyString(cw.header.frame_id, "site");
  StepResult step;
  step.primitive = "science_target";
  step.command_id = kCommandId;
  step.sim_start_s = ctx.Now();
  ctx.Note("science_target");
  if (!command_.Write(cw).ok()) {
    out.failure = "cannot send the rendezvous command";
    return out;
  }
  std::optional<msg::RendezvousStatus> terminal;
  bool at_target = false;
  int pairs = 0;
  const double deadline = spec_.time_budget_s > 0
                              ? step.sim_start_s + spec_.time_budget_s + kGraceS
                              : std::numeric_limits<double>::infinity();
  std::string last_phase;
  out.failure = ctx.WaitUntil([&] {
    pump();
    status_.TakeEach([&](const dds::Sample<rover_apl_RendezvousStatus>& s) {
      if (s->command_id != kCommandId) return;
      const Result<msg::RendezvousStatus> st = msg::RendezvousStatusFromIdl(s.data());
      if (!st.ok()) return;
      pairs = st->images;
      const std::string phase = msg::RendezvousPhaseName(st->phase);
      if (phase != last_phase) ctx.Note("science_target " + phase);
      last_phase = phase;
      if (st->phase == msg::RendezvousPhase::kAtTarget && !at_target && truth) {
        at_target = true;
        // 4. Placement against the truth now (the rover stands still at AT_TARGET).
        const Eigen::Vector3d truth_rover = truth->inverse() * *top_;
        const Eigen::Vector3d e = st->target_in_rover - truth_rover;
        ctx.recorder.AddFigure({"placement_error", 100.0 * e.norm(), kNotJudged, "cm", true,
                                "reported target in the rover frame (the arm's aim) against "
                                "the picked point's truth, 3-D"});
        ctx.recorder.AddFigure({"placement_error_horizontal", 100.0 * e.head<2>().norm(), kNotJudged,
                                "cm", true, "the same, horizontal"});
        ctx.recorder.AddFigure({"standoff_error",
                                100.0 * (truth_rover.head<2>().norm() -
                                         (spec_.standoff > 0 ? spec_.standoff : 1.05)),
                                kNotJudged, "cm", true, "true distance to the target minus the standoff"});
        ctx.recorder.AddFigure({"heading_to_target",
                                std::atan2(truth_rover.y(), truth_rover.x()) * 180.0 / M_PI, kNotJudged,
                                "deg", true, "true bearing of the target from the rover's heading"});
        if (odometry && odometry_at_designation) {
          // Wheel odometry alone: the designated point carried from the designation pose.
          const Eigen::Vector3d by_odometry = odometry->inverse() * *odometry_at_designation *
                                              truth_at_designation.inverse() * *top_;
          ctx.recorder.AddFigure({"odometry_placement_error",
                                  100.0 * (by_odometry - truth_rover).norm(), kNotJudged, "cm", true,
                                  "the target carried by dl/pose_odometry from the designation, "
                                  "against the truth, 3-D"});
        }
      }
      if ((st->phase == msg::RendezvousPhase::kDone || st->phase == msg::RendezvousPhase::kFailed) &&
          !terminal) {
        terminal = *st;
      }
    });
    return terminal.has_value() || ctx.Now() > deadline;
  });
  step.sim_end_s = ctx.Now();
  ctx.recorder.AddFigure({"tracking_pairs", static_cast<double>(pairs), kNotJudged, "count", true,
                          "NAVCAM pairs the approach took after the designation"});
  if (!terminal) {
    msg::RendezvousCommand stop;
    stop.stamp = Time::FromSeconds(ctx.Now());
    stop.command_id = kStopId;
    stop.target = msg::RendezvousTarget::kStop;
    rover_apl_RendezvousCommand sw{};
    msg::RendezvousCommandToIdl(stop, &sw);
    (void)command_.Write(sw);
    if (out.failure.empty()) {
      out.failure = "no terminal apl/rendezvous_status within the command's time budget of " +
                    FormatNumber(spec_.time_budget_s) + " s plus " + FormatNumber(kGraceS) +
                    " s (STOP sent)";
    }
    step.state = "interrupted";
    out.steps.push_back(step);
    return out;
  }
  const std::string fault = msg::RendezvousFaultName(terminal->fault);
  const bool done = terminal->phase == msg::RendezvousPhase::kDone;
  step.state = done ? "succeeded" : "failed";
  step.termination = done ? "at_target" : fault;
  step.message = terminal->message;
  out.steps.push_back(step);
  const bool ok = spec_.expect == "at_target" ? done && at_target : fault == spec_.expect;
  if (!ok) {
    out.failure = "science_target ended " + std::string(msg::RendezvousPhaseName(terminal->phase)) +
                  (done ? "" : " " + fault) + ", expected " + spec_.expect + ": " +
                  terminal->message;
  }
  return out;
}

std::vector<Eigen::Vector2d> ScienceTargetTask::PlannedPath() const {
  std::vector<Eigen::Vector2d> path{{start_x_, start_y_}};
  if (top_) path.push_back(top_->head<2>());
  return path;
}

void RegisterScienceTargetTask(TaskRegistry& registry) {
  registry.Register(
      "science_target",
      "pick a science target in a NAVCAM image, one apl/rendezvous_command TARGET_SCIENCE; "
      "judged on the placement error at the standoff",
      [](const TaskSource& source) -> Result<std::unique_ptr<Task>> {
        ROVER_ASSIGN_OR_RETURN(ScienceTargetSpec spec, ParseScienceTargetTask(source));
        const Scenario& s = source.scenario;
        return std::unique_ptr<Task>(
            std::make_unique<ScienceTargetTask>(std::move(spec), s.start_x, s.start_y));
      });
}

}  // namespace rover::deploy::runner
