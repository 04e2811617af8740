#include "lander_scene.hpp"

#include <cmath>
#include <numbers>
#include <string>
#include <utility>

#include "rover/base/format.hpp"
#include "rover/sim/render/cameras.hpp"
#include "rover/sim/render/renderer.hpp"

namespace rover::apl::rendezvous::testing {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

}  // namespace

Eigen::Isometry3d SiteFromRamp(const sim::terrain::Lander& lander, int ramp) {
  const sim::terrain::LanderRamp& r = lander.ramps[static_cast<std::size_t>(ramp)];
  const Eigen::Vector3d up_slope = (r.top_center - r.bottom_center).normalized();       // u
  const Eigen::Vector3d left(r.direction.y(), -r.direction.x(), 0.0);                  // v
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear().col(0) = up_slope;
  t.linear().col(1) = left;
  t.linear().col(2) = up_slope.cross(left);
  t.translation() = 0.5 * (r.top_center + r.bottom_center);
  return t;
}

LanderScene::~LanderScene() = default;

hwconfig::LanderDescription LanderScene::description() const {
  return lander().params.Description();
}

Result<std::unique_ptr<LanderScene>> LanderScene::Create(const LanderSceneOptions& options) {
  if (!(options.size >= 10.0 && options.size <= 200.0)) {
    return InvalidArgument("size: " + FormatNumber(options.size) + " m is outside [10, 200]");
  }
  sim::terrain::TerrainParams tp;
  tp.size_x = options.size;
  tp.size_y = options.size_y > 0.0 ? options.size_y : options.size;
  tp.center_x = options.center_x;
  tp.resolution = options.resolution;
  tp.seed = options.seed;
  tp.rocks.preset = options.rocks ? sim::terrain::RockPreset::kVl1 : sim::terrain::RockPreset::kNone;
  if (options.rocks && options.rock_k > 0.0) {
    tp.rocks.preset = sim::terrain::RockPreset::kCustom;
    tp.rocks.k = options.rock_k;
  }
  ROVER_ASSIGN_OR_RETURN(sim::terrain::Terrain terrain, sim::terrain::GenerateTerrain(tp));
  if (!options.outcrops.empty()) {
    sim::terrain::TerrainFeatures features;
    features.outcrops = options.outcrops;
    ROVER_RETURN_IF_ERROR(sim::terrain::PlaceFeatures(&terrain, features));
  }
  if (options.lander) {
    sim::terrain::LanderParams lp;
    lp.x = options.lander_x;
    lp.y = options.lander_y;
    lp.yaw_deg = options.lander_yaw_deg;
    ROVER_RETURN_IF_ERROR(sim::terrain::PlaceLander(&terrain, lp));
  }
  for (const sim::terrain::ScienceTargetParams& t : options.science_targets) {
    ROVER_RETURN_IF_ERROR(sim::terrain::AddScienceTarget(&terrain, t).status());
  }

  sim::render::RenderOptions ro;
  ro.seed = options.seed;
  ro.sun.azimuth_deg = options.sun_azimuth_deg;
  ro.sun.elevation_deg = options.sun_elevation_deg;
  ro.sensor.noise = options.noise;
  std::unique_ptr<LanderScene> scene(new LanderScene());
  scene->options_ = options;
  scene->terrain_ = std::make_shared<const sim::terrain::Terrain>(std::move(terrain));
  ROVER_ASSIGN_OR_RETURN(scene->renderer_, sim::render::Renderer::Create(scene->terrain_, ro));
  return scene;
}

Result<LanderShot> LanderScene::Render(const RoverView& view) {
  const sim::terrain::HeightField& g = terrain_->ground;
  if (!g.Contains(view.x, view.y)) {
    return InvalidArgument("view: rover position (" + FormatNumber(view.x) + ", " +
                           FormatNumber(view.y) + ") is off the map");
  }
  return Render(view, sim::render::RoverPoseOnGround(g, view.x, view.y, view.yaw_deg * kDeg));
}

Result<LanderShot> LanderScene::Render(const RoverView& view, const Eigen::Isometry3d& site_from_rover) {
  const auto defs = sim::render::DefaultStereoCameras(options_.image_size);
  ROVER_ASSIGN_OR_RETURN(const sim::render::StereoCameraDefinition navcam,
                         sim::render::FindStereoCamera(defs, "navcam"));
  ROVER_ASSIGN_OR_RETURN(
      const sim::render::CameraPairSpec spec,
      sim::render::MakeCameraPairSpec(navcam, {view.pan_deg * kDeg, view.tilt_deg * kDeg}));
  ROVER_ASSIGN_OR_RETURN(sim::render::StereoImages pair,
                         renderer_->RenderStereoPair(site_from_rover, spec, view.frame));
  LanderShot shot{.left = pair.left.image,
                  .right = pair.right.image,
                  .left_model = spec.LeftInRover(),
                  .right_model = spec.RightInRover(),
                  .view = view,
                  .site_from_rover = site_from_rover,
                  .ramps = {},
                  .up_in_rover = site_from_rover.linear().transpose() * Eigen::Vector3d::UnitZ()};
  const Eigen::Isometry3d rover_from_site = site_from_rover.inverse();
  for (int r = 0; r < 2 && terrain_->lander; ++r) {
    const sim::terrain::LanderRamp& ramp = lander().ramps[static_cast<std::size_t>(r)];
    RampTruth& t = shot.ramps[static_cast<std::size_t>(r)];
    t.rover_from_ramp = rover_from_site * SiteFromRamp(lander(), r);
    t.base_in_rover = rover_from_site * ramp.bottom_center;
    t.up_axis_in_rover =
        rover_from_site.linear() * Eigen::Vector3d(-ramp.direction.x(), -ramp.direction.y(), 0.0);
    t.slope_deg = ramp.SlopeDeg();
  }
  return shot;
}

RoverView LanderScene::ViewOfRamp(int ramp, double distance, double off_axis_deg,
                                  double yaw_offset_deg) const {
  const sim::terrain::LanderRamp& r = lander().ramps[static_cast<std::size_t>(ramp & 1)];
  const double a = off_axis_deg * kDeg;
  const Eigen::Vector2d d = r.direction;
  const Eigen::Vector2d out(std::cos(a) * d.x() - std::sin(a) * d.y(),
                            std::sin(a) * d.x() + std::cos(a) * d.y());
  const Eigen::Vector2d pos = r.bottom_center.head<2>() + distance * out;
  const Eigen::Vector3d mid = 0.5 * (r.top_center + r.bottom_center);
  const Eigen::Vector2d to_mid = mid.head<2>() - pos;
  RoverView v;
  v.x = pos.x();
  v.y = pos.y();
  v.yaw_deg = std::atan2(to_mid.y(), to_mid.x()) / kDeg + yaw_offset_deg;
  const double ground = terrain_->ground.Contains(pos.x(), pos.y())
                            ? terrain_->ground.Height(pos.x(), pos.y())
                            : 0.0;
  v.tilt_deg = std::atan2(mid.z() - (ground + 1.5), to_mid.norm()) / kDeg;
  v.pan_deg = 0.0;
  return v;
}

}  // namespace rover::apl::rendezvous::testing
