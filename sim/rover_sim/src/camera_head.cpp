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

Result<CameraShot> CameraHead::Take(const std::string& camera, std::uint32_t exposure_us,
                                    const Eigen::Isometry3d& site_from_rover,
                                    const render::MastState& mast,
                                    const Eigen::Vector3d& sun_site) {
  ROVER_ASSIGN_OR_RETURN(const render::StereoCameraDefinition def,
                         render::FindStereoCamera(cameras_, camera));
  ROVER_ASSIGN_OR_RETURN(const render::CameraPairSpec spec,
                         render::MakeCameraPairSpec(def, mast, mast_geometry_));
  ROVER_RETURN_IF_ERROR(StartRenderer());
  UpdateSun(sun_site);

  CameraShot shot;
  render::SensorOptions sensor = renderer_->options().sensor;
  sensor.auto_exposure = exposure_us == 0;
  if (exposure_us != 0) sensor.exposure = exposure_us / kExposureUnitUs;
  if (const Status st = renderer_->SetSensor(sensor); !st.ok()) {
    shot.exposure_refused = st.message();
    sensor.auto_exposure = true;
    ROVER_RETURN_IF_ERROR(renderer_->SetSensor(sensor));
  }
  ROVER_ASSIGN_OR_RETURN(shot.images,
                         renderer_->RenderStereoPair(site_from_rover, spec, ++frames_));
  shot.exposure_us = static_cast<std::uint32_t>(
      std::clamp(std::lround(shot.images.left.exposure * kExposureUnitUs), 1L, 4000000000L));
  return shot;
}

}  // namespace rover::sim::rover_sim
