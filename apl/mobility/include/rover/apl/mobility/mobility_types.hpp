#pragma once
/// @file
/// The mobility manager's vocabulary (MER's Mobility Manager, seed 000). The message types are
/// core/msg's (rover/msg/mobility.hpp for apl/mobility_command / apl/mobility_status with the
/// typed faults and their classes, and the dl/* ones the manager sends and reads); this header
/// names them for the manager and adds the mode groups the manager decides by.
///
/// Frames: site frame (x north, y west, z up) for goals, poses and keep-out zones; primitive
/// curvature is signed in the rover frame (positive = turn left), turn angles positive =
/// counter-clockwise seen from above. Metres, radians, run-clock time.
///
/// A value outside an enumeration (e.g. an unknown mode from the wire) is representable and is
/// rejected by MobilityManager::ValidateCommand.

#include "rover/msg/camera.hpp"
#include "rover/msg/drive.hpp"
#include "rover/msg/mast.hpp"
#include "rover/msg/mobility.hpp"
#include "rover/msg/pose.hpp"
#include "rover/msg/range.hpp"

namespace rover::apl::mobility {

// apl/mobility_command, apl/mobility_status.
using Mode = msg::MobilityMode;
using State = msg::MobilityState;
using Fault = msg::MobilityFault;
using msg::FaultClass;
using msg::FaultClassOf;
using msg::KeepOutZone;
using msg::MobilityCommand;
using msg::MobilityStatus;
using msg::ThinkMode;
using Primitive = msg::MobilityPrimitive;
using PrimitiveKind = msg::DrivePrimitive;
inline constexpr int kModeCount = msg::kMobilityModeCount;
inline constexpr int kFaultCount = msg::kMobilityFaultCount;

// What the manager sends to and reads from the device layer.
using msg::CameraId;
using msg::CameraName;
using msg::DriveCommand;
using msg::DriveState;
using msg::DriveStatus;
using msg::DriveTermination;
using msg::MastCommand;
using msg::MastState;
using msg::MastStatus;
using msg::PoseSample;
using msg::RangeRequest;
using msg::RelativePose;

/// Modes that drive to `goal` (and so need a finite goal and tolerance).
bool ModeHasGoal(Mode m);
/// Modes that execute `primitives`.
bool ModeHasPrimitives(Mode m);
/// Modes with visual odometry between steps.
bool ModeUsesVisOdom(Mode m);

}  // namespace rover::apl::mobility
