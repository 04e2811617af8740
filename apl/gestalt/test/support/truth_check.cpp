#include "truth_check.hpp"

#include <cmath>

namespace rover::apl::gestalt::testing {

HazardQuality CompareWithTruth(const nav_core::GoodnessMap& map,
                               const sim::terrain::Terrain& terrain,
                               const Eigen::Vector2d& rover_xy, const GestaltOptions& o,
                               const TruthCheckOptions& check) {
  HazardQuality q;
  for (const sim::terrain::Rock& rock : terrain.rocks) {
    if (rock.height < check.hazard_height) continue;
    const Eigen::Vector2d c = rock.position.head<2>();
    if ((c - rover_xy).norm() > check.radius) continue;
    const nav_core::CellValue v = map.AtPoint(c.x(), c.y());
    if (!v.known() || (check.seen && !check.seen(rock))) continue;
    ++q.hazards_seen;
    if (v.goodness < o.min_allowed_goodness) ++q.hazards_marked;
  }
  const double disc_r = 0.5 * o.rover_disc_diameter;
  for (int j = 0; j < map.height; ++j) {
    for (int i = 0; i < map.width; ++i) {
      const nav_core::CellValue v = map.At(i, j);
      if (!v.known() || v.goodness >= o.min_allowed_goodness) continue;
      const Eigen::Vector2d c = map.CellCenter(i, j);
      if ((c - rover_xy).norm() > check.radius) continue;
      ++q.obstacle_cells;
      bool excused = false;
      for (const sim::terrain::Rock& rock : terrain.rocks) {
        if (rock.height < check.excuse_height) continue;
        if ((rock.position.head<2>() - c).norm() <=
            disc_r + sim::terrain::RockBoundingRadius(rock)) {
          excused = true;
          break;
        }
      }
      if (!excused) {
        const Eigen::Vector3d n = terrain.bare.Normal(c.x(), c.y());
        excused = std::acos(std::min(1.0, n.z())) >= o.max_tilt;
      }
      if (!excused) ++q.false_obstacles;
    }
  }
  return q;
}

}  // namespace rover::apl::gestalt::testing
