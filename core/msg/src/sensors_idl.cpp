#include "rover/msg/sensors_idl.hpp"

#include "idl_enum.hpp"
#include "rover/msg/health_idl.hpp"

namespace rover::msg {

using internal::Vec;
namespace {

template <class A, std::size_t N>
void Copy(const double (&src)[N], A& dst) {
  static_assert(std::tuple_size_v<A> == N, "array sizes differ");
  for (std::size_t i = 0; i < N; ++i) dst[i] = src[i];
}
template <class A, std::size_t N>
void Copy(const A& src, double (&dst)[N]) {
  static_assert(std::tuple_size_v<A> == N, "array sizes differ");
  for (std::size_t i = 0; i < N; ++i) dst[i] = src[i];
}

}  // namespace

void ImuToIdl(const Imu& in, rover_ddl_Imu* out) {
  out->header.stamp_ns = in.stamp.ns;
  out->angular_velocity = Vec(in.angular_velocity);
  out->linear_acceleration = Vec(in.linear_acceleration);
  out->temperature = in.temperature;
  out->health = HealthToIdl(in.health);
}

Result<Imu> ImuFromIdl(const rover_ddl_Imu& in) {
  Imu m;
  m.stamp = Time{in.header.stamp_ns};
  m.angular_velocity = Vec(in.angular_velocity);
  m.linear_acceleration = Vec(in.linear_acceleration);
  m.temperature = in.temperature;
  ROVER_ASSIGN_OR_RETURN(m.health, HealthFromIdl(in.health, "ddl/imu health"));
  return m;
}

void SunSensorToIdl(const SunSensor& in, rover_ddl_SunSensor* out) {
  out->header.stamp_ns = in.stamp.ns;
  out->sun_vector = Vec(in.sun_vector);
  out->valid = in.valid;
  out->intensity = in.intensity;
  out->health = HealthToIdl(in.health);
}

Result<SunSensor> SunSensorFromIdl(const rover_ddl_SunSensor& in) {
  SunSensor m;
  m.stamp = Time{in.header.stamp_ns};
  m.sun_vector = Vec(in.sun_vector);
  m.valid = in.valid;
  m.intensity = in.intensity;
  ROVER_ASSIGN_OR_RETURN(m.health, HealthFromIdl(in.health, "ddl/sun_sensor health"));
  return m;
}

void JointStateToIdl(const JointState& in, rover_ddl_JointState* out) {
  out->header.stamp_ns = in.stamp.ns;
  Copy(in.wheel_angle, out->wheel_angle);
  Copy(in.wheel_rate, out->wheel_rate);
  Copy(in.steer_angle, out->steer_angle);
  Copy(in.rocker_angle, out->rocker_angle);
  Copy(in.bogie_angle, out->bogie_angle);
  out->mast_pan = in.mast_pan;
  out->mast_tilt = in.mast_tilt;
  Copy(in.arm_angle, out->arm_angle);
  out->arm_contact = in.arm_contact;
  out->health = HealthToIdl(in.health);
}

Result<JointState> JointStateFromIdl(const rover_ddl_JointState& in) {
  JointState j;
  j.stamp = Time{in.header.stamp_ns};
  Copy(in.wheel_angle, j.wheel_angle);
  Copy(in.wheel_rate, j.wheel_rate);
  Copy(in.steer_angle, j.steer_angle);
  Copy(in.rocker_angle, j.rocker_angle);
  Copy(in.bogie_angle, j.bogie_angle);
  j.mast_pan = in.mast_pan;
  j.mast_tilt = in.mast_tilt;
  Copy(in.arm_angle, j.arm_angle);
  j.arm_contact = in.arm_contact;
  ROVER_ASSIGN_OR_RETURN(j.health, HealthFromIdl(in.health, "ddl/joint_state health"));
  return j;
}

}  // namespace rover::msg
