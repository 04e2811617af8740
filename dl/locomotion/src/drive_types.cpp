#include "rover/dl/locomotion/drive_types.hpp"

namespace rover::dl::locomotion {

const char* InvalidReasonName(InvalidReason r) {
  switch (r) {
    case InvalidReason::kNone:
      return "none";
    case InvalidReason::kUnknownPrimitive:
      return "unknown_primitive";
    case InvalidReason::kNonFinite:
      return "non_finite";
    case InvalidReason::kCurvatureOutOfRange:
      return "curvature_out_of_range";
    case InvalidReason::kDistanceOutOfRange:
      return "distance_out_of_range";
    case InvalidReason::kAngleOutOfRange:
      return "angle_out_of_range";
    case InvalidReason::kSpeedOutOfRange:
      return "speed_out_of_range";
    case InvalidReason::kTimeoutOutOfRange:
      return "timeout_out_of_range";
    case InvalidReason::kArmNotStowed:
      return "arm_not_stowed";
  }
  return "unknown";
}

}  // namespace rover::dl::locomotion
