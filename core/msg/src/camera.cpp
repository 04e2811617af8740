#include "rover/msg/camera.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <utility>

#include "rover/base/format.hpp"

namespace rover::msg {
namespace {

constexpr double kCentreTolerance = 1e-3;  // [m] CAHVOR C vs pinhole pose position
constexpr double kAxisTolerance = 1e-3;    // [rad] CAHVOR A vs pinhole pose z axis
constexpr double kUnitTolerance = 1e-6;    // quaternion norm

constexpr std::array<const char*, kNumCameras> kCameraNames = {"navcam", "front_hazcam",
                                                               "rear_hazcam"};

Eigen::Vector3d Vec(const std::array<double, 3>& a) { return {a[0], a[1], a[2]}; }
std::array<double, 3> Arr(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

bool IsZero(const std::array<double, 3>& a) { return a[0] == 0.0 && a[1] == 0.0 && a[2] == 0.0; }

std::string Text(const std::array<double, 3>& a) {
  return "(" + FormatNumber(a[0], 9) + ", " + FormatNumber(a[1], 9) + ", " + FormatNumber(a[2], 9) +
         ")";
}

std::string SizeText(int w, int h) { return std::to_string(w) + "x" + std::to_string(h); }

Status CheckFinite(const CameraModelFields& f) {
  const std::pair<const char*, const std::array<double, 3>*> vectors[] = {
      {"c", &f.c},
      {"a", &f.a},
      {"h", &f.h},
      {"v", &f.v},
      {"o", &f.o},
      {"r", &f.r},
      {"pose.position", &f.position}};
  for (const auto& [name, v] : vectors) {
    for (double x : *v) {
      if (!std::isfinite(x)) {
        return InvalidArgument(std::string("camera model field '") + name + "' " + Text(*v) +
                               " is not finite");
      }
    }
  }
  const std::pair<const char*, double> scalars[] = {{"fx", f.fx},
                                                    {"fy", f.fy},
                                                    {"cx", f.cx},
                                                    {"cy", f.cy},
                                                    {"k1", f.k1},
                                                    {"k2", f.k2},
                                                    {"k3", f.k3},
                                                    {"pose.orientation.w", f.orientation[0]},
                                                    {"pose.orientation.x", f.orientation[1]},
                                                    {"pose.orientation.y", f.orientation[2]},
                                                    {"pose.orientation.z", f.orientation[3]}};
  for (const auto& [name, x] : scalars) {
    if (!std::isfinite(x)) {
      return InvalidArgument(std::string("camera model field '") + name + "' is not finite");
    }
  }
  return Status::Ok();
}

Result<Eigen::Isometry3d> PoseOf(const CameraModelFields& f) {
  const Eigen::Quaterniond q(f.orientation[0], f.orientation[1], f.orientation[2],
                             f.orientation[3]);
  if (std::abs(q.norm() - 1.0) > kUnitTolerance) {
    return InvalidArgument("camera model field 'pose.orientation' is not a unit quaternion (norm " +
                           FormatNumber(q.norm(), 9) + ")");
  }
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = q.normalized().toRotationMatrix();
  t.translation() = Vec(f.position);
  return t;
}

Result<geometry::CameraModel> FromCahvorPart(const CameraModelFields& f) {
  if (IsZero(f.r)) {
    geometry::Cahv m;
    m.c = Vec(f.c);
    m.a = Vec(f.a);
    m.h = Vec(f.h);
    m.v = Vec(f.v);
    return geometry::CameraModel::Create(m, f.width, f.height);
  }
  geometry::Cahvor m;
  m.c = Vec(f.c);
  m.a = Vec(f.a);
  m.h = Vec(f.h);
  m.v = Vec(f.v);
  m.o = Vec(f.o);
  m.r = Vec(f.r);
  return geometry::CameraModel::Create(m, f.width, f.height);
}

}  // namespace

const char* CameraName(CameraId c) {
  return IsKnownCamera(c) ? kCameraNames[static_cast<std::size_t>(c)] : "unknown";
}

Result<CameraId> CameraFromName(const std::string& name) {
  for (int i = 0; i < kNumCameras; ++i) {
    if (name == kCameraNames[static_cast<std::size_t>(i)]) return static_cast<CameraId>(i);
  }
  return InvalidArgument("camera '" + name + "' is not one of: navcam, front_hazcam, rear_hazcam");
}

bool CameraModelFields::HasCahvor() const { return !IsZero(a) || !IsZero(h) || !IsZero(v); }
bool CameraModelFields::HasPinhole() const { return fx != 0.0 || fy != 0.0; }

Result<CameraModelFields> CameraModelFieldsFromModel(const geometry::CameraModel& model,
                                                     PinholeFit* fit) {
  CameraModelFields f;
  f.width = model.width();
  f.height = model.height();
  auto pin = geometry::ToPinholeRadial(model);
  if (!pin.ok()) return pin.status();
  const geometry::PinholeRadial& p = pin->model;
  f.fx = p.fx;
  f.fy = p.fy;
  f.cx = p.cx;
  f.cy = p.cy;
  f.k1 = p.k1;
  f.k2 = p.k2;
  f.k3 = p.k3;
  f.position = Arr(p.pose.translation());
  Eigen::Quaterniond q(p.pose.linear());
  if (q.w() < 0.0) q.coeffs() = -q.coeffs();  // the same rotation, w >= 0
  f.orientation = {q.w(), q.x(), q.y(), q.z()};
  if (fit != nullptr) *fit = {pin->rms_error_px, pin->max_error_px};

  geometry::Cahvor cahvor;
  if (const auto* cahv = model.As<geometry::Cahv>()) {
    cahvor.c = cahv->c;
    cahvor.a = cahv->a;
    cahvor.h = cahv->h;
    cahvor.v = cahv->v;
    cahvor.o = cahv->a;
    cahvor.r.setZero();
  } else if (const auto* m = model.As<geometry::Cahvor>()) {
    cahvor = *m;
  } else {
    auto fitted = geometry::ToCahvor(p);
    if (!fitted.ok()) return fitted.status();
    cahvor = fitted->model;
  }
  f.c = Arr(cahvor.c);
  f.a = Arr(cahvor.a);
  f.h = Arr(cahvor.h);
  f.v = Arr(cahvor.v);
  f.o = Arr(cahvor.o);
  f.r = Arr(cahvor.r);
  return f;
}

Result<geometry::CameraModel> CameraModelFromFields(const CameraModelFields& f) {
  ROVER_RETURN_IF_ERROR(CheckFinite(f));
  if (f.width < 1 || f.height < 1) {
    return InvalidArgument("camera model size " + SizeText(f.width, f.height) + " is empty");
  }
  if (!f.HasCahvor() && !f.HasPinhole()) {
    return InvalidArgument(
        "camera model is missing (CAHVOR vectors A, H, V and pinhole fx, fy are all zero)");
  }
  if (f.HasCahvor()) {
    Result<geometry::CameraModel> model = FromCahvorPart(f);
    if (!model.ok()) return model.status().WithPrefix("camera model (CAHVOR part)");
    if (f.HasPinhole()) {
      ROVER_ASSIGN_OR_RETURN(const Eigen::Isometry3d pose, PoseOf(f));
      const double dc = (Vec(f.c) - pose.translation()).norm();
      const Eigen::Vector3d z = pose.linear().col(2);
      const double angle = std::acos(std::clamp(z.dot(Vec(f.a).normalized()), -1.0, 1.0));
      if (dc > kCentreTolerance || angle > kAxisTolerance) {
        return InvalidArgument("camera model CAHVOR and pinhole parts disagree: C " + Text(f.c) +
                               " vs pose.position " + Text(f.position) + " (" +
                               FormatNumber(dc, 9) + " m), A vs pose z axis " +
                               FormatNumber(angle, 9) + " rad");
      }
    }
    return model;
  }
  // Pinhole part only.
  ROVER_ASSIGN_OR_RETURN(const Eigen::Isometry3d pose, PoseOf(f));
  geometry::PinholeRadial p;
  p.fx = f.fx;
  p.fy = f.fy;
  p.cx = f.cx;
  p.cy = f.cy;
  p.k1 = f.k1;
  p.k2 = f.k2;
  p.k3 = f.k3;
  p.pose = pose;
  p.width = f.width;
  p.height = f.height;
  auto model = geometry::CameraModel::Create(p);
  if (!model.ok()) return model.status().WithPrefix("camera model (pinhole part)");
  return model;
}

Status CheckStereoFrame(const StereoFrame& frame) {
  if (frame.width < 1 || frame.height < 1) {
    return InvalidArgument("stereo frame size " + SizeText(frame.width, frame.height) +
                           " is empty");
  }
  if (frame.stamp.ns <= 0) {
    return InvalidArgument("stereo frame stamp " + std::to_string(frame.stamp.ns) +
                           " ns is not positive");
  }
  const std::size_t n =
      static_cast<std::size_t>(frame.width) * static_cast<std::size_t>(frame.height);
  const std::pair<const char*, std::size_t> lengths[] = {{"left", frame.left.size()},
                                                         {"right", frame.right.size()}};
  for (const auto& [name, length] : lengths) {
    if (length != n) {
      return InvalidArgument(std::string(name) + " image has " + std::to_string(length) +
                             " bytes; expected " + SizeText(frame.width, frame.height) + " = " +
                             std::to_string(n));
    }
  }
  const std::pair<const char*, const CameraModelFields*> models[] = {{"left", &frame.left_model},
                                                                     {"right", &frame.right_model}};
  for (const auto& [name, m] : models) {
    if (m->width != frame.width || m->height != frame.height) {
      return InvalidArgument(std::string(name) + " camera model is for " +
                             SizeText(m->width, m->height) + " images but the frame is " +
                             SizeText(frame.width, frame.height));
    }
  }
  return Status::Ok();
}

Status CheckMiFrame(const MiFrame& frame) {
  if (frame.width < 1 || frame.height < 1) {
    return InvalidArgument("microscopic-imager frame size " +
                           SizeText(frame.width, frame.height) + " is empty");
  }
  if (frame.stamp.ns <= 0) {
    return InvalidArgument("microscopic-imager frame stamp " + std::to_string(frame.stamp.ns) +
                           " ns is not positive");
  }
  const std::size_t n =
      static_cast<std::size_t>(frame.width) * static_cast<std::size_t>(frame.height);
  if (frame.image.size() != n) {
    return InvalidArgument("microscopic-imager image has " + std::to_string(frame.image.size()) +
                           " bytes; expected " + SizeText(frame.width, frame.height) + " = " +
                           std::to_string(n));
  }
  return Status::Ok();
}

}  // namespace rover::msg
