#include "src/view_planner.hpp"

#include <gtest/gtest.h>

#include <numbers>

#include "rover/sim/render/cameras.hpp"

namespace rover::sim::render::internal {
namespace {

geometry::CameraModel Pinhole(double f, int w, int h) {
  geometry::PinholeRadial p;
  p.fx = p.fy = f;
  p.cx = 0.5 * (w - 1) + 3.0;
  p.cy = 0.5 * (h - 1) - 2.0;
  p.width = w;
  p.height = h;
  p.pose.linear() = Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  p.pose.translation() = Eigen::Vector3d(1, 2, 3);
  return *geometry::CameraModel::Create(p);
}

// Every mapped output pixel's atlas position, taken back through its view, gives the pixel's ray.
void CheckMapsReproduceRays(const geometry::CameraModel& model, const WarpPlan& plan) {
  const geometry::CameraModel canon = CanonicalModel(model);
  for (int y = 0; y < plan.out_height; y += 37) {
    for (int x = 0; x < plan.out_width; x += 41) {
      const float ax = plan.map_x.at<float>(y, x), ay = plan.map_y.at<float>(y, x);
      ASSERT_GE(ax, 0.0F);
      // Find the view holding this atlas row.
      const VirtualView* v = nullptr;
      for (const auto& view : plan.views)
        if (ay >= view.atlas_y && ay < view.atlas_y + view.height) v = &view;
      ASSERT_NE(v, nullptr);
      EXPECT_GE(ax, 1.0F);
      EXPECT_LE(ax, v->width - 2.0F);
      const Eigen::Vector3d d_view((ax - v->cx) / v->f, (ay - v->atlas_y - v->cy) / v->f, 1.0);
      const Eigen::Vector3d d = (v->cam_from_view * d_view).normalized();
      const auto back = canon.Project(d);
      ASSERT_TRUE(back.has_value());
      EXPECT_NEAR(back->x(), x, 1e-3);
      EXPECT_NEAR(back->y(), y, 1e-3);
    }
  }
}

TEST(ViewPlannerTest, PinholeIsOneViewAtItsFocalLength) {
  const auto m = Pinhole(400, 320, 240);
  auto plan = PlanWarp(m, {});
  ASSERT_TRUE(plan.ok());
  ASSERT_EQ(plan->views.size(), 1u);
  EXPECT_NEAR(plan->views[0].f, 400.0, 1.0);
  EXPECT_EQ(plan->views[0].width, 320 + 2 * 3 + 1);
  CheckMapsReproduceRays(m, *plan);
}

TEST(ViewPlannerTest, NavcamSingleViewHazcamCubeFaces) {
  const auto cams = DefaultStereoCameras(256);
  auto nav = PlanWarp(cams[0].left, {});
  ASSERT_TRUE(nav.ok());
  EXPECT_EQ(nav->views.size(), 1u);
  CheckMapsReproduceRays(cams[0].left, *nav);
  auto haz = PlanWarp(cams[1].left, {});
  ASSERT_TRUE(haz.ok());
  EXPECT_EQ(haz->views.size(), 5u);  // front and four side faces, no back face
  EXPECT_GE(haz->min_density_ratio, 1.0);
  CheckMapsReproduceRays(cams[1].left, *haz);
  // Every pixel of the fisheye has a ray.
  EXPECT_EQ(cv::countNonZero(haz->map_x < 0.0F), 0);
}

TEST(ViewPlannerTest, KeyIgnoresPoseButNotIntrinsics) {
  const auto cams = DefaultStereoCameras(256);
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = Eigen::AngleAxisd(1.1, Eigen::Vector3d(0.3, -1, 0.2).normalized()).toRotationMatrix();
  t.translation() = Eigen::Vector3d(10, -4, 2);
  EXPECT_EQ(WarpKey(cams[0].left), WarpKey(geometry::Transform(cams[0].left, t)));
  EXPECT_EQ(WarpKey(cams[0].left), WarpKey(cams[0].right));
  EXPECT_NE(WarpKey(cams[0].left), WarpKey(cams[1].left));
  EXPECT_NE(WarpKey(cams[0].left), WarpKey(geometry::Scale(cams[0].left, 0.5)));
}

TEST(ViewPlannerTest, OversampleRaisesDensity) {
  const auto m = Pinhole(300, 200, 200);
  PlanOptions o;
  o.oversample = 2.0;
  auto plan = PlanWarp(m, o);
  ASSERT_TRUE(plan.ok());
  EXPECT_NEAR(plan->views[0].f, 600.0, 2.0);
  o.max_atlas_size = 100;
  EXPECT_FALSE(PlanWarp(m, o).ok());
}

}  // namespace
}  // namespace rover::sim::render::internal
