#include "rover/sim/rover_sim/truth_idl.hpp"

#include "rover/base/time.hpp"
#include "rover/msg/pose_idl.hpp"

namespace rover::sim::rover_sim {
namespace {

rover_Vector3 ToIdl(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }
Eigen::Vector3d FromIdl(const rover_Vector3& v) { return {v.x, v.y, v.z}; }

}  // namespace

void TruthToIdl(const TruthSample& in, rover_sim_Truth* out) {
  out->header.stamp_ns = Time::FromSeconds(in.time_s).ns;
  msg::IsometryToIdl(in.pose, &out->pose);
  out->velocity = ToIdl(in.velocity_site);
  out->angular_velocity = ToIdl(in.angular_velocity_body);
  for (std::size_t i = 0; i < in.wheels.size(); ++i) {
    const physics::WheelReading& w = in.wheels[i];
    out->wheels[i] = {w.slip_ratio, w.normal_force_n, w.in_contact, w.sinkage_m};
  }
  for (int i = 0; i < 2; ++i) {
    out->rocker_angle[i] = in.rocker_angle[i];
    out->bogie_angle[i] = in.bogie_angle[i];
  }
  out->odometer = in.odometer;
  out->rock_contacts = in.rock_contacts;
  out->max_contact_rock_height = in.max_contact_rock_height;
  out->tool_point = ToIdl(in.tool_point);
  out->tool_contact = in.tool_contact;
}

TruthSample TruthFromIdl(const rover_sim_Truth& in) {
  TruthSample t;
  t.time_s = Time{in.header.stamp_ns}.seconds();
  t.pose = msg::IsometryFromIdl(in.pose);
  t.velocity_site = FromIdl(in.velocity);
  t.angular_velocity_body = FromIdl(in.angular_velocity);
  for (std::size_t i = 0; i < t.wheels.size(); ++i) {
    const rover_sim_WheelTruth& w = in.wheels[i];
    t.wheels[i].slip_ratio = w.slip;
    t.wheels[i].normal_force_n = w.normal_force;
    t.wheels[i].in_contact = w.in_contact;
    t.wheels[i].sinkage_m = w.sinkage;
  }
  for (int i = 0; i < 2; ++i) {
    t.rocker_angle[i] = in.rocker_angle[i];
    t.bogie_angle[i] = in.bogie_angle[i];
  }
  t.odometer = in.odometer;
  t.rock_contacts = in.rock_contacts;
  t.max_contact_rock_height = in.max_contact_rock_height;
  t.tool_point = FromIdl(in.tool_point);
  t.tool_contact = in.tool_contact;
  return t;
}

}  // namespace rover::sim::rover_sim
