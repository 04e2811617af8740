#pragma once
// GLSL 3.30 core programs of the renderer and a compile/link helper.
//   terrain:  heightfield tiles and the apron; procedural soil/rock/bedrock materials, bump,
//             Lambert sun + sky, cascaded shadow-map lookup; outputs radiance and range.
//   lander:   lander quads with their albedo (RGB -> luminance on upload), same lighting.
//   sky:      full-screen triangle at the far plane; sky radiance by elevation and sun angle.
//   shadow:   depth-only pass for terrain tiles and lander (skirt-aware vertex shader).

#include <string>
#include <vector>

#include "gl.hpp"
#include "rover/base/status.hpp"

namespace rover::sim::render::internal {

struct ProgramSource {
  const char* name;
  std::vector<const char*> vertex;    // concatenated
  std::vector<const char*> fragment;  // concatenated
};

ProgramSource TerrainProgram();
ProgramSource LanderProgram();
ProgramSource SkyProgram();
ProgramSource ShadowProgram();

// Compiles and links; Internal with the driver's log on failure. Needs a current context.
Result<GLuint> BuildProgram(const ProgramSource& source);

}  // namespace rover::sim::render::internal
