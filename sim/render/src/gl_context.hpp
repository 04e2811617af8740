#pragma once
// Headless OpenGL context: EGL on Mesa's surfaceless platform (EGL_PLATFORM_SURFACELESS_MESA via
// eglGetPlatformDisplayEXT; EGL_DEFAULT_DISPLAY as a fallback), a PBUFFER-capable config, an
// OpenGL 3.3 core context made current without a surface (EGL_KHR_surfaceless_context).
// Rendering goes to framebuffer objects. The EGL display is shared by every context of the
// process and terminated when the last one is destroyed.

#include <memory>
#include <string>

#include "gl.hpp"
#include "rover/base/status.hpp"

namespace rover::sim::render::internal {

class GlContext {
 public:
  // Unavailable (with the failing EGL call and error code) if no context can be made.
  static Result<std::unique_ptr<GlContext>> Create();
  ~GlContext();
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;

  Status MakeCurrent() const;
  const std::string& renderer() const { return renderer_; }
  const std::string& version() const { return version_; }
  int max_texture_size() const { return max_texture_size_; }
  int max_renderbuffer_size() const { return max_renderbuffer_size_; }

 private:
  GlContext() = default;
  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLContext context_ = EGL_NO_CONTEXT;
  std::string renderer_, version_;
  int max_texture_size_ = 0;
  int max_renderbuffer_size_ = 0;
};

// "GL error 0x0502 (GL_INVALID_OPERATION) after <what>" if glGetError() reports one.
Status CheckGl(const char* what);

}  // namespace rover::sim::render::internal
