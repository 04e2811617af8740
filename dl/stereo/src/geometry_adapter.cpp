#include "rover/dl/stereo/geometry_adapter.hpp"

#include <cmath>
#include <cstring>
#include <string>

namespace rover::dl::stereo {
namespace {

Result<cv::Mat> MapToMat(const std::vector<float>& map, int width, int height, const char* name) {
  const auto expected = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  if (map.size() != expected) {
    return InvalidArgument(std::string("rectified pair map ") + name + " has " +
                           std::to_string(map.size()) + " entries; expected " +
                           std::to_string(expected) + " (" + std::to_string(width) + "x" +
                           std::to_string(height) + ")");
  }
  cv::Mat m(height, width, CV_32FC1);
  std::memcpy(m.data, map.data(), expected * sizeof(float));
  return m;
}

}  // namespace

Result<StereoSetup> StereoSetupFromGeometry(const geometry::RectifiedPair& pair,
                                            cv::Size raw_size) {
  const geometry::Cahv* left = pair.left.As<geometry::Cahv>();
  const geometry::Cahv* right = pair.right.As<geometry::Cahv>();
  if (left == nullptr || right == nullptr) {
    return InvalidArgument("rectified pair models must be CAHV (got " +
                           std::string(geometry::KindName(pair.left.kind())) + ", " +
                           std::string(geometry::KindName(pair.right.kind())) + ")");
  }
  if ((left->a - right->a).norm() > 1e-9 || (left->h - right->h).norm() > 1e-6 ||
      (left->v - right->v).norm() > 1e-6) {
    return InvalidArgument("rectified pair models do not share A, H and V");
  }
  if (pair.left_map_x.empty()) {
    return InvalidArgument("rectified pair has no remap tables (RectifyOptions::compute_maps)");
  }
  const int w = pair.left.width();
  const int h = pair.left.height();
  StereoSetup setup;
  const std::pair<const std::vector<float>*, cv::Mat*> maps[] = {
      {&pair.left_map_x, &setup.maps.left_x},
      {&pair.left_map_y, &setup.maps.left_y},
      {&pair.right_map_x, &setup.maps.right_x},
      {&pair.right_map_y, &setup.maps.right_y}};
  const char* names[] = {"left_map_x", "left_map_y", "right_map_x", "right_map_y"};
  for (int i = 0; i < 4; ++i) {
    auto m = MapToMat(*maps[i].first, w, h, names[i]);
    if (!m.ok()) return m.status();
    *maps[i].second = std::move(*m);
  }
  setup.maps.raw_size = raw_size;
  ROVER_RETURN_IF_ERROR(setup.maps.Validate());

  const geometry::Intrinsics li = geometry::ComputeIntrinsics(*left);
  const geometry::Intrinsics ri = geometry::ComputeIntrinsics(*right);
  const Eigen::Vector3d a = left->a.normalized();
  const Eigen::Vector3d h_axis = (left->h - li.hc * a) / li.hs;
  const Eigen::Vector3d v_axis = (left->v - li.vc * a) / li.vs;
  setup.camera.model.focal_px = li.hs;
  setup.camera.model.cx = li.hc;
  setup.camera.model.cy = li.vc;
  setup.camera.model.baseline_m = pair.baseline_m;
  setup.camera.model.doffs_px = ri.hc - li.hc;
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear().col(0) = h_axis;
  t.linear().col(1) = v_axis;
  t.linear().col(2) = a;
  t.translation() = left->c;
  setup.camera.rover_from_camera = t;
  ROVER_RETURN_IF_ERROR(setup.camera.Validate().WithPrefix("rectified pair"));
  if (std::abs(li.hs - li.vs) > 1e-6 * li.hs) {
    return InvalidArgument("rectified pair has different horizontal and vertical focal lengths (" +
                           std::to_string(li.hs) + ", " + std::to_string(li.vs) + " px)");
  }
  return setup;
}

Result<StereoSetup> MakeStereoSetup(const geometry::CameraModel& left,
                                    const geometry::CameraModel& right,
                                    const geometry::RectifyOptions& options) {
  if (left.width() != right.width() || left.height() != right.height()) {
    return InvalidArgument("left camera is " + std::to_string(left.width()) + "x" +
                           std::to_string(left.height()) + " but right camera is " +
                           std::to_string(right.width()) + "x" + std::to_string(right.height()) +
                           "; the pipeline needs raw images of one size");
  }
  geometry::RectifyOptions o = options;
  o.compute_maps = true;
  auto pair = geometry::RectifyStereoPair(left, right, o);
  if (!pair.ok()) return pair.status();
  return StereoSetupFromGeometry(*pair, cv::Size(left.width(), left.height()));
}

}  // namespace rover::dl::stereo
