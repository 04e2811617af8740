#include "gl_context.hpp"

#include <cstdio>
#include <cstring>
#include <mutex>

namespace rover::sim::render::internal {
namespace {

std::mutex g_mutex;
EGLDisplay g_display = EGL_NO_DISPLAY;
int g_users = 0;

std::string Hex(unsigned v) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "0x%04X", v);
  return buf;
}

Status EglError(const std::string& call) {
  return Unavailable("EGL: " + call + " failed (error " + Hex(static_cast<unsigned>(eglGetError())) +
                     "); headless rendering needs Mesa's EGL (packages libegl-mesa0, "
                     "libgl1-mesa-dri)");
}

// Opens (or shares) the process's EGL display.
Result<EGLDisplay> AcquireDisplay() {
  std::lock_guard<std::mutex> lock(g_mutex);
  if (g_users > 0) {
    ++g_users;
    return g_display;
  }
  EGLDisplay d = EGL_NO_DISPLAY;
  const char* ext = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (ext != nullptr && std::strstr(ext, "EGL_MESA_platform_surfaceless") != nullptr) {
    auto get_platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
        eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (get_platform_display != nullptr) {
      d = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    }
  }
  EGLint major = 0, minor = 0;
  if (d == EGL_NO_DISPLAY || eglInitialize(d, &major, &minor) != EGL_TRUE) {
    d = eglGetDisplay(EGL_DEFAULT_DISPLAY);
    if (d == EGL_NO_DISPLAY) return EglError("eglGetDisplay(EGL_DEFAULT_DISPLAY)");
    if (eglInitialize(d, &major, &minor) != EGL_TRUE) return EglError("eglInitialize");
  }
  g_display = d;
  g_users = 1;
  return d;
}

void ReleaseDisplay() {
  std::lock_guard<std::mutex> lock(g_mutex);
  if (g_users <= 0) return;
  if (--g_users == 0) {
    eglTerminate(g_display);
    eglReleaseThread();
    g_display = EGL_NO_DISPLAY;
  }
}

}  // namespace

Status CheckGl(const char* what) {
  const GLenum e = glGetError();
  if (e == GL_NO_ERROR) return Status::Ok();
  const char* name = e == GL_INVALID_ENUM                    ? "GL_INVALID_ENUM"
                     : e == GL_INVALID_VALUE                 ? "GL_INVALID_VALUE"
                     : e == GL_INVALID_OPERATION             ? "GL_INVALID_OPERATION"
                     : e == GL_OUT_OF_MEMORY                 ? "GL_OUT_OF_MEMORY"
                     : e == GL_INVALID_FRAMEBUFFER_OPERATION ? "GL_INVALID_FRAMEBUFFER_OPERATION"
                                                             : "?";
  while (glGetError() != GL_NO_ERROR) {
  }
  return Internal("GL error " + Hex(e) + " (" + name + ") after " + what);
}

Result<std::unique_ptr<GlContext>> GlContext::Create() {
  auto display = AcquireDisplay();
  if (!display.ok()) return display.status();
  std::unique_ptr<GlContext> ctx(new GlContext());
  ctx->display_ = *display;
  if (eglBindAPI(EGL_OPENGL_API) != EGL_TRUE) return EglError("eglBindAPI(EGL_OPENGL_API)");
  const EGLint config_attribs[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE,
                                   EGL_OPENGL_BIT, EGL_NONE};
  EGLConfig config = nullptr;
  EGLint count = 0;
  if (eglChooseConfig(ctx->display_, config_attribs, &config, 1, &count) != EGL_TRUE ||
      count < 1) {
    return EglError("eglChooseConfig(EGL_PBUFFER_BIT, EGL_OPENGL_BIT)");
  }
  const EGLint context_attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 3,
                                    EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                    EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
  ctx->context_ = eglCreateContext(ctx->display_, config, EGL_NO_CONTEXT, context_attribs);
  if (ctx->context_ == EGL_NO_CONTEXT) return EglError("eglCreateContext(OpenGL 3.3 core)");
  ROVER_RETURN_IF_ERROR(ctx->MakeCurrent());
  const auto* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  const auto* version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  ctx->renderer_ = renderer != nullptr ? renderer : "?";
  ctx->version_ = version != nullptr ? version : "?";
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &ctx->max_texture_size_);
  glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &ctx->max_renderbuffer_size_);
  ROVER_RETURN_IF_ERROR(CheckGl("context creation"));
  return ctx;
}

GlContext::~GlContext() {
  if (context_ != EGL_NO_CONTEXT) {
    if (eglGetCurrentContext() == context_) {
      eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    }
    eglDestroyContext(display_, context_);
  }
  if (display_ != EGL_NO_DISPLAY) ReleaseDisplay();
}

Status GlContext::MakeCurrent() const {
  if (eglGetCurrentContext() == context_) return Status::Ok();
  if (eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_) != EGL_TRUE) {
    return EglError("eglMakeCurrent(surfaceless)");
  }
  return Status::Ok();
}

}  // namespace rover::sim::render::internal
