#include "render.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/imgcodecs.hpp>

#include "scenes.hpp"

namespace rover::apl::roaman::testing {
namespace {

PlanningGrid SmallGrid() {
  TraversabilityMap t = ClassMap(-2.0, -2.0, 6.0, 2.0, 0.05, CellClass::kSafe);
  Paint(&t, {3.0, 1.0}, {3.0, 1.0}, 0.1, CellClass::kStep);  // left of the goal direction
  RoamanOptions o;
  o.plan_width = 3.0;
  o.plan_back = 0.5;
  return BuildPlanningGrid(t, {0.0, 0.0}, {5.0, 0.0}, 4.0, o);
}

cv::Scalar At(const cv::Mat& m, cv::Point p) {
  const cv::Vec3b v = m.at<cv::Vec3b>(p);
  return {static_cast<double>(v[0]), static_cast<double>(v[1]), static_cast<double>(v[2])};
}

TEST(Render, PlanningGridHasTheGoalUpAndLeftOnTheLeft) {
  const PlanningGrid g = SmallGrid();
  const cv::Mat m = RenderPlanningGrid(g, 2);
  EXPECT_EQ(m.cols, g.width * 2);
  EXPECT_EQ(m.rows, g.height * 2);
  // The step at site (3, 1): 3 m toward the goal, 1 m to its left (west of a goal due north).
  const cv::Point p = GridPixel(g, {3.0, 1.0}, 2);
  EXPECT_LT(p.x, m.cols / 2);
  EXPECT_LT(p.y, m.rows / 2);
  EXPECT_EQ(At(m, p), ClassColour(CellClass::kStep));
  EXPECT_EQ(At(m, GridPixel(g, {3.0, -1.0}, 2)), ClassColour(CellClass::kSafe));
  // The rover (site origin) is near the bottom, in the middle.
  const cv::Point r = GridPixel(g, {0.0, 0.0}, 2);
  EXPECT_EQ(r.x, m.cols / 2);
  EXPECT_EQ(r.y, m.rows - 20);  // 0.5 m = 10 rows of 2 px above the bottom edge
}

TEST(Render, DrawsRoadMapsAndPathsAndWritesPng) {
  const PlanningGrid g = SmallGrid();
  cv::Mat m = RenderPlanningGrid(g, 2);
  const RoadMap road = BuildRoadMap(g, RoamanOptions{});
  DrawRoadMap(&m, g, road, 2);
  DrawPath(&m, g, {{0.0, 0.0}, {2.0, -0.5}, {3.5, 0.0}}, {0, 0, 255}, 2, true, 2);
  EXPECT_EQ(At(m, GridPixel(g, {2.0, -0.5}, 2)), cv::Scalar(0, 0, 255));
  const std::string path =
      (std::filesystem::temp_directory_path() / "roaman_render_test.png").string();
  ASSERT_TRUE(WritePng(path, m).ok());
  const cv::Mat back = cv::imread(path);
  EXPECT_EQ(back.size(), m.size());
  std::filesystem::remove(path);
  EXPECT_FALSE(WritePng("/nonexistent-dir/x.png", m).ok());

  TraversabilityMap t = ClassMap(0.0, 0.0, 1.0, 0.5, 0.05, CellClass::kSafe);
  Paint(&t, {0.925, 0.475}, {0.925, 0.475}, 0.01, CellClass::kBlocked);  // cell (18, 9): NW
  const cv::Mat s = RenderTraversability(t, 1);
  EXPECT_EQ(s.rows, 20);  // north (x) up
  EXPECT_EQ(s.cols, 10);
  EXPECT_EQ(At(s, {0, 1}), ClassColour(CellClass::kBlocked));
}

}  // namespace
}  // namespace rover::apl::roaman::testing
