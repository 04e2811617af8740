#pragma once
// Warp planning: which virtual pinhole views OpenGL renders for a camera model, and the per-pixel
// table that resamples them into the model's image.
//
// Canonical camera frame of a model: centre C, z = pointing axis A (pinhole: pose z), x = H'
// (the unit horizontal direction, (H - hc A)/hs; pinhole: pose x), y = z x x. The plan is made
// for the model expressed in that frame, so it does not change when the camera moves (mast
// pan/tilt, rover motion): it is cached by the canonical model's parameters (WarpKey).
//
// For every output pixel p, Unproject gives a ray direction d (canonical frame). If every ray is
// within single_view_max_angle of z, one view (axes = the canonical frame) is used; otherwise
// cube-map faces (+z, +-x, +-y, -z; a ray goes to the face of its dominant component), each
// cropped to the rays it receives. A view is a pinhole with square pixels: view pixel
//   u = f * (d.x_v / d.z_v) + cx,   v = f * (d.y_v / d.z_v) + cy
// with f = oversample * the largest output-pixel density (pixels per unit of tangent) among its
// rays, so the view samples at least as densely as the output everywhere (capped so that a side
// stays <= max_view_size), and `margin` spare pixels on every side for bilinear interpolation.
// Views are stacked vertically in one atlas image; map_x/map_y give, for every output pixel, the
// atlas coordinate to sample (pixel-centre convention, as cv::remap), -1 where the model has no
// ray.

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "rover/base/status.hpp"
#include "rover/geometry/camera_model.hpp"

namespace rover::sim::render::internal {

struct CameraFrame {
  Eigen::Matrix3d ref_from_cam = Eigen::Matrix3d::Identity();  // columns: x right, y down, z fwd
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
};
CameraFrame CanonicalFrame(const geometry::CameraModel& model);
// The model expressed in its own canonical frame (C = 0, A = z).
geometry::CameraModel CanonicalModel(const geometry::CameraModel& model);
// Cache key: kind, size and the canonical model's parameters (7 significant digits).
std::string WarpKey(const geometry::CameraModel& model);

struct VirtualView {
  Eigen::Matrix3d cam_from_view = Eigen::Matrix3d::Identity();  // view axes in the camera frame
  double f = 1.0;          // [px per unit tangent]
  double cx = 0.0, cy = 0.0;
  int width = 0, height = 0;
  int atlas_y = 0;         // first row of this view in the atlas
  // Pixel of direction d (camera frame); false if behind the view.
  bool Project(const Eigen::Vector3d& d_cam, double* u, double* v) const;
};

struct PlanOptions {
  double oversample = 1.0;
  int max_view_size = 6144;
  int margin = 3;
  double single_view_max_angle_deg = 60.0;
  int max_atlas_size = 16384;
};

struct WarpPlan {
  std::string key;
  int out_width = 0, out_height = 0;
  std::vector<VirtualView> views;
  int atlas_width = 0, atlas_height = 0;
  cv::Mat map_x, map_y;  // CV_32FC1, output size
  cv::Mat map1, map2;    // fixed-point version (cv::convertMaps) for fast bilinear remap
  double min_density_ratio = 1.0;  // smallest view density / output density (< 1 if capped)
};

// Errors: a model with no valid ray, or an atlas larger than max_atlas_size.
Result<WarpPlan> PlanWarp(const geometry::CameraModel& model, const PlanOptions& options);

}  // namespace rover::sim::render::internal
