#pragma once
// How apl-sequencer links the interpreter to its neighbours' messages (private to the service and
// its tests; pure functions, no DDS). The typed requests of commands.hpp become
// msg::MobilityCommand and msg::MastCommand (core/msg's values; the service writes them with
// core/msg's conversions); the neighbours' statuses become an Outcome when they end the command;
// dl/pose becomes a PoseSample; the interpreter's status becomes apl/sequence_status.
//
// Command ids: the sequencer's command ids are the interpreter's (increasing, never repeated in
// a run of the service); the STOP it sends to cancel a mobility command has its own id, with
// bit 31 set (kCancelIdBit), so its status never ends a sequence step.

#include <cstdint>
#include <optional>
#include <string>

#include "rover/apl/sequencer/commands.hpp"
#include "rover/apl/sequencer/interpreter.hpp"
#include "rover/msg/arm.hpp"
#include "rover/msg/mast.hpp"
#include "rover/msg/mobility.hpp"
#include "rover/msg/pose.hpp"
#include "rover/msg/rendezvous.hpp"
#include "rover/msg/sequence.hpp"

namespace rover::apl::sequencer {

inline constexpr std::uint32_t kCancelIdBit = 0x80000000u;

/// The families apl-sequencer dispatches: mobility (apl/mobility_command), mast
/// (dl/mast_command), rendezvous (apl/rendezvous_command) and arm (dl/arm_command).
bool ServiceDispatches(Family f);
/// Ok when every command of the sequence (statements and ON_ABORT block) is one the service
/// dispatches; else InvalidArgument naming the first other one's line and command. Not
/// dispatched: ARM UNSTOW (dl-arm has no unstowed pose; ARM MOVE names one): "line 5: ARM
/// UNSTOW: apl-sequencer does not dispatch it (...)".
Status CheckDispatchable(const Sequence& sequence);

/// The apl/mobility_command of a mobility command, stamped `stamp`. Errors: a speed other than 0
/// (the mobility manager's command carries none; its drive speed is a parameter), naming the
/// value.
Result<msg::MobilityCommand> MobilityCommandOf(const Command& c, Time stamp);
/// The mobility manager's STOP, as sent to cancel an outstanding mobility command, stamped
/// `stamp`.
msg::MobilityCommand MobilityStopCommand(std::uint32_t cancel_id, Time stamp);
/// The dl/mast_command of a mast command, stamped `stamp`.
msg::MastCommand MastCommandOf(const Command& c, Time stamp);
/// The apl/rendezvous_command of a rendezvous command, stamped `stamp`: RETURN_TO_LANDER is
/// TARGET_LANDER (the lander estimate, the standoff; ramp -1, climb off), APPROACH_TARGET is
/// TARGET_SCIENCE (image id and pixel, or the site point with image id 0).
msg::RendezvousCommand RendezvousCommandOf(const Command& c, Time stamp);
/// apl-rendezvous's TARGET_STOP, as sent to cancel an outstanding rendezvous command.
msg::RendezvousCommand RendezvousStopCommand(std::uint32_t cancel_id, Time stamp);
/// The dl/arm_command of an arm command, stamped `stamp`: ARM MOVE is JOINTS, ARM STOW is STOW,
/// ARM PLACE is PLACE with the site-frame point moved into the rover frame by `site_from_rover`
/// (the latest dl/pose), AUTOFOCUS is AUTOFOCUS likewise with focus_steps = steps and
/// focus_span = (steps - 1) step. Errors: ARM PLACE or AUTOFOCUS without a pose, ARM PLACE
/// with hover other than 0 (dl-arm places the instrument until its contact switch closes), an
/// AUTOFOCUS sweep longer than 0.3 m, naming the value.
Result<msg::ArmCommand> ArmCommandOf(const Command& c, const std::optional<Eigen::Isometry3d>& site_from_rover,
                                     Time stamp);
/// dl-arm's STOP, as sent to cancel an outstanding arm command.
msg::ArmCommand ArmStopCommand(std::uint32_t cancel_id, Time stamp);

/// The outcome a mobility status gives its command: SUCCEEDED -> NOMINAL, FAILED -> FAULT,
/// REJECTED -> REJECTED (with the fault mapped by name and the status's class), stamped with
/// the status's stamp; nullopt while IDLE or RUNNING.
std::optional<Outcome> OutcomeOfMobilityStatus(const msg::MobilityStatus& s);
/// The outcome a mast status gives its command: AT_GOAL -> NOMINAL, FAULT -> FAULT OTHER (goal
/// error), REJECTED -> REJECTED BAD_COMMAND; nullopt while IDLE or MOVING.
std::optional<Outcome> OutcomeOfMastStatus(const msg::MastStatus& s);

/// The outcome an arm status gives its command: AT_GOAL, PLACED, STOWED, FOCUSED -> NOMINAL; FAULT ->
/// FAULT OTHER (goal error, dl-arm's message); REJECTED -> REJECTED BAD_COMMAND; nullopt while
/// IDLE or MOVING.
std::optional<Outcome> OutcomeOfArmStatus(const msg::ArmStatus& s);

/// The outcome a rendezvous status gives its command: DONE -> NOMINAL; FAILED -> REJECTED for
/// BAD_COMMAND and BUSY, else FAULT (a goal error), the fault named as apl-rendezvous names it
/// (TARGET_LOST, NOT_FOUND, ...); nullopt for the phases in between.
std::optional<Outcome> OutcomeOfRendezvousStatus(const msg::RendezvousStatus& s);

/// dl/pose as the interpreter's pose input (ZYX roll, pitch, yaw of the estimate).
PoseSample PoseOfEstimate(const msg::PoseEstimate& p);
/// True for a visual-odometry dl/relative_pose sample that failed (any status but CONVERGED).
bool IsVisOdomFailure(const msg::RelativePose& r);

/// apl/sequence_status of the interpreter's status for sequence `command_id`. RUNNING and
/// ABORTING are RUNNING; FAILED and ABORTED are FAILED (the message says which).
msg::SequenceStatus SequenceStatusOf(const SequenceStatus& s, std::uint32_t command_id,
                                     Time stamp);

}  // namespace rover::apl::sequencer
