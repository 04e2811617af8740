#include "rover/ddl/camera/camera_calibration.hpp"

#include <array>

#include "rover/msg/camera.hpp"

namespace rover::ddl::camera {
namespace {

constexpr std::array<const char*, 2> kSides = {"left", "right"};

std::string Key(const std::string& cam, const std::string& rest) { return cam + "." + rest; }

// "file:12: key 'navcam.left.o'" (or just the key when it has no file origin).
std::string Where(const ParamSet& p, const std::string& key) {
  const ParamOrigin& o = p.Origin(key);
  if (o.line > 0 || o.source != "default") return o.ToString() + ": key '" + key + "'";
  return "key '" + key + "'";
}

Eigen::Vector3d Vec(const std::vector<double>& v) { return Eigen::Vector3d(v[0], v[1], v[2]); }

Result<Eigen::Vector3d> NeedVec(const ParamSet& p, const std::string& key,
                                const std::string& kind) {
  const std::vector<double>& v = p.GetDoubleList(key);
  if (v.size() != 3) {
    return InvalidArgument(Where(p, key) + ": " + kind + " needs 3 numbers, got " +
                           std::to_string(v.size()));
  }
  return Vec(v);
}

Result<geometry::CameraModel> BuildModel(const ParamSet& p, const std::string& cam,
                                         const std::string& side) {
  const std::string kind = p.GetString(Key(cam, "model"));
  const int w = static_cast<int>(p.GetInt(Key(cam, "width")));
  const int h = static_cast<int>(p.GetInt(Key(cam, "height")));
  const std::string base = cam + "." + side + ".";
  const Eigen::Vector3d c = Vec(p.GetDoubleList(base + "c"));
  const Eigen::Vector3d a = Vec(p.GetDoubleList(base + "a"));
  const Eigen::Vector3d hv = Vec(p.GetDoubleList(base + "h"));
  const Eigen::Vector3d vv = Vec(p.GetDoubleList(base + "v"));
  Result<geometry::CameraModel> model = InvalidArgument("unknown model kind " + kind);
  if (kind == "CAHV") {
    model = geometry::CameraModel::Create(geometry::Cahv{c, a, hv, vv}, w, h);
  } else {
    auto o = NeedVec(p, base + "o", kind);
    if (!o.ok()) return o.status();
    auto r = NeedVec(p, base + "r", kind);
    if (!r.ok()) return r.status();
    if (kind == "CAHVOR") {
      model = geometry::CameraModel::Create(geometry::Cahvor{c, a, hv, vv, *o, *r}, w, h);
    } else {
      auto e = NeedVec(p, base + "e", kind);
      if (!e.ok()) return e.status();
      geometry::Cahvore m{c, a, hv, vv, *o, *r, *e, geometry::CahvoreType::kPerspective, 0.0};
      const std::string& type = p.GetString(Key(cam, "cahvore_type"));
      m.type = type == "fisheye"   ? geometry::CahvoreType::kFisheye
               : type == "general" ? geometry::CahvoreType::kGeneral
                                   : geometry::CahvoreType::kPerspective;
      m.parameter = p.GetDouble(Key(cam, "cahvore_linearity"));
      model = geometry::CameraModel::Create(m, w, h);
    }
  }
  if (!model.ok()) {
    const ParamOrigin& o = p.Origin(base + "a");
    return model.status().WithPrefix(o.ToString() + ": " + cam + "." + side + " (" + kind + ")");
  }
  return model;
}

}  // namespace

Eigen::Isometry3d MastHeadPose(double pan, double tilt, const MastGeometry& mast) {
  return mast.HeadPose(pan, tilt);
}

std::pair<geometry::CameraModel, geometry::CameraModel> StereoCameraCalibration::InRover(
    double pan, double tilt, const MastGeometry& mast) const {
  if (mount == CameraMount::kBody) return {left, right};
  const Eigen::Isometry3d rover_from_head = MastHeadPose(pan, tilt, mast);
  return {geometry::Transform(left, rover_from_head), geometry::Transform(right, rover_from_head)};
}

void DeclareCameraCalibrationParams(ParamSet& p) {
  const MastGeometry mast;
  p.Declare("mast.pan_joint",
            std::vector<double>{mast.pan_joint.x(), mast.pan_joint.y(), mast.pan_joint.z()},
            "[m] mast pan joint in the rover frame")
      .Size(3)
      .Range(-5.0, 5.0);
  p.Declare("mast.head_height", mast.head_height,
            "[m] tilt axis (mast-head frame origin) above the pan joint")
      .Range(0.0, 10.0);
  for (int i = 0; i < kNumCameras; ++i) {
    const std::string cam = msg::CameraName(static_cast<msg::CameraId>(i));
    p.Declare(Key(cam, "mount"), "body",
              "where the pair is mounted: mast_head (models in the mast-head frame, follow "
              "pan/tilt) or body (models in the rover frame)")
        .OneOf({"mast_head", "body"})
        .Required();
    p.Declare(Key(cam, "model"), "CAHVOR", "camera model kind of both cameras")
        .OneOf({"CAHV", "CAHVOR", "CAHVORE"});
    p.Declare(Key(cam, "width"), 1024, "[px] image width the models are valid for")
        .Range(1, 8192)
        .Required();
    p.Declare(Key(cam, "height"), 1024, "[px] image height the models are valid for")
        .Range(1, 8192)
        .Required();
    p.Declare(Key(cam, "cahvore_type"), "perspective", "CAHVORE projection type")
        .OneOf({"perspective", "fisheye", "general"});
    p.Declare(Key(cam, "cahvore_linearity"), 1.0, "CAHVORE linearity L (type general only)")
        .Range(-1.0, 2.0);
    for (const char* side : kSides) {
      const std::string b = cam + "." + side + ".";
      const std::string which = std::string(side) + " camera";
      p.Declare(b + "c", std::vector<double>{}, "[m] " + which + " centre C")
          .Size(3)
          .Range(-100.0, 100.0)
          .Required();
      p.Declare(b + "a", std::vector<double>{}, which + " pointing axis A (unit)")
          .Size(3)
          .Range(-2.0, 2.0)
          .Required();
      p.Declare(b + "h", std::vector<double>{}, "[px] " + which + " horizontal vector H")
          .Size(3)
          .Range(-1e6, 1e6)
          .Required();
      p.Declare(b + "v", std::vector<double>{}, "[px] " + which + " vertical vector V")
          .Size(3)
          .Range(-1e6, 1e6)
          .Required();
      p.Declare(b + "o", std::vector<double>{},
                which + " optical axis O (unit; CAHVOR and CAHVORE only)")
          .Range(-2.0, 2.0);
      p.Declare(b + "r", std::vector<double>{},
                which + " radial distortion R = r0, r1, r2 (CAHVOR and CAHVORE only)")
          .Range(-1e3, 1e3);
      p.Declare(b + "e", std::vector<double>{},
                "[m] " + which + " entrance-pupil terms E = e0, e1, e2 (CAHVORE only)")
          .Range(-1.0, 1.0);
    }
  }
}

Result<CameraCalibration> CameraCalibrationFromParams(const ParamSet& p) {
  ROVER_RETURN_IF_ERROR(p.Validate());
  CameraCalibration cal;
  const auto& pj = p.GetDoubleList("mast.pan_joint");
  cal.mast.pan_joint = Vec(pj);
  cal.mast.head_height = p.GetDouble("mast.head_height");
  for (int i = 0; i < kNumCameras; ++i) {
    const std::string cam = msg::CameraName(static_cast<msg::CameraId>(i));
    auto left = BuildModel(p, cam, "left");
    if (!left.ok()) return left.status();
    auto right = BuildModel(p, cam, "right");
    if (!right.ok()) return right.status();
    const CameraMount mount =
        p.GetString(Key(cam, "mount")) == "mast_head" ? CameraMount::kMastHead : CameraMount::kBody;
    // The driver sends every model as ddl CameraModel fields (CAHVOR + pinhole); a model that
    // cannot be converted would fail every frame, so refuse it here. Rotations and scaling do
    // not change convertibility, so checking the models as given is enough.
    for (const auto* m : {&*left, &*right}) {
      auto f = msg::CameraModelFieldsFromModel(*m);
      if (!f.ok()) {
        return InvalidArgument(Where(p, Key(cam, "model")) + ": " + cam +
                               " cannot be sent as a ddl CameraModel: " + f.status().message());
      }
    }
    cal.cameras.push_back({cam, mount, std::move(*left), std::move(*right)});
  }
  return cal;
}

Result<CameraCalibration> LoadCameraCalibration(const std::string& path) {
  ParamSet p("cameras");
  DeclareCameraCalibrationParams(p);
  ROVER_RETURN_IF_ERROR(p.LoadYamlFile(path));
  return CameraCalibrationFromParams(p);
}

}  // namespace rover::ddl::camera
