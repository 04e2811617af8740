#include "rover/deploy/runner/tasks/science_target_task.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>

#include "rover/base/format.hpp"
#include "rover/deploy/runner/tasks/arm_steps.hpp"
#include "rover/hwconfig/rover_description.hpp"
#include "rover/msg/arm_idl.hpp"
#include "rover/msg/camera_idl.hpp"
#include "rover/msg/mobility_idl.hpp"
#include "rover/msg/sequence_idl.hpp"
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
// Relative 1-sigma of the ground's stereo range of a picked point (seed 004: 1-2 %).
constexpr double kGroundRangeSigma = 0.015;

}  // namespace

Result<ScienceTargetSpec> ParseScienceTargetTask(const TaskSource& source) {
  const YAML::Node& n = source.section;
  const yaml::FileErrors& err = source.errors;
  ROVER_RETURN_IF_ERROR(yaml::CheckKeys(
      n, "task",
      {"type", "target", "standoff", "pixel_offset", "look_offset", "time_budget_s", "expect",
       "place", "autofocus", "template"},
      err));
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
  for (auto [key, flag] : {std::pair{"place", &spec.place}, {"autofocus", &spec.autofocus}}) {
    if (const YAML::Node p = n[key]) {
      if (!p.IsScalar() || (p.Scalar() != "true" && p.Scalar() != "false")) {
        return err.At(p, "task." + std::string(key) + ": " + yaml::ScalarText(p) +
                             " is not true or false");
      }
      *flag = p.Scalar() == "true";
    }
  }
  if (const YAML::Node x = n["expect"]) {
    ROVER_ASSIGN_OR_RETURN(spec.expect, ParseTaskExpect(x, ScienceExpectChoices(), err));
  }
  if (const YAML::Node t = n["template"]) {
    ROVER_RETURN_IF_ERROR(yaml::CheckKeys(t, "task.template", {"file", "time_budget_s"}, err));
    ROVER_RETURN_IF_ERROR(yaml::RequireKey(t, "task.template", "file", err));
    TemplateSpec ts;
    ts.file = t["file"].as<std::string>();
    if (!ts.file.empty() && ts.file.front() != '/') {
      const std::string dir = std::filesystem::path(source.scenario.file).parent_path().string();
      ts.file = (dir.empty() ? std::string(".") : dir) + "/" + ts.file;
    }
    std::ifstream in(ts.file);
    if (!in) return err.At(t["file"], "task.template.file: cannot read '" + ts.file + "'");
    ROVER_RETURN_IF_ERROR(
        yaml::OptionalNumber(t, "time_budget_s", "task.template", 10, 1e6, err, &ts.time_budget_s));
    spec.template_approach = ts;
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
  ROVER_ASSIGN_OR_RETURN(estimate_, ctx.MakeReader<rover_dl_PoseEstimate>("dl/pose"));
  ROVER_ASSIGN_OR_RETURN(arm_, ctx.MakeWriter<rover_dl_ArmCommand>("dl/arm_command"));
  ROVER_ASSIGN_OR_RETURN(arm_status_, ctx.MakeReader<rover_dl_ArmStatus>("dl/arm_status"));
  if (spec_.template_approach) {
    ROVER_ASSIGN_OR_RETURN(sequence_,
                           ctx.MakeWriter<rover_apl_SequenceCommand>("apl/sequence_command"));
    ROVER_ASSIGN_OR_RETURN(sequence_status_,
                           ctx.MakeReader<rover_apl_SequenceStatus>("apl/sequence_status"));
    ROVER_ASSIGN_OR_RETURN(mobility_,
                           ctx.MakeWriter<rover_apl_MobilityCommand>("apl/mobility_command"));
    ROVER_ASSIGN_OR_RETURN(mobility_status_,
                           ctx.MakeReader<rover_apl_MobilityStatus>("apl/mobility_status"));
  }
  return Status::Ok();
}

bool ScienceTargetTask::Ready() const {
  return command_.valid() && command_.MatchedReaders() > 0 && mast_.MatchedReaders() > 0 &&
         camera_.MatchedReaders() > 0 &&
         (!spec_.template_approach ||
          (sequence_.MatchedReaders() > 0 && mobility_.MatchedReaders() > 0));
}

void ScienceTargetTask::Pump() {
  truth_.TakeEach([&](const dds::Sample<rover_sim_Truth>& s) {
    truth_now_ = msg::IsometryFromIdl(s->pose);
    tool_now_ = Eigen::Vector3d(s->tool_point.x, s->tool_point.y, s->tool_point.z);
    tool_contact_now_ = s->tool_contact;
  });
  arm_status_.TakeEach([&](const dds::Sample<rover_dl_ArmStatus>& s) {
    if (auto a = msg::ArmStatusFromIdl(s.data()); a.ok()) arm_now_ = *a;
  });
  odometry_.TakeEach([&](const dds::Sample<rover_dl_PoseEstimate>& s) {
    if (auto p = msg::PoseSampleFromIdl(s.data()); p.ok()) odometry_now_ = p->site_from_rover;
  });
  estimate_.TakeEach([&](const dds::Sample<rover_dl_PoseEstimate>& s) {
    if (auto p = msg::PoseSampleFromIdl(s.data()); p.ok()) estimate_now_ = p->site_from_rover;
  });
}

std::string ScienceTargetTask::Designate(TaskContext& ctx, std::uint32_t n, StepResult* step,
                                         Designation* d) {
  step->primitive = "designation_pair";
  step->sim_start_s = ctx.Now();
  ctx.Note("science_target: designation pair " + std::to_string(n));
  msg::MastCommand m;
  m.stamp = Time::FromSeconds(ctx.Now());
  m.command_id = kMastId + n - 1;
  m.pointing = msg::MastPointing::kLookAt;
  m.look_at = *top_ + Eigen::Vector3d(spec_.look_offset.x(), spec_.look_offset.y(), 0.0);
  rover_dl_MastCommand mw{};
  msg::MastCommandToIdl(m, &mw);
  dds::CopyString(mw.header.frame_id, "site");
  if (!mast_.Write(mw).ok()) return "cannot send the mast command";
  std::string mast_failure;
  bool at_goal = false;
  std::string failure = ctx.WaitUntil([&] {
    Pump();
    mast_status_.TakeEach([&](const dds::Sample<rover_dl_MastStatus>& s) {
      auto st = msg::MastStatusFromIdl(s.data());
      if (!st.ok() || st->command_id != m.command_id) return;
      if (st->state == msg::MastState::kAtGoal) at_goal = true;
      if (st->state == msg::MastState::kFault || st->state == msg::MastState::kRejected) {
        mast_failure = std::string("dl-mast ") + msg::MastStateName(st->state) + ": " + st->message;
      }
    });
    return at_goal || !mast_failure.empty() || ctx.Now() - step->sim_start_s > 60.0;
  });
  if (!failure.empty()) return failure;
  if (!at_goal) {
    return mast_failure.empty() ? "dl-mast did not reach the designation pointing in 60 s"
                                : mast_failure;
  }
  d->image_id = (kCameraPrefix << 24) | n;
  msg::StereoRequest r;
  r.stamp = Time::FromSeconds(ctx.Now());
  r.request_id = d->image_id;
  r.camera = msg::CameraId::kNavcam;
  rover_ddl_StereoRequest rw{};
  msg::StereoRequestToIdl(r, &rw);
  dds::CopyString(rw.header.frame_id, "rover");
  if (!camera_.Write(rw).ok()) return "cannot send the camera request";
  std::optional<geometry::CameraModel> left_model;
  int width = 0, height = 0;
  const double asked = ctx.Now();
  failure = ctx.WaitUntil([&] {
    Pump();
    frames_.TakeEach([&](const dds::Sample<rover_ddl_StereoFrame>& s) {
      if (s->request_id != d->image_id) return;
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
  if (!failure.empty()) return failure;
  if (!left_model || !truth_now_) {
    return !left_model ? "no NAVCAM pair for the designation within 30 s" : "no sim/truth heard";
  }
  // The operator's pick: the target point projected with the true pose, plus the offset.
  d->truth = *truth_now_;
  d->estimate = estimate_now_;
  d->odometry = odometry_now_;
  const Eigen::Vector3d top_rover = d->truth.inverse() * *top_;
  const auto px = left_model->Project(top_rover);
  if (!px) return "the target is behind the designation camera";
  d->pixel = *px + spec_.pixel_offset;
  // The site point MER's operators would send (seed 003): the ground's stereo range of the
  // picked point, 1-2 % off (seed 004: kGroundRangeSigma, drawn with the run's seed) along the
  // camera's ray, placed in the site frame with the rover's own pose (dl/pose).
  if (d->estimate) {
    const Eigen::Vector3d c = d->truth * left_model->Center();
    const Eigen::Vector3d ray = *top_ - c;
    std::mt19937 rng(0x6e0u + ctx.seed);
    std::normal_distribution<double> unit(0.0, 1.0);
    const Eigen::Vector3d ranged = *top_ + kGroundRangeSigma * unit(rng) * ray;
    d->ground_point = *d->estimate * (d->truth.inverse() * ranged);
  }
  step->sim_end_s = ctx.Now();
  step->state = "succeeded";
  step->message = "target at pixel (" + FormatNumber(d->pixel.x()) + ", " +
                  FormatNumber(d->pixel.y()) + ") of " + std::to_string(width) + "x" +
                  std::to_string(height) + ", " + FormatNumber(top_rover.head<2>().norm()) +
                  " m away";
  return "";
}

void ScienceTargetTask::RunTemplate(TaskContext& ctx, const Designation& d, TaskOutcome* out) {
  const double standoff = spec_.standoff > 0 ? spec_.standoff : 1.05;
  StepResult step;
  step.primitive = "template_approach";
  step.command_id = kSequenceId;
  step.sim_start_s = ctx.Now();
  auto done_with = [&](const std::string& state, const std::string& message) {
    step.sim_end_s = ctx.Now();
    step.state = state;
    step.message = message;
    out->steps.push_back(step);
  };
  if (!d.ground_point) {
    done_with("failed", "the picked pixel has no ground range: no template approach");
    ctx.recorder.AddFigure({"template_done", 0.0, kNotJudged, "", true, "no ground range"});
    return;
  }
  std::ifstream in(spec_.template_approach->file);
  std::stringstream buffer;
  buffer << in.rdbuf();
  const Eigen::Vector3d g = *d.ground_point;
  Result<std::string> overrides = msg::FormatSequenceOverrides(
      {{"target", "(" + FormatNumber(g.x(), 6) + ", " + FormatNumber(g.y(), 6) + ", " +
                      FormatNumber(g.z(), 6) + ")"}});
  if (!overrides.ok()) {
    out->failure = "template: " + overrides.status().message();
    done_with("failed", out->failure);
    return;
  }
  msg::SequenceCommand c;
  c.stamp = Time::FromSeconds(ctx.Now());
  c.command_id = kSequenceId;
  c.text = buffer.str();
  c.overrides = *overrides;
  rover_apl_SequenceCommand cw{};
  if (Status s = msg::SequenceCommandToIdl(c, &cw); !s.ok()) {
    out->failure = "template: " + s.message();
    done_with("failed", out->failure);
    return;
  }
  dds::CopyString(cw.header.frame_id, "site");
  ctx.Note("science_target: template approach");
  if (!sequence_.Write(cw).ok()) {
    out->failure = "cannot send the template sequence";
    done_with("failed", out->failure);
    return;
  }
  std::optional<msg::SequenceStatus> end;
  const double deadline = step.sim_start_s + spec_.template_approach->time_budget_s;
  std::string failure = ctx.WaitUntil([&] {
    Pump();
    sequence_status_.TakeEach([&](const dds::Sample<rover_apl_SequenceStatus>& s) {
      auto st = msg::SequenceStatusFromIdl(s.data());
      if (!st.ok() || st->command_id != kSequenceId) return;
      if (st->state == msg::SequenceState::kDone || st->state == msg::SequenceState::kFailed) end = *st;
    });
    return end.has_value() || ctx.Now() > deadline;
  });
  if (!failure.empty()) {
    out->failure = failure;
    done_with("interrupted", failure);
    return;
  }
  const bool done = end && end->state == msg::SequenceState::kDone;
  ctx.recorder.AddFigure({"template_done", done ? 1.0 : 0.0, kNotJudged, "", true,
                          end ? end->message : "no terminal apl/sequence_status in the budget"});
  // The approach itself ended when the sequence is DONE or failed only at its ARM PLACE (the
  // arm found nothing to touch where the rover believed the target: measured, not excused).
  const bool approached = done || (end && end->message.find("ARM PLACE") != std::string::npos);
  if (approached && truth_now_ && estimate_now_) {
    // The arm is sent to the target as the rover believes it: TARGET through dl/pose. When the
    // template's ARM PLACE touched, the instrument is measured; otherwise that aim.
    const Eigen::Vector3d believed = estimate_now_->inverse() * g;
    const Eigen::Vector3d truth_rover = truth_now_->inverse() * *top_;
    const Eigen::Vector3d aim = believed - truth_rover;
    ctx.recorder.AddFigure({"template_aim_error", 100.0 * aim.norm(), kNotJudged, "cm", true,
                            "template approach: the target point through dl/pose against the "
                            "truth in the rover frame, 3-D"});
    ctx.recorder.AddFigure({"template_instrument_contact", tool_contact_now_ ? 1.0 : 0.0,
                            kNotJudged, "", true,
                            "the template's ARM PLACE left the instrument touching the terrain"});
    const Eigen::Vector3d e = tool_contact_now_ ? Eigen::Vector3d(tool_now_ - *top_) : aim;
    ctx.recorder.AddFigure({"template_placement_error", 100.0 * e.norm(), kNotJudged, "cm", true,
                            tool_contact_now_
                                ? "template approach: the instrument on the target (ARM PLACE at "
                                  "the target through dl/pose) against the picked point, 3-D"
                                : "template approach: the target point through dl/pose against "
                                  "the truth in the rover frame, 3-D"});
    ctx.recorder.AddFigure({"template_placement_error_horizontal", 100.0 * e.head<2>().norm(),
                            kNotJudged, "cm", true, "the same, horizontal"});
    ctx.recorder.AddFigure({"template_standoff_error",
                            100.0 * (truth_rover.head<2>().norm() - standoff), kNotJudged, "cm",
                            true, "template approach: true distance to the target minus the standoff"});
  }
  done_with(done ? "succeeded" : "failed", end ? end->message : "over its budget");
  if (!end) {
    // Over budget: stop the sequence's motion before going back.
    msg::MobilityCommand stop;
    stop.command_id = kReturnDriveId - 1;
    stop.mode = msg::MobilityMode::kStop;
    msg::MobilityCommandMessage sm;
    msg::MobilityCommandToIdl(stop, &sm);
    (void)mobility_.Write(sm.msg);
  }
  // Back to the start for the tracked approach (DIRECTED, by dl/pose), after clearing a motion
  // error the template may have latched (its own run is measured above), the arm stowed.
  if (std::string why = StowArm(ctx); !why.empty()) {
    out->failure = why;
    return;
  }
  {
    msg::MobilityCommand clear;
    clear.stamp = Time::FromSeconds(ctx.Now());
    clear.command_id = kReturnDriveId - 2;
    clear.mode = msg::MobilityMode::kClearFault;
    msg::MobilityCommandMessage cm;
    msg::MobilityCommandToIdl(clear, &cm);
    dds::CopyString(cm.msg.header.frame_id, "site");
    (void)mobility_.Write(cm.msg);
  }
  if (!estimate_now_) return;
  const Eigen::Vector2d at = estimate_now_->translation().head<2>();
  const double yaw = std::atan2((*estimate_now_).linear()(1, 0), (*estimate_now_).linear()(0, 0));
  const Eigen::Vector2d to = Eigen::Vector2d(start_x_, start_y_) - at;
  msg::MobilityCommand back;
  back.stamp = Time::FromSeconds(ctx.Now());
  back.command_id = kReturnDriveId;
  back.mode = msg::MobilityMode::kDirected;
  back.time_budget_s = 900.0;
  const double face = std::remainder(std::atan2(to.y(), to.x()) - yaw, 2.0 * M_PI);
  back.primitives.push_back({msg::DrivePrimitive::kTurnInPlace, 0.0, 0.0, face});
  back.primitives.push_back({msg::DrivePrimitive::kStraight, 0.0, to.norm(), 0.0});
  back.primitives.push_back({msg::DrivePrimitive::kTurnInPlace, 0.0, 0.0,
                             std::remainder(start_yaw_ - (yaw + face), 2.0 * M_PI)});
  msg::MobilityCommandMessage bm;
  msg::MobilityCommandToIdl(back, &bm);
  dds::CopyString(bm.msg.header.frame_id, "site");
  StepResult ret;
  ret.primitive = "return_to_start";
  ret.command_id = kReturnDriveId;
  ret.sim_start_s = ctx.Now();
  ctx.Note("science_target: back to the start");
  if (!mobility_.Write(bm.msg).ok()) {
    out->failure = "cannot send the return drive";
    return;
  }
  std::optional<msg::MobilityStatus> ended;
  failure = ctx.WaitUntil([&] {
    Pump();
    mobility_status_.TakeEach([&](const dds::Sample<rover_apl_MobilityStatus>& s) {
      auto st = msg::MobilityStatusFromIdl(s.data());
      if (!st.ok() || st->command_id != kReturnDriveId) return;
      if (st->state == msg::MobilityState::kSucceeded || st->state == msg::MobilityState::kFailed ||
          st->state == msg::MobilityState::kRejected) {
        ended = *st;
      }
    });
    return ended.has_value() || ctx.Now() - ret.sim_start_s > 960.0;
  });
  ret.sim_end_s = ctx.Now();
  ret.state = ended && ended->state == msg::MobilityState::kSucceeded ? "succeeded" : "failed";
  ret.message = ended ? ended->message : "no end of the return drive";
  out->steps.push_back(ret);
  if (!failure.empty()) out->failure = failure;
}

std::string ScienceTargetTask::StowArm(TaskContext& ctx) {
  ctx.Note("science_target: stowing the arm");
  return StowArmAndWait(ctx, arm_, [&] { Pump(); return arm_now_; }, kStowId, 300.0);
}

TaskOutcome ScienceTargetTask::Run(TaskContext& ctx) {
  TaskOutcome out;
  if (!top_) {
    out.failure = "science_target needs the simulated world (truth) to pick the target";
    return out;
  }
  std::uint32_t pair_n = 1;
  if (spec_.template_approach) {
    StepResult look;
    Designation first;
    out.failure = Designate(ctx, pair_n++, &look, &first);
    out.steps.push_back(look);
    if (!out.failure.empty()) return out;
    RunTemplate(ctx, first, &out);
    if (!out.failure.empty()) return out;
  }
  // 1-2. The designation pair and the operator's pixel.
  StepResult look;
  Designation d;
  out.failure = Designate(ctx, pair_n, &look, &d);
  out.steps.push_back(look);
  if (!out.failure.empty()) return out;
  const Eigen::Isometry3d truth_at_designation = d.truth;
  const std::optional<Eigen::Isometry3d> odometry_at_designation = d.odometry;
  const Eigen::Vector2d pixel = d.pixel;
  const std::uint32_t image_id = d.image_id;
  const Eigen::Vector3d top_rover = truth_at_designation.inverse() * *top_;
  ctx.recorder.AddFigure({"designation_range", top_rover.head<2>().norm(), kNotJudged, "m", true,
                          "true horizontal distance to the target at the designation"});
  std::optional<Eigen::Isometry3d>& truth = truth_now_;
  std::optional<Eigen::Isometry3d>& odometry = odometry_now_;
  auto pump = [&] { Pump(); };

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
  c.place_instrument = spec_.place;
  c.autofocus = spec_.autofocus;
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
  bool placed = false, focused = false;
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
      if (st->phase == msg::RendezvousPhase::kPlaced && !placed && truth) {
        placed = true;
        // 5. The instrument on the target: its face centre (sim/truth) against the picked point.
        const Eigen::Vector3d e = tool_now_ - *top_;
        ctx.recorder.AddFigure({"placement_error", 100.0 * e.norm(), kNotJudged, "cm", true,
                                "the instrument's face centre (arm placed, contact) against the "
                                "picked point, 3-D"});
        ctx.recorder.AddFigure({"placement_error_horizontal", 100.0 * e.head<2>().norm(), kNotJudged,
                                "cm", true, "the same, horizontal"});
        ctx.recorder.AddFigure({"instrument_contact", tool_contact_now_ ? 1.0 : 0.0, kNotJudged, "",
                                true, "the instrument's face touches the terrain at PLACED"});
      }
      if (st->phase == msg::RendezvousPhase::kFocused && !focused && truth) {
        focused = true;
        // 6. The microscopic imager at best focus: its face against the terrain under it.
        const double error = FocusErrorFromTruth(ctx, tool_now_);
        const double dof = hwconfig::RoverDescription{}.arm.imager.DepthOfFieldHalf();
        ctx.recorder.AddFigure({"focus_error", 1000.0 * std::abs(error), kNotJudged, "mm", true,
                                "|face height - (terrain under it + working distance)| at "
                                "FOCUSED; depth of field +-" + FormatNumber(1000.0 * dof, 3) +
                                    " mm"});
        ctx.recorder.AddFigure({"in_focus", std::abs(error) <= dof ? 1.0 : 0.0, kNotJudged, "",
                                true, "the final frame in focus at its centre"});
      }
      if (st->phase == msg::RendezvousPhase::kAtTarget && !at_target && truth) {
        at_target = true;
        // 4. The aim against the truth now (the rover stands still at AT_TARGET).
        const Eigen::Vector3d truth_rover = truth->inverse() * *top_;
        const Eigen::Vector3d e = st->target_in_rover - truth_rover;
        const char* aim = spec_.place ? "aim_error" : "placement_error";
        ctx.recorder.AddFigure({aim, 100.0 * e.norm(), kNotJudged, "cm", true,
                                "reported target in the rover frame (the arm's aim) against "
                                "the picked point's truth, 3-D"});
        ctx.recorder.AddFigure({std::string(aim) + "_horizontal", 100.0 * e.head<2>().norm(),
                                kNotJudged, "cm", true, "the same, horizontal"});
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
  const bool ok = spec_.expect == "at_target"
                      ? done && at_target && (placed || !spec_.place) &&
                            (focused || !spec_.autofocus)
                      : fault == spec_.expect;
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
            std::make_unique<ScienceTargetTask>(std::move(spec), s.start_x, s.start_y, s.start_yaw));
      });
}

}  // namespace rover::deploy::runner
