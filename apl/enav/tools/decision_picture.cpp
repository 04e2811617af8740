#include "decision_picture.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

namespace rover::apl::enav {
namespace {

// Site (x north, y west) to pixels of a window about c: north up, west left.
struct View {
  Eigen::Vector2d c;
  double half = 7.0, ppm = 40.0;
  cv::Point Px(const Eigen::Vector2d& p) const {
    return {static_cast<int>(std::lround((c.y() - p.y() + half) * ppm)),
            static_cast<int>(std::lround((c.x() - p.x() + half) * ppm))};
  }
  Eigen::Vector2d Site(int r, int q) const {
    return {c.x() + half - (r + 0.5) / ppm, c.y() + half - (q + 0.5) / ppm};
  }
  int size() const { return static_cast<int>(std::lround(2 * half * ppm)); }
};

void DrawTreePath(const EnavPlanner& planner, const geometry::Pose2& start, const TreePath& p,
                  const View& v, const cv::Scalar& colour, int width, cv::Mat* img) {
  std::vector<cv::Point> pts{v.Px(start.xy())};
  for (const geometry::Pose2& s : planner.Samples(start, p)) pts.push_back(v.Px(s.xy()));
  cv::polylines(*img, pts, false, colour, width, cv::LINE_AA);
}

void DrawFootprint(const hwconfig::RoverDescription& rover, const geometry::Pose2& at,
                   const View& v, cv::Mat* img) {
  const hwconfig::Footprint f = rover.GroundFootprint();
  const Eigen::Vector2d corners[4] = {
      {f.min_x, f.min_y}, {f.max_x, f.min_y}, {f.max_x, f.max_y}, {f.min_x, f.max_y}};
  std::vector<cv::Point> pts;
  for (const Eigen::Vector2d& c : corners) pts.push_back(v.Px(at.ToSite(c)));
  cv::polylines(*img, pts, true, cv::Scalar(255, 255, 255), 1, cv::LINE_AA);
}

}  // namespace

cv::Mat DrawDecision(const EnavPlanner& planner, const nav_core::HeightMap& m,
                     const hwconfig::RoverDescription& rover,
                     const std::vector<Eigen::Vector2d>& trail,
                     const std::vector<PictureRock>& rocks, const PictureOptions& options) {
  const PlanRecord& rec = planner.last();
  View v;
  v.c = rec.start.xy();
  v.half = options.half;
  v.ppm = options.ppm;
  const int s = v.size();
  cv::Mat left(s, s, CV_8UC3, cv::Scalar(60, 60, 60));
  for (int r = 0; r < s; ++r) {
    for (int q = 0; q < s; ++q) {
      const Eigen::Vector2d p = v.Site(r, q);
      int i = 0, j = 0;
      m.CellOf(p.x(), p.y(), &i, &j);
      if (!m.Contains(i, j)) continue;
      const std::size_t k = m.Index(i, j);
      if (m.count[k] == 0) continue;
      const std::uint8_t h = m.hazard[k];
      cv::Vec3b colour(200, 215, 200);                                         // seen
      if ((h & nav_core::kHazardWheel) != 0) colour = cv::Vec3b(40, 150, 250);  // orange
      if ((h & nav_core::kHazardRocker) != 0) colour = cv::Vec3b(40, 60, 230);  // red
      if ((h & nav_core::kHazardBody) != 0) colour = cv::Vec3b(30, 20, 120);    // dark red
      left.at<cv::Vec3b>(r, q) = colour;
    }
  }
  for (const PictureRock& rock : rocks) {
    cv::circle(left, v.Px(rock.centre), static_cast<int>(std::lround(rock.radius * v.ppm)),
               cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
  }
  const int stride = std::max(1, options.tree_stride);
  for (std::size_t i = 0; i < rec.paths.size(); i += static_cast<std::size_t>(stride)) {
    const TreePath& p = rec.paths[i];
    if (p.direction > 0 && p.turn_index >= 0) {
      DrawTreePath(planner, rec.start, p, v, cv::Scalar(150, 150, 150), 1, &left);
    }
  }
  for (const TreePath& p : rec.paths) {
    if (p.checked == -1) DrawTreePath(planner, rec.start, p, v, cv::Scalar(0, 0, 255), 1, &left);
  }
  std::vector<cv::Point> path_px;
  for (const Eigen::Vector2d& p : trail) path_px.push_back(v.Px(p));
  auto overlay = [&](cv::Mat* img) {
    if (path_px.size() > 1) {
      cv::polylines(*img, path_px, false, cv::Scalar(255, 255, 255), 2, cv::LINE_AA);
    }
    if (rec.route) {
      // The route over poses: forward moves magenta, backward cyan.
      const std::vector<RouteNode>& nodes = rec.route->nodes;
      for (std::size_t k = 1; k < nodes.size(); ++k) {
        if (nodes[k].move == 0) continue;
        cv::line(*img, v.Px(nodes[k - 1].pose.xy()), v.Px(nodes[k].pose.xy()),
                 nodes[k].move > 0 ? cv::Scalar(200, 0, 200) : cv::Scalar(200, 200, 0), 2,
                 cv::LINE_AA);
      }
    }
    if (rec.chosen >= 0) {
      DrawTreePath(planner, rec.start, rec.paths[static_cast<std::size_t>(rec.chosen)], v,
                   cv::Scalar(255, 80, 0), 3, img);
    }
    DrawFootprint(rover, rec.start, v, img);
    cv::circle(*img, v.Px(rec.goal), 8, cv::Scalar(0, 200, 0), 2, cv::LINE_AA);
  };
  overlay(&left);

  const CostToGoField& f = planner.cost_to_go();
  cv::Mat cost(s, s, CV_8UC1, cv::Scalar(0));
  cv::Mat blocked(s, s, CV_8UC1, cv::Scalar(0));
  double lo = 1e18, hi = -1e18;
  for (int r = 0; r < s; ++r) {
    for (int q = 0; q < s; ++q) {
      const double c = f.Cost(v.Site(r, q));
      if (std::isfinite(c)) {
        lo = std::min(lo, c);
        hi = std::max(hi, c);
      }
    }
  }
  for (int r = 0; r < s; ++r) {
    for (int q = 0; q < s; ++q) {
      const double c = f.Cost(v.Site(r, q));
      if (!std::isfinite(c)) {
        blocked.at<std::uint8_t>(r, q) = 255;
        continue;
      }
      cost.at<std::uint8_t>(r, q) =
          static_cast<std::uint8_t>(std::lround(255.0 * (c - lo) / std::max(hi - lo, 1e-9)));
    }
  }
  cv::Mat right;
  cv::applyColorMap(cost, right, cv::COLORMAP_VIRIDIS);
  right.setTo(cv::Scalar(0, 0, 0), blocked);
  overlay(&right);
  cv::Mat both;
  cv::hconcat(left, right, both);
  return both;
}

}  // namespace rover::apl::enav
