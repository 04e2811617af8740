#pragma once
/// @file
/// Planar geometry of drive primitives and keep-out zones (site frame x north, y west; metres,
/// radians; headings counter-clockwise from site x).
///
/// A primitive moves the rover centre in its own frame: an arc of curvature k and signed length
/// s ends at (sin(k s) / k, (1 - cos(k s)) / k) with heading change k s (straight: (s, 0), no
/// turn); a turn in place by a changes the heading only. Poses are (x, y, heading) of the rover
/// centre, from the 3D pose by its yaw (ZYX).

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "rover/apl/mobility/mobility_types.hpp"
#include "rover/base/status.hpp"
#include "rover/geometry/planar.hpp"
#include "rover/geometry/polygon.hpp"

namespace rover::apl::mobility {

// Planar poses and angle wrapping are core/geometry's (rover/geometry/planar.hpp).
using geometry::Pose2;
using geometry::WrapAngle;
/// Yaw of a 3D pose (ZYX), position x, y (geometry::ToPose2).
inline Pose2 PlanarPose(const Eigen::Isometry3d& site_from_rover) {
  return geometry::ToPose2(site_from_rover);
}

/// Pose after driving `p` (kArc, kStraight: distance along curvature; kTurnInPlace: angle;
/// others: no motion) from `start`.
Pose2 Propagate(const Pose2& start, const Primitive& p);
/// Points of the centre's track from `start` every `spacing` metres (and the end); for a turn in
/// place, the centre only.
std::vector<Eigen::Vector2d> SweptCentre(const Pose2& start, const Primitive& p, double spacing);
/// Path length of a primitive (|distance| for arcs and straights, 0 otherwise).
double PathLength(const Primitive& p);

/// Checks a keep-out polygon: 3..16 finite vertices that make a simple polygon
/// (geometry::WhyNotSimple). Messages name `field` and the vertex or edges, e.g.
/// "keep_out[1] ('crater').vertices: edges 0 and 2 cross (the polygon is not simple)".
Status CheckSimplePolygon(const std::string& field, const KeepOutZone& zone);
// Point-in-polygon and boundary distance: core/geometry (rover/geometry/polygon.hpp).
using geometry::DistanceToPolygon;
using geometry::InsidePolygon;

/// The first swept-centre point (index into `points`) that is inside a zone or closer than
/// `margin` to one, and the zone's index; -1 when none.
struct KeepOutHit {
  int point = -1;
  int zone = -1;
  bool hit() const { return point >= 0; }
};
KeepOutHit FirstKeepOutHit(const std::vector<Eigen::Vector2d>& points,
                           const std::vector<KeepOutZone>& zones, double margin);

/// Mars local mean solar time [h, 0..24) at Unix time `unix_s` (UTC) and east longitude
/// `longitude_east` [rad]: Allison & McEwen (2000)'s Mars Sol Date from the Julian date
/// (terrestrial time = UTC + 69.184 s, the leap seconds since 2017 taken as constant),
/// MSD = (JD_TT - 2405522.0028779) / 1.0274912517, mean solar time at the prime meridian
/// 24 frac(MSD), plus longitude / 15 deg. Good to a few seconds, ample for a TOD limit.
double MarsLocalMeanSolarTimeHours(double unix_s, double longitude_east);
/// [s] Earth seconds per Mars hour (1 sol = 88775.244 s).
inline constexpr double kSecondsPerMarsHour = 88775.244 / 24.0;

}  // namespace rover::apl::mobility
