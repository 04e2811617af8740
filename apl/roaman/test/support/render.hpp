#pragma once
/// @file
/// Test support: pictures of ROAMAN's maps and plans (OpenCV, BGR images) for README.md and for
/// looking at a failing test.
///
/// Planning-grid pictures are drawn as FIDO's Figure 3: the goal direction up, each grid cell
/// `scale` pixels square, row j at image row (height - 1 - j) and column i at image column
/// (width - 1 - i) (w, the grid's second axis, points left). Site-frame pictures put north (+x)
/// up and west (+y) left.
/// Colours: safe light grey, border yellow, missing data dark grey, steep slope orange, step
/// dark red, blocked magenta; road-map axis cells blue (kept) or grey (dropped); plans as
/// polylines with their waypoints circled.

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "rover/apl/roaman/planning_grid.hpp"
#include "rover/apl/roaman/road_map.hpp"
#include "rover/apl/roaman/traversability.hpp"
#include "rover/base/status.hpp"

namespace rover::apl::roaman::testing {

/// BGR colour of a class.
cv::Scalar ClassColour(CellClass c);

/// The planning grid's classes.
cv::Mat RenderPlanningGrid(const PlanningGrid& grid, int scale);
/// Image pixel (column, row) of the centre of site point p on a RenderPlanningGrid picture.
cv::Point GridPixel(const PlanningGrid& grid, const Eigen::Vector2d& p, int scale);
/// Adds the road map: every axis cell (kept blue, dropped grey) and the connections between
/// kept ones.
void DrawRoadMap(cv::Mat* image, const PlanningGrid& grid, const RoadMap& road, int scale);
/// Adds a polyline of site points, its vertices circled when `circles`.
void DrawPath(cv::Mat* image, const PlanningGrid& grid, const std::vector<Eigen::Vector2d>& path,
              const cv::Scalar& colour, int thickness, bool circles, int scale);

/// The site-frame traversability map's classes.
cv::Mat RenderTraversability(const TraversabilityMap& map, int scale);

/// Writes `image` as PNG. Errors: Unavailable naming the path.
Status WritePng(const std::string& path, const cv::Mat& image);

}  // namespace rover::apl::roaman::testing
