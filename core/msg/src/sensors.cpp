#include "rover/msg/sensors.hpp"

#include <cmath>

namespace rover::msg {

bool JointState::AllFinite() const {
  auto finite = [](const auto& a) {
    for (double v : a) {
      if (!std::isfinite(v)) return false;
    }
    return true;
  };
  return finite(wheel_angle) && finite(wheel_rate) && finite(steer_angle) && finite(rocker_angle) &&
         finite(bogie_angle);
}

}  // namespace rover::msg
