#pragma once
/// @file
/// Top-down map of a Terrain as an RGB image / PNG, for reports and for eyeballing scenarios.
///
/// Orientation: north (+x) up, west (+y) left, i.e. pixel column c = (max_y - y) * s and row
/// r = (max_x - x) * s with s pixels per metre. Content:
///   - terrain hillshade (Lambert, sun from the north-west at 45 deg elevation) of
///     Terrain::natural, tinted by soil (firm soil ochre, loose sand pale yellow, bedrock
///     grey-brown) and lightly by elevation;
///   - an optional cell layer (e.g. a goodness map): known cells blended in grey from black
///     (value 0) to white (255), unknown cells left as the terrain, the layer's bounds dashed;
///   - rock outlines by height class: height > obstacle_height (0.2 m: a traversability
///     hazard) red, > half of it yellow, smaller ones thin dark (only where at least 3 px wide);
///   - science targets (cyan, labelled T<id>), the lander (deck, legs, ramps, stripes filled
///     from Lander::quads, seen from above), the rover start's rock-free disc (dashed white
///     circle with a cross at the start);
///   - a scale bar, a north arrow, a legend and optional overlay polylines (planned / driven /
///     estimated paths), drawn in the order given (so draw wide lines first, thin ones on top);
///     a path's start is a circle and its end a square, as the legend says.

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "rover/base/status.hpp"

namespace rover::sim::terrain {

struct Terrain;

struct MapColor {
  std::uint8_t r = 0, g = 0, b = 0;
};

/// A polyline overlay, e.g. a planned, driven or estimated path (site-frame x, y in metres).
struct MapPolyline {
  std::vector<Eigen::Vector2d> points;
  MapColor color{0, 90, 255};
  std::string label;      ///< shown in the legend (empty: not listed)
  int thickness = 2;      ///< [px]
  bool mark_ends = true;  ///< circle at the start, square at the end
  bool dashed = false;    ///< drawn as dashes (so that lines under it show through)
};

/// A text at a site-frame point (x, y in metres), drawn over everything on the map.
struct MapLabel {
  Eigen::Vector2d at = Eigen::Vector2d::Zero();
  std::string text;
  MapColor color{255, 255, 255};
};

/// A raster of 8-bit values on a site-frame grid: cell (i, j) covers x in
/// [origin_x + i r, origin_x + (i+1) r), y likewise; index j * width + i.
struct MapCellLayer {
  double origin_x = 0, origin_y = 0, resolution = 0.2;  ///< [m]
  int width = 0, height = 0;
  std::vector<std::uint8_t> value;  ///< 0 black .. 255 white
  std::vector<std::uint8_t> known;  ///< non-zero = drawn
  std::string label;                ///< legend ("goodness (black 0 .. white 255)")
  double opacity = 0.65;            ///< of known cells, (0, 1]
};

struct MapOptions {
  /// Pixels per metre; 0 = one pixel per grid cell, reduced if the image would exceed
  /// max_pixels on its longer side.
  double pixels_per_metre = 0.0;
  int max_pixels = 2000;
  double obstacle_height = 0.2;  ///< [m] rocks higher than this are drawn red
  bool draw_rocks = true;
  bool draw_keep_out = true;
  bool draw_legend = true;  ///< in a panel to the right of the map
  std::string title;  ///< in a band above the map when not empty (wrapped to the image width)
  std::vector<MapPolyline> polylines;
  std::vector<MapLabel> labels;
  std::vector<MapCellLayer> cell_layers;  ///< drawn under the rocks and paths

  Status Validate() const;
};

struct MapImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgb;  ///< row-major, 3 bytes per pixel
  double pixels_per_metre = 0.0;
  /// Where the map itself is: the title band is above it, the legend panel to its right.
  /// max_pixels bounds the map, not the whole image.
  int map_col0 = 0, map_row0 = 0, map_width = 0, map_height = 0;
  /// Pixel (column, row) of a site-frame point.
  Eigen::Vector2d ToPixel(double x, double y) const;
  double max_x = 0.0;
  double max_y = 0.0;
  MapColor At(int col, int row) const;
};

/// Renders the map in memory.
Result<MapImage> RenderTopDownMap(const Terrain& terrain, const MapOptions& options = {});
/// Renders the map and writes it as a PNG. Errors: bad options, unwritable path.
Status WriteTopDownMap(const Terrain& terrain, const std::string& path,
                       const MapOptions& options = {});

}  // namespace rover::sim::terrain
