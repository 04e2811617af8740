#include "rover/sim/render/cameras.hpp"

#include <cmath>
#include <numbers>

#include "rover/base/check.hpp"

namespace rover::sim {
namespace {

using geometry::CameraModel;

constexpr int kDefinitionSize = 1024;

// NAVCAM (MER: 45 deg FOV, 1024 x 1024, 20 cm baseline on the mast head).
constexpr double kNavcamFovDeg = 45.0;
constexpr double kNavcamHalfBaseline = 0.10;
constexpr double kNavcamForward = 0.05;  // [m] in front of the tilt axis
constexpr double kNavcamR1 = -0.01;      // mild barrel distortion

// HAZCAM (MER: 124 deg FOV, 10 cm baseline, ~0.5 m high, 45 deg down). CAHVOR with 120 deg
// across the width, as deploy/config/cameras.yaml (what ddl-camera attaches to its frames).
constexpr double kHazcamFovDeg = 120.0;
constexpr double kHazcamHalfBaseline = 0.05;
constexpr double kHazcamR1 = -0.01;
const Eigen::Vector3d kFrontHazcam(0.52, 0.0, 0.50);
const Eigen::Vector3d kRearHazcam(-0.52, 0.0, 0.50);
constexpr double kHazcamDepressionDeg = 45.0;

double Deg(double d) { return d * std::numbers::pi / 180.0; }

// Camera axes from a head rotation: A = boresight (head x), H' = right (-y), V' = down (-z).
struct Axes {
  Eigen::Vector3d a, h, v;
};
Axes AxesOf(const Eigen::Matrix3d& r) {
  return {r.col(0), -r.col(1), -r.col(2)};
}

CameraModel MakeNavcam(const Eigen::Vector3d& c) {
  const double centre = 0.5 * (kDefinitionSize - 1);
  const double f = 0.5 * kDefinitionSize / std::tan(Deg(0.5 * kNavcamFovDeg));
  const Axes ax = AxesOf(Eigen::Matrix3d::Identity());
  geometry::Cahvor m;
  m.c = c;
  m.a = ax.a;
  m.h = f * ax.h + centre * ax.a;
  m.v = f * ax.v + centre * ax.a;
  m.o = ax.a;
  m.r = Eigen::Vector3d(0.0, kNavcamR1, 0.0);
  auto model = CameraModel::Create(m, kDefinitionSize, kDefinitionSize);
  ROVER_DEMAND(model.ok());
  return *model;
}

CameraModel MakeHazcam(const Eigen::Vector3d& c, const Eigen::Matrix3d& r) {
  const double centre = 0.5 * (kDefinitionSize - 1);
  // CAHVOR radial term: a point at angle theta off O images at f tan(theta) (1 + r1 tan^2).
  const double t_edge = std::tan(Deg(0.5 * kHazcamFovDeg));
  const double f = 0.5 * kDefinitionSize / (t_edge * (1.0 + kHazcamR1 * t_edge * t_edge));
  const Axes ax = AxesOf(r);
  geometry::Cahvor m;
  m.c = c;
  m.a = ax.a;
  m.h = f * ax.h + centre * ax.a;
  m.v = f * ax.v + centre * ax.a;
  m.o = ax.a;
  m.r = Eigen::Vector3d(0.0, kHazcamR1, 0.0);
  auto model = CameraModel::Create(m, kDefinitionSize, kDefinitionSize);
  ROVER_DEMAND(model.ok());
  return *model;
}

StereoCameraDefinition HazcamPair(const std::string& name, const Eigen::Vector3d& centre,
                                  double yaw) {
  const Eigen::Matrix3d r = (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                             Eigen::AngleAxisd(Deg(kHazcamDepressionDeg), Eigen::Vector3d::UnitY()))
                                .toRotationMatrix();
  StereoCameraDefinition d{name, CameraMount::kBody,
                           MakeHazcam(centre + r * Eigen::Vector3d(0, kHazcamHalfBaseline, 0), r),
                           MakeHazcam(centre + r * Eigen::Vector3d(0, -kHazcamHalfBaseline, 0), r)};
  return d;
}

}  // namespace

Status MastGeometry::Validate() const {
  if (!pan_joint.allFinite()) return InvalidArgument("mast.pan_joint: not finite");
  if (!(std::isfinite(head_height) && head_height >= 0.0 && head_height <= 10.0)) {
    return InvalidArgument("mast.head_height: " + std::to_string(head_height) +
                           " is out of range [0, 10] m");
  }
  return Status::Ok();
}

Eigen::Isometry3d MastHeadPose(const MastState& mast, const MastGeometry& geometry) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translation() = geometry.pan_joint + Eigen::Vector3d(0.0, 0.0, geometry.head_height);
  t.linear() = (Eigen::AngleAxisd(mast.pan, Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(-mast.tilt, Eigen::Vector3d::UnitY()))
                   .toRotationMatrix();
  return t;
}

geometry::CameraModel CameraPairSpec::LeftInRover() const {
  return geometry::Transform(left, rover_from_head);
}
geometry::CameraModel CameraPairSpec::RightInRover() const {
  return geometry::Transform(right, rover_from_head);
}

std::vector<StereoCameraDefinition> DefaultStereoCameras(int image_size) {
  ROVER_DEMAND(image_size >= 16 && image_size <= 4096);
  std::vector<StereoCameraDefinition> cams;
  cams.push_back({"navcam", CameraMount::kMastHead,
                  MakeNavcam(Eigen::Vector3d(kNavcamForward, kNavcamHalfBaseline, 0.0)),
                  MakeNavcam(Eigen::Vector3d(kNavcamForward, -kNavcamHalfBaseline, 0.0))});
  cams.push_back(HazcamPair("front_hazcam", kFrontHazcam, 0.0));
  cams.push_back(HazcamPair("rear_hazcam", kRearHazcam, std::numbers::pi));
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
                                          const MastState& mast, const MastGeometry& geometry) {
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

Eigen::Isometry3d RoverPoseOnGround(const HeightField& ground, double x, double y, double yaw) {
  // Least-squares plane z = z0 + a u + b v over the wheel contact points (u forward, v left).
  const double c = std::cos(yaw), s = std::sin(yaw);
  double suu = 0, svv = 0, su = 0, sv = 0, sz = 0, suz = 0, svz = 0;
  int n = 0;
  for (double u : {0.625, 0.0, -0.625}) {
    for (double v : {0.5, -0.5}) {
      const double z = ground.Height(x + c * u - s * v, y + s * u + c * v);
      suu += u * u; svv += v * v; su += u; sv += v; sz += z; suz += u * z; svz += v * z;
      ++n;
    }
  }
  // The sample grid is symmetric (sum u = sum v = sum uv = 0).
  const double a = suz / suu, b = svz / svv, z0 = sz / n;
  (void)su;
  (void)sv;
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

}  // namespace rover::sim
