#pragma once
/// @file
/// Forwarding header: the Mars sun ephemeris moved to core/geometry (rover/geometry/mars_sun.hpp,
/// namespace rover::geometry) so that the pose estimator can use the same model as the
/// simulator. These using-declarations keep the rover::sim names for existing users; new code
/// includes rover/geometry/mars_sun.hpp.

#include "rover/geometry/mars_sun.hpp"

namespace rover::sim {

using geometry::ComputeMarsSolarState;
using geometry::kMarsSolSeconds;
using geometry::kMarsYearSols;
using geometry::LocalTrueSolarTimeHours;
using geometry::MarsSolarState;
using geometry::SolarDeclination;
using geometry::SunAzimuth;
using geometry::SunDirectionSite;
using geometry::SunElevation;
using geometry::SunEphemeris;
using geometry::SunEphemerisOptions;
using geometry::SunState;

}  // namespace rover::sim
