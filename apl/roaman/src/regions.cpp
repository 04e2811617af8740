// Step 4 of the traversability map: regions of similar slope, grown from seeds in raster order.
#include <algorithm>
#include <cmath>
#include <vector>

#include "rover/apl/roaman/traversability.hpp"

namespace rover::apl::roaman {

RegionMap GrowRegions(const ElevationMap& map, const NormalMap& normals,
                      const RoamanOptions& options) {
  const int w = map.geometry.width, h = map.geometry.height;
  RegionMap out;
  out.id = Layer<std::int32_t>(w, h, -1);
  const double cos_tol = std::cos(options.region_tolerance);
  constexpr int kNeighbours[8][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1},
                                     {1, 1}, {-1, -1}, {1, -1}, {-1, 1}};
  std::vector<int> queue;
  for (int sj = 0; sj < h; ++sj) {
    for (int si = 0; si < w; ++si) {
      if (out.id.at(si, sj) >= 0 || !normals.has(si, sj)) continue;
      const std::int32_t id = static_cast<std::int32_t>(out.regions.size());
      Eigen::Vector3d sum = normals.normal.at(si, sj).cast<double>();
      int cells = 1;
      out.id.at(si, sj) = id;
      queue.clear();
      queue.push_back(static_cast<int>(out.id.Index(si, sj)));
      for (std::size_t q = 0; q < queue.size(); ++q) {
        const int ci = queue[q] % w, cj = queue[q] / w;
        const float zc = map.mean.at(ci, cj);
        for (const auto& d : kNeighbours) {
          const int ni = ci + d[0], nj = cj + d[1];
          if (!out.id.Contains(ni, nj) || out.id.at(ni, nj) >= 0 || !normals.has(ni, nj)) continue;
          if (std::abs(map.mean.at(ni, nj) - zc) > options.region_max_jump) continue;
          const Eigen::Vector3d n = normals.normal.at(ni, nj).cast<double>();
          if (n.dot(sum.normalized()) < cos_tol) continue;
          out.id.at(ni, nj) = id;
          sum += n;
          ++cells;
          queue.push_back(static_cast<int>(out.id.Index(ni, nj)));
        }
      }
      SlopeRegion r;
      r.cells = cells;
      r.normal = sum.normalized();
      r.slope = std::acos(std::clamp(r.normal.z(), -1.0, 1.0));
      out.regions.push_back(r);
    }
  }
  return out;
}

}  // namespace rover::apl::roaman
