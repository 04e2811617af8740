#pragma once
// ---- IDL <-> runner conversions ----------------------------------------------------------------
// The runner's only conversions between catalog messages and its own types, kept here in one
// place so that they can be switched to core/msg (issue 10, item 1) without touching the pieces
// that use them (recorder.cpp, tasks/directed_task.cpp).

#include <Eigen/Geometry>

#include "rover/deploy/runner/tasks/directed_task.hpp"
#include "rover/idl/types.hpp"

namespace rover::deploy::runner {

/// A catalog pose (position [m], unit quaternion w, x, y, z) as a rigid transform; the quaternion
/// is normalised.
Eigen::Isometry3d ToIsometry(const rover_Pose3& p);

/// A directed task's primitive as dl/drive_command's enum.
rover_dl_DrivePrimitive ToIdl(Primitive p);

/// dl/drive_status's termination as the name scenarios use in `expect:` ("nominal", "tilt", ...).
const char* TerminationName(rover_dl_DriveTermination t);

}  // namespace rover::deploy::runner
