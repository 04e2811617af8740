#include "src/idl_conversions.hpp"

namespace rover::deploy::runner {

Eigen::Isometry3d ToIsometry(const rover_Pose3& p) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translation() = Eigen::Vector3d(p.position.x, p.position.y, p.position.z);
  t.linear() =
      Eigen::Quaterniond(p.orientation.w, p.orientation.x, p.orientation.y, p.orientation.z)
          .normalized()
          .toRotationMatrix();
  return t;
}

rover_dl_DrivePrimitive ToIdl(Primitive p) {
  switch (p) {
    case Primitive::kStraight:
      return rover_dl_PRIMITIVE_STRAIGHT;
    case Primitive::kArc:
      return rover_dl_PRIMITIVE_ARC;
    case Primitive::kTurnInPlace:
      return rover_dl_PRIMITIVE_TURN_IN_PLACE;
    case Primitive::kSteer:
      return rover_dl_PRIMITIVE_STEER;
    case Primitive::kStop:
      return rover_dl_PRIMITIVE_STOP;
  }
  return rover_dl_PRIMITIVE_STOP;
}

const char* TerminationName(rover_dl_DriveTermination t) {
  switch (t) {
    case rover_dl_TERMINATION_NONE:
      return "none";
    case rover_dl_TERMINATION_NOMINAL:
      return "nominal";
    case rover_dl_TERMINATION_TILT:
      return "tilt";
    case rover_dl_TERMINATION_SUSPENSION:
      return "suspension";
    case rover_dl_TERMINATION_MOTOR_STALL:
      return "motor_stall";
    case rover_dl_TERMINATION_MOTOR_CURRENT:
      return "motor_current";
    case rover_dl_TERMINATION_MOTOR_FAULT:
      return "motor_fault";
    case rover_dl_TERMINATION_TIMEOUT:
      return "timeout";
    case rover_dl_TERMINATION_STOP_COMMAND:
      return "stop_command";
    case rover_dl_TERMINATION_REJECTED_BUSY:
      return "rejected_busy";
    case rover_dl_TERMINATION_REJECTED_INVALID:
      return "rejected_invalid";
    case rover_dl_TERMINATION_STALE_SENSOR:
      return "stale_sensor";
  }
  return "?";
}

}  // namespace rover::deploy::runner
