#pragma once
/// @file
/// Test support: draws a goodness map as a colour image (for README.md and for eyeballing test
/// scenes). Colours: goodness 0 red through yellow (128) to green (255); unknown cells dark grey;
/// border cells drawn paler; optional overlays: truth rocks (outline; red if taller than
/// `hazard_height`, white otherwise), the rover (blue disc with a heading tick) and candidate
/// arcs (the chosen one thick). Image rows run toward -y (west at the top would be confusing:
/// the image is drawn with x to the right and y up, i.e. as seen from above with north right).

#include <Eigen/Geometry>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "rover/apl/nav_core/arc_selector.hpp"
#include "rover/apl/nav_core/goodness_map.hpp"
#include "rover/base/status.hpp"
#include "rover/sim/terrain/terrain.hpp"

namespace rover::apl::gestalt::testing {

struct RenderOptions {
  int pixels_per_cell = 8;
  double hazard_height = 0.20;  ///< [m] rocks at least this tall are drawn red
};

/// The map alone (BGR, width * ppc x height * ppc).
cv::Mat RenderGoodnessMap(const nav_core::GoodnessMap& map, const RenderOptions& options = {});
/// Overlays, in the map's pixel frame.
void DrawRocks(const nav_core::GoodnessMap& map, const std::vector<sim::terrain::Rock>& rocks,
               const RenderOptions& options, cv::Mat* image);
void DrawRover(const nav_core::GoodnessMap& map, const Eigen::Isometry3d& site_from_rover,
               const RenderOptions& options, cv::Mat* image);
/// Every arc candidate thin, the chosen one thick (nothing for turns).
void DrawArcs(const nav_core::GoodnessMap& map, const Eigen::Isometry3d& site_from_rover,
              const nav_core::ArcEvaluation& evaluation, const RenderOptions& options,
              cv::Mat* image);
/// The rover's path so far (site x, y), as a thin blue line.
void DrawPath(const nav_core::GoodnessMap& map, const std::vector<Eigen::Vector2d>& path,
              const RenderOptions& options, cv::Mat* image);
/// Writes a PNG. Errors: Unavailable naming the path.
Status WritePng(const cv::Mat& image, const std::string& path);

}  // namespace rover::apl::gestalt::testing
