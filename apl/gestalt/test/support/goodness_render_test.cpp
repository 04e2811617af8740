#include "goodness_render.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/imgcodecs.hpp>

namespace rover::apl::gestalt::testing {
namespace {

TEST(GoodnessRender, ColoursCellsAndWritesAPng) {
  nav_core::GoodnessMap m;
  m.resolution = 0.2;
  m.width = 4;
  m.height = 3;
  m.goodness = {0, 255, 128, 11, 255, 255, 255, 255, 255, 255, 255, 255};
  m.certainty.assign(12, 255);
  m.flags.assign(12, nav_core::kCellKnown);
  m.flags[3] = 0;  // unknown
  RenderOptions o;
  o.pixels_per_cell = 4;
  const cv::Mat img = RenderGoodnessMap(m, o);
  ASSERT_EQ(img.cols, 16);
  ASSERT_EQ(img.rows, 12);
  // Row j = 0 is drawn at the bottom (y up).
  const cv::Vec3b obstacle = img.at<cv::Vec3b>(10, 1), perfect = img.at<cv::Vec3b>(10, 5);
  const cv::Vec3b unknown = img.at<cv::Vec3b>(10, 13);
  EXPECT_GT(obstacle[2], 200);  // red
  EXPECT_LT(obstacle[1], 30);
  EXPECT_GT(perfect[1], 180);  // green
  EXPECT_LT(perfect[2], 30);
  EXPECT_EQ(unknown, cv::Vec3b(60, 60, 60));
  const std::string path =
      (std::filesystem::temp_directory_path() / "gestalt_render_test.png").string();
  ASSERT_TRUE(WritePng(img, path).ok());
  const cv::Mat back = cv::imread(path);
  EXPECT_EQ(back.cols, 16);
  std::filesystem::remove(path);
  EXPECT_FALSE(WritePng(img, "/nonexistent-dir/x.png").ok());
}

}  // namespace
}  // namespace rover::apl::gestalt::testing
