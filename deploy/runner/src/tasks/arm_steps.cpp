#include "rover/deploy/runner/tasks/arm_steps.hpp"

#include "rover/base/check.hpp"
#include "rover/base/format.hpp"
#include "rover/hwconfig/rover_description.hpp"
#include "rover/msg/arm_idl.hpp"

namespace rover::deploy::runner {

std::string SendArmCommand(dds::Writer<rover_dl_ArmCommand>& writer, const msg::ArmCommand& c) {
  rover_dl_ArmCommand w{};
  msg::ArmCommandToIdl(c, &w);
  dds::CopyString(w.header.frame_id, "rover");
  if (!writer.Write(w).ok()) {
    return std::string("cannot send the arm ") + msg::ArmModeName(c.mode) + " command";
  }
  return "";
}

ArmWait WaitForArm(TaskContext& ctx, const std::function<std::optional<msg::ArmStatus>()>& pump,
                   std::uint32_t command_id, msg::ArmState done, double timeout_s) {
  ArmWait out;
  const double start = ctx.Now();
  out.failure = ctx.WaitUntil([&] {
    const std::optional<msg::ArmStatus> s = pump();
    if (s && s->command_id == command_id &&
        (s->state == done || s->state == msg::ArmState::kFault ||
         s->state == msg::ArmState::kRejected)) {
      out.end = s;
    }
    return out.end.has_value() || ctx.Now() - start > timeout_s;
  });
  return out;
}

std::string StowArmAndWait(TaskContext& ctx, dds::Writer<rover_dl_ArmCommand>& writer,
                           const std::function<std::optional<msg::ArmStatus>()>& pump,
                           std::uint32_t command_id, double timeout_s) {
  const std::optional<msg::ArmStatus> now = pump();
  if (!now || now->stowed) return "";
  msg::ArmCommand stow;
  stow.stamp = Time::FromSeconds(ctx.Now());
  stow.command_id = command_id;
  stow.mode = msg::ArmMode::kStow;
  if (std::string why = SendArmCommand(writer, stow); !why.empty()) return why;
  const ArmWait w = WaitForArm(ctx, pump, command_id, msg::ArmState::kStowed, timeout_s);
  if (!w.failure.empty()) return w.failure;
  if (!w.end) return "the arm did not stow: no answer within " + FormatNumber(timeout_s) + " s";
  if (w.end->state != msg::ArmState::kStowed) {
    return std::string("the arm did not stow: ") + msg::ArmStateName(w.end->state) + " " +
           w.end->message;
  }
  return "";
}

double FocusErrorFromTruth(const TaskContext& ctx, const Eigen::Vector3d& face_site) {
  ROVER_DEMAND(ctx.world != nullptr);
  const double surface = ctx.world->terrain.natural.Height(face_site.x(), face_site.y());
  return face_site.z() - (surface + hwconfig::RoverDescription{}.arm.imager.working_distance);
}

}  // namespace rover::deploy::runner
