#include "goodness_render.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "rover/apl/gestalt/arc_geometry.hpp"

namespace rover::apl::gestalt::testing {
namespace {

// Site point -> image pixel (x right, y up).
cv::Point Pixel(const nav_core::GoodnessMap& map, const RenderOptions& o, double x, double y) {
  const double px = (x - map.origin_x) / map.resolution * o.pixels_per_cell;
  const double py = (map.height - (y - map.origin_y) / map.resolution) * o.pixels_per_cell;
  return {static_cast<int>(std::lround(px)), static_cast<int>(std::lround(py))};
}

cv::Vec3b GoodnessColour(int g, bool border) {
  // Red (0) -> yellow (128) -> green (255), BGR.
  const double t = std::clamp(g, 0, 255) / 255.0;
  double r = 0.0, gr = 0.0;
  if (t < 0.5) {
    r = 230.0;
    gr = 230.0 * t / 0.5;
  } else {
    r = 230.0 * (1.0 - (t - 0.5) / 0.5);
    gr = 200.0 + 30.0 * (1.0 - t);
  }
  cv::Vec3b c(40, static_cast<std::uint8_t>(gr), static_cast<std::uint8_t>(r));
  if (border) {
    for (int k = 0; k < 3; ++k) c[k] = static_cast<std::uint8_t>(c[k] + (255 - c[k]) / 2);
  }
  return c;
}

}  // namespace

cv::Mat RenderGoodnessMap(const nav_core::GoodnessMap& map, const RenderOptions& o) {
  const int ppc = o.pixels_per_cell;
  cv::Mat img(map.height * ppc, map.width * ppc, CV_8UC3, cv::Scalar(60, 60, 60));
  for (int j = 0; j < map.height; ++j) {
    for (int i = 0; i < map.width; ++i) {
      const nav_core::CellValue v = map.At(i, j);
      if (!v.known()) continue;
      const cv::Vec3b c = GoodnessColour(v.goodness, (v.flags & nav_core::kCellBorder) != 0);
      const int row = (map.height - 1 - j) * ppc;
      cv::rectangle(img, cv::Rect(i * ppc, row, ppc, ppc), cv::Scalar(c[0], c[1], c[2]),
                    cv::FILLED);
    }
  }
  return img;
}

void DrawRocks(const nav_core::GoodnessMap& map, const std::vector<sim::terrain::Rock>& rocks,
               const RenderOptions& o, cv::Mat* image) {
  for (const sim::terrain::Rock& rock : rocks) {
    const std::vector<Eigen::Vector2d> outline = sim::terrain::RockOutline(rock, 16);
    std::vector<cv::Point> pts;
    for (const auto& p : outline) pts.push_back(Pixel(map, o, p.x(), p.y()));
    const cv::Scalar colour =
        rock.height >= o.hazard_height ? cv::Scalar(0, 0, 160) : cv::Scalar(235, 235, 235);
    cv::polylines(*image, pts, true, colour, 1, cv::LINE_AA);
  }
}

void DrawRover(const nav_core::GoodnessMap& map, const Eigen::Isometry3d& site_from_rover,
               const RenderOptions& o, cv::Mat* image) {
  const Pose2 pose = PlanarPose(site_from_rover);
  const cv::Point c = Pixel(map, o, pose.x, pose.y);
  const cv::Point h =
      Pixel(map, o, pose.x + 0.6 * std::cos(pose.yaw), pose.y + 0.6 * std::sin(pose.yaw));
  cv::circle(*image, c, o.pixels_per_cell, cv::Scalar(200, 80, 0), cv::FILLED, cv::LINE_AA);
  cv::line(*image, c, h, cv::Scalar(200, 80, 0), 2, cv::LINE_AA);
}

void DrawArcs(const nav_core::GoodnessMap& map, const Eigen::Isometry3d& site_from_rover,
              const nav_core::ArcEvaluation& e, const RenderOptions& o, cv::Mat* image) {
  const Pose2 pose = PlanarPose(site_from_rover);
  const double c = std::cos(pose.yaw), s = std::sin(pose.yaw);
  for (std::size_t k = 0; k < e.candidates.size(); ++k) {
    const nav_core::Candidate& cand = e.candidates[k];
    if (cand.kind != nav_core::MotionKind::kArc) continue;
    const bool chosen = static_cast<int>(k) == e.chosen;
    std::vector<cv::Point> pts;
    for (int n = 0; n <= 30; ++n) {
      const Eigen::Vector2d p = ArcPoint(cand.curvature, cand.direction, cand.length * n / 30.0);
      pts.push_back(Pixel(map, o, pose.x + c * p.x() - s * p.y(), pose.y + s * p.x() + c * p.y()));
    }
    if (e.hazard[k].goodness == 0 && !chosen) continue;  // forbidden: not drawn
    cv::polylines(*image, pts, false,
                  chosen ? cv::Scalar(255, 255, 255) : cv::Scalar(140, 140, 140), chosen ? 3 : 1,
                  cv::LINE_AA);
  }
}

void DrawPath(const nav_core::GoodnessMap& map, const std::vector<Eigen::Vector2d>& path,
              const RenderOptions& o, cv::Mat* image) {
  std::vector<cv::Point> pts;
  for (const auto& p : path) pts.push_back(Pixel(map, o, p.x(), p.y()));
  if (pts.size() >= 2) cv::polylines(*image, pts, false, cv::Scalar(255, 160, 60), 2, cv::LINE_AA);
}

Status WritePng(const cv::Mat& image, const std::string& path) {
  try {
    if (cv::imwrite(path, image)) return Status::Ok();
  } catch (const cv::Exception& e) {
    return Unavailable("cannot write " + path + ": " + e.what());
  }
  return Unavailable("cannot write " + path);
}

}  // namespace rover::apl::gestalt::testing
