#include "rover/sim/physics/rover_simulation.hpp"

// Simbody. Debian's 3.7 is built without NDEBUG: this file must be compiled with -UNDEBUG
// (the SIMBODY flag of rover_add_module). Its headers do not compile as C++20 (ambiguous
// reversed operator== on SimTK index types), so CMakeLists.txt compiles this one file as C++17;
// keep it free of C++20 features. The public header does not include Simbody.
#include <Simbody.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <exception>
#include <string>
#include <utility>
#include <vector>

#include "rover/base/check.hpp"
#include "rover/base/format.hpp"

namespace rover::sim::physics {

using terrain::HeightField;

namespace {

using SimTK::MobilizedBody;
using SimTK::MobilizedBodyIndex;
using SimTK::Rotation;
using SimTK::Transform;
using SimTK::Vec3;

// Simbody's rocker and bogie pins turn about +y of their parent, so their coordinate grows as the
// link pitches nose-down; the rover description's angles grow as the front rises. Readings and
// PoseModel convert with this sign (the model itself is unchanged).
constexpr double kSuspensionSign = -1.0;

Vec3 ToVec3(const Eigen::Vector3d& v) { return Vec3(v.x(), v.y(), v.z()); }
Eigen::Vector3d ToEigen(const Vec3& v) { return Eigen::Vector3d(v[0], v[1], v[2]); }

Eigen::Isometry3d ToIsometry(const Transform& x) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) t.linear()(r, c) = x.R()[r][c];
  }
  t.translation() = ToEigen(x.p());
  return t;
}

// Mass properties of a solid box (half extents `half`) centred at `com` in the body frame;
// Simbody wants the inertia about the body origin.
SimTK::MassProperties BoxMass(double mass, const Vec3& com, const Vec3& half) {
  return SimTK::MassProperties(
      mass, com, SimTK::UnitInertia::brick(half[0], half[1], half[2]).shiftFromCentroid(-com));
}

// Adds the reflected rotor inertia J of a joint's motor about the body's `axis` (0 x, 1 y, 2 z)
// through its origin (the joint axis), as a thin disc (J/2 about the other two axes keeps the
// inertia physical). Approximation: the rotor then also turns with the joint's carrier, which
// for a slow rover only adds a little carrier inertia.
SimTK::MassProperties WithRotor(const SimTK::MassProperties& mp, int axis, double j) {
  SimTK::Inertia inertia = mp.calcInertia();
  Vec3 moments(j / 2);
  moments[axis] = j;
  inertia += SimTK::Inertia(moments);
  return SimTK::MassProperties(mp.getMass(), mp.getMassCenter(), inertia);
}

// A pin joint rotates about the z axis of its F and M frames; these rotations map it onto the
// parent's +y or -y axis while leaving the child's frame aligned with the parent at q = 0.
const Rotation& PinAboutY() {
  static const Rotation r(-SimTK::Pi / 2, SimTK::XAxis);
  return r;
}
const Rotation& PinAboutMinusY() {
  static const Rotation r(SimTK::Pi / 2, SimTK::XAxis);
  return r;
}

// ------------------------------------------------------------------------------------------
// Wheel-terrain and belly-terrain contact as one Simbody force element. Each wheel owns a 2-D
// shear state z (terrain_contact.hpp), allocated as continuous Z variables of the force
// subsystem so the integrator's error control covers it.
class TerrainForce : public SimTK::Force::Custom::Implementation {
 public:
  TerrainForce(const SimTK::SimbodyMatterSubsystem& matter, SimTK::SubsystemIndex forces_ix,
               const HeightField* terrain, const RoverModelParams* params,
               std::array<MobilizedBodyIndex, kNumWheels> wheels, MobilizedBodyIndex chassis,
               std::vector<Vec3> belly_points)
      : matter_(matter),
        forces_ix_(forces_ix),
        terrain_(terrain),
        params_(params),
        wheels_(wheels),
        chassis_(chassis),
        belly_points_(std::move(belly_points)) {}

  void realizeTopology(SimTK::State& s) const override {
    z0_ = s.allocateZ(forces_ix_, SimTK::Vector(2 * kNumWheels, 0.0));
    // The matter subsystem is complete now; cache the body handles (getMobilizedBody() costs a
    // checked downcast in this Simbody build).
    for (int w = 0; w < kNumWheels; ++w) wheel_bodies_[w] = &matter_.getMobilizedBody(wheels_[w]);
    chassis_body_ = &matter_.getMobilizedBody(chassis_);
  }

  void calcForce(const SimTK::State& s, SimTK::Vector_<SimTK::SpatialVec>& body_forces,
                 SimTK::Vector_<Vec3>& /*particle_forces*/,
                 SimTK::Vector& /*mobility_forces*/) const override {
    SimTK::Vector& zdot = s.updZDot(forces_ix_);
    for (int w = 0; w < kNumWheels; ++w) {
      const WheelContact c = Evaluate(s, w);
      zdot[z0_ + 2 * w] = c.shear_rate.x();
      zdot[z0_ + 2 * w + 1] = c.shear_rate.y();
      if (!c.in_contact) continue;
      const MobilizedBody& b = *wheel_bodies_[w];
      const Transform& x_gb = b.getBodyTransform(s);
      b.applyForceToBodyPoint(s, ~x_gb * ToVec3(c.point), ToVec3(c.force), body_forces);
      b.applyBodyTorque(s, ToVec3(c.torque), body_forces);
    }
    const MobilizedBody& chassis = *chassis_body_;
    const Transform& x_gc = chassis.getBodyTransform(s);
    for (const Vec3& p : belly_points_) {
      const Vec3 p_g = x_gc * p;
      const Vec3 v_g = chassis.findStationVelocityInGround(s, p);
      const Eigen::Vector3d f =
          EvaluatePointContact(*terrain_, params_->belly, ToEigen(p_g), ToEigen(v_g));
      if (f.squaredNorm() > 0.0) chassis.applyForceToBodyPoint(s, p, ToVec3(f), body_forces);
    }
  }

  SimTK::Real calcPotentialEnergy(const SimTK::State&) const override { return 0.0; }

  WheelContact Evaluate(const SimTK::State& s, int w) const {
    const MobilizedBody& b = *wheel_bodies_[w];
    const Transform& x_gb = b.getBodyTransform(s);
    WheelKinematics k;
    k.center = ToEigen(x_gb.p());
    k.axis = ToEigen(x_gb.R().y());
    k.velocity = ToEigen(b.getBodyOriginVelocity(s));
    k.angular_velocity = ToEigen(b.getBodyAngularVelocity(s));
    const SimTK::Vector& z = s.getZ(forces_ix_);
    const Eigen::Vector2d shear(z[z0_ + 2 * w], z[z0_ + 2 * w + 1]);
    const hwconfig::RoverDescription& g = params_->geometry;
    return EvaluateWheelContact(*terrain_, params_->contact, g.wheel_radius, g.wheel_width, k,
                                shear);
  }

  void ClearShear(SimTK::State& s) const {
    SimTK::Vector& z = s.updZ(forces_ix_);
    for (int i = 0; i < 2 * kNumWheels; ++i) z[z0_ + i] = 0.0;
  }

 private:
  const SimTK::SimbodyMatterSubsystem& matter_;
  SimTK::SubsystemIndex forces_ix_;
  const HeightField* terrain_;
  const RoverModelParams* params_;
  std::array<MobilizedBodyIndex, kNumWheels> wheels_;
  MobilizedBodyIndex chassis_;
  std::vector<Vec3> belly_points_;
  mutable SimTK::ZIndex z0_;
  mutable std::array<const MobilizedBody*, kNumWheels> wheel_bodies_{};
  mutable const MobilizedBody* chassis_body_ = nullptr;
};

// The rocker differential as a stiff, damped torsional coupling between the rockers:
//   tau_l = tau_r = -k (q_l + q_r) - c (u_l + u_r)
// keeps q_l = -q_r to within the transmitted torque / k.
class DifferentialForce : public SimTK::Force::Custom::Implementation {
 public:
  DifferentialForce(const SimTK::SimbodyMatterSubsystem& matter, MobilizedBodyIndex left,
                    MobilizedBodyIndex right, double stiffness, double damping)
      : matter_(matter), left_(left), right_(right), k_(stiffness), c_(damping) {}

  void realizeTopology(SimTK::State& /*s*/) const override {
    l_ = &matter_.getMobilizedBody(left_);
    r_ = &matter_.getMobilizedBody(right_);
  }

  void calcForce(const SimTK::State& s, SimTK::Vector_<SimTK::SpatialVec>& /*body_forces*/,
                 SimTK::Vector_<Vec3>& /*particle_forces*/,
                 SimTK::Vector& mobility_forces) const override {
    const MobilizedBody& l = *l_;
    const MobilizedBody& r = *r_;
    const double tau =
        -k_ * (l.getOneQ(s, 0) + r.getOneQ(s, 0)) - c_ * (l.getOneU(s, 0) + r.getOneU(s, 0));
    l.applyOneMobilityForce(s, 0, tau, mobility_forces);
    r.applyOneMobilityForce(s, 0, tau, mobility_forces);
  }

  SimTK::Real calcPotentialEnergy(const SimTK::State& s) const override {
    const double e = matter_.getMobilizedBody(left_).getOneQ(s, 0) +
                     matter_.getMobilizedBody(right_).getOneQ(s, 0);
    return 0.5 * k_ * e * e;
  }

 private:
  const SimTK::SimbodyMatterSubsystem& matter_;
  MobilizedBodyIndex left_, right_;
  double k_, c_;
  mutable const MobilizedBody* l_ = nullptr;
  mutable const MobilizedBody* r_ = nullptr;
};

}  // namespace

// Motors 0..kBodyMotors-1 turn Simbody joints; the rest are the kinematic arm's.
constexpr int kBodyMotors = hw::kArmAzimuth;

// ------------------------------------------------------------------------------------------
struct RoverSimulation::Impl {
  Impl(const RoverModelParams& p, std::shared_ptr<const HeightField> t)
      : params(p), terrain(std::move(t)), matter(system), forces(system) {}

  void Build();
  Status Place(const StartPose& start);
  void AdvanceTo(double t_end);
  void ControlTick();
  const MobilizedBody& Body(MobilizedBodyIndex ix) const { return matter.getMobilizedBody(ix); }
  const MobilizedBody& Joint(int motor) const { return *joints[motor]; }
  BodyPoses Poses(const SimTK::State& s) const;
  void InitializeIntegrator(const SimTK::State& s);

  RoverModelParams params;
  std::shared_ptr<const HeightField> terrain;
  SimTK::MultibodySystem system;
  SimTK::SimbodyMatterSubsystem matter;
  SimTK::GeneralForceSubsystem forces;
  SimTK::Force::DiscreteForces motor_forces;
  MobilizedBodyIndex chassis_ix;
  std::array<MobilizedBodyIndex, 2> rocker_ix, bogie_ix;  // left, right
  std::array<MobilizedBodyIndex, kNumWheels> wheel_ix;
  std::array<MobilizedBodyIndex, hwconfig::kNumSteered> steer_ix;  // LF LR RF RR
  std::array<MobilizedBodyIndex, kBodyMotors> joint_ix;    // joint driven by each motor
  std::array<const MobilizedBody*, kBodyMotors> joints{};  // the same, cached after Build()
  // The kinematic arm (motors kBodyMotors..): angles and rates, and its instrument's contact.
  std::array<double, hwconfig::kArmJoints> arm_q{}, arm_u{};
  bool arm_contact = false;
  double ArmQ(int motor) const { return arm_q[static_cast<std::size_t>(motor - kBodyMotors)]; }
  double ArmU(int motor) const { return arm_u[static_cast<std::size_t>(motor - kBodyMotors)]; }
  double JointQ(const SimTK::State& s, int motor) const {
    return motor < kBodyMotors ? Joint(motor).getOneQ(s, 0) : ArmQ(motor);
  }
  double JointU(const SimTK::State& s, int motor) const {
    return motor < kBodyMotors ? Joint(motor).getOneU(s, 0) : ArmU(motor);
  }
  Eigen::Vector3d ToolPoint(const SimTK::State& s, const hwconfig::ArmAngles& q) const;
  // Lowest height of the face's centre and contact ring above the terrain [m].
  double FaceClearance(const SimTK::State& s, const hwconfig::ArmAngles& q) const;
  void ArmTick(const SimTK::State& s);
  MobilizedBodyIndex tilt_ix;
  const TerrainForce* terrain_force = nullptr;
  std::unique_ptr<SimTK::Integrator> integ;
  std::array<MotorController, kNumMotors> motors;
  std::array<double, kNumMotors> counts_per_rad{};
  Eigen::Isometry3d hazcam_front_c = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d hazcam_rear_c = Eigen::Isometry3d::Identity();
  std::vector<Eigen::Vector3d> belly_points;  // chassis frame
  double period = 1e-3;
  std::int64_t tick = 0;
  bool broken = false;
  SimulationStats stats;
  std::int64_t steps_before_init = 0;
};

void RoverSimulation::Impl::Build() {
  const hwconfig::RoverDescription& g = params.geometry;
  const RoverMasses& m = params.masses;
  period = 1.0 / params.integrator.control_rate_hz;

  SimTK::Force::Gravity(forces, matter, -SimTK::ZAxis, params.gravity);
  motor_forces = SimTK::Force::DiscreteForces(forces, matter);

  // Chassis: free joint to Ground (= site frame).
  const Vec3 box_half = ToVec3(g.body_size) / 2;
  const Vec3 box_center = ToVec3(g.body_centre);
  MobilizedBody::Free chassis(matter.Ground(), Transform(),
                              SimTK::Body::Rigid(BoxMass(m.chassis, box_center, box_half)),
                              Transform());
  chassis_ix = chassis.getMobilizedBodyIndex();

  const double r = g.wheel_radius;
  const SimTK::MassProperties wheel_mass(m.wheel, Vec3(0),
                                         SimTK::UnitInertia::cylinderAlongY(r, g.wheel_width / 2));
  auto wheel_body = [&](int motor) {
    return SimTK::Body::Rigid(WithRotor(wheel_mass, 1, params.motors[motor].ReflectedInertia()));
  };
  const double hs = g.steer_height;
  const SimTK::MassProperties steer_mass =
      BoxMass(m.steer_bracket, Vec3(0, 0, -hs / 2), Vec3(0.03, 0.03, std::max(hs / 2, 0.02)));
  auto steer_body = [&](int motor) {
    return SimTK::Body::Rigid(WithRotor(steer_mass, 2, params.motors[motor].ReflectedInertia()));
  };

  for (int side = 0; side < 2; ++side) {
    const double sy = side == 0 ? 1.0 : -1.0;
    const Vec3 pivot(g.rocker_pivot_x, sy * g.rocker_pivot_y, g.rocker_pivot_z);
    const double dy = sy * (g.half_track - g.rocker_pivot_y);
    // Rocker: frame at its pivot; carries the front steering joint and the bogie pivot.
    const Vec3 front_steer(g.front_wheel_x - g.rocker_pivot_x, dy, r + hs - g.rocker_pivot_z);
    const Vec3 bogie_pivot(g.bogie_pivot_x - g.rocker_pivot_x, dy,
                           g.bogie_pivot_z - g.rocker_pivot_z);
    const Vec3 rocker_com = (front_steer + bogie_pivot) / 2;
    const Vec3 rocker_half(std::max(std::abs(front_steer[0] - bogie_pivot[0]) / 2, 0.05), 0.03,
                           0.05);
    MobilizedBody::Pin rocker(chassis, Transform(PinAboutY(), pivot),
                              SimTK::Body::Rigid(BoxMass(m.rocker, rocker_com, rocker_half)),
                              Transform(PinAboutY(), Vec3(0)));
    rocker_ix[side] = rocker.getMobilizedBodyIndex();
    SimTK::Force::MobilityLinearStop(forces, rocker, SimTK::MobilizerQIndex(0), 5000.0, 0.5,
                                     -g.rocker_limit, g.rocker_limit);

    const int w0 = side == 0 ? hwconfig::kWheelLF : hwconfig::kWheelRF;
    const int s0 = side == 0 ? hw::kSteerLF : hw::kSteerRF;  // front; rear = s0 + 1
    MobilizedBody::Pin steer_f(rocker, Transform(front_steer), steer_body(s0), Transform());
    MobilizedBody::Pin wheel_f(steer_f, Transform(PinAboutY(), Vec3(0, 0, -hs)), wheel_body(w0),
                               Transform(PinAboutY(), Vec3(0)));

    // Bogie: frame at its pivot; carries the middle wheel and the rear steering joint.
    const Vec3 middle(g.middle_wheel_x - g.bogie_pivot_x, 0, r - g.bogie_pivot_z);
    const Vec3 rear_steer(g.rear_wheel_x - g.bogie_pivot_x, 0, r + hs - g.bogie_pivot_z);
    const Vec3 bogie_com = (middle + rear_steer) / 2;
    const Vec3 bogie_half(std::max(std::abs(middle[0] - rear_steer[0]) / 2, 0.05), 0.03, 0.05);
    MobilizedBody::Pin bogie(rocker, Transform(PinAboutY(), bogie_pivot),
                             SimTK::Body::Rigid(BoxMass(m.bogie, bogie_com, bogie_half)),
                             Transform(PinAboutY(), Vec3(0)));
    bogie_ix[side] = bogie.getMobilizedBodyIndex();
    SimTK::Force::MobilityLinearStop(forces, bogie, SimTK::MobilizerQIndex(0), 5000.0, 0.5,
                                     -g.bogie_limit, g.bogie_limit);
    MobilizedBody::Pin wheel_m(bogie, Transform(PinAboutY(), middle), wheel_body(w0 + 1),
                               Transform(PinAboutY(), Vec3(0)));
    MobilizedBody::Pin steer_r(bogie, Transform(rear_steer), steer_body(s0 + 1), Transform());
    MobilizedBody::Pin wheel_r(steer_r, Transform(PinAboutY(), Vec3(0, 0, -hs)), wheel_body(w0 + 2),
                               Transform(PinAboutY(), Vec3(0)));

    wheel_ix[w0 + 0] = wheel_f.getMobilizedBodyIndex();
    wheel_ix[w0 + 1] = wheel_m.getMobilizedBodyIndex();
    wheel_ix[w0 + 2] = wheel_r.getMobilizedBodyIndex();
    steer_ix[2 * side + 0] = steer_f.getMobilizedBodyIndex();
    steer_ix[2 * side + 1] = steer_r.getMobilizedBodyIndex();
  }

  // Differential: the rockers rotate opposite. A stiff torsional coupling on q_l + q_r (see
  // DifferentialForce) rather than a CoordinateCoupler constraint: Simbody's constrained
  // ("loop") forward dynamics doubled the cost of every step.
  SimTK::Force::Custom(
      forces, new DifferentialForce(matter, rocker_ix[0], rocker_ix[1],
                                    params.differential_stiffness, params.differential_damping));

  // Mast: pan about +z at the base, tilt about -y at the head.
  MobilizedBody::Pin pan(
      chassis, Transform(ToVec3(g.mast.pan_joint)),
      SimTK::Body::Rigid(
          WithRotor(SimTK::MassProperties(
                        m.mast_pan, Vec3(0, 0, g.mast.head_height / 2),
                        SimTK::UnitInertia::cylinderAlongZ(0.04,
                                                           std::max(g.mast.head_height / 2, 0.01))
                            .shiftFromCentroid(Vec3(0, 0, -g.mast.head_height / 2))),
                    2, params.motors[hw::kMastPan].ReflectedInertia())),
      Transform());
  MobilizedBody::Pin tilt(
      pan, Transform(PinAboutMinusY(), Vec3(0, 0, g.mast.head_height)),
      SimTK::Body::Rigid(WithRotor(BoxMass(m.mast_head, Vec3(0), Vec3(0.05, 0.15, 0.05)), 1,
                                   params.motors[hw::kMastTilt].ReflectedInertia())),
      Transform(PinAboutMinusY(), Vec3(0)));
  tilt_ix = tilt.getMobilizedBodyIndex();

  for (int w = 0; w < kNumWheels; ++w) joint_ix[w] = wheel_ix[w];
  for (int j = 0; j < hwconfig::kNumSteered; ++j) joint_ix[hwconfig::SteerMotor(j)] = steer_ix[j];
  joint_ix[hw::kMastPan] = pan.getMobilizedBodyIndex();
  joint_ix[hw::kMastTilt] = tilt_ix;

  // Belly contact points: bottom face corners, edge midpoints and centre.
  std::vector<Vec3> belly;
  const double zb = box_center[2] - box_half[2];
  for (int ix = -1; ix <= 1; ++ix) {
    for (int iy = -1; iy <= 1; ++iy) {
      belly.emplace_back(box_center[0] + ix * box_half[0], box_center[1] + iy * box_half[1], zb);
    }
  }
  for (const Vec3& p : belly) belly_points.push_back(ToEigen(p));
  auto* tf = new TerrainForce(matter, forces.getMySubsystemIndex(), terrain.get(), &params,
                              wheel_ix, chassis_ix, std::move(belly));
  terrain_force = tf;
  SimTK::Force::Custom(forces, tf);  // the force subsystem takes ownership

  // Fixed HAZCAM mounts in the chassis frame (x boresight pitched down, y left, z up).
  hazcam_front_c = g.front_hazcam.Pose();
  hazcam_rear_c = g.rear_hazcam.Pose();

  for (int i = 0; i < kNumMotors; ++i) counts_per_rad[i] = params.motors[i].CountsPerRad();
  system.realizeTopology();
  for (int i = 0; i < kBodyMotors; ++i) joints[i] = &matter.getMobilizedBody(joint_ix[i]);
}

void RoverSimulation::Impl::InitializeIntegrator(const SimTK::State& s) {
  if (integ) steps_before_init += integ->getNumStepsTaken();
  if (params.integrator.method == IntegratorMethod::kSemiExplicitEulerFixed) {
    integ = std::make_unique<SimTK::SemiExplicitEulerIntegrator>(system, period);
  } else {
    integ = std::make_unique<SimTK::SemiExplicitEuler2Integrator>(system);
    integ->setAccuracy(params.integrator.accuracy);
  }
  integ->setAllowInterpolation(false);
  integ->setMaximumStepSize(period);
  integ->initialize(s);
}

Status RoverSimulation::Impl::Place(const StartPose& start) {
  if (!std::isfinite(start.x) || !std::isfinite(start.y) || !std::isfinite(start.yaw)) {
    return InvalidArgument("start pose has a non-finite value");
  }
  if (!terrain->Contains(start.x, start.y)) {
    return OutOfRange("start (" + FormatNumber(start.x) + ", " + FormatNumber(start.y) +
                      ") is outside the terrain [" + FormatNumber(terrain->min_x()) + ", " +
                      FormatNumber(terrain->max_x()) + "] x [" + FormatNumber(terrain->min_y()) +
                      ", " + FormatNumber(terrain->max_y()) + "]");
  }
  const hwconfig::RoverDescription& g = params.geometry;
  SimTK::State s = system.getDefaultState();
  const MobilizedBody& chassis = Body(chassis_ix);

  // Unknowns x = (z, roll, pitch, rocker_left, bogie_left, bogie_right); residual = the gap
  // between each wheel's lowest point and the terrain. Newton with a finite-difference Jacobian.
  using Vec6 = Eigen::Matrix<double, 6, 1>;
  auto set = [&](const Vec6& x) {
    const Rotation rot = Rotation(start.yaw, SimTK::ZAxis) * Rotation(x[2], SimTK::YAxis) *
                         Rotation(x[1], SimTK::XAxis);
    chassis.setQToFitTransform(s, Transform(rot, Vec3(start.x, start.y, x[0])));
    Body(rocker_ix[0]).setOneQ(s, 0, x[3]);
    Body(rocker_ix[1]).setOneQ(s, 0, -x[3]);
    Body(bogie_ix[0]).setOneQ(s, 0, x[4]);
    Body(bogie_ix[1]).setOneQ(s, 0, x[5]);
    system.realize(s, SimTK::Stage::Position);
  };
  auto residual = [&](const Vec6& x) {
    set(x);
    Vec6 res;
    for (int w = 0; w < kNumWheels; ++w) {
      const Transform& xw = Body(wheel_ix[w]).getBodyTransform(s);
      res[w] = WheelGap(*terrain, g.wheel_radius, ToEigen(xw.p()), ToEigen(xw.R().y()));
    }
    return res;
  };
  Vec6 x = Vec6::Zero();
  {
    const double c = std::cos(start.yaw), sn = std::sin(start.yaw);
    double sum = 0.0;
    for (double wx : {g.front_wheel_x, g.middle_wheel_x, g.rear_wheel_x}) {
      for (double wy : {g.half_track, -g.half_track}) {
        sum += terrain->Height(start.x + c * wx - sn * wy, start.y + sn * wx + c * wy);
      }
    }
    x[0] = sum / 6.0;
  }
  for (int it = 0; it < 30; ++it) {
    const Vec6 r0 = residual(x);
    if (r0.cwiseAbs().maxCoeff() < 1e-7) break;
    Eigen::Matrix<double, 6, 6> jac;
    for (int j = 0; j < 6; ++j) {
      Vec6 xp = x;
      xp[j] += 1e-6;
      jac.col(j) = (residual(xp) - r0) / 1e-6;
    }
    Vec6 dx = -jac.colPivHouseholderQr().solve(r0);
    if (!dx.allFinite()) break;
    const double scale = std::max(1.0, dx.cwiseAbs().maxCoeff() / 0.1);
    x += dx / scale;
  }
  x[3] = std::clamp(x[3], -g.rocker_limit, g.rocker_limit);
  x[4] = std::clamp(x[4], -g.bogie_limit, g.bogie_limit);
  x[5] = std::clamp(x[5], -g.bogie_limit, g.bogie_limit);
  set(x);
  for (int w = 0; w < kNumWheels; ++w) Body(wheel_ix[w]).setOneQ(s, 0, 0.0);  // odometry 0
  s.updU() = 0.0;
  s.setTime(0.0);
  terrain_force->ClearShear(s);
  motor_forces.clearAllForces(s);
  system.realize(s, SimTK::Stage::Position);

  arm_q = params.geometry.arm.stow;
  arm_u = {};
  arm_contact = false;
  for (int i = 0; i < kNumMotors; ++i) {
    motors[i] = MotorController(params.motors[i], params.ambient_temperature_c, JointQ(s, i));
  }
  tick = 0;
  broken = false;
  InitializeIntegrator(s);

  // Settle with all brakes engaged, then restart the clock at 0.
  if (params.integrator.settle_time > 0.0) {
    AdvanceTo(params.integrator.settle_time);
    SimTK::State settled = integ->getState();
    settled.setTime(0.0);
    InitializeIntegrator(settled);
    tick = 0;
  }
  return Status::Ok();
}

void RoverSimulation::Impl::ControlTick() {
  SimTK::State& s = integ->updAdvancedState();
  std::array<double, kNumMotors> torque{};
  for (int i = 0; i < kBodyMotors; ++i) {
    const MobilizedBody& b = Joint(i);
    torque[i] = motors[i].Update(b.getOneQ(s, 0), b.getOneU(s, 0), period);
  }
  for (int i = 0; i < kBodyMotors; ++i) {
    motor_forces.setOneMobilityForce(s, Joint(i), SimTK::MobilizerUIndex(0), torque[i]);
  }
  ArmTick(s);
  integ->reinitialize(SimTK::Stage::Dynamics, false);
  ++stats.control_ticks;
}

Eigen::Vector3d RoverSimulation::Impl::ToolPoint(const SimTK::State& s,
                                                 const hwconfig::ArmAngles& q) const {
  const Eigen::Isometry3d site_from_rover = ToIsometry(Body(chassis_ix).getBodyTransform(s));
  return site_from_rover * params.geometry.arm.Forward(q).face;
}

void RoverSimulation::Impl::ArmTick(const SimTK::State& s) {
  // The arm's joints integrate their motors' torques; a step that would push the instrument's
  // face into the terrain is undone (the face rests on what it touched).
  hwconfig::ArmAngles q = arm_q;
  hwconfig::ArmAngles u = arm_u;
  bool moving = false;
  for (int j = 0; j < hwconfig::kArmJoints; ++j) {
    const auto k = static_cast<std::size_t>(j);
    const int m = kBodyMotors + j;
    const double tau = motors[m].Update(arm_q[k], arm_u[k], period);
    const double inertia = params.motors[m].ReflectedInertia() + kArmLinkInertia;
    u[k] = arm_u[k] + tau / inertia * period;
    q[k] = arm_q[k] + u[k] * period;
    moving = moving || u[k] != 0.0 || arm_u[k] != 0.0;
  }
  if (!moving && (tick % 20) != 0) return;  // at rest: the contact is re-checked at 50 Hz
  if (FaceClearance(s, q) < 0.0) {
    arm_u = {};
    arm_contact = FaceClearance(s, arm_q) < params.geometry.arm.contact_standoff;
    return;
  }
  arm_q = q;
  arm_u = u;
  arm_contact = FaceClearance(s, q) < params.geometry.arm.contact_standoff;
}

double RoverSimulation::Impl::FaceClearance(const SimTK::State& s,
                                            const hwconfig::ArmAngles& q) const {
  // The face's centre and eight points of its contact ring, each against the terrain below
  // it: the ring is what touches first on a rock's edge.
  const Eigen::Isometry3d site_from_rover = ToIsometry(Body(chassis_ix).getBodyTransform(s));
  const hwconfig::ArmDescription& arm = params.geometry.arm;
  const Eigen::Isometry3d imager = site_from_rover * arm.ImagerPose(q);
  double clearance = std::numeric_limits<double>::infinity();
  for (int k = -1; k < 8; ++k) {
    Eigen::Vector3d local = Eigen::Vector3d::Zero();
    if (k >= 0) {
      const double a = k * 0.78539816339744831;  // pi / 4
      local = arm.face_radius * Eigen::Vector3d(std::cos(a), std::sin(a), 0.0);
    }
    const Eigen::Vector3d p = imager * local;
    clearance = std::min(clearance, p.z() - terrain->Height(p.x(), p.y()));
  }
  return clearance;
}

void RoverSimulation::Impl::AdvanceTo(double t_end) {
  constexpr double kTimeEps = 1e-9;
  for (;;) {
    const double t = integ->getTime();
    if (t >= t_end - kTimeEps) break;
    const double t_tick = static_cast<double>(tick) * period;
    if (t >= t_tick - kTimeEps) {
      ControlTick();
      ++tick;
      continue;
    }
    const double t_next = std::min(t_tick, t_end);
    while (integ->getTime() < t_next - kTimeEps) integ->stepTo(t_next);
  }
}

// ------------------------------------------------------------------------------------------
RoverSimulation::RoverSimulation(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
RoverSimulation::~RoverSimulation() = default;

Result<std::unique_ptr<RoverSimulation>> RoverSimulation::Create(
    const RoverModelParams& params, std::shared_ptr<const HeightField> terrain,
    const StartPose& start) {
  ROVER_RETURN_IF_ERROR(params.Validate());
  if (terrain == nullptr || terrain->nx() < 2 || terrain->ny() < 2) {
    return InvalidArgument("terrain is empty (needs at least 2 x 2 samples)");
  }
  auto impl = std::make_unique<Impl>(params, std::move(terrain));
  try {
    impl->Build();
  } catch (const std::exception& e) {
    return Internal(std::string("building the Simbody model failed: ") + e.what());
  }
  std::unique_ptr<RoverSimulation> sim(new RoverSimulation(std::move(impl)));
  ROVER_RETURN_IF_ERROR(sim->Reset(start));
  return sim;
}

Status RoverSimulation::Reset(const StartPose& start) {
  try {
    return impl_->Place(start);
  } catch (const std::exception& e) {
    impl_->broken = true;
    return Internal(std::string("placing the rover failed: ") + e.what());
  }
}

Status RoverSimulation::SetMotorGoal(int motor, MotorMode mode, double position_counts,
                                     double velocity_counts_per_s, double current_limit_a) {
  if (motor < 0 || motor >= kNumMotors) {
    return OutOfRange("motor index " + std::to_string(motor) + " is outside [0, " +
                       std::to_string(kNumMotors - 1) + "]");
  }
  const Status st =
      impl_->motors[motor].SetGoal(mode, position_counts, velocity_counts_per_s, current_limit_a);
  if (!st.ok()) return st.WithPrefix(std::string("motor ") + hw::MotorName(motor));
  return st;
}

Status RoverSimulation::ClearMotorFaults(int motor) {
  if (motor < 0 || motor >= kNumMotors) {
    return OutOfRange("motor index " + std::to_string(motor) + " is outside [0, " +
                       std::to_string(kNumMotors - 1) + "]");
  }
  impl_->motors[motor].ClearFaults();
  return Status::Ok();
}

Status RoverSimulation::SetAmbientTemperature(double celsius) {
  if (!std::isfinite(celsius) || celsius < -200.0 || celsius > 200.0) {
    return InvalidArgument("ambient temperature " + FormatNumber(celsius) +
                           " C is outside [-200, 200]");
  }
  for (MotorController& m : impl_->motors) m.set_ambient_c(celsius);
  return Status::Ok();
}

Status RoverSimulation::Advance(double dt) {
  if (impl_->broken) {
    return FailedPrecondition("the simulation failed earlier; call Reset()");
  }
  if (!std::isfinite(dt) || dt <= 0.0 || dt > impl_->params.integrator.max_advance) {
    return InvalidArgument("Advance dt = " + FormatNumber(dt) + " s is outside (0, " +
                           FormatNumber(impl_->params.integrator.max_advance) + "]");
  }
  try {
    impl_->AdvanceTo(impl_->integ->getTime() + dt);
  } catch (const std::exception& e) {
    impl_->broken = true;
    return Internal(std::string("Simbody integration failed: ") + e.what());
  }
  const SimTK::Vector& y = impl_->integ->getState().getY();
  for (int i = 0; i < y.size(); ++i) {
    if (!std::isfinite(y[i])) {
      impl_->broken = true;
      return Internal("the simulation state became non-finite at t = " + FormatNumber(time()) +
                      " s");
    }
  }
  return Status::Ok();
}

double RoverSimulation::time() const { return impl_->integ->getTime(); }

const RoverModelParams& RoverSimulation::params() const { return impl_->params; }
const HeightField& RoverSimulation::terrain() const { return *impl_->terrain; }

SimulationStats RoverSimulation::stats() const {
  SimulationStats s = impl_->stats;
  s.integrator_steps = impl_->steps_before_init + impl_->integ->getNumStepsTaken();
  return s;
}

MotorReading RoverSimulation::Motor(int motor) const {
  ROVER_DEMAND(motor >= 0 && motor < kNumMotors);
  const SimTK::State& s = impl_->integ->getState();
  MotorReading r = impl_->motors[motor].Reading();
  r.position_counts = impl_->JointQ(s, motor) * impl_->counts_per_rad[motor];
  r.velocity_counts_per_s = impl_->JointU(s, motor) * impl_->counts_per_rad[motor];
  return r;
}

RoverReadings RoverSimulation::Readings() const {
  const Impl& im = *impl_;
  const SimTK::State& s = im.integ->getState();
  RoverReadings out;
  out.time_s = s.getTime();
  for (int i = 0; i < kNumMotors; ++i) {
    out.motors[i] = Motor(i);
    out.joint_angle_rad[i] = im.JointQ(s, i);
  }
  out.tool_contact = im.arm_contact;
  if (im.broken) return out;  // the state is not trustworthy; Advance() reported why
  try {
    im.system.realize(s, SimTK::Stage::Acceleration);
  } catch (const std::exception&) {
    return out;  // cannot happen for a state Advance() accepted; keep the motor readings
  }
  for (int w = 0; w < kNumWheels; ++w) {
    const WheelContact c = im.terrain_force->Evaluate(s, w);
    WheelReading& wr = out.wheels[w];
    wr.in_contact = c.in_contact;
    wr.soil = c.soil;
    wr.normal_force_n = c.normal_force;
    wr.slip_ratio = c.slip_ratio;
    wr.sinkage_m = c.sinkage;
    wr.longitudinal_force_n = c.longitudinal_force;
    wr.lateral_force_n = c.lateral_force;
    wr.contact_point_site = c.point;
    wr.center_site = ToEigen(im.Body(im.wheel_ix[w]).getBodyTransform(s).p());
  }
  out.rocker_left_rad = kSuspensionSign * im.Body(im.rocker_ix[0]).getOneQ(s, 0);
  out.rocker_right_rad = kSuspensionSign * im.Body(im.rocker_ix[1]).getOneQ(s, 0);
  out.bogie_left_rad = kSuspensionSign * im.Body(im.bogie_ix[0]).getOneQ(s, 0);
  out.bogie_right_rad = kSuspensionSign * im.Body(im.bogie_ix[1]).getOneQ(s, 0);

  const MobilizedBody& chassis = im.Body(im.chassis_ix);
  const Transform& x_gc = chassis.getBodyTransform(s);
  ChassisReading& c = out.chassis;
  c.pose_site = ToIsometry(x_gc);
  const Eigen::Matrix3d r_gc = c.pose_site.linear();
  c.linear_velocity_site = ToEigen(chassis.getBodyOriginVelocity(s));
  c.linear_velocity_body = r_gc.transpose() * c.linear_velocity_site;
  c.angular_velocity_body = r_gc.transpose() * ToEigen(chassis.getBodyAngularVelocity(s));
  const Eigen::Vector3d a =
      ToEigen(chassis.findStationAccelerationInGround(s, ToVec3(im.params.geometry.imu_position)));
  c.specific_force_body = r_gc.transpose() * (a + Eigen::Vector3d(0, 0, im.params.gravity));
  out.tool_point = c.pose_site * im.params.geometry.arm.Forward(im.arm_q).face;

  out.bodies = im.Poses(s);

  CameraFrames& cam = out.cameras;
  cam.mast_head_site = ToIsometry(im.Body(im.tilt_ix).getBodyTransform(s));
  cam.mast_head_chassis = c.pose_site.inverse() * cam.mast_head_site;
  cam.hazcam_front_chassis = im.hazcam_front_c;
  cam.hazcam_rear_chassis = im.hazcam_rear_c;
  cam.hazcam_front_site = c.pose_site * im.hazcam_front_c;
  cam.hazcam_rear_site = c.pose_site * im.hazcam_rear_c;
  return out;
}

BodyPoses RoverSimulation::Impl::Poses(const SimTK::State& s) const {
  BodyPoses bodies;
  for (int side = 0; side < 2; ++side) {
    bodies.rockers[side] = ToIsometry(Body(rocker_ix[side]).getBodyTransform(s));
    bodies.bogies[side] = ToIsometry(Body(bogie_ix[side]).getBodyTransform(s));
  }
  for (int w = 0; w < kNumWheels; ++w) {
    bodies.wheels[w] = ToIsometry(Body(wheel_ix[w]).getBodyTransform(s));
  }
  bodies.mast_pan = ToIsometry(Joint(hw::kMastPan).getBodyTransform(s));
  return bodies;
}

ModelGeometry RoverSimulation::PoseModel(const ModelJointAngles& q) const {
  const Impl& im = *impl_;
  // The default state has the chassis at the site origin with the site's axes and every other
  // joint at zero.
  SimTK::State s = im.system.getDefaultState();
  for (int side = 0; side < 2; ++side) {
    im.Body(im.rocker_ix[side]).setOneQ(s, 0, kSuspensionSign * q.rocker[side]);
    im.Body(im.bogie_ix[side]).setOneQ(s, 0, kSuspensionSign * q.bogie[side]);
  }
  for (int j = 0; j < hwconfig::kNumSteered; ++j) {
    im.Joint(hwconfig::SteerMotor(j)).setOneQ(s, 0, q.steer[j]);
  }
  im.Joint(hw::kMastPan).setOneQ(s, 0, q.pan);
  im.Joint(hw::kMastTilt).setOneQ(s, 0, q.tilt);
  im.system.realize(s, SimTK::Stage::Position);
  ModelGeometry m;
  m.bodies = im.Poses(s);
  for (int j = 0; j < hwconfig::kNumSteered; ++j) {
    m.steer_brackets[j] = ToIsometry(im.Body(im.steer_ix[j]).getBodyTransform(s));
  }
  m.cameras.mast_head_site = ToIsometry(im.Body(im.tilt_ix).getBodyTransform(s));
  m.cameras.mast_head_chassis = m.cameras.mast_head_site;
  m.cameras.hazcam_front_site = m.cameras.hazcam_front_chassis = im.hazcam_front_c;
  m.cameras.hazcam_rear_site = m.cameras.hazcam_rear_chassis = im.hazcam_rear_c;
  m.belly_points = im.belly_points;
  m.imu_station = im.params.geometry.imu_position;
  return m;
}

}  // namespace rover::sim::physics
