#include "rover/sim/terrain/features.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "rover/base/check.hpp"
#include "rover/base/format.hpp"
#include "rover/sim/terrain/random.hpp"
#include "rover/sim/terrain/terrain.hpp"

namespace rover::sim::terrain {
namespace {

// The features' own random stream (terrain.cpp's streams are 1..7).
constexpr std::uint64_t kFeatureStream = 11;
// Spacing of a wall's rocks, in rock diameters: neighbours overlap, so the wall has no gap.
constexpr double kWallSpacing = 0.6;
constexpr double kJitter = 0.1;  // relative spread of a wall rock's diameter and height

Status CheckSize(const std::string& what, double diameter, double height, double d_max,
                 double resolution) {
  if (!(diameter >= 2.0 * resolution && diameter <= d_max)) {
    return InvalidArgument(what + ".diameter: " + FormatNumber(diameter) + " is out of range [" +
                           FormatNumber(2.0 * resolution) + ", " + FormatNumber(d_max) + "]");
  }
  if (!(height >= 0.0 && height <= 5.0)) {
    return InvalidArgument(what + ".height: " + FormatNumber(height) + " is out of range [0, 5]");
  }
  return Status::Ok();
}

// Adds one rock, removing generated rocks it overlaps; errors if it is off the map or on the
// start disc.
Status AddRock(Terrain* t, const std::string& what, Rock rock) {
  const HeightField& bare = t->bare;
  const double br = RockBoundingRadius(rock);
  const double x = rock.position.x(), y = rock.position.y();
  if (!std::isfinite(x) || x - br < bare.min_x() || x + br > bare.max_x() || !std::isfinite(y) ||
      y - br < bare.min_y() || y + br > bare.max_y()) {
    return InvalidArgument(what + ": the rock at (" + FormatNumber(x) + ", " + FormatNumber(y) +
                           ") (radius " + FormatNumber(br) + ") is off the map (x in [" +
                           FormatNumber(bare.min_x()) + ", " + FormatNumber(bare.max_x()) +
                           "], y in [" + FormatNumber(bare.min_y()) + ", " +
                           FormatNumber(bare.max_y()) + "])");
  }
  const StartParams& st = t->params.start;
  if (std::hypot(x - st.x, y - st.y) < st.keep_out_radius + br) {
    return InvalidArgument(what + ": the rock at (" + FormatNumber(x) + ", " + FormatNumber(y) +
                           ") is on the rover's rock-free start disc (radius " +
                           FormatNumber(st.keep_out_radius) + " m about the start)");
  }
  std::erase_if(t->rocks, [&](const Rock& o) {
    return !o.science_target && !o.placed &&
           (o.position.head<2>() - rock.position.head<2>()).norm() < br + RockBoundingRadius(o);
  });
  rock.position.z() = bare.Height(x, y);
  rock.id = t->next_rock_id++;
  rock.placed = true;
  t->rocks.push_back(rock);
  return Status::Ok();
}

}  // namespace

Status PlaceFeatures(Terrain* terrain, const TerrainFeatures& f) {
  ROVER_DEMAND(terrain != nullptr);
  const double res = terrain->bare.resolution();
  const double ratio = terrain->params.rocks.height_ratio;
  for (std::size_t i = 0; i < f.rocks.size(); ++i) {
    const PlacedRock& p = f.rocks[i];
    const std::string what = "rocks[" + std::to_string(i) + "]";
    ROVER_RETURN_IF_ERROR(CheckSize(what, p.diameter, p.height, 10.0, res));
    Rock rock;
    rock.position = Eigen::Vector3d(p.x, p.y, 0.0);
    rock.diameter = p.diameter;
    rock.height = p.height > 0 ? p.height : ratio * p.diameter;
    ROVER_RETURN_IF_ERROR(AddRock(terrain, what, rock));
  }
  Rng rng(MixSeed(terrain->params.seed, kFeatureStream));
  for (std::size_t i = 0; i < f.walls.size(); ++i) {
    const RockWall& w = f.walls[i];
    const std::string what = "walls[" + std::to_string(i) + "]";
    ROVER_RETURN_IF_ERROR(CheckSize(what, w.diameter, w.height, 5.0, res));
    if (!w.from.allFinite() || !w.to.allFinite()) {
      return InvalidArgument(what + ": an end point is not finite");
    }
    const Eigen::Vector2d d = w.to - w.from;
    const double len = d.norm();
    if (len < w.diameter) {
      return InvalidArgument(what + ": the wall is " + FormatNumber(len) +
                             " m long, shorter than its rock diameter " + FormatNumber(w.diameter) +
                             " m");
    }
    const int n = static_cast<int>(std::ceil(len / (kWallSpacing * w.diameter))) + 1;
    const double along = std::atan2(d.y(), d.x());
    for (int k = 0; k < n; ++k) {
      const Eigen::Vector2d c = w.from + d * (static_cast<double>(k) / (n - 1));
      Rock rock;
      rock.position = Eigen::Vector3d(c.x(), c.y(), 0.0);
      rock.diameter = w.diameter * rng.Uniform(1.0 - kJitter, 1.0 + kJitter);
      const double h = w.height > 0 ? w.height : ratio * w.diameter;
      rock.height = h * rng.Uniform(1.0 - kJitter, 1.0 + kJitter);
      rock.yaw = along;
      rock.elongation = rng.Uniform(1.0, 1.3);
      rock.bluntness = rng.Uniform(0.3, 0.6);
      rock.texture_id = static_cast<int>(
          rng.UniformInt(static_cast<std::uint64_t>(std::max(1, terrain->params.rocks.texture_count))));
      ROVER_RETURN_IF_ERROR(AddRock(terrain, what + " rock " + std::to_string(k), rock));
    }
  }
  for (std::size_t i = 0; i < f.outcrops.size(); ++i) {
    const Outcrop& o = f.outcrops[i];
    const std::string what = "outcrops[" + std::to_string(i) + "]";
    auto bad = [&](const char* field, double v, const std::string& range) {
      return InvalidArgument(what + "." + field + ": " + FormatNumber(v) + " is out of range " + range);
    };
    if (!(o.length >= 0.5 && o.length <= 20.0)) return bad("length", o.length, "[0.5, 20]");
    if (!(o.depth >= 0.3 && o.depth <= o.length)) {
      return bad("depth", o.depth, "[0.3, length " + FormatNumber(o.length) + "]");
    }
    if (!(o.height >= 0.1 && o.height <= 5.0)) return bad("height", o.height, "[0.1, 5]");
    if (!std::isfinite(o.yaw_deg)) return bad("yaw_deg", o.yaw_deg, "(finite)");
    Rock rock;
    rock.position = Eigen::Vector3d(o.x, o.y, 0.0);
    rock.diameter = o.length;
    rock.elongation = o.length / o.depth;
    rock.height = o.height;
    rock.yaw = o.yaw_deg * std::numbers::pi / 180.0;
    rock.layers = std::max(2, static_cast<int>(std::lround(o.height / kOutcropBedHeight)));
    rock.texture_id = static_cast<int>(
        rng.UniformInt(static_cast<std::uint64_t>(std::max(1, terrain->params.rocks.texture_count))));
    ROVER_RETURN_IF_ERROR(AddRock(terrain, what, rock));
  }
  RebuildHeights(terrain);
  return Status::Ok();
}

void DeclareTerrainFeatures(ParamSet& params, const std::string& prefix) {
  params.Declare(prefix + ".rocks", std::vector<double>{},
                 "placed rocks: [x, y, diameter, height, ...] (site frame, m; height 0 = "
                 "rocks.height_ratio * diameter)");
  params.Declare(prefix + ".walls", std::vector<double>{},
                 "rock walls: [x0, y0, x1, y1, rock diameter, height, ...] (site frame, m)");
  params.Declare(prefix + ".outcrops", std::vector<double>{},
                 "layered outcrops: [x, y, length, depth, height, yaw_deg, ...] (site frame, m; "
                 "beds of ~0.3 m stepped back, straight level edges)");
}

Result<TerrainFeatures> TerrainFeaturesFromParamSet(const ParamSet& ps, const std::string& prefix) {
  TerrainFeatures f;
  const std::string rocks_key = prefix + ".rocks", walls_key = prefix + ".walls";
  const std::vector<double>& r = ps.GetDoubleList(rocks_key);
  if (r.size() % 4 != 0) {
    return InvalidArgument(ps.Origin(rocks_key).ToString() + ": key '" + rocks_key + "': " +
                           std::to_string(r.size()) +
                           " numbers is not a multiple of 4 (x, y, diameter, height per rock)");
  }
  for (std::size_t i = 0; i < r.size(); i += 4) f.rocks.push_back({r[i], r[i + 1], r[i + 2], r[i + 3]});
  const std::vector<double>& w = ps.GetDoubleList(walls_key);
  if (w.size() % 6 != 0) {
    return InvalidArgument(ps.Origin(walls_key).ToString() + ": key '" + walls_key + "': " +
                           std::to_string(w.size()) +
                           " numbers is not a multiple of 6 (x0, y0, x1, y1, diameter, height "
                           "per wall)");
  }
  for (std::size_t i = 0; i < w.size(); i += 6) {
    f.walls.push_back({{w[i], w[i + 1]}, {w[i + 2], w[i + 3]}, w[i + 4], w[i + 5]});
  }
  const std::string outcrops_key = prefix + ".outcrops";
  const std::vector<double>& o = ps.GetDoubleList(outcrops_key);
  if (o.size() % 6 != 0) {
    return InvalidArgument(ps.Origin(outcrops_key).ToString() + ": key '" + outcrops_key + "': " +
                           std::to_string(o.size()) +
                           " numbers is not a multiple of 6 (x, y, length, depth, height, yaw_deg "
                           "per outcrop)");
  }
  for (std::size_t i = 0; i < o.size(); i += 6) {
    f.outcrops.push_back({o[i], o[i + 1], o[i + 2], o[i + 3], o[i + 4], o[i + 5]});
  }
  return f;
}

Status PlaceScenarioFeatures(Terrain* terrain, const ParamSet& ps, const std::string& prefix) {
  ROVER_ASSIGN_OR_RETURN(const TerrainFeatures f, TerrainFeaturesFromParamSet(ps, prefix));
  const Status s = PlaceFeatures(terrain, f);
  if (s.ok()) return s;
  // "walls[1].diameter: ..." -> the walls key's file:line.
  const std::string& m = s.message();
  const std::string key = prefix + (m.rfind("walls", 0) == 0      ? ".walls"
                                    : m.rfind("outcrops", 0) == 0 ? ".outcrops"
                                                                  : ".rocks");
  return Status(s.code(), ps.Origin(key).ToString() + ": key '" + key + "': " + s.message());
}

}  // namespace rover::sim::terrain
