// Range along a ray: a textured plane seen by two pinhole cameras (drawn here from the models,
// so the truth is exact), bad input named, no texture and no overlap reported as not found.
#include "rover/apl/rendezvous/ray_stereo.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

namespace rover::apl::rendezvous {
namespace {

geometry::CameraModel Pinhole(double x_offset) {
  geometry::PinholeRadial p;
  p.fx = p.fy = 400.0;
  p.cx = p.cy = 159.5;
  p.width = p.height = 320;
  p.pose.translation() = Eigen::Vector3d(x_offset, 0.0, 0.0);
  return *geometry::CameraModel::Create(p);
}

// The image of the plane z = depth with a blob texture (texel 5 mm) through `model`.
cv::Mat Draw(const geometry::CameraModel& model, double depth, const cv::Mat& texture) {
  cv::Mat mapx(model.height(), model.width(), CV_32F), mapy(model.height(), model.width(), CV_32F);
  for (int r = 0; r < model.height(); ++r) {
    for (int c = 0; c < model.width(); ++c) {
      const auto ray = model.Unproject(Eigen::Vector2d(c, r));
      const double s = (depth - ray->origin.z()) / ray->direction.z();
      const Eigen::Vector3d p = ray->origin + s * ray->direction;
      mapx.at<float>(r, c) = static_cast<float>(p.x() / 0.005 + texture.cols / 2);
      mapy.at<float>(r, c) = static_cast<float>(p.y() / 0.005 + texture.rows / 2);
    }
  }
  cv::Mat out;
  cv::remap(texture, out, mapx, mapy, cv::INTER_LINEAR, cv::BORDER_REFLECT);
  return out;
}

cv::Mat Texture() {
  cv::Mat t(1200, 1200, CV_8UC1);
  cv::RNG rng(7);
  rng.fill(t, cv::RNG::UNIFORM, 0, 255);
  cv::GaussianBlur(t, t, cv::Size(0, 0), 1.5);
  cv::normalize(t, t, 0, 255, cv::NORM_MINMAX);
  return t;
}

TEST(MatchAlongRayTest, RangesATexturedPlaneToAFractionOfThePixelStep) {
  const auto left = Pinhole(0.0), right = Pinhole(0.2);
  const cv::Mat texture = Texture();
  for (double depth : {1.0, 2.5, 6.0}) {
    const cv::Mat l = Draw(left, depth, texture), r = Draw(right, depth, texture);
    RayMatchOptions o;
    o.t_max = 20.0;
    for (const Eigen::Vector2d& px : {Eigen::Vector2d(100, 120), Eigen::Vector2d(160, 160),
                                      Eigen::Vector2d(140, 60)}) {
      auto m = MatchAlongRay(l, left, r, right, px, o);
      ASSERT_TRUE(m.ok()) << m.status().message();
      ASSERT_TRUE(m->found) << depth << ": " << m->why;
      // Disparity f B / z: 0.1 px of it is z^2 / (f B) x 0.1 in depth.
      const double tol = depth * depth / (400.0 * 0.2) * 0.1 + 1e-4;
      EXPECT_NEAR(m->point.z(), depth, tol) << "depth " << depth << " px " << px.transpose();
      EXPECT_GT(m->ncc, 0.9);
      EXPECT_GT(m->sigma_t, 0.0);
    }
  }
}

TEST(MatchAlongRayTest, NoTextureOrNoOverlapIsNotFound) {
  const auto left = Pinhole(0.0), right = Pinhole(0.2);
  const cv::Mat flat(320, 320, CV_8UC1, cv::Scalar(100));
  auto m = MatchAlongRay(flat, left, flat, right, Eigen::Vector2d(160, 160));
  ASSERT_TRUE(m.ok());
  EXPECT_FALSE(m->found);
  EXPECT_NE(m->why.find("no texture"), std::string::npos) << m->why;
  // Searched only nearer than the plane: the best match is at the far end.
  const cv::Mat texture = Texture();
  const cv::Mat l = Draw(left, 3.0, texture), r = Draw(right, 3.0, texture);
  RayMatchOptions o;
  o.t_min = 1.0;
  o.t_max = 2.0;
  m = MatchAlongRay(l, left, r, right, Eigen::Vector2d(160, 160), o);
  ASSERT_TRUE(m.ok());
  EXPECT_FALSE(m->found);
}

TEST(MatchAlongRayTest, BadInputIsNamed) {
  const auto left = Pinhole(0.0), right = Pinhole(0.2);
  const cv::Mat im(320, 320, CV_8UC1, cv::Scalar(100));
  auto m = MatchAlongRay(im, left, im, right, Eigen::Vector2d(400, 10));
  ASSERT_FALSE(m.ok());
  EXPECT_NE(m.status().message().find("pixel (400, 10)"), std::string::npos) << m.status().message();
  m = MatchAlongRay(cv::Mat(100, 100, CV_8UC1), left, im, right, Eigen::Vector2d(10, 10));
  ASSERT_FALSE(m.ok());
  EXPECT_NE(m.status().message().find("sizes"), std::string::npos);
  RayMatchOptions o;
  o.t_max = 0.1;
  m = MatchAlongRay(im, left, im, right, Eigen::Vector2d(10, 10), o);
  ASSERT_FALSE(m.ok());
  EXPECT_NE(m.status().message().find("ray_match.t_max"), std::string::npos);
}

}  // namespace
}  // namespace rover::apl::rendezvous
