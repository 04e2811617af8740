#include "rover/deploy/runner/tasks/autofocus_task.hpp"

#include <cmath>
#include <limits>
#include <random>

#include "rover/base/format.hpp"
#include "rover/deploy/runner/tasks/arm_steps.hpp"
#include "rover/hwconfig/rover_description.hpp"
#include "rover/msg/arm_idl.hpp"
#include "rover/msg/pose_idl.hpp"

namespace rover::deploy::runner {
namespace {

constexpr double kNotJudgedFigure = std::numeric_limits<double>::quiet_NaN();
// The arm's reach window ahead of the rover (rover frame at the start) [m].
constexpr double kReachMinX = 0.85, kReachMaxX = 1.25, kReachMaxY = 0.45;
// Soil spots: no rock relief within this radius [m] and this far from any other target.
constexpr double kSoilClear = 0.10, kSoilSpacing = 0.10;

Status CountIn(const YAML::Node& n, const std::string& key, const yaml::FileErrors& err,
               int* out) {
  double v = *out;
  ROVER_RETURN_IF_ERROR(yaml::OptionalNumber(n, key, "task", 0, 20, err, &v));
  if (v != std::floor(v)) {
    return err.At(n[key], "task." + key + ": " + yaml::ScalarText(n[key]) + " is not a count");
  }
  *out = static_cast<int>(v);
  return Status::Ok();
}

}  // namespace

Result<AutofocusSpec> ParseAutofocusTask(const TaskSource& source) {
  const YAML::Node& n = source.section;
  const yaml::FileErrors& err = source.errors;
  ROVER_RETURN_IF_ERROR(yaml::CheckKeys(
      n, "task", {"type", "soil", "rock", "height_error", "target_timeout_s", "time_budget_s"},
      err));
  AutofocusSpec spec;
  ROVER_RETURN_IF_ERROR(CountIn(n, "soil", err, &spec.soil));
  ROVER_RETURN_IF_ERROR(CountIn(n, "rock", err, &spec.rock));
  if (spec.soil + spec.rock == 0) {
    return err.At(n, "task: soil and rock are both 0: no target to focus on");
  }
  ROVER_RETURN_IF_ERROR(
      yaml::OptionalNumber(n, "height_error", "task", 0, 0.2, err, &spec.height_error));
  ROVER_RETURN_IF_ERROR(
      yaml::OptionalNumber(n, "target_timeout_s", "task", 10, 3600, err, &spec.target_timeout_s));
  ROVER_RETURN_IF_ERROR(
      yaml::OptionalNumber(n, "time_budget_s", "task", 10, 1e6, err, &spec.time_budget_s));
  return spec;
}

Status AutofocusTask::Open(TaskContext& ctx) {
  ROVER_ASSIGN_OR_RETURN(arm_, ctx.MakeWriter<rover_dl_ArmCommand>("dl/arm_command"));
  ROVER_ASSIGN_OR_RETURN(arm_status_, ctx.MakeReader<rover_dl_ArmStatus>("dl/arm_status"));
  ROVER_ASSIGN_OR_RETURN(truth_, ctx.MakeReader<rover_sim_Truth>("sim/truth"));
  return Status::Ok();
}

bool AutofocusTask::Ready() const { return arm_.valid() && arm_.MatchedReaders() > 0; }

void AutofocusTask::Pump() {
  truth_.TakeEach([&](const dds::Sample<rover_sim_Truth>& s) {
    truth_now_ = msg::IsometryFromIdl(s->pose);
    tool_now_ = Eigen::Vector3d(s->tool_point.x, s->tool_point.y, s->tool_point.z);
  });
  arm_status_.TakeEach([&](const dds::Sample<rover_dl_ArmStatus>& s) {
    if (auto a = msg::ArmStatusFromIdl(s.data()); a.ok()) arm_now_ = *a;
  });
}

std::string AutofocusTask::PickTargets(const TaskContext& ctx,
                                       const Eigen::Isometry3d& site_from_rover,
                                       std::vector<Target>* targets) const {
  const auto& terrain = ctx.world->terrain;
  auto in_reach = [&](const Eigen::Vector3d& site) {
    const Eigen::Vector3d r = site_from_rover.inverse() * site;
    return r.x() >= kReachMinX && r.x() <= kReachMaxX && std::abs(r.y()) <= kReachMaxY;
  };
  // Rocks: the science targets within reach, at their top (highest point within 0.3 of the
  // diameter from the centre, on a 1 cm grid).
  int rocks = 0;
  for (const sim::terrain::Rock& r : terrain.rocks) {
    if (!r.science_target || rocks >= spec_.rock) continue;
    const Eigen::Vector3d c(r.position.x(), r.position.y(), 0.0);
    if (!in_reach(Eigen::Vector3d(c.x(), c.y(), terrain.natural.Height(c.x(), c.y())))) continue;
    Eigen::Vector3d top(c.x(), c.y(), -std::numeric_limits<double>::infinity());
    const double reach = 0.3 * r.diameter;
    for (double dx = -reach; dx <= reach; dx += 0.01) {
      for (double dy = -reach; dy <= reach; dy += 0.01) {
        if (dx * dx + dy * dy > reach * reach) continue;
        const double h = terrain.natural.Height(c.x() + dx, c.y() + dy);
        if (h > top.z()) top = Eigen::Vector3d(c.x() + dx, c.y() + dy, h);
      }
    }
    targets->push_back({top, true});
    ++rocks;
  }
  if (rocks < spec_.rock) {
    return "task.rock: " + std::to_string(spec_.rock) + " rock targets asked, " +
           std::to_string(rocks) + " science targets within the arm's reach (" +
           FormatNumber(kReachMinX) + " to " + FormatNumber(kReachMaxX) + " m ahead, |y| <= " +
           FormatNumber(kReachMaxY) + " m)";
  }
  // Soil: seeded spots in the window with no rock relief nearby.
  std::mt19937_64 rng(0xF0C05ULL ^ ctx.seed);
  std::uniform_real_distribution<double> ux(kReachMinX + 0.05, kReachMaxX - 0.05);
  std::uniform_real_distribution<double> uy(-kReachMaxY + 0.05, kReachMaxY - 0.05);
  int soil = 0;
  for (int tries = 0; tries < 2000 && soil < spec_.soil; ++tries) {
    const Eigen::Vector3d p = site_from_rover * Eigen::Vector3d(ux(rng), uy(rng), 0.0);
    bool clear = true;
    for (double dx = -kSoilClear; dx <= kSoilClear && clear; dx += 0.02) {
      for (double dy = -kSoilClear; dy <= kSoilClear && clear; dy += 0.02) {
        const double x = p.x() + dx, y = p.y() + dy;
        clear = terrain.natural.Height(x, y) - terrain.bare.Height(x, y) < 0.003;
      }
    }
    for (const Target& t : *targets) {
      clear = clear && (t.point.head<2>() - p.head<2>()).norm() >= kSoilSpacing + (t.rock ? 0.1 : 0.0);
    }
    if (!clear) continue;
    targets->push_back({Eigen::Vector3d(p.x(), p.y(), terrain.natural.Height(p.x(), p.y())), false});
    ++soil;
  }
  if (soil < spec_.soil) {
    return "task.soil: found only " + std::to_string(soil) + " of " +
           std::to_string(spec_.soil) + " soil spots clear of rocks within the arm's reach";
  }
  return "";
}

std::string AutofocusTask::Stow(TaskContext& ctx) {
  return StowArmAndWait(ctx, arm_, [&] { Pump(); return arm_now_; }, kStowId, 120.0);
}

TaskOutcome AutofocusTask::Run(TaskContext& ctx) {
  TaskOutcome out;
  if (ctx.world == nullptr) {
    out.failure = "autofocus needs the simulated world (truth) to pick its targets";
    return out;
  }
  const double task_start = ctx.Now();
  out.failure = ctx.WaitUntil([&] {
    Pump();
    return (truth_now_.has_value() && arm_now_.has_value()) || ctx.Now() - task_start > 30.0;
  });
  if (!out.failure.empty()) return out;
  if (!truth_now_ || !arm_now_) {
    out.failure = !truth_now_ ? "no sim/truth heard within 30 s" : "no dl/arm_status heard within 30 s";
    return out;
  }
  std::vector<Target> targets;
  if (std::string why = PickTargets(ctx, *truth_now_, &targets); !why.empty()) {
    out.failure = why;
    return out;
  }
  const hwconfig::MicroscopeOptics optics = hwconfig::RoverDescription{}.arm.imager;
  const double dof_half = optics.DepthOfFieldHalf();
  std::mt19937_64 rng(0xE5717ULL ^ ctx.seed);
  std::normal_distribution<double> height_error(0.0, spec_.height_error);
  int right[2] = {0, 0}, count[2] = {0, 0}, predicted = 0, failed = 0, frames = 0, focused = 0;
  double error_sum = 0.0, error_worst = 0.0;
  for (std::size_t i = 0; i < targets.size(); ++i) {
    const Target& t = targets[i];
    const int kind = t.rock ? 1 : 0;
    const char* kind_name = t.rock ? "rock" : "soil";
    ++count[kind];
    const double e = spec_.height_error > 0.0 ? height_error(rng) : 0.0;
    StepResult step;
    step.primitive = std::string("autofocus_") + kind_name;
    step.command_id = kFirstId + static_cast<std::uint32_t>(i);
    step.sim_start_s = ctx.Now();
    if (ctx.Now() - task_start > spec_.time_budget_s) {
      out.failure = "time budget of " + FormatNumber(spec_.time_budget_s) + " s used up after " +
                    std::to_string(i) + " targets";
      return out;
    }
    Pump();
    msg::ArmCommand c;
    c.stamp = Time::FromSeconds(ctx.Now());
    c.command_id = step.command_id;
    c.mode = msg::ArmMode::kAutofocus;
    c.target = truth_now_->inverse() * t.point + Eigen::Vector3d(0.0, 0.0, e);
    ctx.Note("autofocus " + std::to_string(i + 1) + "/" + std::to_string(targets.size()) + " (" +
             kind_name + ", height off by " + FormatNumber(e * 100.0, 3) + " cm)");
    if (std::string why = SendArmCommand(arm_, c); !why.empty()) {
      out.failure = why;
      return out;
    }
    const ArmWait wait = WaitForArm(ctx, [&] { Pump(); return arm_now_; }, c.command_id,
                                    msg::ArmState::kFocused, spec_.target_timeout_s);
    const std::string& failure = wait.failure;
    const std::optional<msg::ArmStatus>& end = wait.end;
    step.sim_end_s = ctx.Now();
    if (!failure.empty()) {
      step.state = "interrupted";
      out.steps.push_back(step);
      out.failure = failure;
      return out;
    }
    if (!end || end->state != msg::ArmState::kFocused) {
      ++failed;
      step.state = "failed";
      step.message = end ? std::string(msg::ArmStateName(end->state)) + ": " + end->message
                         : "no FOCUSED within " + FormatNumber(spec_.target_timeout_s) + " s";
      if (out.failure.empty()) {
        out.failure = "target " + std::to_string(i + 1) + " (" + kind_name + ") " + step.message;
      }
      out.steps.push_back(step);
      if (std::string why = Stow(ctx); !why.empty()) {
        out.failure += "; " + why;
        return out;
      }
      continue;
    }
    ++focused;
    Pump();
    // The truth: the face against the surface under the imager's axis (straight down).
    const double error = FocusErrorFromTruth(ctx, tool_now_);
    const bool ok = std::abs(error) <= dof_half;
    right[kind] += ok ? 1 : 0;
    predicted += end->focus_predicted ? 1 : 0;
    frames += end->focus_images;
    error_sum += std::abs(error);
    error_worst = std::max(error_worst, std::abs(error));
    step.state = "succeeded";
    step.termination = ok ? "in_focus" : "out_of_focus";
    step.message = "focus error " + FormatNumber(error * 1000.0, 3) + " mm (depth of field +-" +
                   FormatNumber(dof_half * 1000.0, 3) + " mm), designated height off by " +
                   FormatNumber(e * 1000.0, 3) + " mm, " + std::to_string(end->focus_images) +
                   " frames" + (end->focus_predicted ? ", predicted from the contact" : "");
    out.steps.push_back(step);
    if (std::string why = Stow(ctx); !why.empty()) {
      out.failure = why;
      return out;
    }
  }
  auto share = [](int n, int of) { return of > 0 ? 100.0 * n / of : kNotJudgedFigure; };
  ctx.recorder.AddFigure({"focus_right_soil", share(right[0], count[0]), kNotJudgedFigure, "%",
                          true, "soil targets whose final frame is in focus at its centre (" +
                                    std::to_string(right[0]) + " of " + std::to_string(count[0]) +
                                    "); FIDO: 100 %"});
  ctx.recorder.AddFigure({"focus_right_rock", share(right[1], count[1]), kNotJudgedFigure, "%",
                          true, "rock targets in focus (" + std::to_string(right[1]) + " of " +
                                    std::to_string(count[1]) + "); FIDO: 82 %"});
  ctx.recorder.AddFigure({"focus_error_mean", focused > 0 ? 1000.0 * error_sum / focused
                                                          : kNotJudgedFigure,
                          kNotJudgedFigure, "mm", true,
                          "|face height - (surface + working distance)| at FOCUSED, mean"});
  ctx.recorder.AddFigure({"focus_error_worst", focused > 0 ? 1000.0 * error_worst : kNotJudgedFigure,
                          kNotJudgedFigure, "mm", true, "the same, worst"});
  ctx.recorder.AddFigure({"focus_predicted", static_cast<double>(predicted), kNotJudgedFigure,
                          "count", true, "targets focused by prediction from the contact"});
  ctx.recorder.AddFigure({"focus_frames_mean", focused > 0 ? static_cast<double>(frames) / focused
                                                           : kNotJudgedFigure,
                          kNotJudgedFigure, "count", true,
                          "microscopic-imager frames per focused target"});
  ctx.recorder.AddFigure({"focus_failed", static_cast<double>(failed), kNotJudgedFigure, "count",
                          true, "targets that did not end FOCUSED"});
  return out;
}

void RegisterAutofocusTask(TaskRegistry& registry) {
  registry.Register(
      "autofocus",
      "FIDO's auto-focus trials: the microscopic imager focused on soil spots and science "
      "targets within the arm's reach, each from a height with a seeded error; judged in focus "
      "from truth",
      [](const TaskSource& source) -> Result<std::unique_ptr<Task>> {
        ROVER_ASSIGN_OR_RETURN(AutofocusSpec spec, ParseAutofocusTask(source));
        const Scenario& s = source.scenario;
        return std::unique_ptr<Task>(std::make_unique<AutofocusTask>(spec, s.start_x, s.start_y));
      });
}

}  // namespace rover::deploy::runner
