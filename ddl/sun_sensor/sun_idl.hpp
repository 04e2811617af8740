#pragma once
/// @file
/// Conversions between the IDL C structs of ddl-sun's topics and the ddl_sun_sensor library's
/// plain structs: hw/sun_sensor in, ddl/sun_sensor out. Headers are the caller's.

#include "rover/ddl/sun_sensor/sun_sensor_driver.hpp"
#include "rover/hwconfig/hw_bus.hpp"
#include "rover/idl/types.hpp"

namespace rover::ddl {

/// hw/sun_sensor (stamp from the header).
hw::SunSensorRaw SunSensorRawFromIdl(const rover_hw_SunSensorRaw& in);
/// ddl/sun_sensor, except the header.
void SunSensorToIdl(const SunSensor& in, rover_ddl_SunSensor* out);
/// rover::SensorHealth -> the IDL enum (same order).
rover_SensorHealth SunHealthToIdl(SensorHealth h);

}  // namespace rover::ddl
