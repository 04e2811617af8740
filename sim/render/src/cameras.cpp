#include "rover/sim/render/cameras.hpp"

#include <cmath>
#include <numbers>

#include "rover/base/check.hpp"
#include "rover/base/units.hpp"

namespace rover::sim::render {

using terrain::HeightField;

namespace {

using geometry::CameraModel;

constexpr int kDefinitionSize = 1024;

// Lenses; the mounts (positions, boresights, baselines) are the rover description's.
// NAVCAM (MER: 45 deg FOV, 1024 x 1024).
constexpr double kNavcamFovDeg = 45.0;
constexpr double kNavcamR1 = -0.01;  // mild barrel distortion

// HAZCAM (MER: 124 deg FOV). CAHVOR with 120 deg across the width, as deploy/config/cameras.yaml
// (what ddl-camera attaches to its frames).
constexpr double kHazcamFovDeg = 120.0;
constexpr double kHazcamR1 = -0.01;

// Camera axes from a head rotation: A = boresight (head x), H' = right (-y), V' = down (-z).
struct Axes {
  Eigen::Vector3d a, h, v;
};
Axes AxesOf(const Eigen::Matrix3d& r) {
  return {r.col(0), -r.col(1), -r.col(2)};
}

// A CAHVOR camera at optical centre `c` with axes from the pair rotation `r`, focal length
// `f` [px] and radial term r1, defined at kDefinitionSize.
CameraModel MakeCamera(const Eigen::Vector3d& c, const Eigen::Matrix3d& r, double f, double r1) {
  const double centre = 0.5 * (kDefinitionSize - 1);
  const Axes ax = AxesOf(r);
  geometry::Cahvor m;
  m.c = c;
  m.a = ax.a;
  m.h = f * ax.h + centre * ax.a;
  m.v = f * ax.v + centre * ax.a;
  m.o = ax.a;
  m.r = Eigen::Vector3d(0.0, r1, 0.0);
  auto model = CameraModel::Create(m, kDefinitionSize, kDefinitionSize);
  ROVER_DEMAND(model.ok());
  return *model;
}

// The two cameras of a pair on `mount`, the left one at +baseline/2 along the pair's y.
StereoCameraDefinition Pair(const std::string& name, CameraMount where,
                            const hwconfig::StereoMount& mount, double f, double r1) {
  const Eigen::Matrix3d r = mount.Pose().linear();
  const Eigen::Vector3d half(0, 0.5 * mount.baseline, 0);
  return {name, where, MakeCamera(mount.position + r * half, r, f, r1),
          MakeCamera(mount.position + r * -half, r, f, r1)};
}

}  // namespace

Eigen::Isometry3d MastHeadPose(const MastState& mast, const hwconfig::MastDescription& geometry) {
  return geometry.HeadPose(mast.pan, mast.tilt);
}

geometry::CameraModel CameraPairSpec::LeftInRover() const {
  return geometry::Transform(left, rover_from_head);
}
geometry::CameraModel CameraPairSpec::RightInRover() const {
  return geometry::Transform(right, rover_from_head);
}

std::vector<StereoCameraDefinition> DefaultStereoCameras(int image_size,
                                                         const hwconfig::RoverDescription& rover) {
  ROVER_DEMAND(image_size >= 16 && image_size <= 4096);
  const double navcam_f = 0.5 * kDefinitionSize / std::tan(DegToRad(0.5 * kNavcamFovDeg));
  // CAHVOR radial term: a point at angle theta off O images at f tan(theta) (1 + r1 tan^2).
  const double t_edge = std::tan(DegToRad(0.5 * kHazcamFovDeg));
  const double hazcam_f = 0.5 * kDefinitionSize / (t_edge * (1.0 + kHazcamR1 * t_edge * t_edge));
  std::vector<StereoCameraDefinition> cams;
  cams.push_back(Pair("navcam", CameraMount::kMastHead, rover.navcam, navcam_f, kNavcamR1));
  cams.push_back(Pair("front_hazcam", CameraMount::kBody, rover.front_hazcam, hazcam_f, kHazcamR1));
  cams.push_back(Pair("rear_hazcam", CameraMount::kBody, rover.rear_hazcam, hazcam_f, kHazcamR1));
  if (image_size != kDefinitionSize) {
    const double s = static_cast<double>(image_size) / kDefinitionSize;
    for (auto& c : cams) {
      c.left = geometry::Scale(c.left, s);
      c.right = geometry::Scale(c.right, s);
    }
  }
  return cams;
}

Result<StereoCameraDefinition> FindStereoCamera(const std::vector<StereoCameraDefinition>& cameras,
                                                const std::string& name) {
  std::string known;
  for (const auto& c : cameras) {
    if (c.name == name) return c;
    known += (known.empty() ? "" : ", ") + c.name;
  }
  return NotFound("camera '" + name + "' is unknown; known cameras: " + known);
}

Result<CameraPairSpec> MakeCameraPairSpec(const StereoCameraDefinition& camera,
                                          const MastState& mast,
                                          const hwconfig::MastDescription& geometry) {
  if (!std::isfinite(mast.pan) || !std::isfinite(mast.tilt)) {
    return InvalidArgument("mast: pan/tilt must be finite");
  }
  ROVER_RETURN_IF_ERROR(geometry.Validate());
  CameraPairSpec spec{camera.left, camera.right, Eigen::Isometry3d::Identity()};
  if (camera.mount == CameraMount::kMastHead) spec.rover_from_head = MastHeadPose(mast, geometry);
  return spec;
}

Eigen::Isometry3d RoverPoseFromXyYaw(double x, double y, double z, double yaw) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translation() = Eigen::Vector3d(x, y, z);
  t.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return t;
}

Eigen::Isometry3d RoverPoseOnGround(const HeightField& ground, double x, double y, double yaw,
                                    const hwconfig::RoverDescription& rover) {
  // Least-squares plane z = z0 + a (u - u_m) + b v over the wheel contact points (u forward,
  // v left; u_m their mean x). The wheels are mirror-symmetric, so sum v = sum (u - u_m) v = 0.
  const double c = std::cos(yaw), s = std::sin(yaw);
  const double wheel_x[3] = {rover.front_wheel_x, rover.middle_wheel_x, rover.rear_wheel_x};
  const double um = (wheel_x[0] + wheel_x[1] + wheel_x[2]) / 3.0;
  double suu = 0, svv = 0, sz = 0, suz = 0, svz = 0;
  int n = 0;
  for (double u : wheel_x) {
    for (double v : {rover.half_track, -rover.half_track}) {
      const double z = ground.Height(x + c * u - s * v, y + s * u + c * v);
      const double du = u - um;
      suu += du * du; svv += v * v; sz += z; suz += du * z; svz += v * z;
      ++n;
    }
  }
  const double a = suz / suu, b = svz / svv, z0 = sz / n - a * um;
  const Eigen::Vector3d fwd(c, s, 0.0), left(-s, c, 0.0);
  const Eigen::Vector3d x_axis = (fwd + a * Eigen::Vector3d::UnitZ()).normalized();
  const Eigen::Vector3d y_tmp = (left + b * Eigen::Vector3d::UnitZ()).normalized();
  const Eigen::Vector3d z_axis = x_axis.cross(y_tmp).normalized();
  const Eigen::Vector3d y_axis = z_axis.cross(x_axis);
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear().col(0) = x_axis;
  t.linear().col(1) = y_axis;
  t.linear().col(2) = z_axis;
  t.translation() = Eigen::Vector3d(x, y, z0);
  return t;
}

}  // namespace rover::sim::render
