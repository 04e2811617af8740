#pragma once
/// @file
/// The autofocus task: FIDO's auto-focus trials (seed 004: 50 runs on soil and rock targets,
/// the right best focus in 100 % / 82 %). The rover stands at its start; the runner picks
/// targets within the arm's reach from the world (soil spots clear of rocks, and the tops of
/// the scenario's science targets), gives each to dl-arm as an ARM_MODE_AUTOFOCUS at the
/// target's true surface point with a seeded height error (the error a stereo range from afar
/// has: seed 004's "3 or more centimetres"), and stows the arm between targets.
///
///   task:
///     type: autofocus
///     soil: 3               # soil targets per run (seeded spots, no rock within 0.1 m)
///     rock: 2               # science targets within reach, in scenario order
///     height_error: 0.025   # [m] 1-sigma of the designated height's error (normal, seeded)
///     target_timeout_s: 240 # [s] simulated, per target
///     time_budget_s: 1800   # [s] simulated, the whole task
///
/// Reach window (rover frame at the start): 0.85 <= x <= 1.25 m, |y| <= 0.45 m. Each target
/// is judged from truth after FOCUSED: the instrument face (sim/truth tool_point) against the
/// terrain under the imager's axis plus the working distance (core/hwconfig
/// MicroscopeOptics), focus_error = face z - (surface z + working distance); right when
/// |focus_error| <= MicroscopeOptics::DepthOfFieldHalf() (the blur at the image centre at most
/// max_sharp_blur_px). Figures: focus_right_soil / focus_right_rock [%], focus_error_mean /
/// focus_error_worst [mm, |error|], focus_predicted (targets focused from the contact),
/// focus_frames_mean, focus_failed (targets not FOCUSED). The run fails when a target does
/// not end FOCUSED (a FAULT or REJECTED from dl-arm, or no answer within target_timeout_s)
/// or the world has fewer science targets in reach than `rock` asks.

#include <optional>
#include <string>

#include "rover/deploy/runner/task.hpp"
#include "rover/msg/arm.hpp"

namespace rover::deploy::runner {

struct AutofocusSpec {
  int soil = 3;
  int rock = 2;
  double height_error = 0.025;
  double target_timeout_s = 240.0;
  double time_budget_s = 1800.0;
};

/// Parses and checks the section (names file, line and key on error).
Result<AutofocusSpec> ParseAutofocusTask(const TaskSource& source);

class AutofocusTask : public Task {
 public:
  static constexpr std::uint32_t kFirstId = 0x4F000001u;
  static constexpr std::uint32_t kStowId = 0x4F0000FFu;

  AutofocusTask(AutofocusSpec spec, double start_x, double start_y)
      : spec_(spec), start_x_(start_x), start_y_(start_y) {}
  Status Open(TaskContext& ctx) override;
  bool Ready() const override;
  TaskOutcome Run(TaskContext& ctx) override;
  std::vector<Eigen::Vector2d> PlannedPath() const override { return {{start_x_, start_y_}}; }
  const AutofocusSpec& spec() const { return spec_; }

  /// A target: where (site frame, on the surface) and what.
  struct Target {
    Eigen::Vector3d point = Eigen::Vector3d::Zero();
    bool rock = false;
  };

 private:
  void Pump();
  // The targets for the rover at `site_from_rover`; "" or why not.
  std::string PickTargets(const TaskContext& ctx, const Eigen::Isometry3d& site_from_rover,
                          std::vector<Target>* targets) const;
  std::string Stow(TaskContext& ctx);

  AutofocusSpec spec_;
  double start_x_, start_y_;
  dds::Writer<rover_dl_ArmCommand> arm_;
  dds::Reader<rover_dl_ArmStatus> arm_status_;
  dds::Reader<rover_sim_Truth> truth_;
  std::optional<Eigen::Isometry3d> truth_now_;
  Eigen::Vector3d tool_now_ = Eigen::Vector3d::Zero();
  std::optional<msg::ArmStatus> arm_now_;
};

/// Registers autofocus.
void RegisterAutofocusTask(TaskRegistry& registry);

}  // namespace rover::deploy::runner
