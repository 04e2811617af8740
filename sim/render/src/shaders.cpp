#include "shaders.hpp"

#include <algorithm>

namespace rover::sim::render::internal {
namespace {

constexpr const char* kVersion = "#version 330 core\n";

// Lighting and shadows shared by terrain and lander.
constexpr const char* kLighting = R"GLSL(
uniform vec3 u_cam;             // camera centre (render coordinates)
uniform vec3 u_sun;             // unit vector towards the sun
uniform float u_sun_irr;
uniform float u_sky_irr;
uniform sampler2DArrayShadow u_shadow;
uniform mat4 u_light[4];        // render coords -> [0,1]^3 shadow-map coordinates
uniform float u_cascade_far[4]; // [m] distance from u_shadow_center where cascade k ends
uniform float u_shadow_texel[4];// [m] texel size of cascade k
uniform float u_depth_scale[4]; // 1 / depth range of cascade k [1/m]
uniform int u_cascades;
uniform vec3 u_shadow_center;
uniform sampler2DShadow u_shadow_global;  // whole terrain
uniform mat4 u_light_global;
uniform float u_global_texel;
uniform float u_global_depth_scale;
uniform sampler2D u_detail;     // soil detail: albedo/2, slope u, slope v, height
uniform float u_contrast;
const float kSlopeRange = 2.0;

float ShadowFactor(vec3 p, vec3 n_geom) {
  float ndl = dot(n_geom, u_sun);
  if (ndl <= 0.0) return 0.0;
  float d = length(p - u_shadow_center);
  int k = -1;
  for (int i = 0; i < 4; ++i) {
    if (i < u_cascades && d < u_cascade_far[i]) { k = i; break; }
  }
  // Normal offset grows at grazing sun (the receiver's slope in light space).
  float sin_l = sqrt(max(0.0, 1.0 - ndl * ndl));
  float s = 0.0;
  if (k < 0) {
    float texel = u_global_texel;
    vec4 c = u_light_global * vec4(p + n_geom * texel * (1.0 + 1.5 * sin_l), 1.0);
    if (c.x <= 0.0 || c.y <= 0.0 || c.x >= 1.0 || c.y >= 1.0) return 1.0;
    float ref = c.z - (0.6 * texel + 0.002) * u_global_depth_scale;
    vec2 t = vec2(1.0) / vec2(textureSize(u_shadow_global, 0));
    s += texture(u_shadow_global, vec3(c.xy + t * vec2(-0.5, -0.25), ref));
    s += texture(u_shadow_global, vec3(c.xy + t * vec2(0.5, 0.25), ref));
    return s * 0.5;
  }
  float texel = u_shadow_texel[k];
  vec4 c = u_light[k] * vec4(p + n_geom * texel * (1.0 + 1.5 * sin_l), 1.0);
  if (c.x <= 0.0 || c.y <= 0.0 || c.x >= 1.0 || c.y >= 1.0) return 1.0;
  float ref = c.z - (0.6 * texel + 0.002) * u_depth_scale[k];
  vec2 t = vec2(1.0) / vec2(textureSize(u_shadow, 0).xy);
  s += texture(u_shadow, vec4(c.xy + t * vec2(-0.5, -0.25), float(k), ref));
  s += texture(u_shadow, vec4(c.xy + t * vec2(0.5, 0.25), float(k), ref));
  return s * 0.5;
}

float Radiance(float albedo, vec3 n_shade, float shadow) {
  float direct = u_sun_irr * max(dot(n_shade, u_sun), 0.0) * shadow;
  float sky = u_sky_irr * (0.6 + 0.4 * n_shade.z);
  return albedo * (direct + sky);
}

// Detail texel at uv: (albedo multiplier, slope u, slope v) with contrast applied.
vec3 Detail(vec2 uv) {
  vec4 t = texture(u_detail, uv);
  vec2 s = (t.gb - 0.5) * (2.0 * kSlopeRange);
  return vec3(1.0 + (t.r * 2.0 - 1.0) * u_contrast, s * u_contrast);
}
)GLSL";

constexpr const char* kTerrainVertex = R"GLSL(
layout(location = 0) in vec4 a_pos;   // xyz render coordinates, w = skirt flag
uniform mat4 u_mvp;
uniform float u_skirt_depth;
out vec3 v_world;
void main() {
  vec3 p = a_pos.xyz;
  p.z -= a_pos.w * u_skirt_depth;
  v_world = p;
  gl_Position = u_mvp * vec4(p, 1.0);
}
)GLSL";

constexpr const char* kTerrainFragment = R"GLSL(
in vec3 v_world;
layout(location = 0) out float o_radiance;
layout(location = 1) out float o_range;
uniform vec2 u_grid_min;       // render coordinates of sample (0, 0)
uniform float u_grid_res;
uniform ivec2 u_grid_n;
uniform sampler2D u_surface;   // RGBA16F: normal x, normal y, rock relief [m], macro albedo
uniform sampler2D u_material;  // RG8: loose-sand weight, bedrock weight
uniform isampler2D u_rock_id;  // R32I: rock index or -1
uniform samplerBuffer u_rocks; // RGBA32F per rock: albedo, texture layer, period [m], phase
uniform sampler2DArray u_rock_tex;
uniform float u_soil_albedo;
uniform float u_sand_albedo;
uniform float u_bedrock_albedo;
uniform int u_apron;           // 1: flat ground outside the map (no rocks, flat normal)

vec3 Bump(vec3 n, vec3 slope_world, float k) {
  vec3 b = slope_world - dot(slope_world, n) * n;
  return normalize(n - k * b);
}

// Grain below the textures' resolution (sand grains, crystals: 0.15 and 0.4 mm value noise),
// seen only by a close-up camera: its weight is 1 at a pixel footprint of 0.15 mm and 0 from
// 0.6 mm, so the NAVCAM and HAZCAM images (footprints of a millimetre and more) do not change.
float GrainHash(ivec2 c, uint salt) {
  uint h = (uint(c.x) * 0x8da6b343u) ^ (uint(c.y) * 0xd8163841u) ^ (salt * 0xcb1ab31fu);
  h ^= h >> 13;
  h *= 0x5bd1e995u;
  h ^= h >> 15;
  return float(h & 0xffffffu) / 16777215.0;
}
float GrainNoise(vec2 x, uint salt) {
  vec2 i = floor(x);
  vec2 f = x - i;
  vec2 u = f * f * (3.0 - 2.0 * f);
  ivec2 c = ivec2(i);
  float a = GrainHash(c, salt), b = GrainHash(c + ivec2(1, 0), salt);
  float d = GrainHash(c + ivec2(0, 1), salt), e = GrainHash(c + ivec2(1, 1), salt);
  return mix(mix(a, b, u.x), mix(d, e, u.x), u.y);
}
// Albedo factor of the grain at p [m]; `salt` 1 soil, 2 rock.
float Grain(vec2 p, float weight, uint salt) {
  if (weight <= 0.0) return 1.0;
  float g = 0.6 * GrainNoise(p / 0.00015, salt) + 0.4 * GrainNoise(p / 0.0004, salt + 7u) - 0.5;
  return 1.0 + 0.6 * g * weight * u_contrast;
}

void main() {
  vec2 g = (v_world.xy - u_grid_min) / u_grid_res;
  vec2 uv = (g + 0.5) / vec2(u_grid_n);
  vec4 surf = texture(u_surface, uv);
  vec3 n = vec3(surf.x, surf.y, sqrt(max(0.0, 1.0 - dot(surf.xy, surf.xy))));
  float relief = surf.z;
  float macro = surf.w;
  vec2 mat = texture(u_material, uv).rg;
  if (u_apron == 1) { n = vec3(0.0, 0.0, 1.0); relief = 0.0; }
  float footprint = length(fwidth(v_world));
  float w_grain = 1.0 - smoothstep(0.00015, 0.0006, footprint);

  // Soil: detail at two scales (1 m period, and 0.29 m rotated by 37 deg) breaks up tiling.
  const mat2 R = mat2(0.7986, 0.6018, -0.6018, 0.7986);  // columns: rotation by 37 deg
  vec2 p = v_world.xy;
  vec3 d1 = Detail(p);
  vec3 d2 = Detail(R * p / 0.29 + vec2(0.37, 0.61));
  vec3 slope = vec3(d1.yz + 0.5 * (transpose(R) * d2.yz), 0.0);
  float f_soil = d1.x * (0.55 + 0.45 * d2.x);
  float sand = mat.r, bed = mat.g;
  float firm = max(0.0, 1.0 - sand - bed);
  // Bedrock: plates from the first rock texture at a large scale.
  vec4 bt = bed > 0.002 ? texture(u_rock_tex, vec3(p / 1.3, 0.0)) : vec4(0.5);
  float f_bed = 1.0 + (bt.r * 2.0 - 1.0) * u_contrast;
  vec2 bslope = (bt.gb - 0.5) * (2.0 * kSlopeRange) * u_contrast;
  float a_soil = macro * (firm * u_soil_albedo * f_soil +
                          sand * u_sand_albedo * (1.0 + 0.35 * (f_soil - 1.0)) +
                          bed * u_bedrock_albedo * f_bed * (0.8 + 0.2 * d1.x));
  vec3 s_soil = (firm + 0.3 * sand) * slope + bed * vec3(bslope * 0.5 + 0.3 * d1.yz, 0.0);
  vec3 n_soil = Bump(n, s_soil, 0.5);

  a_soil *= Grain(v_world.xy, w_grain, 1u);
  float albedo = a_soil;
  vec3 n_shade = n_soil;
  float w_rock = smoothstep(0.004, 0.02, relief);
  if (w_rock > 0.0) {
    ivec2 cell = clamp(ivec2(floor(g + 0.5)), ivec2(0), u_grid_n - 1);
    int id = texelFetch(u_rock_id, cell, 0).r;
    vec4 rp = id >= 0 ? texelFetch(u_rocks, id) : vec4(0.16, 0.0, 0.4, 0.0);
    // Biplanar mapping: the top projection and the dominant side projection.
    vec3 w = pow(abs(n), vec3(4.0));
    bool side_x = w.x > w.y;
    w = side_x ? vec3(w.x, 0.0, w.z) : vec3(0.0, w.y, w.z);
    w /= (w.x + w.y + w.z);
    vec3 q = v_world / rp.z + vec3(rp.w, 1.7 * rp.w, 2.3 * rp.w);
    vec4 ts = texture(u_rock_tex, vec3(side_x ? q.yz : q.xz, rp.y));
    vec4 tx = ts, ty = ts;
    vec4 tz = texture(u_rock_tex, vec3(q.xy, rp.y));
    float f = 2.0 * (tx.r * w.x + ty.r * w.y + tz.r * w.z);
    f = 1.0 + (f - 1.0) * 1.5 * u_contrast;
    vec2 sx = (tx.gb - 0.5) * (2.0 * kSlopeRange);
    vec2 sy = (ty.gb - 0.5) * (2.0 * kSlopeRange);
    vec2 sz = (tz.gb - 0.5) * (2.0 * kSlopeRange);
    vec3 b = w.x * vec3(0.0, sx.x, sx.y) + w.y * vec3(sy.x, 0.0, sy.y) + w.z * vec3(sz.x, sz.y, 0.0);
    vec3 n_rock = Bump(n, b * u_contrast, 0.5);
    float a_rock = rp.x * f;
    // Dust settles on the upward-facing tops of rocks.
    float dust = 0.55 * smoothstep(0.82, 0.98, n.z);
    a_rock = mix(a_rock, u_soil_albedo * macro * (0.8 + 0.2 * d1.x), dust);
    a_rock *= Grain(v_world.xy + vec2(0.61, 0.29) * v_world.z, w_grain, 2u);
    albedo = mix(a_soil, a_rock, w_rock);
    n_shade = normalize(mix(n_soil, n_rock, w_rock));
  }
  float sh = ShadowFactor(v_world, n);
  o_radiance = Radiance(albedo, n_shade, sh);
  o_range = length(v_world - u_cam);
}
)GLSL";

constexpr const char* kLanderVertex = R"GLSL(
layout(location = 0) in vec4 a_pos;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in float a_albedo;
uniform mat4 u_mvp;
out vec3 v_world;
out vec3 v_normal;
out float v_albedo;
void main() {
  v_world = a_pos.xyz;
  v_normal = a_normal;
  v_albedo = a_albedo;
  gl_Position = u_mvp * vec4(a_pos.xyz, 1.0);
}
)GLSL";

constexpr const char* kLanderFragment = R"GLSL(
in vec3 v_world;
in vec3 v_normal;
in float v_albedo;
layout(location = 0) out float o_radiance;
layout(location = 1) out float o_range;
void main() {
  vec3 n = normalize(v_normal);
  if (dot(n, u_cam - v_world) < 0.0) n = -n;
  // Slight dust/wear texture (planar projection along the dominant normal axis).
  vec3 a = abs(n);
  vec2 uv = a.z > max(a.x, a.y) ? v_world.xy : (a.x > a.y ? v_world.yz : v_world.xz);
  float f = 1.0 + 0.12 * (Detail(uv * 0.7).x - 1.0);
  float sh = ShadowFactor(v_world, n);
  o_radiance = Radiance(v_albedo * f, n, sh);
  o_range = length(v_world - u_cam);
}
)GLSL";

constexpr const char* kSkyVertex = R"GLSL(
void main() {
  vec2 p = vec2(gl_VertexID == 1 ? 3.0 : -1.0, gl_VertexID == 2 ? 3.0 : -1.0);
  gl_Position = vec4(p, 1.0, 1.0);
}
)GLSL";

constexpr const char* kSkyFragment = R"GLSL(
layout(location = 0) out float o_radiance;
layout(location = 1) out float o_range;
uniform mat3 u_render_from_view;  // view axes (x right, y down, z forward) in render coords
uniform vec4 u_intrinsics;        // f, cx, cy, atlas row of the view
uniform vec3 u_sun;
uniform float u_sky_radiance;
void main() {
  float u = gl_FragCoord.x - 0.5;
  float v = gl_FragCoord.y - 0.5 - u_intrinsics.w;
  vec3 d = normalize(u_render_from_view *
                     vec3((u - u_intrinsics.y) / u_intrinsics.x, (v - u_intrinsics.z) / u_intrinsics.x, 1.0));
  float el = max(d.z, 0.0);
  float horizon = 1.0 + 0.9 * exp(-el / 0.12);
  float cs = acos(clamp(dot(d, u_sun), -1.0, 1.0));
  float circumsolar = 2.0 * exp(-cs / 0.15);
  o_radiance = u_sky_radiance * (horizon + circumsolar);
  o_range = 0.0;
}
)GLSL";

constexpr const char* kShadowFragment = R"GLSL(
void main() {}
)GLSL";

Result<GLuint> Compile(GLenum type, const std::vector<const char*>& parts, const char* name) {
  const GLuint s = glCreateShader(type);
  glShaderSource(s, static_cast<GLsizei>(parts.size()), parts.data(), nullptr);
  glCompileShader(s);
  GLint ok = 0;
  glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    GLint len = 0;
    glGetShaderiv(s, GL_INFO_LOG_LENGTH, &len);
    std::string log(static_cast<std::size_t>(std::max(len, 1)), '\0');
    glGetShaderInfoLog(s, len, nullptr, log.data());
    glDeleteShader(s);
    return Internal(std::string("GLSL ") + (type == GL_VERTEX_SHADER ? "vertex" : "fragment") +
                    " shader '" + name + "' does not compile: " + log);
  }
  return s;
}

}  // namespace

ProgramSource TerrainProgram() {
  return {"terrain", {kVersion, kTerrainVertex}, {kVersion, kLighting, kTerrainFragment}};
}
ProgramSource LanderProgram() {
  return {"lander", {kVersion, kLanderVertex}, {kVersion, kLighting, kLanderFragment}};
}
ProgramSource SkyProgram() { return {"sky", {kVersion, kSkyVertex}, {kVersion, kSkyFragment}}; }
ProgramSource ShadowProgram() {
  return {"shadow", {kVersion, kTerrainVertex}, {kVersion, kShadowFragment}};
}

Result<GLuint> BuildProgram(const ProgramSource& source) {
  auto vs = Compile(GL_VERTEX_SHADER, source.vertex, source.name);
  if (!vs.ok()) return vs.status();
  auto fs = Compile(GL_FRAGMENT_SHADER, source.fragment, source.name);
  if (!fs.ok()) {
    glDeleteShader(*vs);
    return fs.status();
  }
  const GLuint p = glCreateProgram();
  glAttachShader(p, *vs);
  glAttachShader(p, *fs);
  glLinkProgram(p);
  glDeleteShader(*vs);
  glDeleteShader(*fs);
  GLint ok = 0;
  glGetProgramiv(p, GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) {
    GLint len = 0;
    glGetProgramiv(p, GL_INFO_LOG_LENGTH, &len);
    std::string log(static_cast<std::size_t>(std::max(len, 1)), '\0');
    glGetProgramInfoLog(p, len, nullptr, log.data());
    glDeleteProgram(p);
    return Internal(std::string("GLSL program '") + source.name + "' does not link: " + log);
  }
  return p;
}

}  // namespace rover::sim::render::internal
