#include "rover/sim/rover_sim/camera_head.hpp"

#include <algorithm>
#include <cmath>

#include "rover/base/check.hpp"
#include "rover/base/param_binder.hpp"
#include "rover/base/range_check.hpp"

namespace rover::sim::rover_sim {
namespace {
constexpr double kRadToDeg = 180.0 / 3.14159265358979323846;
}  // namespace

Status CameraHeadOptions::Validate() const {
  ROVER_RETURN_IF_ERROR(CheckIntRange("image_size", image_size, 64, 2048));
  return CheckIntRange("render_seed", render_seed, 0, INT64_MAX);
}

void CameraHeadOptions::BindParams(ParamBinder<CameraHeadOptions>& b) {
  b.Bind("image_size", &CameraHeadOptions::image_size, "px",
         "side of the rendered camera images (MER: 1024)")
      .Range(64, 2048);
  b.Bind("render_seed", &CameraHeadOptions::render_seed, "",
         "seed of the rendered textures and image noise")
      .Min(0);
}

CameraHead::CameraHead(const CameraHeadOptions& options,
                       std::shared_ptr<const terrain::Terrain> terrain,
                       const hwconfig::RoverDescription& rover)
    : options_(options),
      terrain_(std::move(terrain)),
      mast_geometry_(rover.mast),
      arm_(rover.arm),
      cameras_(render::DefaultStereoCameras(options.image_size, rover)) {
  ROVER_DEMAND(terrain_ != nullptr);
}

Status CameraHead::StartRenderer() {
  if (renderer_) return Status::Ok();
  if (!renderer_error_.ok()) return renderer_error_;
  render::RenderOptions o;
  o.seed = static_cast<std::uint64_t>(options_.render_seed);
  auto r = render::Renderer::Create(terrain_, o);
  if (!r.ok()) {
    renderer_error_ = Unavailable("cameras unavailable: " + r.status().message());
    return renderer_error_;
  }
  renderer_ = std::move(*r);
  return Status::Ok();
}

void CameraHead::UpdateSun(const Eigen::Vector3d& sun_site) {
  if (sun_set_ && std::acos(std::clamp(sun_site.dot(last_sun_), -1.0, 1.0)) <= kSunUpdateRad) {
    return;
  }
  render::SunOptions so;
  so.azimuth_deg = std::atan2(sun_site.y(), sun_site.x()) * kRadToDeg;
  so.elevation_deg =
      std::max(kMinSunElevationDeg, std::asin(std::clamp(sun_site.z(), -1.0, 1.0)) * kRadToDeg);
  if (renderer_->SetSun(so).ok()) {
    last_sun_ = sun_site;
    sun_set_ = true;
  }
}

Status CameraHead::CheckReadout(int readout_width, int sensor_width, const std::string& camera) {
  if (readout_width == 0) return Status::Ok();
  const std::string what = "readout_width " + std::to_string(readout_width) + " px";
  if (readout_width < 0) return InvalidArgument(what + " is negative (0 = the full sensor)");
  if (readout_width > sensor_width) {
    return InvalidArgument(what + " is wider than the " + camera + " sensor (" +
                           std::to_string(sensor_width) + " px)");
  }
  if (sensor_width % readout_width != 0) {
    return InvalidArgument(what + " is not the " + camera + " sensor width (" +
                           std::to_string(sensor_width) + " px) divided by a whole binning factor");
  }
  return Status::Ok();
}

Result<CameraShot> CameraHead::Take(const std::string& camera, std::uint32_t exposure_us,
                                    const Eigen::Isometry3d& site_from_rover,
                                    const render::MastState& mast, const Eigen::Vector3d& sun_site,
                                    int readout_width) {
  ROVER_ASSIGN_OR_RETURN(render::StereoCameraDefinition def,
                         render::FindStereoCamera(cameras_, camera));
  const int sensor_width = def.left.width();
  ROVER_RETURN_IF_ERROR(CheckReadout(readout_width, sensor_width, camera));
  if (readout_width != 0 && readout_width != sensor_width) {
    const double s = static_cast<double>(readout_width) / sensor_width;
    def.left = geometry::Scale(def.left, s);
    def.right = geometry::Scale(def.right, s);
  }
  ROVER_ASSIGN_OR_RETURN(const render::CameraPairSpec spec,
                         render::MakeCameraPairSpec(def, mast, mast_geometry_));
  ROVER_RETURN_IF_ERROR(StartRenderer());
  UpdateSun(sun_site);

  CameraShot shot;
  // A binned readout sums b x b pixels' charge before one read, and the renderer integrates
  // the light over them (render::SensorOptions::binning, RenderOptions::binned_supersample).
  ROVER_RETURN_IF_ERROR(SetExposure(
      exposure_us, readout_width == 0 ? 1 : sensor_width / readout_width, &shot.exposure_refused));
  ROVER_ASSIGN_OR_RETURN(shot.images,
                         renderer_->RenderStereoPair(site_from_rover, spec, ++frames_));
  shot.exposure_us = static_cast<std::uint32_t>(
      std::clamp(std::lround(shot.images.left.exposure * kExposureUnitUs), 1L, 4000000000L));
  return shot;
}

Status CameraHead::SetExposure(std::uint32_t exposure_us, int binning, std::string* refused) {
  render::SensorOptions sensor = renderer_->options().sensor;
  sensor.auto_exposure = exposure_us == 0;
  sensor.binning = binning;
  if (exposure_us != 0) sensor.exposure = exposure_us / kExposureUnitUs;
  if (const Status st = renderer_->SetSensor(sensor); !st.ok()) {
    *refused = st.message();
    sensor.auto_exposure = true;
    ROVER_RETURN_IF_ERROR(renderer_->SetSensor(sensor));
  }
  return Status::Ok();
}

geometry::CameraModel CameraHead::MicroscopeModel(const hwconfig::ArmAngles& arm) const {
  const hwconfig::MicroscopeOptics& o = arm_.imager;
  geometry::PinholeRadial p;
  p.fx = p.fy = o.focal_px;
  p.cx = p.cy = 0.5 * (o.image_size - 1);
  p.width = p.height = o.image_size;
  p.pose = arm_.ImagerPose(arm);
  auto model = geometry::CameraModel::Create(p);
  ROVER_DEMAND(model.ok());  // a valid description gives a valid pinhole
  return *model;
}

Result<MicroscopeShot> CameraHead::TakeMicroscope(std::uint32_t exposure_us,
                                                  const Eigen::Isometry3d& site_from_rover,
                                                  const hwconfig::ArmAngles& arm,
                                                  const Eigen::Vector3d& sun_site) {
  for (double a : arm) {
    if (!std::isfinite(a)) return InvalidArgument("arm angles are not finite");
  }
  ROVER_RETURN_IF_ERROR(StartRenderer());
  UpdateSun(sun_site);
  MicroscopeShot shot;
  ROVER_RETURN_IF_ERROR(SetExposure(exposure_us, 1, &shot.exposure_refused));
  render::DepthOfField dof;
  dof.focus_distance = arm_.imager.working_distance;
  dof.blur_constant = arm_.imager.focal_px * arm_.imager.aperture;
  dof.near = std::min(0.002, 0.5 * dof.focus_distance);
  ROVER_ASSIGN_OR_RETURN(shot.image, renderer_->RenderCloseUp(site_from_rover,
                                                              MicroscopeModel(arm), dof, ++frames_));
  shot.exposure_us = static_cast<std::uint32_t>(
      std::clamp(std::lround(shot.image.exposure * kExposureUnitUs), 1L, 4000000000L));
  return shot;
}

}  // namespace rover::sim::rover_sim
