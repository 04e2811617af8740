#pragma once
/// @file
/// ddl/imu, ddl/sun_sensor and ddl/joint_state <-> their idlc C structs (conventions: see
/// rover/msg/camera_idl.hpp). Numbers are copied as they are (the consumers check finiteness);
/// an unknown health value is an error.

#include "rover/base/status.hpp"
#include "rover/idl/types.hpp"
#include "rover/msg/sensors.hpp"

namespace rover::msg {

void ImuToIdl(const Imu& in, rover_ddl_Imu* out);
Result<Imu> ImuFromIdl(const rover_ddl_Imu& in);

void SunSensorToIdl(const SunSensor& in, rover_ddl_SunSensor* out);
Result<SunSensor> SunSensorFromIdl(const rover_ddl_SunSensor& in);

void JointStateToIdl(const JointState& in, rover_ddl_JointState* out);
Result<JointState> JointStateFromIdl(const rover_ddl_JointState& in);

}  // namespace rover::msg
