#include "src/gl_context.hpp"

#include <gtest/gtest.h>

namespace rover::sim::render::internal {
namespace {

TEST(GlContextTest, CreatesHeadlessContextOrSaysWhy) {
  auto ctx = GlContext::Create();
  if (!ctx.ok()) {
    EXPECT_EQ(ctx.status().code(), StatusCode::kUnavailable);
    EXPECT_NE(ctx.status().message().find("EGL"), std::string::npos);
    GTEST_SKIP() << "no headless OpenGL here: " << ctx.status().message();
  }
  EXPECT_FALSE((*ctx)->renderer().empty());
  EXPECT_GE((*ctx)->max_texture_size(), 4096);
  EXPECT_TRUE((*ctx)->MakeCurrent().ok());
  EXPECT_TRUE(CheckGl("test").ok());
  // A second context shares the display; destroying one leaves the other usable.
  auto second = GlContext::Create();
  ASSERT_TRUE(second.ok());
  second->reset();
  EXPECT_TRUE((*ctx)->MakeCurrent().ok());
  GLint size = 0;
  glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &size);
  EXPECT_GE(size, 4096);
  EXPECT_TRUE(CheckGl("query").ok());
  // A GL error is reported with its name (surfaceless: no default framebuffer to clear).
  glClear(GL_COLOR_BUFFER_BIT);
  const Status s = CheckGl("clear");
  if (!s.ok()) {
    EXPECT_NE(s.message().find("after clear"), std::string::npos);
  }
}

}  // namespace
}  // namespace rover::sim::render::internal
