#include "rover/sim/physics/terrain_contact.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "rover/base/format.hpp"
#include "rover/base/range_check.hpp"

namespace rover::sim::physics {

using terrain::HeightField;
using terrain::Soil;
using terrain::SoilName;

namespace {

// Unit direction in the wheel plane (perpendicular to `axis`) closest to `n`; false when `n`
// is (nearly) parallel to the axle, i.e. the wheel lies on its side.
bool InPlaneDirection(const Eigen::Vector3d& n, const Eigen::Vector3d& axis, Eigen::Vector3d* d) {
  Eigen::Vector3d v = n - n.dot(axis) * axis;
  const double len = v.norm();
  if (len < 1e-6) return false;
  *d = v / len;
  return true;
}

Eigen::Vector3d NormalFromGradient(const Eigen::Vector2d& g) {
  return Eigen::Vector3d(-g.x(), -g.y(), 1.0).normalized();
}

// Deepest rim direction d (pointing from the rim point to the centre, i.e. "up" in the wheel
// plane) for a slice centred at c.
bool DeepestDirection(const HeightField& terrain, double radius, const Eigen::Vector3d& c,
                      const Eigen::Vector3d& axis, Eigen::Vector3d* d) {
  Eigen::Vector2d g;
  terrain.HeightAndGradient(c.x(), c.y(), &g);
  if (!InPlaneDirection(NormalFromGradient(g), axis, d)) return false;
  for (int it = 0; it < 2; ++it) {
    const Eigen::Vector3d p = c - radius * *d;
    terrain.HeightAndGradient(p.x(), p.y(), &g);
    Eigen::Vector3d d_new;
    if (!InPlaneDirection(NormalFromGradient(g), axis, &d_new)) return false;
    *d = d_new;
  }
  return true;
}

}  // namespace

Status SoilParams::Validate(const std::string& name) const {
  ROVER_RETURN_IF_ERROR(CheckRange(name + ".stiffness", stiffness, 1.0, 1e9));
  ROVER_RETURN_IF_ERROR(CheckRange(name + ".damping", damping, 0.0, 1e4));
  ROVER_RETURN_IF_ERROR(CheckRange(name + ".mu_max", mu_max, 1e-3, 5.0));
  ROVER_RETURN_IF_ERROR(CheckRange(name + ".shear_k", shear_k, 1e-4, 10.0));
  ROVER_RETURN_IF_ERROR(CheckRange(name + ".patch_length", patch_length, 1e-4, 10.0));
  ROVER_RETURN_IF_ERROR(CheckRange(name + ".rolling_resistance", rolling_resistance, 0.0, 2.0));
  return Status::Ok();
}

SoilParams DefaultSoilParams(Soil soil) {
  SoilParams p;
  switch (soil) {
    case Soil::kBedrock:
      p.stiffness = 80e3;
      p.damping = 8.0;
      p.mu_max = 0.8;
      p.shear_k = 0.05;
      p.patch_length = 0.05;
      p.rolling_resistance = 0.015;
      break;
    case Soil::kFirmSoil:
      p.stiffness = 30e3;
      p.damping = 10.0;
      p.mu_max = 0.65;
      p.shear_k = 0.12;
      p.patch_length = 0.08;
      p.rolling_resistance = 0.02;
      break;
    case Soil::kLooseSand:
      p.stiffness = 12e3;
      p.damping = 15.0;
      p.mu_max = 0.45;
      p.shear_k = 0.2;
      p.patch_length = 0.12;
      p.rolling_resistance = 0.08;
      break;
  }
  return p;
}

Status ContactParams::Validate() const {
  for (int s = 0; s < kNumSoils; ++s) {
    ROVER_RETURN_IF_ERROR(
        soils[s].Validate(std::string("contact.soils.") + SoilName(static_cast<Soil>(s))));
  }
  if (slices < 1 || slices > 5) {
    return InvalidArgument("contact.slices = " + FormatNumber(slices) + " is outside [1, 5]");
  }
  for (double a : fan_angles_deg) {
    ROVER_RETURN_IF_ERROR(CheckRange("contact.fan_angles_deg[]", a, 0.0, 89.0));
  }
  ROVER_RETURN_IF_ERROR(CheckRange("contact.shear_cap", shear_cap, 0.1, 50.0));
  ROVER_RETURN_IF_ERROR(CheckRange("contact.shear_damping_time", shear_damping_time, 0, 10));
  ROVER_RETURN_IF_ERROR(
      CheckRange("contact.shear_free_relax_time", shear_free_relax_time, 1e-4, 100.0));
  ROVER_RETURN_IF_ERROR(CheckRange("contact.rolling_speed_eps", rolling_speed_eps, 1e-6, 1));
  ROVER_RETURN_IF_ERROR(CheckRange("contact.spin_radius", spin_radius, 0.0, 1.0));
  ROVER_RETURN_IF_ERROR(CheckRange("contact.spin_rate_eps", spin_rate_eps, 1e-6, 10.0));
  return Status::Ok();
}

Status PointContactParams::Validate() const {
  ROVER_RETURN_IF_ERROR(CheckRange("belly.stiffness", stiffness, 1.0, 1e9));
  ROVER_RETURN_IF_ERROR(CheckRange("belly.damping", damping, 0.0, 1e4));
  ROVER_RETURN_IF_ERROR(CheckRange("belly.friction", friction, 0.0, 5.0));
  ROVER_RETURN_IF_ERROR(CheckRange("belly.slip_speed_eps", slip_speed_eps, 1e-6, 10.0));
  return Status::Ok();
}

double TractionCoefficient(const SoilParams& soil, double slip) {
  const double mag = soil.mu_max * (1.0 - std::exp(-std::abs(slip) / soil.shear_k));
  return slip < 0.0 ? -mag : mag;
}

double SteadyStateSlip(const SoilParams& soil, double slope_rad) {
  const double need = std::tan(slope_rad) + soil.rolling_resistance;
  if (need >= soil.mu_max) return std::numeric_limits<double>::infinity();
  return -soil.shear_k * std::log(1.0 - need / soil.mu_max);
}

int FindWheelSamples(const HeightField& terrain, const ContactParams& params, double radius,
                     double width, const Eigen::Vector3d& center, const Eigen::Vector3d& axis,
                     std::array<ContactSample, kMaxContactSamples>* samples) {
  if (!center.allFinite() || !axis.allFinite()) return 0;  // HeightField needs finite x, y
  // The deepest direction follows the local tangent plane, which all slices share.
  Eigen::Vector3d d;
  if (!DeepestDirection(terrain, radius, center, axis, &d)) return 0;
  const Eigen::Vector3d ahead = axis.cross(d);
  std::array<Eigen::Vector3d, 7> offsets;  // rim points relative to a slice centre
  int num_offsets = 0;
  for (int k = -3; k <= 3; ++k) {
    double t = 0.0;
    if (k != 0) {
      const double deg = params.fan_angles_deg[std::abs(k) - 1];
      if (deg <= 0.0) continue;
      t = (k < 0 ? -deg : deg) * std::numbers::pi / 180.0;
    }
    offsets[num_offsets++] = -radius * (std::cos(t) * d + std::sin(t) * ahead);
  }
  int count = 0;
  const int slices = params.slices;
  for (int s = 0; s < slices; ++s) {
    const Eigen::Vector3d c = center + (width * ((s + 0.5) / slices - 0.5)) * axis;
    for (int k = 0; k < num_offsets; ++k) {
      const Eigen::Vector3d p = c + offsets[k];
      Eigen::Vector2d g;
      const double h = terrain.HeightAndGradient(p.x(), p.y(), &g);
      const double gap = h - p.z();
      if (gap <= 0.0) continue;
      ContactSample& cs = (*samples)[count++];
      cs.point = p;
      cs.normal = NormalFromGradient(g);
      cs.depth = gap * cs.normal.z();
      cs.soil = terrain.SoilAt(p.x(), p.y());
    }
  }
  return count;
}

double WheelGap(const HeightField& terrain, double radius, const Eigen::Vector3d& center,
                const Eigen::Vector3d& axis) {
  if (!center.allFinite() || !axis.allFinite()) return std::numeric_limits<double>::quiet_NaN();
  Eigen::Vector3d d;
  if (!DeepestDirection(terrain, radius, center, axis, &d)) d = Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d p = center - radius * d;
  return p.z() - terrain.Height(p.x(), p.y());
}

WheelContact EvaluateWheelContact(const HeightField& terrain, const ContactParams& params,
                                  double radius, double width, const WheelKinematics& wheel,
                                  const Eigen::Vector2d& shear) {
  WheelContact out;
  if (!wheel.center.allFinite() || !wheel.axis.allFinite() || !shear.allFinite()) return out;
  std::array<ContactSample, kMaxContactSamples> samples;
  const int n =
      FindWheelSamples(terrain, params, radius, width, wheel.center, wheel.axis, &samples);
  out.num_samples = n;
  if (n == 0) {
    out.shear_rate = -shear / params.shear_free_relax_time;
    return out;
  }
  out.in_contact = true;

  // Normal force.
  double sum_f = 0.0, sum_depth = 0.0;
  Eigen::Vector3d f_n = Eigen::Vector3d::Zero(), p_f = Eigen::Vector3d::Zero(),
                  p_d = Eigen::Vector3d::Zero(), n_d = Eigen::Vector3d::Zero();
  for (int k = 0; k < n; ++k) {
    const ContactSample& cs = samples[k];
    const SoilParams& soil = params.soil(cs.soil);
    const double rate = -wheel.velocity.dot(cs.normal);
    const double f =
        std::max(0.0, soil.stiffness / params.slices * cs.depth * (1.0 + soil.damping * rate));
    sum_f += f;
    f_n += f * cs.normal;
    p_f += f * cs.point;
    sum_depth += cs.depth;
    p_d += cs.depth * cs.point;
    n_d += cs.depth * cs.normal;
    out.sinkage = std::max(out.sinkage, cs.depth);
  }
  const double f_n_norm = f_n.norm();
  if (sum_f > 0.0 && f_n_norm > 1e-12) {
    out.point = p_f / sum_f;
    out.normal = f_n / f_n_norm;
  } else {
    out.point = p_d / sum_depth;
    out.normal = n_d.normalized();
  }
  const double N = sum_f;
  out.normal_force = N;
  out.soil = terrain.SoilAt(out.point.x(), out.point.y());
  const SoilParams& soil = params.soil(out.soil);

  // Contact basis.
  Eigen::Vector3d f = wheel.axis.cross(out.normal);
  const double f_len = f.norm();
  Eigen::Vector3d force = f_n;
  if (f_len < 0.1) {  // wheel on its side: no rolling contact model
    out.force = force;
    out.shear_rate = -shear / params.shear_free_relax_time;
    return out;
  }
  f /= f_len;
  const Eigen::Vector3d l = out.normal.cross(f);
  out.forward = f;

  const double v_w = wheel.angular_velocity.dot(wheel.axis) * radius;
  const double v_x = wheel.velocity.dot(f);
  const double v_y = wheel.velocity.dot(l);
  const Eigen::Vector2d v_s(v_w - v_x, -v_y);
  const double v_roll = std::max(std::abs(v_w), std::abs(v_x));
  const double k_j = soil.shear_k * soil.patch_length;

  Eigen::Vector2d zdot = v_s / k_j - (v_roll / soil.patch_length) * shear;
  const double z_norm = shear.norm();
  if (z_norm >= params.shear_cap) {
    const Eigen::Vector2d u = shear / z_norm;
    const double outward = zdot.dot(u);
    if (outward > 0.0) zdot -= outward * u;
  }
  out.shear_rate = zdot;

  Eigen::Vector2d traction = Eigen::Vector2d::Zero();
  if (z_norm > 1e-12) {
    // mu_max (1 - e^-|z|) z/|z|, written to stay accurate for tiny |z|.
    traction = soil.mu_max * N * (-std::expm1(-z_norm) / z_norm) * shear;
  }
  traction += soil.mu_max * N * params.shear_damping_time * zdot;
  const double t_norm = traction.norm();
  const double t_max = soil.mu_max * N;
  if (t_norm > t_max) traction *= t_max / t_norm;
  const double resistance =
      -soil.rolling_resistance * N * std::tanh(v_x / params.rolling_speed_eps);

  out.longitudinal_force = traction.x() + resistance;
  out.lateral_force = traction.y();
  force += out.longitudinal_force * f + out.lateral_force * l;
  out.force = force;

  // The motion resistance is the resultant of radial soil stresses: it acts through the hub, so
  // moving it from the hub to `point` adds the moment (c - p) x F_rr.
  const double w_n = wheel.angular_velocity.dot(out.normal);
  out.torque =
      -soil.mu_max * N * params.spin_radius * std::tanh(w_n / params.spin_rate_eps) * out.normal +
      (wheel.center - out.point).cross(resistance * f);
  // The normal forces press on a rigid rim, so they pass through the axle and cannot spin the
  // wheel. The terrain normal at a penetrating rim sample is not radial where the surface bends
  // under the rim (a dip, a rock's flank, a height-field cell edge); applied at `point` it would
  // turn the wheel about its axle. Remove that axle moment; its other components (the patch
  // off the wheel's mid-plane) stay, as on a real wheel.
  const double axle_moment = wheel.axis.dot((out.point - wheel.center).cross(f_n));
  out.torque -= axle_moment * wheel.axis;

  const double denom = std::max(std::abs(v_w), std::abs(v_x));
  out.slip_ratio = denom > 1e-4 ? (v_w - v_x) / denom : 0.0;
  return out;
}

Eigen::Vector3d EvaluatePointContact(const HeightField& terrain, const PointContactParams& params,
                                     const Eigen::Vector3d& point,
                                     const Eigen::Vector3d& velocity) {
  if (!point.allFinite() || !velocity.allFinite()) return Eigen::Vector3d::Zero();
  Eigen::Vector2d g;
  const double h = terrain.HeightAndGradient(point.x(), point.y(), &g);
  const double gap = h - point.z();
  if (gap <= 0.0) return Eigen::Vector3d::Zero();
  const Eigen::Vector3d n = NormalFromGradient(g);
  const double depth = gap * n.z();
  const double rate = -velocity.dot(n);
  const double fn = std::max(0.0, params.stiffness * depth * (1.0 + params.damping * rate));
  const Eigen::Vector3d v_t = velocity - velocity.dot(n) * n;
  const double speed = v_t.norm();
  Eigen::Vector3d ft = Eigen::Vector3d::Zero();
  if (speed > 1e-12) {
    ft = -params.friction * fn * std::tanh(speed / params.slip_speed_eps) * (v_t / speed);
  }
  return fn * n + ft;
}

}  // namespace rover::sim::physics
