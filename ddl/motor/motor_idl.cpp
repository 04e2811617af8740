#include "motor_idl.hpp"

#include <cstdint>
#include <cstring>

#include "rover/runtime/dds.hpp"

namespace rover::ddl {
namespace {

// The integer stored in a C enum field, whatever its value on the wire.
template <class E>
std::int32_t RawEnum(const E& e) {
  static_assert(sizeof(E) == sizeof(std::int32_t), "IDL enums are 32 bit");
  std::int32_t v = 0;
  std::memcpy(&v, &e, sizeof v);
  return v;
}

}  // namespace

static_assert(rover_ddl_GROUP_POSITION == static_cast<int>(GroupMode::kPosition));
static_assert(rover_ddl_GROUP_VELOCITY == static_cast<int>(GroupMode::kVelocity));
static_assert(rover_ddl_GROUP_STOP == static_cast<int>(GroupMode::kStop));
static_assert(rover_ddl_GROUP_IDLE == static_cast<int>(GroupState::kIdle));
static_assert(rover_ddl_GROUP_REJECTED == static_cast<int>(GroupState::kRejected));
static_assert(rover_ddl_MOTOR_FAULT_NONE == static_cast<int>(MotorFault::kNone));
static_assert(rover_ddl_MOTOR_FAULT_STALL == static_cast<int>(MotorFault::kStall));
static_assert(rover_ddl_MOTOR_FAULT_STOPPED == static_cast<int>(MotorFault::kStopped));
static_assert(rover_hw_MOTOR_IDLE == static_cast<int>(hw::MotorMode::kIdle));
static_assert(rover_hw_MOTOR_POSITION == static_cast<int>(hw::MotorMode::kPosition));
static_assert(rover_hw_MOTOR_VELOCITY == static_cast<int>(hw::MotorMode::kVelocity));
static_assert(rover_hw_MOTOR_BRAKE == static_cast<int>(hw::MotorMode::kBrake));
static_assert(rover_hw_kNumMotors == hw::kNumMotors);
static_assert(rover_HEALTH_OK == static_cast<int>(SensorHealth::kOk));
static_assert(rover_HEALTH_DEGRADED == static_cast<int>(SensorHealth::kDegraded));
static_assert(rover_HEALTH_FAILED == static_cast<int>(SensorHealth::kFailed));
static_assert(rover_HEALTH_STALE == static_cast<int>(SensorHealth::kStale));

rover_SensorHealth HealthToIdl(SensorHealth h) {
  return static_cast<rover_SensorHealth>(static_cast<int>(h));
}

MotorCommand MotorCommandFromIdl(const rover_ddl_MotorCommand& in) {
  MotorCommand c;
  c.stamp_ns = in.header.stamp_ns;
  c.command_id = in.command_id;
  c.motor_mask = in.motor_mask;
  c.mode = static_cast<GroupMode>(RawEnum(in.mode));
  for (std::size_t i = 0; i < c.goal.size(); ++i) {
    c.goal[i] = in.goal[i];
    c.max_rate[i] = in.max_rate[i];
  }
  c.timeout_s = in.timeout_s;
  return c;
}

hw::MotorTelemetry MotorTelemetryFromIdl(const rover_hw_MotorTelemetry& in) {
  hw::MotorTelemetry t;
  t.stamp_ns = in.header.stamp_ns;
  t.command_id = in.command_id;
  for (std::size_t i = 0; i < t.motors.size(); ++i) {
    const rover_hw_MotorReading& r = in.motors[i];
    t.motors[i] = {r.position, r.velocity, r.current_adc, r.temperature_adc, r.flags};
  }
  return t;
}

void MotorGoalsToIdl(const hw::MotorGoals& in, rover_hw_MotorGoals* out) {
  out->command_id = in.command_id;
  for (std::size_t i = 0; i < in.goals.size(); ++i) {
    const hw::MotorGoal& g = in.goals[i];
    rover_hw_MotorGoal& o = out->goals[i];
    o.mode = static_cast<rover_hw_MotorMode>(static_cast<int>(g.mode));
    o.position = g.position;
    o.velocity = g.velocity;
    o.current_limit_ma = g.current_limit_ma;
  }
}

void MotorStatusToIdl(const MotorStatus& in, rover_ddl_MotorStatus* out) {
  out->command_id = in.command_id;
  out->state = static_cast<rover_ddl_GroupState>(static_cast<int>(in.state));
  out->fault = static_cast<rover_ddl_MotorFault>(static_cast<int>(in.fault));
  out->fault_motor = in.fault_motor;
  dds::CopyString(out->message, in.message);
  for (std::size_t i = 0; i < in.position.size(); ++i) {
    out->position[i] = in.position[i];
    out->velocity[i] = in.velocity[i];
    out->current[i] = in.current[i];
    out->temperature[i] = in.temperature[i];
  }
}

}  // namespace rover::ddl
