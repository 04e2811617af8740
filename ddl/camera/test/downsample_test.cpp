#include "rover/ddl/camera/downsample.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "test_models.hpp"

namespace rover::ddl::camera {
namespace {

GrayImage Image(int w, int h, std::uint8_t fill = 0) {
  GrayImage im;
  im.width = w;
  im.height = h;
  im.pixels.assign(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), fill);
  return im;
}

// A Gaussian spot of amplitude 250 centred on pixel coordinate (x, y) (pixel-centre convention).
GrayImage Spot(int w, int h, double x, double y, double sigma) {
  GrayImage im = Image(w, h);
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      const double d2 = (i - x) * (i - x) + (j - y) * (j - y);
      im.pixels[static_cast<std::size_t>(j) * w + i] =
          static_cast<std::uint8_t>(std::lround(250.0 * std::exp(-d2 / (2 * sigma * sigma))));
    }
  }
  return im;
}

Eigen::Vector2d Centroid(const GrayImage& im) {
  double s = 0.0, sx = 0.0, sy = 0.0;
  for (int j = 0; j < im.height; ++j) {
    for (int i = 0; i < im.width; ++i) {
      const double v = im.pixels[static_cast<std::size_t>(j) * im.width + i];
      s += v;
      sx += v * i;
      sy += v * j;
    }
  }
  return {sx / s, sy / s};
}

TEST(AreaDownsample, IntegerFactorIsTheBlockMean) {
  GrayImage in = Image(8, 4);
  for (int j = 0; j < 4; ++j) {
    for (int i = 0; i < 8; ++i)
      in.pixels[static_cast<std::size_t>(j * 8 + i)] = static_cast<std::uint8_t>(10 * i + j);
  }
  auto out = AreaDownsample(in, 2, 1);
  ASSERT_TRUE(out.ok()) << out.status().ToString();
  ASSERT_EQ(out->pixels.size(), 2u);
  // Block 0: columns 0..3, rows 0..3: mean = 10 * 1.5 + 1.5 = 16.5 -> 17 (round half away).
  EXPECT_EQ(out->pixels[0], 17);
  EXPECT_EQ(out->pixels[1], 57);  // 10 * 5.5 + 1.5
}

TEST(AreaDownsample, PreservesUniformBrightnessForAnyFactor) {
  const GrayImage in = Image(1024, 768, 137);
  for (int w : {1024, 512, 300, 256, 77, 1}) {
    const int h = std::max(1, static_cast<int>(std::lround(768.0 * w / 1024)));
    auto out = AreaDownsample(in, w, h);
    ASSERT_TRUE(out.ok());
    for (std::uint8_t p : out->pixels) ASSERT_EQ(p, 137) << w;
  }
}

TEST(AreaDownsample, RejectsBadSizes) {
  EXPECT_FALSE(AreaDownsample(Image(4, 4), 8, 2).ok());  // upsampling
  EXPECT_FALSE(AreaDownsample(Image(4, 4), 0, 2).ok());
  GrayImage bad = Image(4, 4);
  bad.pixels.pop_back();
  EXPECT_FALSE(AreaDownsample(bad, 2, 2).ok());
  EXPECT_FALSE(AreaDownsample(Image(0, 0), 1, 1).ok());
}

TEST(DownsampleStereo, ScaledModelProjectsPointsToTheScaledPixel) {
  const geometry::CameraModel left = test::NavcamCahvor(0.0);
  const geometry::CameraModel right = test::NavcamCahvor(0.2);
  const GrayImage img = Image(1024, 768, 50);
  auto d = DownsampleStereo(img, img, left, right, 256);
  ASSERT_TRUE(d.ok()) << d.status().ToString();
  EXPECT_EQ(d->left.width, 256);
  EXPECT_EQ(d->left.height, 192);
  EXPECT_EQ(d->left_model.width(), 256);
  EXPECT_EQ(d->left_model.height(), 192);
  EXPECT_DOUBLE_EQ(d->scale_x, 0.25);
  for (const Eigen::Vector3d& p : {Eigen::Vector3d(0.3, -0.2, 3.0), Eigen::Vector3d(-1.0, 0.5, 4.0),
                                   Eigen::Vector3d(0.0, 0.0, 10.0)}) {
    for (int side = 0; side < 2; ++side) {
      const auto& full = side == 0 ? left : right;
      const auto& small = side == 0 ? d->left_model : d->right_model;
      const auto xf = full.Project(p);
      const auto xs = small.Project(p);
      ASSERT_TRUE(xf && xs);
      EXPECT_NEAR(xs->x(), 0.25 * (xf->x() + 0.5) - 0.5, 1e-9);
      EXPECT_NEAR(xs->y(), 0.25 * (xf->y() + 0.5) - 0.5, 1e-9);
    }
  }
}

TEST(DownsampleStereo, ImageContentAndModelAgree) {
  // A spot drawn where a 3D point projects in the full image lands, after downsampling, where
  // the scaled model projects the same point.
  const geometry::CameraModel model = test::NavcamCahvor();
  const Eigen::Vector3d p(0.41, -0.27, 3.0);
  const Eigen::Vector2d xf = *model.Project(p);
  const GrayImage spot = Spot(1024, 768, xf.x(), xf.y(), 6.0);
  for (int w : {256, 300}) {
    auto d = DownsampleStereo(spot, spot, model, model, w);
    ASSERT_TRUE(d.ok());
    const Eigen::Vector2d xs = *d->left_model.Project(p);
    const Eigen::Vector2d c = Centroid(d->left);
    EXPECT_NEAR(c.x(), xs.x(), 0.05) << w;
    EXPECT_NEAR(c.y(), xs.y(), 0.05) << w;
    EXPECT_TRUE(d->left_model.InImage(xs));
  }
}

TEST(DownsampleStereo, FullSizeAndErrors) {
  const geometry::CameraModel model = test::NavcamCahvor();
  const GrayImage img = Image(1024, 768, 9);
  auto same = DownsampleStereo(img, img, model, model, 0);
  ASSERT_TRUE(same.ok());
  EXPECT_EQ(same->left.width, 1024);
  EXPECT_EQ(same->left.pixels, img.pixels);
  EXPECT_NEAR((*same->left_model.Project(Eigen::Vector3d(0.1, 0.1, 2.0)) -
               *model.Project(Eigen::Vector3d(0.1, 0.1, 2.0)))
                  .norm(),
              0.0, 1e-9);
  EXPECT_FALSE(DownsampleStereo(img, Image(512, 384), model, model, 256).ok());
  EXPECT_FALSE(DownsampleStereo(img, img, model, model, 2048).ok());
  const auto small_model = geometry::Scale(model, 0.5);
  auto mismatch = DownsampleStereo(img, img, small_model, model, 256);
  ASSERT_FALSE(mismatch.ok());
  EXPECT_NE(mismatch.status().message().find("left model is for 512x384"), std::string::npos)
      << mismatch.status().message();
}

}  // namespace
}  // namespace rover::ddl::camera
