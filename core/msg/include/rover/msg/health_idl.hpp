#pragma once
/// @file
/// SensorHealth <-> rover_common.idl SensorHealth (same ordinals).

#include <string_view>

#include "rover/base/status.hpp"
#include "rover/idl/types.hpp"
#include "rover/msg/health.hpp"

namespace rover::msg {

rover_SensorHealth HealthToIdl(SensorHealth h);
/// InvalidArgument "<field> = 9 is not a SensorHealth (0..3)" for a value no enumerator has.
Result<SensorHealth> HealthFromIdl(const rover_SensorHealth& h, std::string_view field = "health");

}  // namespace rover::msg
