#include "rover/geometry/mars_sun.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "rover/base/units.hpp"

namespace rover::geometry {
namespace {

TEST(MarsSun, Mars24WorkedExample) {
  // Mars24 / Allison & McEwen worked example: 2000-01-06 00:00:00 UTC, JD(TT) 2451549.50074:
  // Ls = 277.18758 deg, MTC = 23:59:39.057, EOT = -0.014410 sol, LTST(0 deg) = 23:38:53.998.
  const MarsSolarState s = ComputeMarsSolarState(2451549.50074 - 2451545.0);
  EXPECT_NEAR(s.ls_deg, 277.18758, 2e-4);
  EXPECT_NEAR(s.mtc_hours, 23.0 + 59.0 / 60.0 + 39.057 / 3600.0, 1e-5);
  EXPECT_NEAR(s.eot_deg, -0.014410 * 360.0, 5e-4);
  EXPECT_NEAR(LocalTrueSolarTimeHours(s, 0.0), 23.0 + 38.0 / 60.0 + 53.998 / 3600.0, 1e-5);
}

TEST(MarsSun, DeclinationFollowsTheSeasons) {
  EXPECT_NEAR(SolarDeclination(0.0), 0.0, 1e-12);
  EXPECT_NEAR(SolarDeclination(180.0), 0.0, 1e-12);
  EXPECT_NEAR(SolarDeclination(90.0) / kDegree, 25.44, 0.01);  // northern summer solstice
  EXPECT_NEAR(SolarDeclination(270.0) / kDegree, -25.44, 0.01);
  // Spirit's landing (2004-01-04) was in southern summer, Ls ~ 328.
  EXPECT_NEAR(ComputeMarsSolarState(1463.69).ls_deg, 327.7, 0.5);
}

TEST(MarsSun, NoonSunIsOnTheMeridianAtTheRightElevation) {
  for (double lat : {-14.57, 0.0, 22.5, 60.0}) {
    for (double ls : {0.0, 90.0, 200.0, 270.0}) {
      const double dec = SolarDeclination(ls);
      const Eigen::Vector3d d = SunDirectionSite(lat * kDegree, dec, 12.0);
      EXPECT_NEAR(d.norm(), 1.0, 1e-12);
      EXPECT_NEAR(d.y(), 0.0, 1e-12) << "noon sun has no east-west component";
      // Elevation at noon: 90 deg - |latitude - declination|; north of the site if dec > lat.
      EXPECT_NEAR(SunElevation(d), M_PI / 2 - std::abs(lat * kDegree - dec), 1e-9);
      if (dec > lat * kDegree + 1e-9) {
        EXPECT_GT(d.x(), 0.0);
      }
      if (dec < lat * kDegree - 1e-9) {
        EXPECT_LT(d.x(), 0.0);
      }
      // Local noon is the highest sun of the day.
      EXPECT_GT(SunElevation(d), SunElevation(SunDirectionSite(lat * kDegree, dec, 11.0)));
      EXPECT_GT(SunElevation(d), SunElevation(SunDirectionSite(lat * kDegree, dec, 13.0)));
    }
  }
}

TEST(MarsSun, MorningEastAfternoonWestMidnightBelowHorizon) {
  const double lat = -14.57 * kDegree, dec = SolarDeclination(330.0);
  const Eigen::Vector3d morning = SunDirectionSite(lat, dec, 9.0);
  const Eigen::Vector3d afternoon = SunDirectionSite(lat, dec, 15.0);
  EXPECT_LT(morning.y(), 0.0);  // east = -y (site y is west)
  EXPECT_GT(afternoon.y(), 0.0);
  EXPECT_NEAR(SunElevation(morning), SunElevation(afternoon), 1e-12);
  EXPECT_NEAR(SunAzimuth(morning) + SunAzimuth(afternoon), 2.0 * M_PI, 1e-9);
  EXPECT_LT(SunDirectionSite(lat, dec, 0.0).z(), 0.0);
  EXPECT_LT(SunDirectionSite(lat, dec, 23.5).z(), 0.0);
  // Midnight elevation = -(90 deg - |lat + dec|).
  EXPECT_NEAR(SunElevation(SunDirectionSite(lat, dec, 0.0)), -(M_PI / 2 - std::abs(lat + dec)),
              1e-9);
  // Equinox at the equator: sunrise at 6 h, sunset at 18 h (no refraction, point sun).
  EXPECT_NEAR(SunDirectionSite(0.0, 0.0, 6.0).z(), 0.0, 1e-12);
  EXPECT_NEAR(SunDirectionSite(0.0, 0.0, 18.0).z(), 0.0, 1e-12);
}

TEST(MarsSun, SeasonModeAdvancesLocalTimeBySols) {
  SunEphemerisOptions o;
  o.ls_deg = 10.0;
  o.ltst_hours = 11.0;
  const SunEphemeris e(o);
  EXPECT_NEAR(e.At(0.0).ltst_hours, 11.0, 1e-12);
  EXPECT_NEAR(e.At(kMarsSolSeconds / 24.0).ltst_hours, 12.0, 1e-9);
  EXPECT_NEAR(e.At(kMarsSolSeconds).ltst_hours, 11.0, 1e-9);
  EXPECT_NEAR(e.At(kMarsSolSeconds).ls_deg, 10.0 + 360.0 / kMarsYearSols, 1e-9);
  const SunState noon = e.At(kMarsSolSeconds / 24.0);
  EXPECT_NEAR(noon.hour_angle_rad, 0.0, 1e-9);
  EXPECT_NEAR(noon.direction_site.y(), 0.0, 1e-9);
  EXPECT_TRUE(std::abs(noon.azimuth_rad) < 1e-6 || std::abs(noon.azimuth_rad - M_PI) < 1e-6);
}

TEST(MarsSun, DateModeMatchesTheAlgorithm) {
  SunEphemerisOptions o;
  o.mode = SunEphemerisOptions::Mode::kDate;
  o.j2000_tt_days = 1463.69;
  o.east_longitude_deg = 175.47;
  const SunEphemeris e(o);
  const SunState s = e.At(3600.0);
  const MarsSolarState st = ComputeMarsSolarState(1463.69 + 3600.0 / 86400.0);
  EXPECT_NEAR(s.ls_deg, st.ls_deg, 1e-12);
  EXPECT_NEAR(s.ltst_hours, LocalTrueSolarTimeHours(st, 175.47), 1e-12);
  // One Earth hour is 0.973 Mars hours of local time.
  const double dt_h = e.At(3600.0).ltst_hours - e.At(0.0).ltst_hours;
  EXPECT_NEAR(std::fmod(dt_h + 24.0, 24.0), 24.0 * 3600.0 / kMarsSolSeconds, 2e-3);
}

TEST(MarsSun, OptionsAreValidated) {
  SunEphemerisOptions o;
  EXPECT_TRUE(o.Validate().ok());
  o.latitude_deg = 95.0;
  EXPECT_FALSE(o.Validate().ok());
  o = SunEphemerisOptions{};
  o.ltst_hours = 24.0;
  EXPECT_NE(o.Validate().message().find("ltst_hours"), std::string::npos);
  o = SunEphemerisOptions{};
  o.ls_deg = std::nan("");
  EXPECT_FALSE(o.Validate().ok());
}

TEST(MarsSun, OptionsAreParameters) {
  ParamSet ps("dl-pose");
  DeclareParams<SunEphemerisOptions>(ps, "ephemeris.");
  ASSERT_TRUE(ps.LoadYamlString("ephemeris:\n  mode: date\n  latitude_deg: 4.5\n", "p.yaml").ok());
  auto o = ReadParams<SunEphemerisOptions>(ps, "ephemeris.");
  ASSERT_TRUE(o.ok()) << o.status().ToString();
  EXPECT_EQ(o->mode, SunEphemerisOptions::Mode::kDate);
  EXPECT_EQ(o->latitude_deg, 4.5);
  EXPECT_EQ(o->ls_deg, SunEphemerisOptions().ls_deg);  // the default
  ParamSet bad("dl-pose");
  DeclareParams<SunEphemerisOptions>(bad, "ephemeris.");
  ASSERT_TRUE(bad.LoadYamlString("ephemeris:\n  mode: calendar\n", "p.yaml").ok());
  const auto r = ReadParams<SunEphemerisOptions>(bad, "ephemeris.");
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("ephemeris.mode"), std::string::npos) << r.status().message();
}

}  // namespace
}  // namespace rover::geometry
