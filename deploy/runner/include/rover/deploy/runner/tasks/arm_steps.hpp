#pragma once
/// @file
/// The runner's arm steps, shared by the tasks that move dl-arm (science_target, autofocus):
/// one dl/arm_command sent as an operator would, and the wait for its end on dl/arm_status.

#include <Eigen/Core>
#include <functional>
#include <optional>
#include <string>

#include "rover/deploy/runner/task.hpp"
#include "rover/msg/arm.hpp"

namespace rover::deploy::runner {

/// Sends `command` (frame "rover"); "" or why not.
std::string SendArmCommand(dds::Writer<rover_dl_ArmCommand>& writer, const msg::ArmCommand& command);

/// How an arm command ended.
struct ArmWait {
  std::string failure;               ///< the run's failure line when the wait was cut short
  std::optional<msg::ArmStatus> end; ///< `done`, FAULT or REJECTED for the id; none: timed out
};

/// Waits (simulated time) until the latest dl/arm_status that `pump` returns (after taking new
/// samples) is for `command_id` and `done`, FAULT or REJECTED, or `timeout_s` passes.
ArmWait WaitForArm(TaskContext& ctx, const std::function<std::optional<msg::ArmStatus>()>& pump,
                   std::uint32_t command_id, msg::ArmState done, double timeout_s);

/// STOW unless the latest status says stowed; "" when stowed, else why not ("arm STOW ended
/// FAULT: ...", "no answer within 300 s").
std::string StowArmAndWait(TaskContext& ctx, dds::Writer<rover_dl_ArmCommand>& writer,
                           const std::function<std::optional<msg::ArmStatus>()>& pump,
                           std::uint32_t command_id, double timeout_s);

/// The microscopic imager's focus error from truth [m]: the face's height (site frame, the
/// imager looking straight down its axis) less the terrain under it plus the working distance;
/// positive = too high. Needs ctx.world (the runner's own truth).
double FocusErrorFromTruth(const TaskContext& ctx, const Eigen::Vector3d& face_site);

}  // namespace rover::deploy::runner
