// SPDX-License-Identifier: MIT
// The one place that includes the GL headers: OpenGL 4.5 core prototypes straight from libOpenGL (GLVND),
// no loader (style.md 5.1).
#pragma once
#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES 1
#endif
#include <GL/gl.h>
#include <GL/glext.h>
