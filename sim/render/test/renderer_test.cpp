#include "rover/sim/render/renderer.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <vector>

#include "rover/base/units.hpp"
#include "rover/geometry/camera_model.hpp"
#include "rover/sim/render/cameras.hpp"

namespace rover::sim::render {

using terrain::GenerateTerrain;
using terrain::Lander;
using terrain::LanderParams;
using terrain::LanderPart;
using terrain::LanderQuad;
using terrain::PlaceLander;
using terrain::RebuildHeights;
using terrain::Rock;
using terrain::RockPreset;
using terrain::RockRelief;
using terrain::Terrain;
using terrain::TerrainParams;

namespace {

using geometry::CameraModel;
std::shared_ptr<Terrain> MakeTerrain(double size, double hills, RockPreset rocks,
                                     std::uint64_t seed = 3) {
  TerrainParams p;
  p.size_x = p.size_y = size;
  p.hills.amplitude = hills;
  p.craters.count = 0;
  p.rocks.preset = rocks;
  p.seed = seed;
  auto t = GenerateTerrain(p);
  EXPECT_TRUE(t.ok()) << t.status().message();
  return std::make_shared<Terrain>(std::move(*t));
}

RenderOptions GeometryOptions() {
  RenderOptions o;
  o.sensor.noise = false;
  o.sensor.vignetting = 0.0;
  o.output_range = true;
  o.output_radiance = true;
  return o;
}

// Creates a renderer or skips the test when there is no headless OpenGL.
#define CREATE_OR_SKIP(var, terrain, options)                                        \
  auto var##_result = Renderer::Create(terrain, options);                            \
  if (!var##_result.ok() && var##_result.status().code() == StatusCode::kUnavailable) \
    GTEST_SKIP() << "no headless OpenGL: " << var##_result.status().message();       \
  ASSERT_TRUE(var##_result.ok()) << var##_result.status().message();                 \
  Renderer& var = **var##_result

// Camera rotation (columns: right, down, forward) looking along `forward` with +z up.
Eigen::Matrix3d LookAlong(const Eigen::Vector3d& forward) {
  const Eigen::Vector3d f = forward.normalized();
  const Eigen::Vector3d right = f.cross(Eigen::Vector3d::UnitZ()).normalized();
  Eigen::Matrix3d r;
  r.col(0) = right;
  r.col(1) = f.cross(right);
  r.col(2) = f;
  return r;
}

CameraModel PinholeAt(const Eigen::Vector3d& c, const Eigen::Vector3d& forward, double f, int size) {
  geometry::PinholeRadial p;
  p.fx = p.fy = f;
  p.cx = p.cy = 0.5 * (size - 1);
  p.width = p.height = size;
  p.pose.linear() = LookAlong(forward);
  p.pose.translation() = c;
  return *CameraModel::Create(p);
}

// Strong CAHVOR: barrel distortion, optical axis 1 deg off the pointing axis.
CameraModel CahvorAt(const Eigen::Vector3d& c, const Eigen::Vector3d& forward, double f, int size) {
  const Eigen::Matrix3d r = LookAlong(forward);
  geometry::Cahvor m;
  const double centre = 0.5 * (size - 1);
  m.c = c;
  m.a = r.col(2);
  m.h = f * r.col(0) + (centre + 4.0) * m.a;
  m.v = f * r.col(1) + (centre - 3.0) * m.a;
  m.o = (Eigen::AngleAxisd(1.0 * kDegree, r.col(0)) * m.a).normalized();
  m.r = Eigen::Vector3d(0.0, -0.2, 0.05);
  return *CameraModel::Create(m, size, size);
}

LanderQuad Square(const Eigen::Vector2d& centre, double side, double z, double albedo,
                  LanderPart part) {
  LanderQuad q;
  const double h = 0.5 * side;
  q.corners = {Eigen::Vector3d(centre.x() - h, centre.y() - h, z),
               Eigen::Vector3d(centre.x() + h, centre.y() - h, z),
               Eigen::Vector3d(centre.x() + h, centre.y() + h, z),
               Eigen::Vector3d(centre.x() - h, centre.y() + h, z)};
  q.albedo = Eigen::Vector3d::Constant(albedo);
  q.part = part;
  return q;
}

// Ground point (z = 0) seen through `pixel`.
Eigen::Vector3d GroundPoint(const CameraModel& m, const Eigen::Vector2d& pixel) {
  const auto ray = m.Unproject(pixel);
  EXPECT_TRUE(ray.has_value());
  const double t = -ray->origin.z() / ray->direction.z();
  return ray->origin + t * ray->direction;
}

// Area-weighted centroid of a dark square marker on a white background near `predicted`:
// weight = how dark a pixel is between the white and black levels.
Eigen::Vector2d DarkCentroid(const cv::Mat& radiance, const CameraModel& m,
                             const std::array<Eigen::Vector3d, 4>& corners) {
  double x0 = 1e9, x1 = -1e9, y0 = 1e9, y1 = -1e9;
  for (const auto& c : corners) {
    const auto p = m.Project(c);
    EXPECT_TRUE(p.has_value());
    x0 = std::min(x0, p->x());
    x1 = std::max(x1, p->x());
    y0 = std::min(y0, p->y());
    y1 = std::max(y1, p->y());
  }
  const double cx = 0.5 * (x0 + x1), cy = 0.5 * (y0 + y1);
  const double hx = 0.8 * (x1 - x0) + 2.0, hy = 0.8 * (y1 - y0) + 2.0;
  const int c0 = std::max(0, static_cast<int>(cx - hx)), c1 = std::min(radiance.cols - 1, static_cast<int>(cx + hx));
  const int r0 = std::max(0, static_cast<int>(cy - hy)), r1 = std::min(radiance.rows - 1, static_cast<int>(cy + hy));
  // White level: median of the window's border (all on the white square); black: the minimum.
  std::vector<float> border;
  float black = 1e9F;
  for (int r = r0; r <= r1; ++r)
    for (int c = c0; c <= c1; ++c) {
      black = std::min(black, radiance.at<float>(r, c));
      if (r == r0 || r == r1 || c == c0 || c == c1) border.push_back(radiance.at<float>(r, c));
    }
  std::nth_element(border.begin(), border.begin() + static_cast<std::ptrdiff_t>(border.size() / 2), border.end());
  const float white = border[border.size() / 2];
  double sw = 0, sx = 0, sy = 0;
  for (int r = r0; r <= r1; ++r)
    for (int c = c0; c <= c1; ++c) {
      double w = std::clamp((white - radiance.at<float>(r, c)) / (white - black), 0.0F, 1.0F);
      if (w < 0.2) w = 0.0;  // texture of the white square, not the marker
      sw += w;
      sx += w * c;
      sy += w * r;
    }
  return {sx / sw, sy / sw};
}

// Renders a black 10 cm square on a white 80 cm square lying on flat ground where `pixel` of
// `model` looks, and compares its measured centre with model.Project.
void CheckMarker(const CameraModel& model, const Eigen::Vector2d& pixel, double side = 0.1,
                 double bound_px = 0.3) {
  auto terrain = MakeTerrain(16.0, 0.0, RockPreset::kNone);
  const Eigen::Vector3d p = GroundPoint(model, pixel);
  Lander lander;
  lander.quads.push_back(Square(p.head<2>(), 8.0 * side, 0.003, 0.85, LanderPart::kDeck));
  lander.quads.push_back(Square(p.head<2>(), side, 0.006, 0.03, LanderPart::kStripe));
  terrain->lander = lander;
  CREATE_OR_SKIP(renderer, terrain, GeometryOptions());
  auto img = renderer.RenderCamera(Eigen::Isometry3d::Identity(), model);
  ASSERT_TRUE(img.ok()) << img.status().message();
  // The model's prediction of the marker's image: the area centroid of its projected outline
  // (each edge projected at 40 points, so distortion is included). Under perspective this is
  // not the projection of the square's centre (the near half looks bigger).
  std::vector<Eigen::Vector2d> outline;
  const auto& q = lander.quads[1].corners;
  for (int e = 0; e < 4; ++e) {
    for (int k = 0; k < 40; ++k) {
      const Eigen::Vector3d x = q[static_cast<std::size_t>(e)] +
                                (q[static_cast<std::size_t>((e + 1) % 4)] - q[static_cast<std::size_t>(e)]) * (k / 40.0);
      const auto px = model.Project(x);
      ASSERT_TRUE(px.has_value());
      outline.push_back(*px);
    }
  }
  double area = 0, cx = 0, cy = 0;
  for (std::size_t k = 0; k < outline.size(); ++k) {
    const Eigen::Vector2d& a = outline[k];
    const Eigen::Vector2d& b = outline[(k + 1) % outline.size()];
    const double cross = a.x() * b.y() - b.x() * a.y();
    area += cross;
    cx += (a.x() + b.x()) * cross;
    cy += (a.y() + b.y()) * cross;
  }
  const std::optional<Eigen::Vector2d> predicted = Eigen::Vector2d(cx / (3 * area), cy / (3 * area));
  const Eigen::Vector2d measured = DarkCentroid(img->radiance, model, lander.quads[1].corners);
  EXPECT_LT((measured - *predicted).norm(), 1.0)
      << "predicted " << predicted->transpose() << " measured " << measured.transpose();
  EXPECT_LT((measured - *predicted).norm(), bound_px)  // what the warp achieves (README)
      << "predicted " << predicted->transpose() << " measured " << measured.transpose();
  std::printf("[ info ] marker at (%.1f, %.1f): error %.3f px\n", predicted->x(), predicted->y(),
              (measured - *predicted).norm());
}

TEST(RenderOptionsTest, BinnedSupersampleIsCheckedByName) {
  RenderOptions o;
  EXPECT_TRUE(o.Validate().ok());
  o.binned_supersample = 5;
  EXPECT_NE(o.Validate().message().find("binned_supersample"), std::string::npos)
      << o.Validate().message();
  o.binned_supersample = 0;
  EXPECT_FALSE(o.Validate().ok());
}

TEST(RendererTest, MarkerAppearsWherePinholePredicts) {
  const CameraModel m = PinholeAt({0, 0, 1.5}, {1, 0, -0.6}, 450.0, 512);
  CheckMarker(m, {256, 256});
  CheckMarker(m, {70, 430});
}

TEST(RendererTest, MarkerAppearsWhereCahvorPredicts) {
  const CameraModel m = CahvorAt({0, 0, 1.5}, {1, 0, -0.6}, 450.0, 512);
  CheckMarker(m, {60, 440});
  CheckMarker(m, {470, 300});
}

TEST(RendererTest, MarkerAppearsWhereHazcamPredicts) {
  // The 120 deg CAHVOR stretches the field edges; a small far marker covers few pixels, so the
  // bound is wider than for the NAVCAM (measured 0.32 / 0.16 / 0.50 px, README).
  const auto haz = *FindStereoCamera(DefaultStereoCameras(512), "front_hazcam");
  CheckMarker(haz.left, {256, 300}, 0.05, 0.6);
  CheckMarker(haz.left, {40, 470}, 0.05, 0.6);   // side cube face
  CheckMarker(haz.left, {380, 190}, 0.15, 0.6);  // farther away, towards the horizon
}

// Range image: every pixel's point C + range * ray lies on the terrain surface.
TEST(RendererTest, RangeLiesOnTerrain) {
  auto terrain = MakeTerrain(30.0, 0.35, RockPreset::kNone);
  CREATE_OR_SKIP(renderer, terrain, GeometryOptions());
  const Eigen::Isometry3d pose = RoverPoseOnGround(terrain->ground, 0.5, 0.3, 0.4);
  const auto cams = DefaultStereoCameras(512);
  for (const auto& def : cams) {
    auto spec = MakeCameraPairSpec(def, {0.2, -30 * kDegree});
    ASSERT_TRUE(spec.ok());
    auto pair = renderer.RenderStereoPair(pose, *spec);
    ASSERT_TRUE(pair.ok()) << pair.status().message();
    const CameraModel site = geometry::Transform(spec->LeftInRover(), pose);
    std::vector<double> err;
    for (int y = 0; y < 512; y += 7) {
      for (int x = 0; x < 512; x += 7) {
        const float r = pair->left.range.at<float>(y, x);
        if (!(r > 0.0F) || r > 14.0F) continue;
        const auto ray = site.Unproject(Eigen::Vector2d(x, y));
        ASSERT_TRUE(ray.has_value());
        const Eigen::Vector3d p = ray->origin + r * ray->direction;
        if (!terrain->natural.Contains(p.x(), p.y())) continue;
        err.push_back(std::abs(p.z() - terrain->natural.Height(p.x(), p.y())));
      }
    }
    ASSERT_GT(err.size(), 1000u) << def.name;
    std::sort(err.begin(), err.end());
    EXPECT_LT(err[err.size() / 2], 0.005) << def.name;
    EXPECT_LT(err[err.size() * 95 / 100], 0.03) << def.name;
  }
}

// A stereo pair looking straight down at flat textured ground from 2 m: after rectification the
// disparity found by 7x7 SAD correlation equals f B / Z.
TEST(RendererTest, DisparityMatchesStereoGeometry) {
  auto terrain = MakeTerrain(16.0, 0.0, RockPreset::kNone);
  RenderOptions o;  // realistic sensor noise
  CREATE_OR_SKIP(renderer, terrain, o);
  const double z = 2.0, b = 0.2, f = 500.0;
  auto make = [&](double y) {
    geometry::Cahv m;
    m.c = Eigen::Vector3d(0.3, y, z);
    m.a = Eigen::Vector3d(0, 0, -1);
    m.h = f * Eigen::Vector3d(0, -1, 0) + 255.5 * m.a;
    m.v = f * Eigen::Vector3d(-1, 0, 0) + 255.5 * m.a;
    return *CameraModel::Create(m, 512, 512);
  };
  const CameraPairSpec spec{make(0.5 * b), make(-0.5 * b), Eigen::Isometry3d::Identity()};
  auto pair = renderer.RenderStereoPair(Eigen::Isometry3d::Identity(), spec, 4);
  ASSERT_TRUE(pair.ok()) << pair.status().message();
  auto rect = geometry::RectifyStereoPair(spec.left, spec.right);
  ASSERT_TRUE(rect.ok());
  auto warp = [](const cv::Mat& img, const std::vector<float>& mx, const std::vector<float>& my) {
    cv::Mat map_x(img.rows, img.cols, CV_32FC1, const_cast<float*>(mx.data()));
    cv::Mat map_y(img.rows, img.cols, CV_32FC1, const_cast<float*>(my.data()));
    cv::Mat out;
    cv::remap(img, out, map_x, map_y, cv::INTER_LINEAR);
    return out;
  };
  cv::Mat l, r;
  warp(pair->left.image, rect->left_map_x, rect->left_map_y).convertTo(l, CV_32F);
  warp(pair->right.image, rect->right_map_x, rect->right_map_y).convertTo(r, CV_32F);
  const double expected = rect->focal_px * rect->baseline_m / z;
  std::vector<double> d;
  for (int y = 40; y < 470; y += 20) {
    for (int x = 120; x < 470; x += 20) {
      std::vector<double> sad;
      const int dmin = 20, dmax = 90;
      for (int dd = dmin; dd <= dmax; ++dd) {
        double s = 0;
        for (int v = -3; v <= 3; ++v)
          for (int u = -3; u <= 3; ++u) s += std::abs(l.at<float>(y + v, x + u) - r.at<float>(y + v, x + u - dd));
        sad.push_back(s);
      }
      const auto best = std::min_element(sad.begin() + 1, sad.end() - 1) - sad.begin();
      const double a = sad[static_cast<std::size_t>(best - 1)], c = sad[static_cast<std::size_t>(best)],
                   e = sad[static_cast<std::size_t>(best + 1)];
      const double denom = a - 2 * c + e;
      d.push_back(dmin + best + (denom > 0 ? 0.5 * (a - e) / denom : 0.0));
    }
  }
  std::sort(d.begin(), d.end());
  const double median = d[d.size() / 2];
  EXPECT_NEAR(median, expected, 0.5) << "expected f B / Z = " << expected;
  std::printf("[ info ] disparity: median %.3f px, f B / Z = %.3f px\n", median, expected);
  const auto good = std::count_if(d.begin(), d.end(), [&](double v) { return std::abs(v - expected) < 1.0; });
  EXPECT_GT(static_cast<double>(good) / d.size(), 0.9) << "SAD matches within 1 px";
}

TEST(RendererTest, SameSeedSameImages) {
  auto terrain = MakeTerrain(20.0, 0.35, RockPreset::kVl1);
  RenderOptions o;
  CREATE_OR_SKIP(a, terrain, o);
  const auto nav = *FindStereoCamera(DefaultStereoCameras(256), "navcam");
  const auto spec = *MakeCameraPairSpec(nav, {0.0, -25 * kDegree});
  const Eigen::Isometry3d pose = RoverPoseOnGround(terrain->ground, 0, 0, 0.2);
  auto p1 = a.RenderStereoPair(pose, spec, 7);
  auto p2 = a.RenderStereoPair(pose, spec, 7);
  auto p3 = a.RenderStereoPair(pose, spec, 8);
  ASSERT_TRUE(p1.ok() && p2.ok() && p3.ok());
  EXPECT_EQ(cv::norm(p1->left.image, p2->left.image, cv::NORM_L1), 0.0);
  EXPECT_EQ(cv::norm(p1->right.image, p2->right.image, cv::NORM_L1), 0.0);
  EXPECT_GT(cv::norm(p1->left.image, p3->left.image, cv::NORM_L1), 0.0);  // new noise
  EXPECT_GT(cv::norm(p1->left.image, p1->right.image, cv::NORM_L1), 0.0);
  CREATE_OR_SKIP(b, terrain, o);  // a second renderer, same seed
  auto q = b.RenderStereoPair(pose, spec, 7);
  ASSERT_TRUE(q.ok());
  EXPECT_EQ(cv::norm(p1->left.image, q->left.image, cv::NORM_L1), 0.0);
  o.seed = 2;
  CREATE_OR_SKIP(c, terrain, o);
  auto s = c.RenderStereoPair(pose, spec, 7);
  ASSERT_TRUE(s.ok());
  EXPECT_GT(cv::norm(p1->left.image, s->left.image, cv::NORM_L1), 0.0);
}

// Soil only (no rocks): the fine texture must give corner detectors and correlation structure.
TEST(RendererTest, SoilHasTexture) {
  auto terrain = MakeTerrain(30.0, 0.35, RockPreset::kNone);
  RenderOptions o;
  CREATE_OR_SKIP(renderer, terrain, o);
  const Eigen::Isometry3d pose = RoverPoseOnGround(terrain->ground, 0, 0, 0.0);
  for (int size : {256, 512, 1024}) {
    const auto nav = *FindStereoCamera(DefaultStereoCameras(size), "navcam");
    auto pair = renderer.RenderStereoPair(pose, *MakeCameraPairSpec(nav, {0.0, -40 * kDegree}));
    ASSERT_TRUE(pair.ok());
    const cv::Mat& img = pair->left.image;
    std::vector<cv::Point2f> corners;
    cv::goodFeaturesToTrack(img, corners, 5000, 0.01, 5);
    // Local contrast: 7x7 standard deviation.
    cv::Mat f, mean, sq;
    img.convertTo(f, CV_32F);
    cv::blur(f, mean, cv::Size(7, 7));
    cv::blur(f.mul(f), sq, cv::Size(7, 7));
    cv::Mat sd;
    cv::sqrt(cv::max(sq - mean.mul(mean), 0.0), sd);
    const double mean_sd = cv::mean(sd)[0];
    const double per_mpx = corners.size() / (size * size / 1.0e6);
    EXPECT_GT(per_mpx, 1500.0) << size << " px: " << corners.size() << " corners";
    EXPECT_GT(mean_sd, 3.0) << size << " px";
    std::printf("[ info ] navcam %d px soil: %zu Shi-Tomasi corners, mean 7x7 sd %.1f DN\n", size,
                corners.size(), mean_sd);
  }
}

// One rock, sun from the north (+x) 30 deg high, seen from the east (-y): its north flank is
// lit, its south flank and the ground south of it are in shadow.
TEST(RendererTest, RockShadowSideIsDarker) {
  auto terrain = MakeTerrain(16.0, 0.0, RockPreset::kNone);
  Rock rock;
  rock.id = terrain->next_rock_id++;
  rock.position = Eigen::Vector3d(3.0, 0.0, 0.0);
  rock.diameter = 1.0;
  rock.height = 0.5;
  rock.bluntness = 0.5;
  terrain->rocks.push_back(rock);
  RebuildHeights(terrain.get());
  RenderOptions o = GeometryOptions();
  o.sun.azimuth_deg = 0.0;
  o.sun.elevation_deg = 30.0;
  CREATE_OR_SKIP(renderer, terrain, o);
  const CameraModel m = PinholeAt({3.0, -4.0, 1.2}, {0.0, 4.0, -1.0}, 500.0, 512);
  auto img = renderer.RenderCamera(Eigen::Isometry3d::Identity(), m);
  ASSERT_TRUE(img.ok());
  auto sample = [&](const Eigen::Vector3d& p) {
    const auto px = m.Project(p);
    EXPECT_TRUE(px && m.InImage(*px));
    const int c = static_cast<int>(std::lround(px->x())), r = static_cast<int>(std::lround(px->y()));
    // The surface seen there is the point itself (not occluded).
    EXPECT_NEAR(img->range.at<float>(r, c), (p - m.Center()).norm(), 0.05);
    return cv::mean(img->radiance(cv::Rect(c - 2, r - 2, 5, 5)))[0];
  };
  auto on_rock = [&](double phi) {
    const double x = 3.0 + 0.3 * std::cos(phi), y = 0.3 * std::sin(phi);
    return Eigen::Vector3d(x, y, RockRelief(rock, x, y));
  };
  const double lit = sample(on_rock(-40 * kDegree)), dark = sample(on_rock(-140 * kDegree));
  EXPECT_GT(lit, 1.8 * dark) << "lit flank " << lit << ", shadow flank " << dark;
  const double ground_shadow = sample({2.35, 0.0, 0.0});
  const double ground_lit = sample({2.35, -1.0, 0.0});
  EXPECT_LT(ground_shadow, 0.6 * ground_lit) << "cast shadow " << ground_shadow << ", open ground " << ground_lit;
}

TEST(RendererTest, LanderIsDrawn) {
  TerrainParams p;
  p.size_x = p.size_y = 20.0;
  p.rocks.preset = RockPreset::kNone;
  auto t = GenerateTerrain(p);
  ASSERT_TRUE(t.ok());
  LanderParams lp;
  lp.x = 5.0;
  ASSERT_TRUE(PlaceLander(&*t, lp).ok());
  auto terrain = std::make_shared<Terrain>(std::move(*t));
  CREATE_OR_SKIP(renderer, terrain, GeometryOptions());
  const CameraModel m = PinholeAt({0.0, 0.0, 1.5}, {1.0, 0.0, -0.15}, 400.0, 256);
  auto img = renderer.RenderCamera(Eigen::Isometry3d::Identity(), m);
  ASSERT_TRUE(img.ok());
  // The deck's front edge at x = 5 - 1.5 cos 30 is 1 m up: the centre column sees it there.
  const auto deck = m.Project(Eigen::Vector3d(5.0 - 1.3, 0.0, terrain->lander->deck_z - 0.1));
  ASSERT_TRUE(deck.has_value());
  const float r = img->range.at<float>(static_cast<int>(deck->y()), static_cast<int>(deck->x()));
  EXPECT_NEAR(r, (Eigen::Vector3d(5.0 - 1.3, 0.0, terrain->lander->deck_z - 0.1) - m.Center()).norm(), 0.3);
}

// The microscopic imager's close-up: a camera looking straight down from the focus distance
// sees the soil's texture sharp; 2 cm higher the same patch is blurred by the depth of field.
TEST(RendererTest, CloseUpHasDepthOfField) {
  auto terrain = MakeTerrain(8.0, 0.0, RockPreset::kNone);
  RenderOptions o;
  o.sensor.noise = false;
  CREATE_OR_SKIP(r, terrain, o);
  const double ground = terrain->natural.Height(1.0, 0.5);
  DepthOfField dof;  // in focus 6 cm ahead
  auto shoot = [&](double above) {
    geometry::PinholeRadial p;
    p.fx = p.fy = 750.0;
    p.cx = p.cy = 127.5;
    p.width = p.height = 256;
    p.pose.linear().col(0) = Eigen::Vector3d(0, -1, 0);  // right
    p.pose.linear().col(1) = Eigen::Vector3d(-1, 0, 0);  // down
    p.pose.linear().col(2) = Eigen::Vector3d(0, 0, -1);  // forward: straight down
    p.pose.translation() = Eigen::Vector3d(1.0, 0.5, ground + above);
    auto img = r.RenderCloseUp(Eigen::Isometry3d::Identity(), *CameraModel::Create(p), dof, 1);
    EXPECT_TRUE(img.ok()) << img.status().message();
    return *img;
  };
  const CameraImage sharp = shoot(0.06);
  const CameraImage blurred = shoot(0.08);
  // The range is returned: the ground at the image centre 6 cm away.
  EXPECT_NEAR(sharp.range.at<float>(128, 128), 0.06, 0.002);
  auto detail = [](const cv::Mat& img) {
    cv::Mat f, lap;
    img.convertTo(f, CV_32F);
    cv::Laplacian(f, lap, CV_32F, 3);
    cv::Scalar mean, sd;
    cv::meanStdDev(lap, mean, sd);
    return sd[0];
  };
  cv::Scalar mean, sd;
  cv::meanStdDev(sharp.image, mean, sd);
  EXPECT_GT(sd[0], 3.0) << "no texture at the close-up scale";
  EXPECT_GT(detail(sharp.image), 2.0 * detail(blurred.image));
  DepthOfField bad;
  bad.near = 0.1;
  EXPECT_FALSE(r.RenderCloseUp(Eigen::Isometry3d::Identity(),
                               PinholeAt({1, 0.5, 1}, {1, 0, -1}, 300, 64), bad)
                   .ok());
}

TEST(RendererTest, BadInputIsReported) {
  auto terrain = MakeTerrain(8.0, 0.0, RockPreset::kNone);
  RenderOptions o;
  o.tile_cells = 48;
  auto r = Renderer::Create(terrain, o);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("render.tile_cells"), std::string::npos);
  o = {};
  o.sun.elevation_deg = 0.0;
  EXPECT_NE(Renderer::Create(terrain, o).status().message().find("sun.elevation_deg"), std::string::npos);
  EXPECT_EQ(Renderer::Create(nullptr, {}).status().code(), StatusCode::kInvalidArgument);
  CREATE_OR_SKIP(renderer, terrain, RenderOptions{});
  Eigen::Isometry3d bad = Eigen::Isometry3d::Identity();
  bad.translation().x() = std::nan("");
  const auto nav = *FindStereoCamera(DefaultStereoCameras(64), "navcam");
  auto pair = renderer.RenderStereoPair(bad, *MakeCameraPairSpec(nav));
  ASSERT_FALSE(pair.ok());
  EXPECT_EQ(pair.status().code(), StatusCode::kInvalidArgument);
  bad = Eigen::Isometry3d::Identity();
  bad.linear() *= 2.0;
  EXPECT_FALSE(renderer.RenderStereoPair(bad, *MakeCameraPairSpec(nav)).ok());
  EXPECT_FALSE(renderer.SetSun({0.0, -5.0}).ok());
  EXPECT_TRUE(renderer.SetSun({90.0, 60.0}).ok());
  EXPECT_TRUE(renderer.RenderStereoPair(Eigen::Isometry3d::Identity(), *MakeCameraPairSpec(nav)).ok());
}

}  // namespace
}  // namespace rover::sim::render
