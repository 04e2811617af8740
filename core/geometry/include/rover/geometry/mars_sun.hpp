#pragma once
/// @file
/// A simple Mars solar ephemeris: where the sun is in the site frame (x north, y west, z up).
/// Shared by the simulator's sun sensor (sim/sensors) and the pose estimator (dl-pose), which
/// must agree on the sun's direction; like the camera models it is a model, not an algorithm of
/// one layer, so it lives in core/geometry.
///
/// Season and time of day (Allison & McEwen 2000, "A post-Pathfinder evaluation of areocentric
/// solar coordinates", PSS 48; the Mars24 algorithm page of NASA GISS), from the days since
/// J2000 in TT, dt:
///   M      = 19.3871 + 0.52402073 dt                    (mean anomaly, deg)
///   a_FMS  = 270.3871 + 0.524038496 dt                  (fictitious mean sun, deg)
///   PBS    = sum_i A_i cos(0.985626 dt / tau_i + phi_i)  (7 planetary perturbation terms)
///   v - M  = (10.691 + 3e-7 dt) sin M + 0.623 sin 2M + 0.050 sin 3M + 0.005 sin 4M
///            + 0.0005 sin 5M + PBS                       (equation of centre)
///   Ls     = a_FMS + (v - M)                            (areocentric solar longitude)
///   EOT    = 2.861 sin 2Ls - 0.071 sin 4Ls + 0.002 sin 6Ls - (v - M)   (deg)
///   MTC    = 24 h frac((dt - 4.5) / 1.0274912517 + 44796.0 - 0.0009626)  (Mars coordinated time)
///   LTST   = MTC + (east longitude + EOT) / 15 deg/h     (local true solar time, mod 24 h)
///   delta  = asin(0.42565 sin Ls) + 0.25 deg sin Ls      (solar declination)
/// Direction (hour angle H = (LTST - 12 h) 15 deg/h, latitude phi):
///   north = cos phi sin delta - sin phi cos delta cos H
///   west  = cos delta sin H
///   up    = sin phi sin delta + cos phi cos delta cos H   (= sin elevation)
/// Ignored: refraction (negligible in Mars' thin air), the sun's angular radius (0.18 deg),
/// parallax, terrain horizon; the site frame's "north" is assumed to be true (areographic)
/// north. Accuracy of Ls ~0.01 deg, of the direction a few 0.01 deg over decades.
///
/// SunEphemeris turns run-clock time into a sun direction in one of two modes:
///  * kSeason: Ls and LTST given at run time 0; LTST advances 24 h per sol (88775.244 s) and Ls
///    at the mean rate 360 deg / 668.6 sols (the EOT drift over a run is ignored).
///  * kDate: the J2000 TT day at run time 0 and the site's east longitude; everything follows
///    from the algorithm above.

#include <Eigen/Core>

#include "rover/base/param_binder.hpp"
#include "rover/base/status.hpp"

namespace rover::geometry {

inline constexpr double kMarsSolSeconds = 88775.244147;  ///< mean solar day [s]
inline constexpr double kMarsYearSols = 668.5991;        ///< tropical year [sols]

/// Mars solar time quantities at one instant (angles in degrees).
struct MarsSolarState {
  double j2000_tt_days = 0.0;  ///< days since J2000 (TT)
  double mars_sol_date = 0.0;  ///< MSD
  double mtc_hours = 0.0;      ///< Mars coordinated time (mean solar time at 0 deg) [0, 24)
  double ls_deg = 0.0;         ///< areocentric solar longitude [0, 360)
  double eot_deg = 0.0;        ///< equation of time (true - mean solar time) [deg]
  double declination_rad = 0.0;
};

/// The Allison & McEwen / Mars24 quantities at `j2000_tt_days`.
MarsSolarState ComputeMarsSolarState(double j2000_tt_days);

/// Local true solar time [h, 0..24) at `east_longitude_deg`.
double LocalTrueSolarTimeHours(const MarsSolarState& state, double east_longitude_deg);

/// Solar declination [rad] at areocentric solar longitude `ls_deg`.
double SolarDeclination(double ls_deg);

/// Unit sun direction in the site frame (x north, y west, z up).
Eigen::Vector3d SunDirectionSite(double latitude_rad, double declination_rad, double ltst_hours);

/// Elevation above the horizon [rad] of a site-frame direction.
double SunElevation(const Eigen::Vector3d& direction_site);
/// Azimuth [rad] of a site-frame direction, from north towards east, in [0, 2 pi).
double SunAzimuth(const Eigen::Vector3d& direction_site);

struct SunEphemerisOptions {
  enum class Mode { kSeason, kDate };
  Mode mode = Mode::kSeason;
  double latitude_deg = -14.57;  ///< Gusev crater (Spirit)
  double east_longitude_deg = 175.47;
  double ls_deg = 330.0;           ///< kSeason: Ls at run time 0
  double ltst_hours = 11.0;        ///< kSeason: local true solar time at run time 0
  double j2000_tt_days = 1463.69;  ///< kDate: TT days since J2000 at run time 0 (Spirit landing)
  /// Latitude in [-90, 90], longitude in [-360, 360], ls in [0, 360), ltst in [0, 24), finite.
  Status Validate() const;
  /// Keys mode ('season' or 'date'), latitude_deg, east_longitude_deg, ls_deg, ltst_hours,
  /// j2000_tt_days ("at run start" = at run-clock time 0 of the ephemeris).
  static void BindParams(ParamBinder<SunEphemerisOptions>& b);
};

/// The sun at one instant.
struct SunState {
  double ls_deg = 0.0;
  double ltst_hours = 0.0;
  double declination_rad = 0.0;
  double hour_angle_rad = 0.0;  ///< 0 at local noon, + in the afternoon
  Eigen::Vector3d direction_site = Eigen::Vector3d::UnitZ();
  double elevation_rad = 0.0;
  double azimuth_rad = 0.0;  ///< from north towards east
};

class SunEphemeris {
 public:
  /// Precondition: options.Validate() ok.
  explicit SunEphemeris(const SunEphemerisOptions& options);
  /// The sun at run time `run_time_s` [s] since the run started.
  SunState At(double run_time_s) const;
  const SunEphemerisOptions& options() const { return options_; }

 private:
  SunEphemerisOptions options_;
};

}  // namespace rover::geometry
