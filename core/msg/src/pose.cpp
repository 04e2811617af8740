#include "rover/msg/pose.hpp"

namespace rover::msg {

const char* MotionSourceName(MotionSource s) {
  switch (s) {
    case MotionSource::kWheelOdometry:
      return "wheel_odometry";
    case MotionSource::kVisualOdometry:
      return "visual_odometry";
    case MotionSource::kSunSensor:
      return "sun_sensor";
    case MotionSource::kAccelerometer:
      return "accelerometer";
    case MotionSource::kExternal:
      return "external";
  }
  return "unknown";
}

bool IsKnownMotionSource(MotionSource s) {
  const auto v = static_cast<std::int32_t>(s);
  return v >= static_cast<std::int32_t>(MotionSource::kWheelOdometry) &&
         v <= static_cast<std::int32_t>(MotionSource::kExternal);
}

const char* RelativePoseStatusName(RelativePoseStatus s) {
  switch (s) {
    case RelativePoseStatus::kConverged:
      return "converged";
    case RelativePoseStatus::kTooFewFeatures:
      return "too_few_features";
    case RelativePoseStatus::kLimitsFailed:
      return "limits_failed";
    case RelativePoseStatus::kNotConverged:
      return "not_converged";
    case RelativePoseStatus::kBadInput:
      return "bad_input";
  }
  return "unknown";
}

}  // namespace rover::msg
