#pragma once
/// @file
/// Conversions between the IDL C structs of ddl-imu's topics and the ddl_imu library's plain
/// structs: hw/imu in, ddl/imu out. Headers are the caller's.

#include "rover/ddl/imu/imu_driver.hpp"
#include "rover/hwconfig/hw_bus.hpp"
#include "rover/idl/types.hpp"

namespace rover::ddl {

/// hw/imu (stamp from the header).
hw::ImuRaw ImuRawFromIdl(const rover_hw_ImuRaw& in);
/// ddl/imu, except the header.
void ImuToIdl(const Imu& in, rover_ddl_Imu* out);
/// rover::SensorHealth -> the IDL enum (same order).
rover_SensorHealth ImuHealthToIdl(SensorHealth h);

}  // namespace rover::ddl
