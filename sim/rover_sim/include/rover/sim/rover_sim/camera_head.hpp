#pragma once
/// @file
/// The simulated camera head, without DDS: takes a stereo pair of a named camera for the rover
/// at a pose, with the mast where it is and the sun where it is. The rover-sim service turns
/// hw/camera_request into Take() and the shot into hw/camera_frame.
///
/// The renderer (EGL/OpenGL) is created at the first Take(), so a simulator without a GPU
/// still runs everything but its cameras. Shadows are recomputed only when the sun has moved
/// more than kSunUpdateRad; a sun below kMinSunElevationDeg lights the scene from that
/// elevation (below the horizon the cameras would see nothing).
///
/// Exposure: the sensor model's relative exposure 1 (radiance 1 fills the well, sensor_model.hpp)
/// is kExposureUnitUs of integration time (MER NAVCAM exposures are tens to hundreds of
/// milliseconds in daylight); exposure_us 0 asks for auto-exposure. An exposure the sensor model
/// refuses falls back to auto-exposure and is reported in the shot.

#include <Eigen/Geometry>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "rover/base/param_binder.hpp"
#include "rover/base/status.hpp"
#include "rover/hwconfig/rover_description.hpp"
#include "rover/sim/render/cameras.hpp"
#include "rover/sim/render/renderer.hpp"

namespace rover::sim::rover_sim {

inline constexpr double kExposureUnitUs = 100000.0;
inline constexpr double kSunUpdateRad = 0.5 * 3.14159265358979323846 / 180.0;
inline constexpr double kMinSunElevationDeg = 2.0;

struct CameraHeadOptions {
  int image_size = 1024;         ///< [px] side of the square images (MER: 1024)
  std::int64_t render_seed = 1;  ///< seed of the rendered textures and image noise

  /// image_size in [64, 2048], render_seed >= 0. Messages start with the field.
  Status Validate() const;
  static void BindParams(ParamBinder<CameraHeadOptions>& b);
};

/// One stereo pair as taken.
struct CameraShot {
  render::StereoImages images;
  std::uint32_t exposure_us = 0;  ///< [us] exposure used, in [1, 4e9]
  /// Set when the requested exposure was refused and auto-exposure used instead (the reason).
  std::string exposure_refused;
};

/// One microscopic-imager frame as taken.
struct MicroscopeShot {
  render::CameraImage image;  ///< image and its range [m] (ray length; 0 = nothing)
  std::uint32_t exposure_us = 0;
  std::string exposure_refused;
};

class CameraHead {
 public:
  /// Preconditions: options.Validate() is Ok; `terrain` is not null.
  CameraHead(const CameraHeadOptions& options, std::shared_ptr<const terrain::Terrain> terrain,
             const hwconfig::RoverDescription& rover);

  /// Takes a pair of `camera` ("navcam", "front_hazcam", "rear_hazcam") for the rover at
  /// `site_from_rover` with the mast at `mast` and the unit sun direction `sun_site` (site
  /// frame). `exposure_us` 0 = auto. `readout_width` 0 reads the full sensor (image_size);
  /// otherwise it is image_size / b for a whole binning factor b, and the pair is rendered at
  /// (image_size / b)^2 pixels through the models geometry::Scale(model, 1 / b) (what binning
  /// b x b does to a CAHVOR model), so a binned readout costs the pixels it has, not the
  /// sensor's. Errors: NotFound for an unknown camera (names the known ones), Unavailable when
  /// the renderer cannot start (then every later call says so again without retrying),
  /// InvalidArgument for a bad pose, mast angle or readout width (names the value and the
  /// sensor width), Internal for GL failures.
  Result<CameraShot> Take(const std::string& camera, std::uint32_t exposure_us,
                          const Eigen::Isometry3d& site_from_rover, const render::MastState& mast,
                          const Eigen::Vector3d& sun_site, int readout_width = 0);

  /// Takes one microscopic-imager frame with the arm at `arm` (core/hwconfig MicroscopeOptics:
  /// a pinhole at the instrument face, ArmDescription::ImagerPose, rendered with the lens's
  /// depth of field). Errors as Take's (bad pose, renderer unavailable, GL failure).
  Result<MicroscopeShot> TakeMicroscope(std::uint32_t exposure_us,
                                        const Eigen::Isometry3d& site_from_rover,
                                        const hwconfig::ArmAngles& arm,
                                        const Eigen::Vector3d& sun_site);
  /// The imager's camera model in the rover frame for arm angles `arm`.
  geometry::CameraModel MicroscopeModel(const hwconfig::ArmAngles& arm) const;

  /// Ok when `readout_width` is a readout a `sensor_width`-px sensor can produce (see Take).
  static Status CheckReadout(int readout_width, int sensor_width, const std::string& camera);

  /// Renders made so far (also the noise frame counter).
  std::uint64_t frames() const { return frames_; }

 private:
  Status StartRenderer();
  // Sets the sensor's exposure (0 = auto); a refused one falls back to auto, the reason in
  // *refused.
  Status SetExposure(std::uint32_t exposure_us, int binning, std::string* refused);
  void UpdateSun(const Eigen::Vector3d& sun_site);

  CameraHeadOptions options_;
  std::shared_ptr<const terrain::Terrain> terrain_;
  hwconfig::MastDescription mast_geometry_;
  hwconfig::ArmDescription arm_;
  std::vector<render::StereoCameraDefinition> cameras_;
  std::unique_ptr<render::Renderer> renderer_;
  Status renderer_error_;
  Eigen::Vector3d last_sun_ = Eigen::Vector3d::UnitZ();
  bool sun_set_ = false;
  std::uint64_t frames_ = 0;
};

}  // namespace rover::sim::rover_sim
