#include "rover/geometry/mars_sun.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "rover/base/check.hpp"
#include "rover/base/units.hpp"

namespace rover::geometry {
namespace {

double Wrap(double x, double period) {
  double r = std::fmod(x, period);
  if (r < 0.0) r += period;
  return r;
}

// Planetary perturbations of Mars' heliocentric longitude: amplitude [deg], period [Julian
// years], phase [deg] (Allison & McEwen 2000, table 5).
struct Perturbation {
  double amplitude, period, phase;
};
constexpr Perturbation kPerturbations[] = {{0.0071, 2.2353, 49.409},  {0.0057, 2.7543, 168.173},
                                           {0.0039, 1.1177, 191.837}, {0.0037, 15.7866, 21.736},
                                           {0.0021, 2.1354, 15.704},  {0.0020, 2.4694, 95.528},
                                           {0.0018, 32.8493, 49.095}};

}  // namespace

double SolarDeclination(double ls_deg) {
  const double s = std::sin(ls_deg * kDegree);
  return std::asin(0.42565 * s) + 0.25 * kDegree * s;
}

MarsSolarState ComputeMarsSolarState(double dt) {
  MarsSolarState st;
  st.j2000_tt_days = dt;
  const double m = (19.3871 + 0.52402073 * dt) * kDegree;
  const double alpha_fms = 270.3871 + 0.524038496 * dt;
  double pbs = 0.0;
  for (const Perturbation& p : kPerturbations) {
    pbs += p.amplitude * std::cos((0.985626 * dt / p.period + p.phase) * kDegree);
  }
  const double v_minus_m = (10.691 + 3.0e-7 * dt) * std::sin(m) + 0.623 * std::sin(2.0 * m) +
                           0.050 * std::sin(3.0 * m) + 0.005 * std::sin(4.0 * m) +
                           0.0005 * std::sin(5.0 * m) + pbs;
  st.ls_deg = Wrap(alpha_fms + v_minus_m, 360.0);
  const double ls = st.ls_deg * kDegree;
  st.eot_deg = 2.861 * std::sin(2.0 * ls) - 0.071 * std::sin(4.0 * ls) +
               0.002 * std::sin(6.0 * ls) - v_minus_m;
  st.mars_sol_date = (dt - 4.5) / 1.0274912517 + 44796.0 - 0.0009626;
  st.mtc_hours = Wrap(24.0 * st.mars_sol_date, 24.0);
  st.declination_rad = SolarDeclination(st.ls_deg);
  return st;
}

double LocalTrueSolarTimeHours(const MarsSolarState& state, double east_longitude_deg) {
  return Wrap(state.mtc_hours + (east_longitude_deg + state.eot_deg) / 15.0, 24.0);
}

Eigen::Vector3d SunDirectionSite(double latitude_rad, double declination_rad, double ltst_hours) {
  const double h = (ltst_hours - 12.0) * 15.0 * kDegree;
  const double sp = std::sin(latitude_rad), cp = std::cos(latitude_rad);
  const double sd = std::sin(declination_rad), cd = std::cos(declination_rad);
  const Eigen::Vector3d d(cp * sd - sp * cd * std::cos(h), cd * std::sin(h),
                          sp * sd + cp * cd * std::cos(h));
  return d.normalized();
}

double SunElevation(const Eigen::Vector3d& d) {
  return std::asin(std::clamp(d.z() / d.norm(), -1.0, 1.0));
}

double SunAzimuth(const Eigen::Vector3d& d) {
  return Wrap(std::atan2(-d.y(), d.x()), 2.0 * kPi);  // east = -west
}

void SunEphemerisOptions::BindParams(ParamBinder<SunEphemerisOptions>& b) {
  b.BindEnum("mode", &SunEphemerisOptions::mode, {{"season", Mode::kSeason}, {"date", Mode::kDate}},
             "'season': Ls and local true solar time at run start; 'date': J2000 TT days");
  b.Bind("latitude_deg", &SunEphemerisOptions::latitude_deg, "deg",
         "landing-site latitude (+ north)")
      .Range(-90.0, 90.0);
  b.Bind("east_longitude_deg", &SunEphemerisOptions::east_longitude_deg, "deg",
         "landing-site east longitude (mode 'date')")
      .Range(-360.0, 360.0);
  b.Bind("ls_deg", &SunEphemerisOptions::ls_deg, "deg", "areocentric solar longitude at run start")
      .Range(0.0, 359.999999);
  b.Bind("ltst_hours", &SunEphemerisOptions::ltst_hours, "h", "local true solar time at run start")
      .Range(0.0, 23.999999);
  b.Bind("j2000_tt_days", &SunEphemerisOptions::j2000_tt_days, "days",
         "TT days since J2000 at run start (mode 'date')")
      .Range(-1.0e6, 1.0e6);
}

Status SunEphemerisOptions::Validate() const {
  auto check = [](const char* key, double v, double lo, double hi, bool hi_open) -> Status {
    if (!std::isfinite(v) || v < lo || (hi_open ? v >= hi : v > hi)) {
      return InvalidArgument(std::string("ephemeris.") + key + ": " + std::to_string(v) +
                             " is out of range [" + std::to_string(lo) + ", " + std::to_string(hi) +
                             (hi_open ? ")" : "]"));
    }
    return Status::Ok();
  };
  ROVER_RETURN_IF_ERROR(check("latitude_deg", latitude_deg, -90.0, 90.0, false));
  ROVER_RETURN_IF_ERROR(check("east_longitude_deg", east_longitude_deg, -360.0, 360.0, false));
  ROVER_RETURN_IF_ERROR(check("ls_deg", ls_deg, 0.0, 360.0, true));
  ROVER_RETURN_IF_ERROR(check("ltst_hours", ltst_hours, 0.0, 24.0, true));
  ROVER_RETURN_IF_ERROR(check("j2000_tt_days", j2000_tt_days, -1.0e6, 1.0e6, false));
  return Status::Ok();
}

SunEphemeris::SunEphemeris(const SunEphemerisOptions& options) : options_(options) {
  ROVER_DEMAND(options.Validate().ok());
}

SunState SunEphemeris::At(double t) const {
  SunState s;
  if (options_.mode == SunEphemerisOptions::Mode::kSeason) {
    const double sols = t / kMarsSolSeconds;
    s.ls_deg = Wrap(options_.ls_deg + 360.0 * sols / kMarsYearSols, 360.0);
    s.ltst_hours = Wrap(options_.ltst_hours + 24.0 * sols, 24.0);
    s.declination_rad = SolarDeclination(s.ls_deg);
  } else {
    const MarsSolarState st = ComputeMarsSolarState(options_.j2000_tt_days + t / 86400.0);
    s.ls_deg = st.ls_deg;
    s.ltst_hours = LocalTrueSolarTimeHours(st, options_.east_longitude_deg);
    s.declination_rad = st.declination_rad;
  }
  s.hour_angle_rad = (s.ltst_hours - 12.0) * 15.0 * kDegree;
  s.direction_site =
      SunDirectionSite(options_.latitude_deg * kDegree, s.declination_rad, s.ltst_hours);
  s.elevation_rad = SunElevation(s.direction_site);
  s.azimuth_rad = SunAzimuth(s.direction_site);
  return s;
}

}  // namespace rover::geometry
