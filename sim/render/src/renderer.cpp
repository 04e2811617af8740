#include "rover/sim/render/renderer.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <numbers>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "gl_context.hpp"
#include "rover/base/check.hpp"
#include "rover/base/format.hpp"
#include "rover/base/units.hpp"
#include "rover/sim/render/depth_of_field.hpp"
#include "rover/sim/terrain/noise.hpp"
#include "rover/sim/terrain/random.hpp"
#include "shaders.hpp"
#include "terrain_mesh.hpp"
#include "textures.hpp"
#include "view_planner.hpp"

namespace rover::sim::render {

using terrain::FractalNoise;
using terrain::HeightField;
using terrain::LanderPart;
using terrain::LanderQuad;
using terrain::MixSeed;
using terrain::Rng;
using terrain::Rock;
using terrain::RockBoundingRadius;
using terrain::RockRelief;
using terrain::Soil;
using terrain::Terrain;

using internal::CameraFrame;
using internal::VirtualView;
using internal::WarpPlan;

namespace {

constexpr double kNear = 0.05;    // [m] camera near plane
constexpr double kFar = 4000.0;   // [m] camera far plane
constexpr double kCloseUpFar = 50.0;  // [m] far plane of close-up renders (depth precision)
constexpr int kDetailSize = 1024;
constexpr int kRockTexSize = 512;
// Texture units.
constexpr int kUnitSurface = 0, kUnitMaterial = 1, kUnitRockId = 2, kUnitRocks = 3,
              kUnitDetail = 4, kUnitRockTex = 5, kUnitShadow = 6, kUnitShadowGlobal = 7, kUnitScratch = 15;

Status BadOption(const std::string& field, double value, const std::string& what) {
  return InvalidArgument("render." + field + ": " + FormatNumber(value) + " " + what);
}

// Range along each pixel's ray -> distance along the camera's optical axis (0 stays 0).
cv::Mat AxialDepth(const cv::Mat& range, const geometry::CameraModel& model) {
  cv::Mat depth(range.size(), CV_32FC1, cv::Scalar(0));
  // The optical axis as the ray of the image centre (the close-up camera's principal point).
  const auto centre = model.Unproject(Eigen::Vector2d(0.5 * (range.cols - 1), 0.5 * (range.rows - 1)));
  const Eigen::Vector3d axis = centre ? centre->direction : Eigen::Vector3d::UnitZ();
  for (int r = 0; r < range.rows; ++r) {
    const float* g = range.ptr<float>(r);
    float* d = depth.ptr<float>(r);
    for (int c = 0; c < range.cols; ++c) {
      if (g[c] <= 0.0F) continue;
      const auto ray = model.Unproject(Eigen::Vector2d(c, r));
      if (!ray) continue;
      d[c] = static_cast<float>(g[c] * std::max(0.0, ray->direction.dot(axis)));
    }
  }
  return depth;
}

double Ms(std::chrono::steady_clock::time_point a) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - a).count();
}

const void* Offset(std::size_t bytes) {
  return reinterpret_cast<const void*>(static_cast<std::uintptr_t>(bytes));
}

using Planes = std::array<Eigen::Vector4d, 6>;

// Frustum planes (a, b, c, d; inside where a x + b y + c z + d >= 0) of a clip matrix.
Planes FrustumPlanes(const Eigen::Matrix4d& m) {
  Planes p;
  const Eigen::Vector4d r0 = m.row(0), r1 = m.row(1), r2 = m.row(2), r3 = m.row(3);
  p[0] = r3 + r0;
  p[1] = r3 - r0;
  p[2] = r3 + r1;
  p[3] = r3 - r1;
  p[4] = r3 + r2;
  p[5] = r3 - r2;
  return p;
}

bool BoxVisible(const Planes& planes, const Eigen::Vector3f& lo, const Eigen::Vector3f& hi) {
  for (const auto& pl : planes) {
    const double x = pl.x() >= 0 ? hi.x() : lo.x();
    const double y = pl.y() >= 0 ? hi.y() : lo.y();
    const double z = pl.z() >= 0 ? hi.z() : lo.z();
    if (pl.x() * x + pl.y() * y + pl.z() * z + pl.w() < 0.0) return false;
  }
  return true;
}

void SetMat4(GLuint prog, const char* name, const Eigen::Matrix4d& m) {
  const Eigen::Matrix4f f = m.cast<float>();
  glUniformMatrix4fv(glGetUniformLocation(prog, name), 1, GL_FALSE, f.data());
}
void SetVec3(GLuint prog, const char* name, const Eigen::Vector3d& v) {
  glUniform3f(glGetUniformLocation(prog, name), static_cast<float>(v.x()), static_cast<float>(v.y()),
              static_cast<float>(v.z()));
}
void SetFloat(GLuint prog, const char* name, double v) {
  glUniform1f(glGetUniformLocation(prog, name), static_cast<float>(v));
}
void SetInt(GLuint prog, const char* name, int v) {
  glUniform1i(glGetUniformLocation(prog, name), v);
}

bool HasExtension(const char* name) {
  GLint n = 0;
  glGetIntegerv(GL_NUM_EXTENSIONS, &n);
  for (GLint i = 0; i < n; ++i) {
    const auto* e = reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, static_cast<GLuint>(i)));
    if (e != nullptr && std::strcmp(e, name) == 0) return true;
  }
  return false;
}

// A camera placed for one render: its plan and frame in render coordinates.
struct PlacedCamera {
  std::shared_ptr<const WarpPlan> plan;
  Eigen::Matrix3d render_from_cam = Eigen::Matrix3d::Identity();
  Eigen::Vector3d center = Eigen::Vector3d::Zero();  // render coordinates
};

// Projection of a view (see the README): camera-frame point -> clip, pixel-centre convention,
// image row v at window row v (so glReadPixels returns the image top row first).
Eigen::Matrix4d ViewProjection(const VirtualView& v, double near, double far) {
  Eigen::Matrix4d p = Eigen::Matrix4d::Zero();
  p(0, 0) = 2.0 * v.f / v.width;
  p(0, 2) = 2.0 * (v.cx + 0.5) / v.width - 1.0;
  p(1, 1) = 2.0 * v.f / v.height;
  p(1, 2) = 2.0 * (v.cy + 0.5) / v.height - 1.0;
  p(2, 2) = (far + near) / (far - near);
  p(2, 3) = -2.0 * far * near / (far - near);
  p(3, 2) = 1.0;
  return p;
}

Eigen::Matrix4d RigidInverse(const Eigen::Matrix3d& r, const Eigen::Vector3d& t) {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.topLeftCorner<3, 3>() = r.transpose();
  m.topRightCorner<3, 1>() = -(r.transpose() * t);
  return m;
}

}  // namespace

// ---- options ------------------------------------------------------------------------------

Status SunOptions::Validate() const {
  if (!std::isfinite(azimuth_deg)) return BadOption("sun.azimuth_deg", azimuth_deg, "is not finite");
  if (!(elevation_deg > 0.0 && elevation_deg <= 90.0)) {
    return BadOption("sun.elevation_deg", elevation_deg, "is out of range (0, 90]");
  }
  return Status::Ok();
}

Eigen::Vector3d SunOptions::Direction() const {
  const double az = azimuth_deg * kDegree, el = elevation_deg * kDegree;
  return Eigen::Vector3d(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el));
}

Status RenderOptions::Validate() const {
  ROVER_RETURN_IF_ERROR(sun.Validate());
  ROVER_RETURN_IF_ERROR(sensor.Validate());
  auto range = [](const char* field, double v, double lo, double hi) -> Status {
    if (!(v >= lo && v <= hi)) {
      return BadOption(field, v,
                       "is out of range [" + FormatNumber(lo) + ", " + FormatNumber(hi) + "]");
    }
    return Status::Ok();
  };
  ROVER_RETURN_IF_ERROR(range("sun_irradiance", sun_irradiance, 0.0, 100.0));
  ROVER_RETURN_IF_ERROR(range("sky_irradiance", sky_irradiance, 0.0, 100.0));
  ROVER_RETURN_IF_ERROR(range("sky_radiance", sky_radiance, 0.0, 100.0));
  ROVER_RETURN_IF_ERROR(range("soil_albedo", soil_albedo, 0.0, 1.0));
  ROVER_RETURN_IF_ERROR(range("sand_albedo", sand_albedo, 0.0, 1.0));
  ROVER_RETURN_IF_ERROR(range("bedrock_albedo", bedrock_albedo, 0.0, 1.0));
  ROVER_RETURN_IF_ERROR(range("rock_albedo_min", rock_albedo_min, 0.0, 1.0));
  ROVER_RETURN_IF_ERROR(range("rock_albedo_max", rock_albedo_max, rock_albedo_min, 1.0));
  ROVER_RETURN_IF_ERROR(range("target_albedo", target_albedo, 0.0, 1.0));
  ROVER_RETURN_IF_ERROR(range("texture_contrast", texture_contrast, 0.0, 2.0));
  if (texture_anisotropy < 1 || texture_anisotropy > 16) {
    return BadOption("texture_anisotropy", texture_anisotropy, "is out of range [1, 16]");
  }
  if (tile_cells < 8 || tile_cells > 256 || (tile_cells & (tile_cells - 1)) != 0) {
    return BadOption("tile_cells", tile_cells, "must be a power of two in [8, 256]");
  }
  ROVER_RETURN_IF_ERROR(range("lod_error_px", lod_error_px, 0.0, 100.0));
  ROVER_RETURN_IF_ERROR(range("lod_max_cell_px", lod_max_cell_px, 0.5, 1000.0));
  ROVER_RETURN_IF_ERROR(range("apron_m", apron_m, 0.0, 3000.0));
  ROVER_RETURN_IF_ERROR(range("oversample", oversample, 1.0, 3.0));
  if (binned_supersample < 1 || binned_supersample > 4) {
    return BadOption("binned_supersample", binned_supersample, "is out of range [1, 4]");
  }
  ROVER_RETURN_IF_ERROR(range("max_view_size", max_view_size, 64, 16384));
  if (shadow_map_size < 256 || shadow_map_size > 8192) {
    return BadOption("shadow_map_size", shadow_map_size, "is out of range [256, 8192]");
  }
  if (shadow_cascades < 1 || shadow_cascades > 3) {
    return BadOption("shadow_cascades", shadow_cascades, "is out of range [1, 3]");
  }
  ROVER_RETURN_IF_ERROR(range("shadow_distance", shadow_distance, 1.0, 1000.0));
  if (shadow_reference_width < 256 || shadow_reference_width > 8192) {
    return BadOption("shadow_reference_width", shadow_reference_width,
                     "is out of range [256, 8192]");
  }
  if (global_shadow_map_size < 512 || global_shadow_map_size > 8192) {
    return BadOption("global_shadow_map_size", global_shadow_map_size, "is out of range [512, 8192]");
  }
  return Status::Ok();
}

// ---- implementation -------------------------------------------------------------------------

class Renderer::Impl {
 public:
  RenderOptions options;
  std::shared_ptr<const Terrain> terrain;
  std::unique_ptr<internal::GlContext> gl;
  RenderStats stats;

  Status Init();
  ~Impl();
  void InvalidateShadows() { global_valid_ = false; }
  // A render's clipping planes and extras: the close-up camera (depth of field) renders with
  // a near plane of millimetres and always needs the range.
  struct Pass {
    double near = kNear;
    double far = kFar;
    bool want_range = false;
    const DepthOfField* dof = nullptr;
  };
  Result<StereoImages> Render(const Eigen::Isometry3d& site_from_rover,
                              const std::vector<geometry::CameraModel>& models_in_rover,
                              std::uint64_t frame, const Pass& pass);

 private:
  Result<std::shared_ptr<const WarpPlan>> Plan(const geometry::CameraModel& model_site);
  void BuildSurfaceTextures();
  void BuildRockData();
  void BuildLander();
  void BuildApron();
  Status BuildShadowTargets();
  Status EnsureAtlas(int width, int height);
  void SelectLods(const Eigen::Vector3d& camera, double focal_px);
  void SetLightingUniforms(GLuint prog, const Eigen::Vector3d& cam);
  void DrawTerrain(GLuint prog, const Planes& planes, long long* triangles);
  void DrawLander(GLuint prog, long long* triangles);
  // `image_width` [px] of the images being rendered sets the cascades' size (see
  // RenderOptions::shadow_reference_width).
  void RenderShadows(const std::vector<PlacedCamera>& cams, const Eigen::Vector3d& center,
                     int image_width);
  void RenderGlobalShadow();
  // Light frame (rows: x, y, z = light travel) and the scene's light-space box.
  Eigen::Matrix3d LightFrame(Eigen::Vector3d* box_min, Eigen::Vector3d* box_max) const;
  Eigen::Matrix4d LightClip(const Eigen::Matrix3d& light_from_render, double xmin, double xmax,
                            double ymin, double ymax, double zmin, double zmax) const;
  Result<cv::Mat> RenderAtlas(const PlacedCamera& cam, const Pass& pass, cv::Mat* range_atlas);

  internal::TerrainMesh mesh_;  // vertices/indices freed after upload; tiles kept
  Eigen::Vector3d origin_ = Eigen::Vector3d::Zero();
  Eigen::Vector3f scene_min_ = Eigen::Vector3f::Zero(), scene_max_ = Eigen::Vector3f::Zero();
  std::vector<int> lod_;         // per tile, for the current render
  std::vector<int> draw_order_;  // tiles by distance from the cameras

  GLuint terrain_prog_ = 0, lander_prog_ = 0, sky_prog_ = 0, shadow_prog_ = 0;
  GLuint terrain_vao_ = 0, terrain_vbo_ = 0, terrain_ibo_ = 0;
  GLuint apron_vao_ = 0, apron_vbo_ = 0;
  GLuint lander_vao_ = 0, lander_vbo_ = 0;
  GLsizei lander_solid_vertices_ = 0, lander_stripe_vertices_ = 0;
  GLuint empty_vao_ = 0;
  GLuint tex_surface_ = 0, tex_material_ = 0, tex_rock_id_ = 0, tex_rocks_ = 0, buf_rocks_ = 0,
         tex_detail_ = 0, tex_rock_ = 0;
  GLuint shadow_tex_ = 0, shadow_fbo_ = 0, global_tex_ = 0, global_fbo_ = 0;
  bool global_valid_ = false;
  Eigen::Matrix4d global_light_ = Eigen::Matrix4d::Identity();
  float global_texel_ = 0.0F, global_depth_scale_ = 0.0F;
  GLuint atlas_fbo_ = 0, atlas_color_ = 0, atlas_range_ = 0, atlas_depth_ = 0;
  int atlas_w_ = 0, atlas_h_ = 0;

  // Shadow state of the current render.
  std::array<Eigen::Matrix4d, 4> light_{};
  std::array<float, 4> cascade_far_{}, shadow_texel_{}, depth_scale_{};
  Eigen::Vector3d shadow_center_ = Eigen::Vector3d::Zero();

  std::map<std::string, std::shared_ptr<const WarpPlan>> plans_;
};

Status Renderer::Impl::Init() {
  auto ctx = internal::GlContext::Create();
  if (!ctx.ok()) return ctx.status();
  gl = std::move(*ctx);
  const HeightField& hf = terrain->natural;
  origin_ = Eigen::Vector3d(0.5 * (hf.min_x() + hf.max_x()), 0.5 * (hf.min_y() + hf.max_y()), 0.0);
  mesh_ = internal::BuildTerrainMesh(hf, options.tile_cells, origin_);
  lod_.assign(mesh_.tiles.size(), 0);
  for (std::size_t k = 0; k < mesh_.tiles.size(); ++k) draw_order_.push_back(static_cast<int>(k));

  // Programs.
  for (auto [prog, src] : {std::pair<GLuint*, internal::ProgramSource>{&terrain_prog_, internal::TerrainProgram()},
                           {&lander_prog_, internal::LanderProgram()},
                           {&sky_prog_, internal::SkyProgram()},
                           {&shadow_prog_, internal::ShadowProgram()}}) {
    auto p = internal::BuildProgram(src);
    if (!p.ok()) return p.status();
    *prog = *p;
  }

  // Terrain geometry.
  glGenVertexArrays(1, &terrain_vao_);
  glBindVertexArray(terrain_vao_);
  glGenBuffers(1, &terrain_vbo_);
  glBindBuffer(GL_ARRAY_BUFFER, terrain_vbo_);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(mesh_.vertices.size() * sizeof(float)),
               mesh_.vertices.data(), GL_STATIC_DRAW);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 4, GL_FLOAT, GL_FALSE, 4 * sizeof(float), Offset(0));
  glGenBuffers(1, &terrain_ibo_);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, terrain_ibo_);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER,
               static_cast<GLsizeiptr>(mesh_.indices.size() * sizeof(std::uint32_t)),
               mesh_.indices.data(), GL_STATIC_DRAW);
  glBindVertexArray(0);
  ROVER_RETURN_IF_ERROR(internal::CheckGl("terrain upload"));
  mesh_.vertices = {};
  mesh_.indices = {};

  scene_min_ = Eigen::Vector3f::Constant(1e30F);
  scene_max_ = Eigen::Vector3f::Constant(-1e30F);
  for (const auto& t : mesh_.tiles) {
    scene_min_ = scene_min_.cwiseMin(t.box_min);
    scene_max_ = scene_max_.cwiseMax(t.box_max);
  }

  BuildSurfaceTextures();
  BuildRockData();
  BuildLander();
  BuildApron();
  ROVER_RETURN_IF_ERROR(internal::CheckGl("scene upload"));
  ROVER_RETURN_IF_ERROR(BuildShadowTargets());
  glGenVertexArrays(1, &empty_vao_);

  // Static uniforms.
  for (GLuint prog : {terrain_prog_, lander_prog_}) {
    glUseProgram(prog);
    SetInt(prog, "u_surface", kUnitSurface);
    SetInt(prog, "u_material", kUnitMaterial);
    SetInt(prog, "u_rock_id", kUnitRockId);
    SetInt(prog, "u_rocks", kUnitRocks);
    SetInt(prog, "u_detail", kUnitDetail);
    SetInt(prog, "u_rock_tex", kUnitRockTex);
    SetInt(prog, "u_shadow", kUnitShadow);
    SetInt(prog, "u_shadow_global", kUnitShadowGlobal);
    SetFloat(prog, "u_contrast", options.texture_contrast);
  }
  glUseProgram(terrain_prog_);
  glUniform2f(glGetUniformLocation(terrain_prog_, "u_grid_min"),
              static_cast<float>(hf.min_x() - origin_.x()), static_cast<float>(hf.min_y() - origin_.y()));
  SetFloat(terrain_prog_, "u_grid_res", hf.resolution());
  glUniform2i(glGetUniformLocation(terrain_prog_, "u_grid_n"), hf.nx(), hf.ny());
  SetFloat(terrain_prog_, "u_soil_albedo", options.soil_albedo);
  SetFloat(terrain_prog_, "u_sand_albedo", options.sand_albedo);
  SetFloat(terrain_prog_, "u_bedrock_albedo", options.bedrock_albedo);
  glUseProgram(0);
  return internal::CheckGl("renderer initialisation");
}

void Renderer::Impl::BuildSurfaceTextures() {
  const HeightField& nat = terrain->natural;
  const HeightField& bare = terrain->bare;
  const int nx = nat.nx(), ny = nat.ny();
  const double res = nat.resolution();
  const std::size_t n = static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny);
  // Macro albedo: fBm 6 m .. 0.4 m, +-18 %, seeded.
  std::vector<double> macro(n, 0.0);
  {
    Rng rng(MixSeed(options.seed, 11));
    FractalNoise fbm(&rng, Eigen::Vector2d(nat.min_x(), nat.min_y()),
                     Eigen::Vector2d(nat.max_x(), nat.max_y()), 6.0, 4, 0.6);
    fbm.AddToGrid(nat.min_x(), nat.min_y(), res, nx, ny, 1.0 / fbm.max_abs(), macro.data());
  }
  std::vector<float> surface(n * 4);
  cv::Mat material(ny, nx, CV_8UC2);
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const int i0 = std::max(0, i - 1), i1 = std::min(nx - 1, i + 1);
      const int j0 = std::max(0, j - 1), j1 = std::min(ny - 1, j + 1);
      const double dzdx = (nat.at(i1, j) - nat.at(i0, j)) / ((i1 - i0) * res);
      const double dzdy = (nat.at(i, j1) - nat.at(i, j0)) / ((j1 - j0) * res);
      const Eigen::Vector3d nrm = Eigen::Vector3d(-dzdx, -dzdy, 1.0).normalized();
      const std::size_t k = static_cast<std::size_t>(j) * nx + i;
      surface[4 * k + 0] = static_cast<float>(nrm.x());
      surface[4 * k + 1] = static_cast<float>(nrm.y());
      // Rock relief, dilated by one cell: the central-difference normals of the cells next to
      // a rock already lean with the rock's flank, so they must get the rock's material too
      // (otherwise a bright soil-coloured rim appears around the rock's base).
      float relief = 0.0F;
      for (int jj = j0; jj <= j1; ++jj)
        for (int ii = i0; ii <= i1; ++ii) relief = std::max(relief, nat.at(ii, jj) - bare.at(ii, jj));
      surface[4 * k + 2] = relief;
      surface[4 * k + 3] = static_cast<float>(std::clamp(1.0 + 0.18 * macro[k], 0.5, 1.5));
      const Soil s = nat.soil(i, j);
      auto* m = material.ptr<std::uint8_t>(j) + 2 * i;
      m[0] = s == Soil::kLooseSand ? 255 : 0;
      m[1] = s == Soil::kBedrock ? 255 : 0;
    }
  }
  // Soften soil-patch borders over ~20 cm.
  cv::blur(material, material, cv::Size(5, 5));
  glGenTextures(1, &tex_surface_);
  glActiveTexture(GL_TEXTURE0 + kUnitSurface);
  glBindTexture(GL_TEXTURE_2D, tex_surface_);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA16F, nx, ny, 0, GL_RGBA, GL_FLOAT, surface.data());
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);

  glGenTextures(1, &tex_material_);
  glActiveTexture(GL_TEXTURE0 + kUnitMaterial);
  glBindTexture(GL_TEXTURE_2D, tex_material_);
  cv::Mat mat_cont = material.isContinuous() ? material : material.clone();
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RG8, nx, ny, 0, GL_RG, GL_UNSIGNED_BYTE, mat_cont.data);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);

  // Procedural detail textures, mipmapped, repeating.
  const float aniso = options.texture_anisotropy > 1 &&
                              (HasExtension("GL_ARB_texture_filter_anisotropic") ||
                               HasExtension("GL_EXT_texture_filter_anisotropic"))
                          ? static_cast<float>(options.texture_anisotropy)
                          : 0.0F;
  const internal::TextureImage detail = internal::MakeSoilDetailTexture(MixSeed(options.seed, 12), kDetailSize);
  glGenTextures(1, &tex_detail_);
  glActiveTexture(GL_TEXTURE0 + kUnitDetail);
  glBindTexture(GL_TEXTURE_2D, tex_detail_);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, detail.size, detail.size, 0, GL_RGBA, GL_UNSIGNED_BYTE,
               detail.rgba.data());
  glGenerateMipmap(GL_TEXTURE_2D);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
  if (aniso > 0.0F) glTexParameterf(GL_TEXTURE_2D, GL_TEXTURE_MAX_ANISOTROPY, aniso);

  const internal::TextureImage rocks = internal::MakeRockTextures(MixSeed(options.seed, 13), kRockTexSize);
  glGenTextures(1, &tex_rock_);
  glActiveTexture(GL_TEXTURE0 + kUnitRockTex);
  glBindTexture(GL_TEXTURE_2D_ARRAY, tex_rock_);
  glTexImage3D(GL_TEXTURE_2D_ARRAY, 0, GL_RGBA8, rocks.size, rocks.size, rocks.layers, 0, GL_RGBA,
               GL_UNSIGNED_BYTE, rocks.rgba.data());
  glGenerateMipmap(GL_TEXTURE_2D_ARRAY);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_T, GL_REPEAT);
  if (aniso > 0.0F) glTexParameterf(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAX_ANISOTROPY, aniso);
}

void Renderer::Impl::BuildRockData() {
  const HeightField& nat = terrain->natural;
  const int nx = nat.nx(), ny = nat.ny();
  const double res = nat.resolution();
  const std::size_t n = static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny);
  std::vector<std::int32_t> ids(n, -1);
  std::vector<float> score(n, -1e30F);
  std::vector<float> params;
  const auto& rocks = terrain->rocks;
  for (std::size_t r = 0; r < rocks.size(); ++r) {
    const Rock& rock = rocks[r];
    Rng rng(MixSeed(options.seed, 1000 + static_cast<std::uint64_t>(rock.id)));
    const int tid = std::max(0, rock.texture_id);
    const double albedo = rock.science_target
                              ? options.target_albedo * rng.Uniform(0.95, 1.05)
                              : rng.Uniform(options.rock_albedo_min, options.rock_albedo_max);
    const int layer = rock.science_target
                          ? internal::kGenericRockLayers + tid % internal::kScienceLayers
                          : tid % internal::kGenericRockLayers;
    const double period = rock.science_target ? 0.3 : rng.Uniform(0.35, 0.6);
    params.insert(params.end(), {static_cast<float>(albedo), static_cast<float>(layer),
                                 static_cast<float>(period), static_cast<float>(rng.Uniform())});
    const double reach = RockBoundingRadius(rock) + 1.5 * res;
    const double cx = rock.position.x(), cy = rock.position.y();
    const int i0 = std::max(0, static_cast<int>(std::floor((cx - reach - nat.min_x()) / res)));
    const int i1 = std::min(nx - 1, static_cast<int>(std::ceil((cx + reach - nat.min_x()) / res)));
    const int j0 = std::max(0, static_cast<int>(std::floor((cy - reach - nat.min_y()) / res)));
    const int j1 = std::min(ny - 1, static_cast<int>(std::ceil((cy + reach - nat.min_y()) / res)));
    for (int j = j0; j <= j1; ++j) {
      for (int i = i0; i <= i1; ++i) {
        const double x = nat.min_x() + i * res, y = nat.min_y() + j * res;
        const double d = std::hypot(x - cx, y - cy);
        if (d > reach) continue;
        const double relief = RockRelief(rock, x, y);
        const float s = relief > 0.0 ? static_cast<float>(relief) : static_cast<float>(-d);
        const std::size_t k = static_cast<std::size_t>(j) * nx + i;
        if (s > score[k]) {
          score[k] = s;
          ids[k] = static_cast<std::int32_t>(r);
        }
      }
    }
  }
  if (params.empty()) params = {0.16F, 0.0F, 0.4F, 0.0F};
  glGenTextures(1, &tex_rock_id_);
  glActiveTexture(GL_TEXTURE0 + kUnitRockId);
  glBindTexture(GL_TEXTURE_2D, tex_rock_id_);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_R32I, nx, ny, 0, GL_RED_INTEGER, GL_INT, ids.data());
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);

  glGenBuffers(1, &buf_rocks_);
  glBindBuffer(GL_TEXTURE_BUFFER, buf_rocks_);
  glBufferData(GL_TEXTURE_BUFFER, static_cast<GLsizeiptr>(params.size() * sizeof(float)),
               params.data(), GL_STATIC_DRAW);
  glGenTextures(1, &tex_rocks_);
  glActiveTexture(GL_TEXTURE0 + kUnitRocks);
  glBindTexture(GL_TEXTURE_BUFFER, tex_rocks_);
  glTexBuffer(GL_TEXTURE_BUFFER, GL_RGBA32F, buf_rocks_);
  glBindBuffer(GL_TEXTURE_BUFFER, 0);
}

void Renderer::Impl::BuildLander() {
  std::vector<float> solid, stripes;
  if (terrain->lander) {
    for (const LanderQuad& q : terrain->lander->quads) {
      const Eigen::Vector3d nrm = q.Normal();
      const double lum = 0.2126 * q.albedo.x() + 0.7152 * q.albedo.y() + 0.0722 * q.albedo.z();
      auto& out = q.part == LanderPart::kStripe ? stripes : solid;
      for (int k : {0, 1, 2, 0, 2, 3}) {
        const Eigen::Vector3d p = q.corners[static_cast<std::size_t>(k)] - origin_;
        out.insert(out.end(), {static_cast<float>(p.x()), static_cast<float>(p.y()),
                               static_cast<float>(p.z()), 0.0F, static_cast<float>(nrm.x()),
                               static_cast<float>(nrm.y()), static_cast<float>(nrm.z()),
                               static_cast<float>(lum)});
        scene_min_ = scene_min_.cwiseMin(p.cast<float>());
        scene_max_ = scene_max_.cwiseMax(p.cast<float>());
      }
    }
  }
  lander_solid_vertices_ = static_cast<GLsizei>(solid.size() / 8);
  lander_stripe_vertices_ = static_cast<GLsizei>(stripes.size() / 8);
  solid.insert(solid.end(), stripes.begin(), stripes.end());
  if (solid.empty()) return;
  glGenVertexArrays(1, &lander_vao_);
  glBindVertexArray(lander_vao_);
  glGenBuffers(1, &lander_vbo_);
  glBindBuffer(GL_ARRAY_BUFFER, lander_vbo_);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(solid.size() * sizeof(float)), solid.data(),
               GL_STATIC_DRAW);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 4, GL_FLOAT, GL_FALSE, 8 * sizeof(float), Offset(0));
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 8 * sizeof(float), Offset(4 * sizeof(float)));
  glEnableVertexAttribArray(2);
  glVertexAttribPointer(2, 1, GL_FLOAT, GL_FALSE, 8 * sizeof(float), Offset(7 * sizeof(float)));
  glBindVertexArray(0);
}

void Renderer::Impl::BuildApron() {
  if (options.apron_m <= 0.0) return;
  const HeightField& hf = terrain->natural;
  double sum = 0.0;
  int count = 0;
  for (int i = 0; i < hf.nx(); ++i) {
    sum += hf.at(i, 0) + hf.at(i, hf.ny() - 1);
    count += 2;
  }
  for (int j = 0; j < hf.ny(); ++j) {
    sum += hf.at(0, j) + hf.at(hf.nx() - 1, j);
    count += 2;
  }
  const float z = static_cast<float>(sum / count - origin_.z() - 0.01);
  const float x0 = static_cast<float>(hf.min_x() - origin_.x()), x1 = static_cast<float>(hf.max_x() - origin_.x());
  const float y0 = static_cast<float>(hf.min_y() - origin_.y()), y1 = static_cast<float>(hf.max_y() - origin_.y());
  const float a = static_cast<float>(options.apron_m);
  // Four quads framing the map: south, north (full width), west, east.
  const float quads[4][4] = {{x0 - a, x0, y0 - a, y1 + a}, {x1, x1 + a, y0 - a, y1 + a},
                             {x0, x1, y1, y1 + a}, {x0, x1, y0 - a, y0}};
  std::vector<float> v;
  for (const auto& q : quads) {
    const float xa = q[0], xb = q[1], ya = q[2], yb = q[3];
    for (auto [x, y] : {std::pair{xa, ya}, {xb, ya}, {xb, yb}, {xa, ya}, {xb, yb}, {xa, yb}}) {
      v.insert(v.end(), {x, y, z, 0.0F});
    }
  }
  glGenVertexArrays(1, &apron_vao_);
  glBindVertexArray(apron_vao_);
  glGenBuffers(1, &apron_vbo_);
  glBindBuffer(GL_ARRAY_BUFFER, apron_vbo_);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(v.size() * sizeof(float)), v.data(),
               GL_STATIC_DRAW);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 4, GL_FLOAT, GL_FALSE, 4 * sizeof(float), Offset(0));
  glBindVertexArray(0);
}

Status Renderer::Impl::BuildShadowTargets() {
  auto setup = [](GLenum target) {
    glTexParameteri(target, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(target, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(target, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(target, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTexParameteri(target, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    glTexParameteri(target, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
  };
  const int s = options.shadow_map_size;
  glGenTextures(1, &shadow_tex_);
  glActiveTexture(GL_TEXTURE0 + kUnitShadow);
  glBindTexture(GL_TEXTURE_2D_ARRAY, shadow_tex_);
  glTexImage3D(GL_TEXTURE_2D_ARRAY, 0, GL_DEPTH_COMPONENT32F, s, s, options.shadow_cascades, 0,
               GL_DEPTH_COMPONENT, GL_FLOAT, nullptr);
  setup(GL_TEXTURE_2D_ARRAY);
  const int g = options.global_shadow_map_size;
  glGenTextures(1, &global_tex_);
  glActiveTexture(GL_TEXTURE0 + kUnitShadowGlobal);
  glBindTexture(GL_TEXTURE_2D, global_tex_);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT32F, g, g, 0, GL_DEPTH_COMPONENT, GL_FLOAT,
               nullptr);
  setup(GL_TEXTURE_2D);
  for (auto [fbo, attach] : {std::pair{&shadow_fbo_, 0}, {&global_fbo_, 1}}) {
    glGenFramebuffers(1, fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, *fbo);
    if (attach == 0) {
      glFramebufferTextureLayer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, shadow_tex_, 0, 0);
    } else {
      glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, global_tex_, 0);
    }
    glDrawBuffer(GL_NONE);
    glReadBuffer(GL_NONE);
    const GLenum st = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    if (st != GL_FRAMEBUFFER_COMPLETE) {
      return Internal("shadow-map framebuffer incomplete (status " + std::to_string(st) + ")");
    }
  }
  return internal::CheckGl("shadow-map allocation");
}

Status Renderer::Impl::EnsureAtlas(int width, int height) {
  if (width <= atlas_w_ && height <= atlas_h_) return Status::Ok();
  const int w = std::max(width, atlas_w_), h = std::max(height, atlas_h_);
  if (atlas_fbo_ == 0) {
    glGenFramebuffers(1, &atlas_fbo_);
    glGenTextures(1, &atlas_color_);
    glGenTextures(1, &atlas_range_);
    glGenRenderbuffers(1, &atlas_depth_);
  }
  glActiveTexture(GL_TEXTURE0 + kUnitScratch);  // do not disturb the scene's texture units
  for (GLuint t : {atlas_color_, atlas_range_}) {
    glBindTexture(GL_TEXTURE_2D, t);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_R32F, w, h, 0, GL_RED, GL_FLOAT, nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  }
  glBindRenderbuffer(GL_RENDERBUFFER, atlas_depth_);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, w, h);
  glBindFramebuffer(GL_FRAMEBUFFER, atlas_fbo_);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, atlas_color_, 0);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_TEXTURE_2D, atlas_range_, 0);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, atlas_depth_);
  const GLenum st = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  if (st != GL_FRAMEBUFFER_COMPLETE) {
    return Internal("render framebuffer " + std::to_string(w) + " x " + std::to_string(h) +
                    " incomplete (status " + std::to_string(st) + ")");
  }
  atlas_w_ = w;
  atlas_h_ = h;
  return internal::CheckGl("render framebuffer allocation");
}

Result<std::shared_ptr<const WarpPlan>> Renderer::Impl::Plan(const geometry::CameraModel& model) {
  const std::string key = internal::WarpKey(model);
  if (auto it = plans_.find(key); it != plans_.end()) return it->second;
  const auto t0 = std::chrono::steady_clock::now();
  internal::PlanOptions po;
  po.oversample = options.oversample;
  po.max_view_size = std::min(options.max_view_size, gl->max_renderbuffer_size());
  po.max_atlas_size = std::min(gl->max_renderbuffer_size(), gl->max_texture_size());
  auto plan = internal::PlanWarp(model, po);
  if (!plan.ok()) return plan.status();
  auto shared = std::make_shared<const WarpPlan>(std::move(*plan));
  if (plans_.size() > 16) plans_.clear();
  plans_[key] = shared;
  stats.plan_ms += Ms(t0);
  return shared;
}

void Renderer::Impl::SelectLods(const Eigen::Vector3d& camera, double focal_px) {
  const Eigen::Vector3f c = camera.cast<float>();
  std::vector<std::pair<float, int>> by_distance;
  for (std::size_t k = 0; k < mesh_.tiles.size(); ++k) {
    const auto& t = mesh_.tiles[k];
    lod_[k] = internal::SelectLod(t, c, focal_px, terrain->natural.resolution(),
                                  options.lod_error_px, options.lod_max_cell_px);
    by_distance.emplace_back((c.cwiseMax(t.box_min).cwiseMin(t.box_max) - c).norm(),
                             static_cast<int>(k));
  }
  std::sort(by_distance.begin(), by_distance.end());
  draw_order_.clear();
  for (const auto& [d, k] : by_distance) draw_order_.push_back(k);
}

void Renderer::Impl::SetLightingUniforms(GLuint prog, const Eigen::Vector3d& cam) {
  SetVec3(prog, "u_cam", cam);
  SetVec3(prog, "u_sun", options.sun.Direction());
  SetFloat(prog, "u_sun_irr", options.sun_irradiance);
  SetFloat(prog, "u_sky_irr", options.sky_irradiance);
  std::array<float, 64> m{};
  for (int k = 0; k < 4; ++k) {
    const Eigen::Matrix4f f = light_[static_cast<std::size_t>(k)].cast<float>();
    std::memcpy(&m[static_cast<std::size_t>(16 * k)], f.data(), 16 * sizeof(float));
  }
  glUniformMatrix4fv(glGetUniformLocation(prog, "u_light"), 4, GL_FALSE, m.data());
  glUniform1fv(glGetUniformLocation(prog, "u_cascade_far"), 4, cascade_far_.data());
  glUniform1fv(glGetUniformLocation(prog, "u_shadow_texel"), 4, shadow_texel_.data());
  glUniform1fv(glGetUniformLocation(prog, "u_depth_scale"), 4, depth_scale_.data());
  SetInt(prog, "u_cascades", options.shadow_cascades);
  SetVec3(prog, "u_shadow_center", shadow_center_);
  SetMat4(prog, "u_light_global", global_light_);
  SetFloat(prog, "u_global_texel", global_texel_);
  SetFloat(prog, "u_global_depth_scale", global_depth_scale_);
}

void Renderer::Impl::DrawTerrain(GLuint prog, const Planes& planes, long long* triangles) {
  glBindVertexArray(terrain_vao_);
  const GLint skirt = glGetUniformLocation(prog, "u_skirt_depth");
  // Near tiles first so that early depth tests reject hidden fragments (and skirts).
  for (int k : draw_order_) {
    const auto& t = mesh_.tiles[static_cast<std::size_t>(k)];
    if (!BoxVisible(planes, t.box_min, t.box_max)) continue;
    const auto& lod = t.lods[static_cast<std::size_t>(lod_[static_cast<std::size_t>(k)])];
    glUniform1f(skirt, lod.skirt_depth);
    glDrawElementsBaseVertex(GL_TRIANGLES, static_cast<GLsizei>(lod.index_count), GL_UNSIGNED_INT,
                             Offset(lod.first_index * sizeof(std::uint32_t)),
                             static_cast<GLint>(t.first_vertex));
    *triangles += lod.index_count / 3;
  }
}

void Renderer::Impl::DrawLander(GLuint prog, long long* triangles) {
  (void)prog;
  if (lander_vao_ == 0) return;
  glBindVertexArray(lander_vao_);
  glDrawArrays(GL_TRIANGLES, 0, lander_solid_vertices_);
  if (lander_stripe_vertices_ > 0) {
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(-1.0F, -2.0F);
    glDrawArrays(GL_TRIANGLES, lander_solid_vertices_, lander_stripe_vertices_);
    glDisable(GL_POLYGON_OFFSET_FILL);
  }
  *triangles += (lander_solid_vertices_ + lander_stripe_vertices_) / 3;
}

Eigen::Matrix3d Renderer::Impl::LightFrame(Eigen::Vector3d* box_min,
                                           Eigen::Vector3d* box_max) const {
  const Eigen::Vector3d lz = -options.sun.Direction();  // direction the light travels
  Eigen::Vector3d lx = Eigen::Vector3d::UnitZ().cross(lz);
  if (lx.norm() < 1e-6) lx = Eigen::Vector3d::UnitX();
  lx.normalize();
  const Eigen::Vector3d ly = lz.cross(lx);
  Eigen::Matrix3d l;
  l.row(0) = lx;
  l.row(1) = ly;
  l.row(2) = lz;
  *box_min = Eigen::Vector3d::Constant(1e30);
  *box_max = Eigen::Vector3d::Constant(-1e30);
  for (int c = 0; c < 8; ++c) {
    const Eigen::Vector3d p((c & 1) ? scene_max_.x() : scene_min_.x(),
                            (c & 2) ? scene_max_.y() : scene_min_.y(),
                            (c & 4) ? scene_max_.z() : scene_min_.z());
    const Eigen::Vector3d q = l * p;
    *box_min = box_min->cwiseMin(q);
    *box_max = box_max->cwiseMax(q);
  }
  box_min->z() -= 0.5;
  box_max->z() += 0.5;
  return l;
}

Eigen::Matrix4d Renderer::Impl::LightClip(const Eigen::Matrix3d& light_from_render, double xmin,
                                          double xmax, double ymin, double ymax, double zmin,
                                          double zmax) const {
  Eigen::Matrix4d view = Eigen::Matrix4d::Identity();
  view.topLeftCorner<3, 3>() = light_from_render;
  Eigen::Matrix4d ortho = Eigen::Matrix4d::Identity();
  ortho(0, 0) = 2.0 / (xmax - xmin);
  ortho(0, 3) = -(xmax + xmin) / (xmax - xmin);
  ortho(1, 1) = 2.0 / (ymax - ymin);
  ortho(1, 3) = -(ymax + ymin) / (ymax - ymin);
  ortho(2, 2) = 2.0 / (zmax - zmin);
  ortho(2, 3) = -(zmax + zmin) / (zmax - zmin);
  return ortho * view;
}

namespace {

Eigen::Matrix4d BiasToUnit() {
  Eigen::Matrix4d bias = Eigen::Matrix4d::Identity() * 0.5;
  bias(3, 3) = 1.0;
  bias.topRightCorner<3, 1>() = Eigen::Vector3d::Constant(0.5);
  return bias;
}
}  // namespace

void Renderer::Impl::RenderGlobalShadow() {
  const auto t0 = std::chrono::steady_clock::now();
  Eigen::Vector3d lo, hi;
  const Eigen::Matrix3d l = LightFrame(&lo, &hi);
  const Eigen::Matrix4d clip = LightClip(l, lo.x(), hi.x(), lo.y(), hi.y(), lo.z(), hi.z());
  global_light_ = BiasToUnit() * clip;
  global_texel_ = static_cast<float>(std::max(hi.x() - lo.x(), hi.y() - lo.y()) /
                                     options.global_shadow_map_size);
  global_depth_scale_ = static_cast<float>(1.0 / (hi.z() - lo.z()));
  glBindFramebuffer(GL_FRAMEBUFFER, global_fbo_);
  glViewport(0, 0, options.global_shadow_map_size, options.global_shadow_map_size);
  glUseProgram(shadow_prog_);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(1.5F, 2.0F);
  glClear(GL_DEPTH_BUFFER_BIT);
  SetMat4(shadow_prog_, "u_mvp", clip);
  // Full resolution everywhere (the map is rendered once per sun direction).
  std::vector<int> saved = lod_;
  std::fill(lod_.begin(), lod_.end(), 0);
  long long tris = 0;
  DrawTerrain(shadow_prog_, FrustumPlanes(clip), &tris);
  lod_ = std::move(saved);
  if (lander_vao_ != 0) {
    SetFloat(shadow_prog_, "u_skirt_depth", 0.0);
    glBindVertexArray(lander_vao_);
    glDrawArrays(GL_TRIANGLES, 0, lander_solid_vertices_ + lander_stripe_vertices_);
  }
  glDisable(GL_POLYGON_OFFSET_FILL);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  global_valid_ = true;
  stats.shadow_triangles += tris;
  stats.shadow_ms += Ms(t0);
}

void Renderer::Impl::RenderShadows(const std::vector<PlacedCamera>& cams,
                                   const Eigen::Vector3d& center, int image_width) {
  if (!global_valid_) RenderGlobalShadow();
  // The cascades' size for this image width: a power of two in [min(512, S), S]; they fill the
  // lower-left corner of each S x S layer, and the light matrices map into that corner.
  const int full = options.shadow_map_size;
  int size = full;
  while (size / 2 >= 512 &&
         static_cast<double>(size / 2) >=
             static_cast<double>(full) * image_width / options.shadow_reference_width) {
    size /= 2;
  }
  Eigen::Matrix4d corner = Eigen::Matrix4d::Identity();
  corner(0, 0) = corner(1, 1) = static_cast<double>(size) / full;
  const auto t0 = std::chrono::steady_clock::now();
  const int kc = options.shadow_cascades;
  Eigen::Vector3d lo, hi;
  const Eigen::Matrix3d light_from_render = LightFrame(&lo, &hi);
  // Cascade split distances from `center` (practical split scheme, lambda = 0.75).
  const double far_d = options.shadow_distance, near_d = 0.1;
  std::vector<double> split(static_cast<std::size_t>(kc + 1));
  for (int i = 0; i <= kc; ++i) {
    const double f = static_cast<double>(i) / kc;
    split[static_cast<std::size_t>(i)] =
        0.75 * near_d * std::pow(far_d / near_d, f) + 0.25 * (near_d + (far_d - near_d) * f);
  }
  split[0] = 0.0;
  // Sample directions of every view of every camera.
  std::vector<Eigen::Vector3d> dirs;
  for (const auto& cam : cams) {
    for (const auto& v : cam.plan->views) {
      for (int a = 0; a <= 6; ++a) {
        for (int b = 0; b <= 6; ++b) {
          const double u = -0.5 + v.width * a / 6.0, w = -0.5 + v.height * b / 6.0;
          const Eigen::Vector3d d_view((u - v.cx) / v.f, (w - v.cy) / v.f, 1.0);
          dirs.push_back((cam.render_from_cam * v.cam_from_view * d_view).normalized());
        }
      }
    }
  }
  glBindFramebuffer(GL_FRAMEBUFFER, shadow_fbo_);
  glViewport(0, 0, size, size);
  glUseProgram(shadow_prog_);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(1.5F, 2.0F);
  for (int k = 0; k < 4; ++k) {
    cascade_far_[static_cast<std::size_t>(k)] =
        k < kc ? static_cast<float>(split[static_cast<std::size_t>(k + 1)]) : 0.0F;
  }
  for (int k = 0; k < kc; ++k) {
    const double d0 = split[static_cast<std::size_t>(k)];
    const double d1 = split[static_cast<std::size_t>(k + 1)] * 1.05 + 0.05;
    double xmin = 1e30, xmax = -1e30, ymin = 1e30, ymax = -1e30;
    for (const auto& d : dirs) {
      for (double r : {d0, 0.5 * (d0 + d1), d1}) {
        const Eigen::Vector3d q = light_from_render * (center + r * d);
        xmin = std::min(xmin, q.x());
        xmax = std::max(xmax, q.x());
        ymin = std::min(ymin, q.y());
        ymax = std::max(ymax, q.y());
      }
    }
    xmin = std::max(xmin, lo.x());
    xmax = std::min(xmax, hi.x());
    ymin = std::max(ymin, lo.y());
    ymax = std::min(ymax, hi.y());
    if (!(xmax > xmin)) { xmin = lo.x(); xmax = hi.x(); }
    if (!(ymax > ymin)) { ymin = lo.y(); ymax = hi.y(); }
    const double margin = 0.02 * std::max(xmax - xmin, ymax - ymin) + 0.05;
    xmin -= margin; xmax += margin; ymin -= margin; ymax += margin;
    const Eigen::Matrix4d clip = LightClip(light_from_render, xmin, xmax, ymin, ymax, lo.z(), hi.z());
    light_[static_cast<std::size_t>(k)] = corner * BiasToUnit() * clip;
    shadow_texel_[static_cast<std::size_t>(k)] =
        static_cast<float>(std::max(xmax - xmin, ymax - ymin) / size);
    depth_scale_[static_cast<std::size_t>(k)] = static_cast<float>(1.0 / (hi.z() - lo.z()));
    glFramebufferTextureLayer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, shadow_tex_, 0, k);
    glClear(GL_DEPTH_BUFFER_BIT);
    SetMat4(shadow_prog_, "u_mvp", clip);
    DrawTerrain(shadow_prog_, FrustumPlanes(clip), &stats.shadow_triangles);
    if (lander_vao_ != 0) {
      SetFloat(shadow_prog_, "u_skirt_depth", 0.0);
      glBindVertexArray(lander_vao_);
      glDrawArrays(GL_TRIANGLES, 0, lander_solid_vertices_ + lander_stripe_vertices_);
    }
  }
  glDisable(GL_POLYGON_OFFSET_FILL);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  shadow_center_ = center;
  stats.shadow_ms += Ms(t0);
}

Result<cv::Mat> Renderer::Impl::RenderAtlas(const PlacedCamera& cam, const Pass& pass,
                                            cv::Mat* range_atlas) {
  const WarpPlan& plan = *cam.plan;
  ROVER_RETURN_IF_ERROR(EnsureAtlas(plan.atlas_width, plan.atlas_height));
  glBindFramebuffer(GL_FRAMEBUFFER, atlas_fbo_);
  const bool want_range = range_atlas != nullptr;
  const GLenum both[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
  glDrawBuffers(want_range ? 2 : 1, both);
  glViewport(0, 0, atlas_w_, atlas_h_);
  glDisable(GL_SCISSOR_TEST);
  glClearColor(0.0F, 0.0F, 0.0F, 0.0F);
  glClearDepth(1.0);
  glDepthMask(GL_TRUE);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);

  for (const VirtualView& v : plan.views) {
    ++stats.views;
    glViewport(0, v.atlas_y, v.width, v.height);
    const Eigen::Matrix3d render_from_view = cam.render_from_cam * v.cam_from_view;
    const Eigen::Matrix4d mvp =
        ViewProjection(v, pass.near, pass.far) * RigidInverse(render_from_view, cam.center);
    const Planes planes = FrustumPlanes(mvp);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glUseProgram(terrain_prog_);
    SetMat4(terrain_prog_, "u_mvp", mvp);
    SetLightingUniforms(terrain_prog_, cam.center);
    SetInt(terrain_prog_, "u_apron", 0);
    DrawTerrain(terrain_prog_, planes, &stats.triangles);
    if (apron_vao_ != 0) {
      SetInt(terrain_prog_, "u_apron", 1);
      SetFloat(terrain_prog_, "u_skirt_depth", 0.0);
      glBindVertexArray(apron_vao_);
      glDrawArrays(GL_TRIANGLES, 0, 24);
      stats.triangles += 8;
    }
    if (lander_vao_ != 0) {
      glUseProgram(lander_prog_);
      SetMat4(lander_prog_, "u_mvp", mvp);
      SetLightingUniforms(lander_prog_, cam.center);
      DrawLander(lander_prog_, &stats.triangles);
    }
    // Sky where nothing was drawn.
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_FALSE);
    glUseProgram(sky_prog_);
    const Eigen::Matrix3f rv = render_from_view.cast<float>();
    glUniformMatrix3fv(glGetUniformLocation(sky_prog_, "u_render_from_view"), 1, GL_FALSE, rv.data());
    glUniform4f(glGetUniformLocation(sky_prog_, "u_intrinsics"), static_cast<float>(v.f),
                static_cast<float>(v.cx), static_cast<float>(v.cy), static_cast<float>(v.atlas_y));
    SetVec3(sky_prog_, "u_sun", options.sun.Direction());
    SetFloat(sky_prog_, "u_sky_radiance", options.sky_radiance);
    glBindVertexArray(empty_vao_);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDepthMask(GL_TRUE);
  }
  glBindVertexArray(0);
  glUseProgram(0);
  cv::Mat radiance(plan.atlas_height, plan.atlas_width, CV_32FC1);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glReadBuffer(GL_COLOR_ATTACHMENT0);
  glReadPixels(0, 0, plan.atlas_width, plan.atlas_height, GL_RED, GL_FLOAT, radiance.data);
  if (want_range) {
    *range_atlas = cv::Mat(plan.atlas_height, plan.atlas_width, CV_32FC1);
    glReadBuffer(GL_COLOR_ATTACHMENT1);
    glReadPixels(0, 0, plan.atlas_width, plan.atlas_height, GL_RED, GL_FLOAT, range_atlas->data);
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  ROVER_RETURN_IF_ERROR(internal::CheckGl("camera render"));
  return radiance;
}

Result<StereoImages> Renderer::Impl::Render(const Eigen::Isometry3d& site_from_rover,
                                            const std::vector<geometry::CameraModel>& models,
                                            std::uint64_t frame, const Pass& pass) {
  stats = RenderStats{};
  const bool want_range = options.output_range || pass.want_range || pass.dof != nullptr;
  if (!site_from_rover.matrix().allFinite()) {
    return InvalidArgument("rover pose: not finite");
  }
  const Eigen::Matrix3d r = site_from_rover.linear();
  if ((r.transpose() * r - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() > 1e-6 ||
      r.determinant() < 0.0) {
    return InvalidArgument("rover pose: rotation is not orthonormal (a rigid transform is needed)");
  }
  ROVER_RETURN_IF_ERROR(gl->MakeCurrent());
  // A binned readout renders `super` times finer; the radiance is area-averaged back below
  // (geometry::Scale aligns the outer pixel edges, as the area filter does).
  const int super = std::min(options.sensor.binning, options.binned_supersample);
  std::vector<PlacedCamera> cams;
  double focal = 1.0;
  Eigen::Vector3d mid = Eigen::Vector3d::Zero();
  for (const auto& output_model : models) {
    const geometry::CameraModel m =
        super > 1 ? geometry::Scale(output_model, static_cast<double>(super)) : output_model;
    const geometry::CameraModel site = geometry::Transform(m, site_from_rover);
    auto plan = Plan(site);
    if (!plan.ok()) return plan.status();
    const CameraFrame f = internal::CanonicalFrame(site);
    PlacedCamera pc{*plan, f.ref_from_cam, f.center - origin_};
    for (const auto& v : pc.plan->views) focal = std::max(focal, v.f);
    mid += pc.center;
    cams.push_back(pc);
  }
  mid /= static_cast<double>(cams.size());
  // The terrain's level of detail is chosen for the readout's pixels: a binned readout is
  // rendered finer to integrate its light, not to see finer geometry than it resolves.
  SelectLods(mid, focal / static_cast<double>(super));
  RenderShadows(cams, mid, super * models.front().width());

  StereoImages out;
  for (std::size_t c = 0; c < cams.size(); ++c) {
    const WarpPlan& plan = *cams[c].plan;
    auto t0 = std::chrono::steady_clock::now();
    cv::Mat range_atlas;
    auto atlas = RenderAtlas(cams[c], pass, want_range ? &range_atlas : nullptr);
    if (!atlas.ok()) return atlas.status();
    stats.gl_ms += Ms(t0);
    t0 = std::chrono::steady_clock::now();
    CameraImage& img = c == 0 ? out.left : out.right;
    cv::Mat radiance;
    cv::remap(*atlas, radiance, plan.map1, plan.map2, cv::INTER_LINEAR, cv::BORDER_CONSTANT,
              cv::Scalar(0));
    if (want_range) {
      cv::remap(range_atlas, img.range, plan.map_x, plan.map_y, cv::INTER_NEAREST,
                cv::BORDER_CONSTANT, cv::Scalar(0));
    }
    if (super > 1) {
      const cv::Size size(models[c].width(), models[c].height());
      cv::resize(radiance, radiance, size, 0, 0, cv::INTER_AREA);
      if (want_range) cv::resize(img.range, img.range, size, 0, 0, cv::INTER_NEAREST);
    }
    if (pass.dof != nullptr) {
      radiance = ApplyDepthOfField(radiance, AxialDepth(img.range, models[c]), *pass.dof);
    }
    stats.warp_ms += Ms(t0);
    t0 = std::chrono::steady_clock::now();
    if (c == 0) {
      img.exposure = options.sensor.auto_exposure ? AutoExposure(radiance, options.sensor)
                                                  : options.sensor.exposure;
    } else {
      img.exposure = out.left.exposure;
    }
    const std::uint64_t seed = MixSeed(MixSeed(options.seed ^ 0x5E5503ULL, frame), c);
    img.image = ApplySensorModel(radiance, options.sensor, img.exposure, seed);
    if (options.output_radiance) img.radiance = radiance;
    stats.sensor_ms += Ms(t0);
  }
  return out;
}

Renderer::Impl::~Impl() {
  if (!gl || !gl->MakeCurrent().ok()) return;
  for (GLuint p : {terrain_prog_, lander_prog_, sky_prog_, shadow_prog_}) {
    if (p != 0) glDeleteProgram(p);
  }
  for (GLuint v : {terrain_vao_, apron_vao_, lander_vao_, empty_vao_}) {
    if (v != 0) glDeleteVertexArrays(1, &v);
  }
  for (GLuint b : {terrain_vbo_, terrain_ibo_, apron_vbo_, lander_vbo_, buf_rocks_}) {
    if (b != 0) glDeleteBuffers(1, &b);
  }
  for (GLuint t : {tex_surface_, tex_material_, tex_rock_id_, tex_rocks_, tex_detail_, tex_rock_,
                   shadow_tex_, global_tex_, atlas_color_, atlas_range_}) {
    if (t != 0) glDeleteTextures(1, &t);
  }
  for (GLuint f : {shadow_fbo_, global_fbo_, atlas_fbo_}) {
    if (f != 0) glDeleteFramebuffers(1, &f);
  }
  if (atlas_depth_ != 0) glDeleteRenderbuffers(1, &atlas_depth_);
}

// ---- public API -------------------------------------------------------------------------------

Renderer::Renderer(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Renderer::~Renderer() = default;

Result<std::unique_ptr<Renderer>> Renderer::Create(std::shared_ptr<const Terrain> terrain,
                                                   const RenderOptions& options) {
  ROVER_RETURN_IF_ERROR(options.Validate());
  if (terrain == nullptr) return InvalidArgument("terrain: null");
  if (terrain->natural.nx() < 2 || terrain->natural.ny() < 2 ||
      terrain->bare.nx() != terrain->natural.nx() || terrain->bare.ny() != terrain->natural.ny()) {
    return InvalidArgument("terrain: empty or inconsistent heightfields (natural " +
                           std::to_string(terrain->natural.nx()) + " x " +
                           std::to_string(terrain->natural.ny()) + ", bare " +
                           std::to_string(terrain->bare.nx()) + " x " +
                           std::to_string(terrain->bare.ny()) + ")");
  }
  auto impl = std::make_unique<Impl>();
  impl->options = options;
  impl->terrain = std::move(terrain);
  ROVER_RETURN_IF_ERROR(impl->Init());
  return std::unique_ptr<Renderer>(new Renderer(std::move(impl)));
}

Result<StereoImages> Renderer::RenderStereoPair(const Eigen::Isometry3d& site_from_rover,
                                                const CameraPairSpec& pair, std::uint64_t frame) {
  if (!pair.rover_from_head.matrix().allFinite()) {
    return InvalidArgument("camera pair: rover_from_head is not finite");
  }
  return impl_->Render(site_from_rover, {pair.LeftInRover(), pair.RightInRover()}, frame, {});
}

Result<CameraImage> Renderer::RenderCamera(const Eigen::Isometry3d& site_from_rover,
                                           const geometry::CameraModel& model_in_rover,
                                           std::uint64_t frame) {
  auto r = impl_->Render(site_from_rover, {model_in_rover}, frame, {});
  if (!r.ok()) return r.status();
  return std::move(r->left);
}

Result<CameraImage> Renderer::RenderCloseUp(const Eigen::Isometry3d& site_from_rover,
                                            const geometry::CameraModel& model_in_rover,
                                            const DepthOfField& dof, std::uint64_t frame) {
  ROVER_RETURN_IF_ERROR(dof.Validate());
  Impl::Pass pass;
  pass.near = dof.near;
  pass.far = kCloseUpFar;
  pass.want_range = true;
  pass.dof = &dof;
  auto r = impl_->Render(site_from_rover, {model_in_rover}, frame, pass);
  if (!r.ok()) return r.status();
  return std::move(r->left);
}

Status Renderer::SetSun(const SunOptions& sun) {
  ROVER_RETURN_IF_ERROR(sun.Validate());
  impl_->options.sun = sun;
  impl_->InvalidateShadows();
  return Status::Ok();
}

Status Renderer::SetSensor(const SensorOptions& sensor) {
  ROVER_RETURN_IF_ERROR(sensor.Validate());
  impl_->options.sensor = sensor;
  return Status::Ok();
}

const RenderOptions& Renderer::options() const { return impl_->options; }
const RenderStats& Renderer::last_stats() const { return impl_->stats; }
std::string Renderer::gl_renderer() const { return impl_->gl->renderer(); }

}  // namespace rover::sim::render
