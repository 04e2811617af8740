#pragma once
// DrawDecision: a picture of one ENav decision, for enav-demo and autonav-kinematic (tools
// only; OpenCV). Left: the height map's hazard classes (grey seen, orange wheel, red rocker,
// dark red body), the true rock outlines when given (black circles), a thinned path tree (grey),
// the paths checked and refused (red), the chosen path (blue), the rover's ground footprint at
// the decision (white box) and the trail driven so far (white). Right: the cost-to-go field
// (viridis, low = dark; black = blocked or unreached) with the trail and the chosen path.
// North (site +x) is up, west (+y) left; `half` metres each side of the decision's start.
#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

#include "rover/apl/enav/enav_planner.hpp"
#include "rover/apl/nav_core/height_map.hpp"

namespace rover::apl::enav {

struct PictureRock {
  Eigen::Vector2d centre;
  double radius = 0.0;  ///< [m]
};

struct PictureOptions {
  double half = 7.0;  ///< [m] half the window's side
  double ppm = 40.0;  ///< pixels per metre
  int tree_stride = 7;  ///< every n-th path of the tree is drawn
};

cv::Mat DrawDecision(const EnavPlanner& planner, const nav_core::HeightMap& map,
                     const hwconfig::RoverDescription& rover,
                     const std::vector<Eigen::Vector2d>& trail,
                     const std::vector<PictureRock>& rocks, const PictureOptions& options = {});

}  // namespace rover::apl::enav
