#pragma once
/// @file
/// Wheel-terrain contact against a HeightField: geometry, normal force, and a
/// terramechanics-inspired slip-traction model with a per-wheel shear-deformation state.
/// Pure C++ on Eigen (no Simbody); RoverSimulation calls it from a Simbody force element.
/// Frames: everything in the site frame (x north, y west, z up), SI units.
///
/// Geometry. A wheel is a cylinder (radius R, width b, unit axle a, centre c) cut into S slices
/// across its width (slice centres c_s = c + a b ((s + 1/2)/S - 1/2)). The deepest rim direction
/// against the local tangent plane comes from two fixed-point iterations of
/// d = normalize(n - (n.a) a), p = c - R d, n = terrain normal at p (shared by all slices); a fan
/// of rim points p_k = c_s - R (cos t_k d + sin t_k (a x d)) at t_k = 0, +-fan angles per slice
/// catches steps and rocks ahead of and behind the wheel. A sample penetrates when h(p_k) > p_k.z;
/// its depth along the local normal n_k is  delta_k = (h(p_k) - p_k.z) n_k.z.
///
/// Normal force (Hunt-Crossley, per sample, stiffness of the soil under the sample):
///   f_k = max(0, (k_soil / S) delta_k (1 + alpha ddelta_k)),  ddelta_k = -v_c . n_k
///   N = sum f_k,  contact point p = sum f_k p_k / N,  normal n = normalize(sum f_k n_k).
///
/// Tangential force. Contact basis f = normalize(a x n) (rolling direction), l = n x f. Rim speed
/// V_w = (w . a) R, hub velocity components v_x = v_c . f, v_y = v_c . l, slip velocity
/// v_s = (V_w - v_x, -v_y). Shear state z (2-vector in (f, l), dimensionless, in units of the
/// shear deformation modulus K_j = K L) follows the soil deformation under the patch:
///   dz/dt = v_s / K_j - (V_roll / L) z,    V_roll = max(|V_w|, |v_x|)
/// (fresh soil enters the patch of length L at V_roll), with |z| capped at shear_cap (the
/// outward part of dz/dt is removed there: plastic flow). Traction:
///   F_t = N [ mu_max (1 - exp(-|z|)) z/|z| + mu_max beta dz/dt ],   |F_t| <= mu_max N
/// In steady rolling with slip ratio s = (V_w - v_x)/V_w this gives z = s/K and the
/// Janosi-Hanamoto-like slip-traction curve  mu(s) = mu_max (1 - exp(-s/K)). At rest (v_s = 0,
/// V_roll = 0) z stays put, so a parked rover on a slope does not creep.
/// Motion (compaction) resistance along f, through the hub (radial stresses make no moment
/// about the axle): F_rr = -c_rr N tanh(v_x / v_rr); the drive must supply c_rr N R of torque
/// by gross traction, i.e. by slip, even on flat ground.
/// Normal forces press on a rigid rim and pass through the axle: the axle component of their
/// moment about the hub, a . ((p - c) x sum f_k n_k), is cancelled by a pure torque (the terrain
/// normal at a rim sample is not radial where the surface bends under the wheel, and would
/// otherwise spin it), so only traction turns a wheel about its axle.
/// Spin (scrub) resistance about n: T = -mu_max N r_spin tanh((w . n) / w_spin).
/// On a uniform slope theta with all wheels at the same slip, sum mu(s) N_i = W (sin + c_rr cos),
/// so mu(s) = tan theta + c_rr and s = -K ln(1 - (tan theta + c_rr)/mu_max): slip grows with slope
/// and diverges as the required coefficient approaches mu_max (loose sand near 20 deg).

#include <Eigen/Core>
#include <array>
#include <string>

#include "rover/base/status.hpp"
#include "rover/sim/heightfield.hpp"

namespace rover::sim::physics {

inline constexpr int kNumSoils = 3;

/// Per-soil contact and traction parameters.
struct SoilParams {
  double stiffness = 30e3;           ///< [N/m] normal stiffness of one whole wheel
  double damping = 10.0;             ///< [s/m] Hunt-Crossley alpha
  double mu_max = 0.65;              ///< maximum gross traction / normal load
  double shear_k = 0.12;             ///< K: slip at which mu reaches 63% of mu_max
  double patch_length = 0.08;        ///< [m] L: contact patch length
  double rolling_resistance = 0.02;  ///< c_rr: motion resistance / normal load

  Status Validate(const std::string& name) const;
};

/// MER-like defaults for bedrock, firm soil (packed soil, duricrust) and loose (drift) sand.
SoilParams DefaultSoilParams(terrain::Soil soil);

struct ContactParams {
  std::array<SoilParams, kNumSoils> soils = {DefaultSoilParams(terrain::Soil::kBedrock),
                                             DefaultSoilParams(terrain::Soil::kFirmSoil),
                                             DefaultSoilParams(terrain::Soil::kLooseSand)};
  int slices = 3;  ///< S, slices across the wheel width (1..5)
  std::array<double, 3> fan_angles_deg = {25.0, 50.0, 75.0};  ///< +- fan; 0 disables an entry
  double shear_cap = 5.0;                                     ///< cap of |z| (mu = 99.3% of mu_max)
  double shear_damping_time = 0.1;                            ///< [s] beta
  double shear_free_relax_time = 0.05;  ///< [s] z decays with this time constant out of contact
  double rolling_speed_eps = 0.01;      ///< [m/s] v_rr
  double spin_radius = 0.03;            ///< [m] r_spin
  double spin_rate_eps = 0.05;          ///< [rad/s] w_spin

  const SoilParams& soil(terrain::Soil s) const { return soils[static_cast<int>(s)]; }
  Status Validate() const;
};

/// mu(s) = mu_max (1 - exp(-|s|/K)) sign(s): the steady slip-traction curve.
double TractionCoefficient(const SoilParams& soil, double slip);
/// Steady uphill slip on a uniform slope [rad] when every wheel carries the same slip;
/// returns +infinity when the soil cannot hold the rover (tan + c_rr >= mu_max).
double SteadyStateSlip(const SoilParams& soil, double slope_rad);

/// One penetrating rim sample.
struct ContactSample {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  double depth = 0.0;  ///< [m] along normal
  terrain::Soil soil = terrain::Soil::kFirmSoil;
};

inline constexpr int kMaxContactSamples = 5 * 7;

/// Penetrating rim samples of a wheel (see the file comment). Returns their number (<= capacity
/// kMaxContactSamples); 0 for non-finite input. `axis` must be a unit vector.
int FindWheelSamples(const terrain::HeightField& terrain, const ContactParams& params,
                     double radius, double width, const Eigen::Vector3d& center,
                     const Eigen::Vector3d& axis,
                     std::array<ContactSample, kMaxContactSamples>* samples);

/// Vertical gap between the lowest point of the middle slice and the terrain (positive when
/// clear, negative when penetrating); used to place the rover on the terrain.
double WheelGap(const terrain::HeightField& terrain, double radius, const Eigen::Vector3d& center,
                const Eigen::Vector3d& axis);

/// Kinematics of one wheel body (site frame).
struct WheelKinematics {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  Eigen::Vector3d axis = Eigen::Vector3d::UnitY();     ///< unit axle; +spin rolls along axis x n
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();  ///< of the centre
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();  ///< of the wheel body
};

/// Result of the contact model for one wheel.
struct WheelContact {
  bool in_contact = false;
  int num_samples = 0;
  terrain::Soil soil = terrain::Soil::kFirmSoil;
  double normal_force = 0.0;        ///< N [N]
  double sinkage = 0.0;             ///< deepest sample depth [m]
  double slip_ratio = 0.0;          ///< (V_w - v_x) / max(|V_w|, |v_x|); 0 when both ~0
  double longitudinal_force = 0.0;  ///< traction along f incl. motion resistance [N]
  double lateral_force = 0.0;       ///< along l [N]
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  ///< where `force` acts
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d forward = Eigen::Vector3d::UnitX();
  Eigen::Vector3d force = Eigen::Vector3d::Zero();       ///< total force on the wheel [N]
  Eigen::Vector3d torque = Eigen::Vector3d::Zero();      ///< additional pure torque [N m] (spin
                                                         ///< resistance, resistance moment shift)
  Eigen::Vector2d shear_rate = Eigen::Vector2d::Zero();  ///< dz/dt of the shear state
};

/// Evaluates the contact model. `shear` is the wheel's shear state z.
WheelContact EvaluateWheelContact(const terrain::HeightField& terrain, const ContactParams& params,
                                  double radius, double width, const WheelKinematics& wheel,
                                  const Eigen::Vector2d& shear);

/// Penalty contact of a point on the chassis belly (high-centring on rocks): Hunt-Crossley
/// normal force and regularised Coulomb friction. Returns the force on the body [N].
struct PointContactParams {
  double stiffness = 50e3;  ///< [N/m]
  double damping = 5.0;     ///< [s/m]
  double friction = 0.5;
  double slip_speed_eps = 0.01;  ///< [m/s]
  Status Validate() const;
};
Eigen::Vector3d EvaluatePointContact(const terrain::HeightField& terrain,
                                     const PointContactParams& params, const Eigen::Vector3d& point,
                                     const Eigen::Vector3d& velocity);

}  // namespace rover::sim::physics
