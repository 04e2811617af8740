#include "scenes.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

#include "rover/apl/roaman/grid.hpp"

namespace rover::apl::roaman::testing {
namespace {

// Raises every sample within half_width of any of `segments` (pairs a, b) by `height`, once.
void RaiseNear(sim::terrain::HeightField* g,
               const std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>>& segments,
               double half_width, double height) {
  for (int j = 0; j < g->ny(); ++j) {
    for (int i = 0; i < g->nx(); ++i) {
      const Eigen::Vector2d p(g->min_x() + i * g->resolution(), g->min_y() + j * g->resolution());
      for (const auto& [a, b] : segments) {
        if (DistanceToSegment(p, a, b) <= half_width) {
          g->at(i, j) += static_cast<float>(height);
          break;
        }
      }
    }
  }
}

}  // namespace

sim::terrain::HeightField HeightFieldOf(double x0, double y0, double x1, double y1,
                                        double resolution,
                                        const std::function<double(double, double)>& f) {
  const int nx = static_cast<int>(std::lround((x1 - x0) / resolution)) + 1;
  const int ny = static_cast<int>(std::lround((y1 - y0) / resolution)) + 1;
  sim::terrain::HeightField g(nx, ny, resolution, Eigen::Vector2d(x0, y0));
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      g.at(i, j) = static_cast<float>(f(x0 + i * resolution, y0 + j * resolution));
    }
  }
  return g;
}

sim::terrain::HeightField FlatGround(double x0, double y0, double x1, double y1,
                                     double resolution) {
  return HeightFieldOf(x0, y0, x1, y1, resolution, [](double, double) { return 0.0; });
}

void AddRock(sim::terrain::HeightField* g, double x, double y, double diameter, double height) {
  const double r = 0.5 * diameter;
  for (int j = 0; j < g->ny(); ++j) {
    for (int i = 0; i < g->nx(); ++i) {
      const double px = g->min_x() + i * g->resolution(), py = g->min_y() + j * g->resolution();
      const double rho2 = ((px - x) * (px - x) + (py - y) * (py - y)) / (r * r);
      if (rho2 < 1.0) g->at(i, j) += static_cast<float>(height * std::sqrt(1.0 - rho2));
    }
  }
}

void AddWall(sim::terrain::HeightField* g, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
             double half_width, double height) {
  RaiseNear(g, {{a, b}}, half_width, height);
}

void AddCulDeSac(sim::terrain::HeightField* g, const Eigen::Vector2d& base,
                 const Eigen::Vector2d& mouth, double inner_width, double depth, double thickness,
                 double height) {
  const Eigen::Vector2d m = mouth.normalized();
  const Eigen::Vector2d side(-m.y(), m.x());
  const double half = 0.5 * (inner_width + thickness);  // arm centre lines
  const double t = 0.5 * thickness;
  // The base, then the two arms from its ends toward the mouth.
  RaiseNear(g,
            {{base - half * side, base + half * side},
             {base - half * side, base - half * side + depth * m},
             {base + half * side, base + half * side + depth * m}},
            t, height);
}

sim::terrain::Terrain RockField(double k, std::uint64_t seed, double size, double resolution) {
  sim::terrain::TerrainParams p;
  p.size_x = size;
  p.size_y = size;
  p.resolution = resolution;
  p.seed = seed;
  p.hills.amplitude = 0.15;
  p.craters.count = 0;
  p.rocks.preset = sim::terrain::RockPreset::kCustom;
  p.rocks.k = k;
  p.start.keep_out_radius = 1.5;
  p.start.blend_width = 0.5;
  auto t = sim::terrain::GenerateTerrain(p);
  if (!t.ok()) throw std::runtime_error("RockField: " + t.status().ToString());
  return std::move(t).value();
}

GridGeometry CellGeometry(int w, int h, double origin_x, double origin_y) {
  GridGeometry g;
  g.origin_x = origin_x;
  g.origin_y = origin_y;
  g.cell = 0.05;
  g.width = w;
  g.height = h;
  return g;
}

ElevationMap SampledElevation(const sim::terrain::HeightField& ground,
                              const GridGeometry& geometry) {
  ElevationMap m;
  m.geometry = geometry;
  const int w = geometry.width, h = geometry.height;
  m.mean = Layer<float>(w, h);
  m.top = Layer<float>(w, h);
  m.bottom = Layer<float>(w, h);
  m.sigma = Layer<float>(w, h, 0.0f);
  m.count = Layer<std::uint32_t>(w, h, 1);
  m.source = Layer<HeightSource>(w, h, HeightSource::kMeasured);
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      const Eigen::Vector2d c = geometry.Center(i, j);
      const float z = static_cast<float>(ground.Height(c.x(), c.y()));
      m.mean.at(i, j) = m.top.at(i, j) = m.bottom.at(i, j) = z;
    }
  }
  m.measured = w * h;
  return m;
}

TraversabilityMap ClassMap(double x0, double y0, double x1, double y1, double cell,
                           CellClass fill) {
  TraversabilityMap t;
  t.geometry.origin_x = x0;
  t.geometry.origin_y = y0;
  t.geometry.cell = cell;
  t.geometry.width = static_cast<int>(std::lround((x1 - x0) / cell));
  t.geometry.height = static_cast<int>(std::lround((y1 - y0) / cell));
  t.cls = Layer<CellClass>(t.geometry.width, t.geometry.height, fill);
  return t;
}

void Paint(TraversabilityMap* map, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
           double half_width, CellClass c) {
  for (int j = 0; j < map->geometry.height; ++j) {
    for (int i = 0; i < map->geometry.width; ++i) {
      if (DistanceToSegment(map->geometry.Center(i, j), a, b) <= half_width) map->cls.at(i, j) = c;
    }
  }
}

}  // namespace rover::apl::roaman::testing
