#include "render.hpp"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

namespace rover::apl::roaman::testing {

cv::Scalar ClassColour(CellClass c) {
  switch (c) {
    case CellClass::kSafe:
      return {225, 225, 225};
    case CellClass::kBorder:
      return {90, 210, 240};
    case CellClass::kMissing:
      return {70, 70, 70};
    case CellClass::kSteep:
      return {40, 140, 250};
    case CellClass::kStep:
      return {30, 30, 150};
    case CellClass::kBlocked:
      return {200, 40, 200};
  }
  return {0, 0, 0};
}

cv::Mat RenderPlanningGrid(const PlanningGrid& grid, int scale) {
  cv::Mat image(grid.height * scale, grid.width * scale, CV_8UC3);
  for (int j = 0; j < grid.height; ++j) {
    for (int i = 0; i < grid.width; ++i) {
      const cv::Rect cell((grid.width - 1 - i) * scale, (grid.height - 1 - j) * scale, scale, scale);
      image(cell).setTo(ClassColour(grid.cls.at(i, j)));
    }
  }
  return image;
}

cv::Point GridPixel(const PlanningGrid& grid, const Eigen::Vector2d& p, int scale) {
  const Eigen::Vector2d q = grid.frame.ToFrame(p);
  const double col = (q.y() - grid.across0) / grid.cell;  // along i
  const double row = (q.x() - grid.along0) / grid.cell;   // along j
  return {static_cast<int>(std::lround((grid.width - col) * scale)),
          static_cast<int>(std::lround((grid.height - row) * scale))};
}

void DrawRoadMap(cv::Mat* image, const PlanningGrid& grid, const RoadMap& road, int scale) {
  for (int k = 0; k < road.nodes(); ++k) {
    const Eigen::Vector2i a = road.NodeCell(k);
    const cv::Point pa = GridPixel(grid, grid.Center(a.x(), a.y()), scale);
    for (int e = road.edge_first[k]; e < road.edge_first[k + 1]; ++e) {
      const Eigen::Vector2i b = road.NodeCell(road.edge_to[static_cast<std::size_t>(e)]);
      // Only connections to the next rows: the rest are long shortcuts that hide the map.
      if (b.y() - a.y() > 2) continue;
      cv::line(*image, pa, GridPixel(grid, grid.Center(b.x(), b.y()), scale), {200, 150, 90}, 1,
               cv::LINE_AA);
    }
  }
  for (const AxisRun& r : road.runs) {
    const cv::Point p = GridPixel(grid, grid.Center(r.axis, r.j), scale);
    const cv::Rect dot(p.x - scale / 2, p.y - scale / 2, std::max(1, scale), std::max(1, scale));
    (*image)(dot & cv::Rect(0, 0, image->cols, image->rows))
        .setTo(r.kept ? cv::Scalar(200, 90, 20) : cv::Scalar(150, 150, 150));
  }
}

void DrawPath(cv::Mat* image, const PlanningGrid& grid, const std::vector<Eigen::Vector2d>& path,
              const cv::Scalar& colour, int thickness, bool circles, int scale) {
  for (std::size_t k = 1; k < path.size(); ++k) {
    cv::line(*image, GridPixel(grid, path[k - 1], scale), GridPixel(grid, path[k], scale), colour,
             thickness, cv::LINE_AA);
  }
  if (!circles) return;
  for (const Eigen::Vector2d& p : path) {
    cv::circle(*image, GridPixel(grid, p, scale), 2 * thickness + 2, colour, thickness, cv::LINE_AA);
  }
}

cv::Mat RenderTraversability(const TraversabilityMap& map, int scale) {
  const int w = map.geometry.width, h = map.geometry.height;
  cv::Mat image(std::max(1, w * scale), std::max(1, h * scale), CV_8UC3, ClassColour(CellClass::kMissing));
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      // North (+i) up, west (+j) left.
      const cv::Rect cell((h - 1 - j) * scale, (w - 1 - i) * scale, scale, scale);
      image(cell).setTo(ClassColour(map.cls.at(i, j)));
    }
  }
  return image;
}

Status WritePng(const std::string& path, const cv::Mat& image) {
  try {
    if (cv::imwrite(path, image)) return Status::Ok();
  } catch (const cv::Exception& e) {
    return Unavailable("cannot write '" + path + "': " + e.what());
  }
  return Unavailable("cannot write '" + path + "'");
}

}  // namespace rover::apl::roaman::testing
