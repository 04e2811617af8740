#pragma once
/// @file
/// Test fixture (LAYER tests): rendered NAVCAM views of a simulated lander with their truth, for
/// the rendezvous vision tests (stripes at close range, the lander outline at mid range).
///
/// A LanderScene owns one seeded terrain with a lander and one renderer (setup ~1.5 s: create
/// one per test suite, e.g. in SetUpTestSuite, and render many views from it, ~1 s per 1024^2
/// pair). Render(view) places the rover on the ground at (x, y, yaw) with the given mast pan/tilt
/// and returns the NAVCAM pair (sensor noise on by default), the two CAHVOR models in the ROVER
/// frame (as the running system attaches them to a frame) and the truth of both ramps.
///
/// Frames (metres, radians inside, degrees in the option fields):
///   site:  the simulator's world frame, x north, y west, z up.
///   rover: x forward, y left, z up, origin on the ground below the rocker pivots.
///   G:     per ramp, the ramp-surface frame of hwconfig::LanderDescription: origin at the centre
///          of the ramp surface (middle of the stripe block), u up the slope towards the deck,
///          v across to the left when facing up the ramp, w = u x v out of the surface.
/// Note: the simulator lifts the stripe quads 3 mm above the ramp surface (no z-fighting); the
/// truth below is the surface frame itself, so a stripe-based estimate sits ~3 mm off along w.
///
/// Default world: 28 m x 28 m VL-1 rocks, lander deck centre at the site origin with yaw 0, so
/// ramp 0 descends towards +x (its base at x = apothem + ramp_length = 4.30 m) and ramp 1
/// towards -x (base at x = -4.30 m). Views up to ~9 m from either base stay on the map.

#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <memory>
#include <vector>
#include <opencv2/core.hpp>

#include "rover/base/status.hpp"
#include "rover/geometry/camera_model.hpp"
#include "rover/hwconfig/lander_description.hpp"
#include "rover/sim/terrain/features.hpp"
#include "rover/sim/terrain/lander.hpp"
#include "rover/sim/terrain/terrain.hpp"

namespace rover::sim::render {
class Renderer;
}  // namespace rover::sim::render

namespace rover::apl::rendezvous::testing {

/// The world a LanderScene builds.
struct LanderSceneOptions {
  std::uint64_t seed = 4;        ///< terrain, texture and noise seed
  double size = 28.0;            ///< [m] map side along x (and y unless size_y > 0)
  double size_y = 0.0;           ///< [m] map side along y; 0: `size`
  double center_x = 0.0;         ///< [m] map centre along x (long-range views: a long map)
  double resolution = 0.04;      ///< [m] terrain cells (long maps: 0.05, as the scenarios)
  /// Layered outcrops (sim/terrain features.hpp), the long-range search's distractors.
  std::vector<sim::terrain::Outcrop> outcrops;
  bool lander = true;            ///< place the lander (false: none)
  /// Science-target rocks (sim/terrain lander.hpp), placed after the lander.
  std::vector<sim::terrain::ScienceTargetParams> science_targets;
  double lander_x = 0.0;         ///< [m] deck centre, site frame
  double lander_y = 0.0;         ///< [m]
  double lander_yaw_deg = 0.0;   ///< [deg] direction ramp 0 descends, from +x towards +y
  bool rocks = true;             ///< VL-1 rock field (false: no rocks)
  double rock_k = 0.0;           ///< > 0: this rock cover k instead of VL-1's (when rocks)
  bool noise = true;             ///< sensor shot and read noise
  int image_size = 1024;         ///< NAVCAM side [px] (1024 = the flight camera, 512 = binned)
  double sun_azimuth_deg = 135;  ///< [deg] from +x towards +y
  double sun_elevation_deg = 35; ///< [deg]
};

/// Where the rover stands and where its mast looks.
struct RoverView {
  double x = 0.0;        ///< [m] site frame
  double y = 0.0;        ///< [m]
  double yaw_deg = 0.0;  ///< [deg] heading from +x towards +y
  double pan_deg = 0.0;  ///< [deg] mast pan, + looks left
  double tilt_deg = -15.0;  ///< [deg] mast tilt, + looks up
  std::uint64_t frame = 0;  ///< noise stream
};

/// Truth of one ramp seen from the rover.
struct RampTruth {
  Eigen::Isometry3d rover_from_ramp = Eigen::Isometry3d::Identity();  ///< frame G -> rover frame
  Eigen::Vector3d base_in_rover = Eigen::Vector3d::Zero();  ///< [m] middle of the ramp's ground edge
  Eigen::Vector3d up_axis_in_rover = Eigen::Vector3d::UnitX();  ///< horizontal unit, up the ramp
  double slope_deg = 0.0;  ///< inclination of the ramp surface
};

/// One rendered stereo view with its truth.
struct LanderShot {
  cv::Mat left;   ///< CV_8UC1 NAVCAM left image
  cv::Mat right;  ///< CV_8UC1 NAVCAM right image
  geometry::CameraModel left_model;   ///< CAHVOR in the rover frame
  geometry::CameraModel right_model;  ///< CAHVOR in the rover frame
  RoverView view;
  Eigen::Isometry3d site_from_rover = Eigen::Isometry3d::Identity();
  std::array<RampTruth, 2> ramps;  ///< indexed by ramp
  /// Rover up (unit, against gravity) in the rover frame (the rover may stand tilted).
  Eigen::Vector3d up_in_rover = Eigen::Vector3d::UnitZ();
};

class LanderScene {
 public:
  /// Builds the terrain, places the lander and sets up the renderer. Errors: bad options (naming
  /// the field), a lander that does not fit, Unavailable when OpenGL cannot be initialised.
  static Result<std::unique_ptr<LanderScene>> Create(const LanderSceneOptions& options = {});
  ~LanderScene();
  LanderScene(const LanderScene&) = delete;
  LanderScene& operator=(const LanderScene&) = delete;

  /// Renders the NAVCAM pair for `view` (the rover resting on the ground at (x, y) with heading
  /// yaw). Errors: the position off the map, a render failure.
  Result<LanderShot> Render(const RoverView& view);
  /// The same for a rover pose given in full (e.g. one driven off the ground's heading).
  Result<LanderShot> Render(const RoverView& view, const Eigen::Isometry3d& site_from_rover);

  /// A view of ramp `ramp` (0/1): the rover `distance` m (horizontal) from the middle of the
  /// ramp's ground edge, `off_axis_deg` around the base from the ramp's axis (+ = counter-
  /// clockwise seen from above), heading at the middle of the ramp plus `yaw_offset_deg`, with
  /// the mast tilted to look at the middle of the ramp (pan 0).
  RoverView ViewOfRamp(int ramp, double distance, double off_axis_deg,
                       double yaw_offset_deg = 0.0) const;

  const sim::terrain::Terrain& terrain() const { return *terrain_; }
  /// Precondition: options().lander.
  const sim::terrain::Lander& lander() const { return *terrain_->lander; }
  /// The lander as the rover knows it (the simulator's lander is built from it).
  hwconfig::LanderDescription description() const;
  const LanderSceneOptions& options() const { return options_; }

 private:
  LanderScene() = default;
  LanderSceneOptions options_;
  std::shared_ptr<const sim::terrain::Terrain> terrain_;
  std::unique_ptr<sim::render::Renderer> renderer_;
};

/// site_from_G of ramp `ramp` of a simulated lander (see the file comment for G).
Eigen::Isometry3d SiteFromRamp(const sim::terrain::Lander& lander, int ramp);

}  // namespace rover::apl::rendezvous::testing
