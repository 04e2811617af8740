#pragma once
/// @file
/// Renderer: gives the simulated cameras real pixels. It draws a sim/terrain Terrain (the
/// `natural` heightfield = ground + rocks, the lander quads, science targets) with procedural
/// multi-scale textures, Lambertian sun shading with cast shadows (cascaded shadow maps) and a
/// sky term, through an exact camera model, and applies a sensor model (sensor_model.hpp). It
/// only makes images: nothing else leaves it (the range image is a test option).
///
/// Optics. Each camera is rendered by OpenGL as one or more virtual pinhole views (one view for
/// fields up to ~60 deg off axis; up to five cube-map faces for fisheye lenses), packed in one
/// framebuffer, then warped to the camera model: for every output pixel the model's Unproject
/// gives a ray, which projects exactly into a virtual view; the image value is interpolated
/// bilinearly there (cv::remap with a cached table). A scene point therefore appears where
/// CameraModel::Project puts it, including CAHVOR/CAHVORE distortion (measured < 0.1 px; see
/// README.md). Virtual views are sampled at least as densely as the output pixels.
/// Limitation: CAHVORE pupil motion (E != 0) is ignored (rays from C).
///
/// Scene radiance (reflectance units, see sensor_model.hpp), per surface point with albedo a,
/// shading normal n (heightfield normal + texture bump), sun direction s, shadow factor
/// 0 <= sh <= 1 from the shadow maps:
///   L = a * (sun_irradiance * max(0, n.s) * sh + sky_irradiance * (0.6 + 0.4 n.z))
/// The sky seen directly has radiance sky_radiance, brighter towards the horizon and the sun.
///
/// Frames: site frame x north, y west, z up; sun azimuth from +x towards +y, elevation above
/// the horizon; rover pose = site_from_rover; models in the rover frame (cameras.hpp).
///
/// Threading: a Renderer owns an EGL context; use it from one thread at a time (each call makes
/// its context current). Create() returns Unavailable when EGL/OpenGL cannot be initialised
/// (no crash): callers and tests report or skip.

#include <Eigen/Geometry>
#include <cstdint>
#include <memory>
#include <opencv2/core.hpp>
#include <string>

#include "rover/base/status.hpp"
#include "rover/geometry/camera_model.hpp"
#include "rover/sim/render/cameras.hpp"
#include "rover/sim/render/depth_of_field.hpp"
#include "rover/sim/render/sensor_model.hpp"
#include "rover/sim/terrain/terrain.hpp"

namespace rover::sim::render {

struct SunOptions {
  double azimuth_deg = 135.0;   ///< [deg] from +x (north) towards +y (west): 135 = south-west
  double elevation_deg = 35.0;  ///< [deg] above the horizon, (0, 90]
  Status Validate() const;
  /// Unit vector towards the sun, site frame.
  Eigen::Vector3d Direction() const;
};

struct RenderOptions {
  /// Seed of the procedural textures and (mixed with the frame number) the sensor noise.
  std::uint64_t seed = 1;
  SunOptions sun;
  double sun_irradiance = 1.0;  ///< direct sun, reflectance units
  double sky_irradiance = 0.22; ///< diffuse sky on a horizontal surface (Mars: dusty sky)
  double sky_radiance = 0.12;   ///< sky seen directly (zenith; brighter near the horizon)

  // Materials (albedo, dimensionless).
  double soil_albedo = 0.24;
  double sand_albedo = 0.30;
  double bedrock_albedo = 0.19;
  double rock_albedo_min = 0.11;  ///< ordinary rocks: per-rock albedo uniform in [min, max]
  double rock_albedo_max = 0.21;
  double target_albedo = 0.30;    ///< science targets (light-toned, distinctive textures)
  double texture_contrast = 1.0;  ///< scales every texture's albedo modulation, [0, 2]
  /// Anisotropic texture filtering (1 = off, trilinear only). llvmpipe filters anisotropically
  /// in software, which costs several times the whole frame; raise it on a real GPU.
  int texture_anisotropy = 1;

  // Geometry and level of detail.
  int tile_cells = 64;          ///< terrain tile edge in grid cells (power of two, 8..256)
  double lod_error_px = 1.0;    ///< allowed screen-space height error of a coarser tile LOD
  double lod_max_cell_px = 12;  ///< a coarser LOD's cells must stay below this size on screen
  double apron_m = 1000.0;      ///< flat ground drawn around the map out to this distance

  // Optics.
  double oversample = 1.0;      ///< virtual-view pixel density / output density, [1, 3]
  /// A binned readout (sensor.binning b > 1) is rendered s = min(b, binned_supersample) times
  /// finer and its radiance area-averaged to the readout before the sensor model: a binned
  /// pixel integrates the light of b x b sensor pixels, and point-sampling the scene at the
  /// readout's own pixels loses the fine texture stereo matches on (a 256-px readout of the
  /// 1024-px HAZCAM rendered at 256 px ranged a third fewer points 2.5-3.5 m out, with twice the
  /// height error of the full frame area-averaged; at s = 2 it is within a third of it:
  /// tests/consistency/stereo_on_sim_images_test.cpp). Costs s^2 the readout's pixels. [1, 4]
  int binned_supersample = 2;
  int max_view_size = 6144;     ///< largest virtual-view side [px]

  // Shadows.
  // Shadows: `shadow_cascades` shadow maps fitted to the cameras' view out to shadow_distance
  // (re-rendered every frame), and beyond that one static map of the whole terrain (rendered
  // once per sun direction).
  int shadow_map_size = 2048;         ///< per camera-fitted cascade, [256, 8192]
  /// shadow_map_size is for images this wide; a narrower image (a binned readout) renders its
  /// cascades proportionally smaller (a power of two, at least 512), keeping the shadow texels
  /// per image pixel: on llvmpipe the cascades cost a third of a 256-px HAZCAM pair otherwise.
  /// [256, 8192]
  int shadow_reference_width = 1024;
  int shadow_cascades = 2;            ///< camera-fitted cascades, [1, 3]
  double shadow_distance = 12;        ///< [m] reach of the camera-fitted cascades, [1, 1000]
  int global_shadow_map_size = 4096;  ///< whole-terrain map, [512, 8192]

  SensorOptions sensor;
  bool output_range = false;    ///< also return range images (tests and tools only)
  bool output_radiance = false; ///< also return the warped radiance before the sensor model

  /// Checks every field; the message names it ("render.tile_cells: ...").
  Status Validate() const;
};

/// One rendered camera image.
struct CameraImage {
  cv::Mat image;     ///< CV_8UC1, the camera's width x height
  /// CV_32FC1 [m]: distance from the camera centre to the surface seen along each pixel's ray;
  /// 0 = sky / no surface. Only with RenderOptions::output_range.
  cv::Mat range;
  cv::Mat radiance;  ///< CV_32FC1 before the sensor model; only with output_radiance
  double exposure = 0.0;  ///< exposure used (sensor_model.hpp)
};

struct StereoImages {
  CameraImage left;
  CameraImage right;
};

/// Work and timing of the last call (for benchmarks and logs).
struct RenderStats {
  int views = 0;              ///< virtual pinhole views rendered (all cameras)
  long long triangles = 0;    ///< triangles submitted, camera passes
  long long shadow_triangles = 0;
  double shadow_ms = 0.0;     ///< shadow-map passes
  double gl_ms = 0.0;         ///< camera passes incl. readback
  double warp_ms = 0.0;       ///< cv::remap of radiance (and range)
  double sensor_ms = 0.0;     ///< sensor model
  double plan_ms = 0.0;       ///< warp tables built (0 when cached)
};

class Renderer {
 public:
  /// Builds the GPU scene from `terrain` (tiles with LOD, textures, rock and lander data).
  /// Errors: InvalidArgument for bad options or an empty terrain, Unavailable when EGL/OpenGL
  /// cannot be initialised (message says why), Internal for a GL failure.
  static Result<std::unique_ptr<Renderer>> Create(std::shared_ptr<const terrain::Terrain> terrain,
                                                  const RenderOptions& options = {});
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  /// Renders both cameras of `pair` for the rover at `site_from_rover`. The shadow maps are
  /// shared by both; auto-exposure is computed on the left image and used for both. `frame`
  /// seeds the noise (with RenderOptions::seed; left and right get different streams).
  /// Errors: non-finite or non-rigid pose (InvalidArgument), GL failure (Internal).
  Result<StereoImages> RenderStereoPair(const Eigen::Isometry3d& site_from_rover,
                                        const CameraPairSpec& pair, std::uint64_t frame = 0);

  /// Renders one camera whose model is in the rover frame.
  Result<CameraImage> RenderCamera(const Eigen::Isometry3d& site_from_rover,
                                   const geometry::CameraModel& model_in_rover,
                                   std::uint64_t frame = 0);

  /// Renders one close-up camera (model in the rover frame) with a shallow depth of field
  /// (depth_of_field.hpp) and a near plane of dof.near: the microscopic imager. The image's
  /// range is always returned. Errors: dof.Validate(), and those of RenderCamera.
  Result<CameraImage> RenderCloseUp(const Eigen::Isometry3d& site_from_rover,
                                    const geometry::CameraModel& model_in_rover,
                                    const DepthOfField& dof, std::uint64_t frame = 0);

  /// Changes the sun (the next render recomputes the shadow maps).
  Status SetSun(const SunOptions& sun);
  /// Changes the sensor model.
  Status SetSensor(const SensorOptions& sensor);

  const RenderOptions& options() const;
  const RenderStats& last_stats() const;
  /// "llvmpipe (LLVM 15.0.6, 256 bits)" etc.
  std::string gl_renderer() const;

  class Impl;

 private:
  explicit Renderer(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace rover::sim::render
