#include "rover/hwconfig/hw_bus.hpp"

namespace rover::hw {

const char* MotorName(int motor) {
  static constexpr const char* kNames[kNumMotors] = {
      "drive_lf", "drive_lm", "drive_lr", "drive_rf", "drive_rm", "drive_rr",
      "steer_lf", "steer_lr", "steer_rf", "steer_rr", "mast_pan", "mast_tilt",
      "arm_azimuth", "arm_shoulder", "arm_elbow", "arm_wrist"};
  return (motor >= 0 && motor < kNumMotors) ? kNames[motor] : "?";
}

const char* MotorModeName(MotorMode m) {
  switch (m) {
    case MotorMode::kIdle:
      return "idle";
    case MotorMode::kPosition:
      return "position";
    case MotorMode::kVelocity:
      return "velocity";
    case MotorMode::kBrake:
      return "brake";
  }
  return "?";
}

const char* PotName(int pot) {
  static constexpr const char* kNames[kNumPots] = {"left_rocker", "right_rocker", "left_bogie",
                                                   "right_bogie"};
  return (pot >= 0 && pot < kNumPots) ? kNames[pot] : "?";
}

std::int32_t WrapCounter(std::int64_t count) {
  // Conversion of an out-of-range value to a signed type is modular since C++20.
  return static_cast<std::int32_t>(static_cast<std::uint32_t>(static_cast<std::uint64_t>(count)));
}

std::int64_t CounterDelta(std::int32_t newer, std::int32_t older) {
  const std::uint32_t d = static_cast<std::uint32_t>(newer) - static_cast<std::uint32_t>(older);
  return static_cast<std::int64_t>(static_cast<std::int32_t>(d));
}

}  // namespace rover::hw
