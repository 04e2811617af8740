#include "rover/dl/stereo/frame_images.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace rover::dl::stereo {
namespace {

TEST(FrameImages, ViewTheFrameImagesRowMajor) {
  // w x h images whose pixel (u, v) of the left image is u + v and of the right image 2u.
  const int w = 16, h = 8;
  std::vector<std::uint8_t> left(static_cast<std::size_t>(w * h)), right(left.size());
  for (int v = 0; v < h; ++v) {
    for (int u = 0; u < w; ++u) {
      left[static_cast<std::size_t>(v * w + u)] = static_cast<std::uint8_t>(u + v);
      right[static_cast<std::size_t>(v * w + u)] = static_cast<std::uint8_t>(2 * u);
    }
  }
  msg::StereoFrame f;
  f.stamp = Time{5'000'000'000};
  f.width = w;
  f.height = h;
  f.left_model.width = f.right_model.width = w;
  f.left_model.height = f.right_model.height = h;
  f.left = left;
  f.right = right;
  const FrameImages images = ViewFrameImages(f);
  EXPECT_EQ(images.left.cols, 16);
  EXPECT_EQ(images.left.rows, 8);
  EXPECT_EQ(images.left.type(), CV_8UC1);
  EXPECT_EQ(images.left.at<std::uint8_t>(3, 5), 8);
  EXPECT_EQ(images.right.at<std::uint8_t>(7, 6), 12);
  EXPECT_EQ(images.left.data, left.data());  // a view, no copy
  EXPECT_EQ(images.right.data, right.data());
}

}  // namespace
}  // namespace rover::dl::stereo
