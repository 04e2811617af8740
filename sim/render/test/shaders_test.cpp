#include "src/shaders.hpp"

#include <gtest/gtest.h>

#include "src/gl_context.hpp"

namespace rover::sim::render::internal {
namespace {

TEST(ShadersTest, AllProgramsCompileAndLink) {
  auto ctx = GlContext::Create();
  if (!ctx.ok()) GTEST_SKIP() << "no headless OpenGL here: " << ctx.status().message();
  for (const auto& src : {TerrainProgram(), LanderProgram(), SkyProgram(), ShadowProgram()}) {
    auto p = BuildProgram(src);
    ASSERT_TRUE(p.ok()) << p.status().message();
    glDeleteProgram(*p);
  }
}

TEST(ShadersTest, CompileErrorIsReported) {
  auto ctx = GlContext::Create();
  if (!ctx.ok()) GTEST_SKIP() << "no headless OpenGL here: " << ctx.status().message();
  ProgramSource bad{"broken", {"#version 330 core\nvoid main() { gl_Position = vec4(1.0) }\n"},
                    {"#version 330 core\nvoid main() {}\n"}};
  auto p = BuildProgram(bad);
  ASSERT_FALSE(p.ok());
  EXPECT_EQ(p.status().code(), StatusCode::kInternal);
  EXPECT_NE(p.status().message().find("broken"), std::string::npos);
}

}  // namespace
}  // namespace rover::sim::render::internal
