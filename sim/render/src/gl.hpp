#pragma once
// OpenGL 3.3 core prototypes (libOpenGL from glvnd exports them) and EGL.
#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES 1
#endif
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/glcorearb.h>
