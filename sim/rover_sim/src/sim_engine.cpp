#include "rover/sim/rover_sim/sim_engine.hpp"

#include <cmath>

#include "rover/base/format.hpp"
#include "rover/base/param_binder.hpp"

namespace rover::sim::rover_sim {

using hw::kNumMotors;
using physics::kMotorFaultOverCurrent;
using physics::kMotorFaultOverTemperature;
using physics::kMotorFaultStall;
using physics::MotorMode;
using physics::MotorParams;
using physics::MotorReading;
using physics::RoverModelParams;
using physics::RoverReadings;
using physics::RoverSimulation;
using physics::StartPose;
using sensors::DeclareSimSensorParams;
using sensors::MotorPhysical;
using sensors::SensorSuite;
using sensors::SensorTruth;
using sensors::SimSensorOptions;
using sensors::SimSensorOptionsFromParams;
using terrain::HeightField;
using world::BuildWorld;
using world::DeclareWorldParams;
using world::World;

namespace {

// The rover description's keys: the same as the stack's (dl-locomotion, dl-pose).
constexpr const char* kGeometryPrefix = "geometry.";

MotorMode ToPhysics(hw::MotorMode m) {
  switch (m) {
    case hw::MotorMode::kPosition: return MotorMode::kPosition;
    case hw::MotorMode::kVelocity: return MotorMode::kVelocity;
    case hw::MotorMode::kBrake:
    case hw::MotorMode::kIdle: return MotorMode::kOff;
  }
  return MotorMode::kOff;
}

// The simulated controllers must use the calibration the drivers use. A goal asks a controller
// to saturate at MotorSpec::current_limit (ddl-motor's goals carry it), and a motor held there is
// a stall, not an over-current (ddl/motor motor_types.hpp). The controller's own trip therefore
// sits above the saturation by the margin ddl-motor's over-current monitor uses: at the limit
// itself, a motor that saturated while still turning read the limit plus its no-load current and
// tripped within 50 ms (two VL-1 autonav runs ended MOT so: a wheel pushing over a rock at 1.3 A,
// a steering motor turning a loaded wheel at 0.9 A).
constexpr double kOverCurrentTripMargin = 0.15;

void ApplyHardware(const HardwareConfig& hw, RoverModelParams* p) {
  for (int i = 0; i < kNumMotors; ++i) {
    const MotorSpec& s = hw.motors[static_cast<std::size_t>(i)];
    MotorParams& m = p->motors[static_cast<std::size_t>(i)];
    m.gear_ratio = s.gear_ratio;
    m.encoder_counts_per_motor_rev = s.counts_per_rev;
    m.max_speed = s.max_rate;
    m.max_acceleration = s.max_acceleration;
    m.overcurrent_trip = s.current_limit * (1.0 + kOverCurrentTripMargin);
    m.max_current = std::max(m.max_current, m.overcurrent_trip);
    m.max_temperature = s.max_temperature;
    m.min_angle = s.min_angle;
    m.max_angle = s.max_angle;
  }
}

}  // namespace

Status EngineOptions::Validate() const {
  if (!(period_s >= 0.001 && period_s <= 0.1)) {
    return InvalidArgument("sim.period_s: " + std::to_string(period_s) + " is out of range [0.001, 0.1]");
  }
  if (!(truth_rate_hz > 0 && truth_rate_hz <= 1.0 / period_s)) {
    return InvalidArgument("sim.truth_rate_hz: must be in (0, 1/period_s]");
  }
  if (!(physics_rate_hz >= 100.0 && physics_rate_hz <= 10000.0)) {
    return InvalidArgument("sim.physics_rate_hz: " + FormatNumber(physics_rate_hz) +
                           " Hz is out of range [100, 10000]");
  }
  const double steps = period_s * physics_rate_hz;
  if (std::abs(steps - std::round(steps)) > 1e-6) {
    return InvalidArgument("sim.physics_rate_hz: " + FormatNumber(physics_rate_hz) +
                           " Hz does not divide sim.period_s = " + FormatNumber(period_s) +
                           " s into whole steps");
  }
  return Status::Ok();
}

void SimEngine::DeclareParams(ParamSet& p) {
  DeclareWorldParams(p);
  DeclareSimSensorParams(p, "sensors");
  DeclareHardwareParams(p, "hardware");
  rover::DeclareParams<hwconfig::RoverDescription>(p, kGeometryPrefix);
  p.Declare("sim.period_s", 0.01, "[s] simulation step and sim/clock period").Range(0.001, 0.1);
  p.Declare("sim.truth_rate_hz", 50.0, "[Hz] sim/truth rate (simulated time)").Range(1.0, 1000.0);
  p.Declare("sim.physics_rate_hz", 500.0,
            "[Hz] physics step and motor-controller rate (a whole number per sim.period_s)")
      .Range(100.0, 10000.0);
  p.Declare("sim.seed", 1, "sensor noise seed").Min(0);
  p.Declare("sim.traversable_height", 0.20, "[m] rocks taller than this count as contacts")
      .Range(0.01, 2.0);
}

Result<std::unique_ptr<SimEngine>> SimEngine::Create(const ParamSet& p) {
  auto world = BuildWorld(p);
  if (!world.ok()) return world.status();
  auto hw = HardwareConfigFromParams(p, "hardware");
  if (!hw.ok()) return hw.status();
  auto sensors = SimSensorOptionsFromParams(p, "sensors");
  if (!sensors.ok()) return sensors.status();
  ROVER_ASSIGN_OR_RETURN(const hwconfig::RoverDescription rover,
                         ReadParams<hwconfig::RoverDescription>(p, kGeometryPrefix));
  EngineOptions o;
  o.period_s = p.GetDouble("sim.period_s");
  o.truth_rate_hz = p.GetDouble("sim.truth_rate_hz");
  o.physics_rate_hz = p.GetDouble("sim.physics_rate_hz");
  o.seed = static_cast<std::uint64_t>(p.GetInt("sim.seed"));
  o.traversable_height = p.GetDouble("sim.traversable_height");
  sensors->seed = o.seed;
  return Create(std::move(*world), *hw, *sensors, o, rover);
}

Result<std::unique_ptr<SimEngine>> SimEngine::Create(World world, const HardwareConfig& hw,
                                                     const SimSensorOptions& sensors,
                                                     const EngineOptions& options,
                                                     const hwconfig::RoverDescription& rover) {
  ROVER_RETURN_IF_ERROR(options.Validate());
  ROVER_RETURN_IF_ERROR(hw.Validate());
  std::unique_ptr<SimEngine> e(new SimEngine());
  e->world_ = std::move(world);
  e->hw_ = hw;
  e->options_ = options;
  e->sensor_options_ = sensors;
  e->ground_ = std::make_shared<const HeightField>(e->world_.terrain.ground);
  RoverModelParams mp;
  mp.geometry = rover;
  mp.integrator.control_rate_hz = options.physics_rate_hz;
  ApplyHardware(hw, &mp);
  auto physics = RoverSimulation::Create(
      mp, e->ground_, StartPose{e->world_.start_x, e->world_.start_y, e->world_.start_yaw});
  if (!physics.ok()) return physics.status();
  e->physics_ = std::move(*physics);
  auto suite = SensorSuite::Create(hw, sensors);
  if (!suite.ok()) return suite.status();
  e->sensors_ = std::make_unique<SensorSuite>(std::move(*suite));
  e->truth_every_ = std::max(1, static_cast<int>(std::lround(1.0 / (options.period_s * options.truth_rate_hz))));
  e->rock_touched_.assign(e->world_.terrain.rocks.size(), false);
  for (std::size_t i = 0; i < e->world_.terrain.rocks.size(); ++i) {
    if (e->world_.terrain.rocks[i].height > e->options_.traversable_height) {
      e->tall_rocks_.push_back(i);
    }
  }
  return e;
}

Status SimEngine::ApplyMotorGoals(const hw::MotorGoals& goals) {
  Status first_error;
  for (int i = 0; i < kNumMotors; ++i) {
    const hw::MotorGoal& g = goals.goals[static_cast<std::size_t>(i)];
    if (g.mode == hw::MotorMode::kIdle) continue;
    (void)physics_->ClearMotorFaults(i);
    // 0 mA = the motor's configured current limit.
    const double limit_a = g.current_limit_ma > 0
                               ? g.current_limit_ma / 1000.0
                               : hw_.motors[static_cast<std::size_t>(i)].current_limit;
    Status s = physics_->SetMotorGoal(i, ToPhysics(g.mode), g.position, g.velocity, limit_a);
    if (!s.ok()) {
      (void)physics_->SetMotorGoal(i, MotorMode::kOff, 0, 0, 0);
      if (first_error.ok()) first_error = s;
    }
  }
  applied_command_id_ = goals.command_id;
  return first_error;
}

TruthSample SimEngine::MakeTruth(const RoverReadings& r) {
  TruthSample t;
  t.time_s = time_s_;
  t.pose = r.chassis.pose_site;
  t.velocity_site = r.chassis.linear_velocity_site;
  t.angular_velocity_body = r.chassis.angular_velocity_body;
  t.wheels = r.wheels;
  t.rocker_angle[0] = r.rocker_left_rad;
  t.rocker_angle[1] = r.rocker_right_rad;
  t.bogie_angle[0] = r.bogie_left_rad;
  t.bogie_angle[1] = r.bogie_right_rad;
  t.odometer = odometer_;
  t.tool_point = r.tool_point;
  t.tool_contact = r.tool_contact;
  t.rock_contacts = rock_contacts_;
  t.max_contact_rock_height = max_contact_height_;
  return t;
}

Result<StepOutput> SimEngine::Step() {
  ROVER_RETURN_IF_ERROR(physics_->Advance(options_.period_s));
  ++step_;
  time_s_ = step_ * options_.period_s;  // no accumulated rounding
  const RoverReadings r = physics_->Readings();

  // Odometer and contacts with tall rocks (wheel contact point inside a rock's footprint).
  const Eigen::Vector2d xy = r.chassis.pose_site.translation().head<2>();
  if (last_xy_) odometer_ += (xy - *last_xy_).norm();
  last_xy_ = xy;
  const auto& rocks = world_.terrain.rocks;
  for (const auto& w : r.wheels) {
    if (!w.in_contact) continue;
    for (const std::size_t i : tall_rocks_) {
      if (rock_touched_[i]) continue;
      if ((w.contact_point_site.head<2>() - rocks[i].position.head<2>()).norm() < rocks[i].diameter / 2) {
        rock_touched_[i] = true;
        ++rock_contacts_;
        max_contact_height_ = std::max(max_contact_height_, rocks[i].height);
      }
    }
  }

  SensorTruth st;
  st.stamp = Time::FromSeconds(time_s_);
  st.applied_command_id = applied_command_id_;
  for (int i = 0; i < kNumMotors; ++i) {
    const MotorReading& m = r.motors[static_cast<std::size_t>(i)];
    MotorPhysical& p = st.motors[static_cast<std::size_t>(i)];
    const double cpr = physics_->params().motors[static_cast<std::size_t>(i)].CountsPerRad();
    p.position_rad = m.position_counts / cpr;
    p.velocity_rad_s = m.velocity_counts_per_s / cpr;
    p.current_a = m.current_a;
    p.temperature_c = m.temperature_c;
    p.enabled = m.mode != MotorMode::kOff;
    p.at_goal = m.goal_reached;
    p.stall = (m.faults & kMotorFaultStall) != 0;
    p.over_current = (m.faults & kMotorFaultOverCurrent) != 0;
    p.over_temp = (m.faults & kMotorFaultOverTemperature) != 0;
  }
  st.suspension = {r.rocker_left_rad, r.rocker_right_rad, r.bogie_left_rad, r.bogie_right_rad};
  st.arm_contact = r.tool_contact;
  // The gyro integrates, as the LN-200's delta-angle output does: its rate is the mean over the
  // engine step, taken from the attitude change, so the chassis' contact vibration cannot alias
  // into a heading drift. This is the mean over the IMU's sample period when the IMU samples
  // every step (the default: 100 Hz IMU, 10 ms step); at a lower IMU rate it is the mean over
  // the last step only.
  const Eigen::Matrix3d attitude = r.chassis.pose_site.linear();
  if (last_attitude_) {
    const Eigen::AngleAxisd turned(last_attitude_->transpose() * attitude);
    st.imu.angular_velocity_rover = turned.axis() * (turned.angle() / options_.period_s);
  } else {
    st.imu.angular_velocity_rover = r.chassis.angular_velocity_body;
  }
  last_attitude_ = attitude;
  st.imu.specific_force_rover = r.chassis.specific_force_body;
  st.site_from_rover = r.chassis.pose_site.linear();

  StepOutput out;
  out.time_s = time_s_;
  out.sensors = sensors_->Step(st);
  if (step_ % truth_every_ == 0) out.truth = MakeTruth(r);
  return out;
}

Status SimEngine::Reset() {
  ROVER_RETURN_IF_ERROR(
      physics_->Reset(StartPose{world_.start_x, world_.start_y, world_.start_yaw}));
  auto suite = SensorSuite::Create(hw_, sensor_options_);
  if (!suite.ok()) return suite.status();
  sensors_ = std::make_unique<SensorSuite>(std::move(*suite));
  time_s_ = 0;
  step_ = 0;
  odometer_ = 0;
  last_xy_.reset();
  last_attitude_.reset();
  rock_touched_.assign(world_.terrain.rocks.size(), false);
  rock_contacts_ = 0;
  max_contact_height_ = 0;
  return Status::Ok();
}

Eigen::Vector3d SimEngine::SunDirectionSite() const {
  return sensors_->ephemeris().At(time_s_).direction_site;
}

}  // namespace rover::sim::rover_sim
