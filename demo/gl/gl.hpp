// SPDX-License-Identifier: MIT
// The one place that includes the GL headers. Every GL entry point is a function pointer (the Khronos
// <GL/glcorearb.h> types and enums, and a table generated from it by demo/gl/gl_functions.cmake) that
// emcv::gl::context fills from the platform it made current: eglGetProcAddress (EGL device / surfaceless,
// the same GLVND dispatch as linking libOpenGL), OSMesaGetProcAddress (libOSMesa exports no DSA symbols, but
// resolves them), glfwGetProcAddress. Code writes glCreateBuffers(...) as with prototypes.
// libepoxy was tried first and cannot serve OSMesa: its dispatch asserts "Couldn't find current GLX or EGL
// context" (epoxy 1.5.10), so the table is ours (docs/porting.md, "GL entry points").
#pragma once

#include <GL/glcorearb.h>

#include <cstddef>

// Later includes of the compatibility headers (<GL/gl.h> from GLFW or another library) become no-ops instead
// of redeclaring every entry point as a function.
#ifndef __gl_h_
#define __gl_h_
#endif
#ifndef __gl_glext_h_
#define __gl_glext_h_
#endif
// <GL/gl.h>'s calling-convention macro, for callbacks written against it (glDebugMessageCallback's)
#ifndef GLAPIENTRY
#define GLAPIENTRY APIENTRY
#endif

#include "emcv_gl_functions.hpp"

namespace emcv::gl::detail {

using gl_proc = void (*)();
using gl_get_proc_address = gl_proc (*)(const char* name);

/// The resolver the table was last filled from (null before the first context): for diagnostics.
inline gl_get_proc_address current_get_proc_address = nullptr;

/// Fills every pointer from `get` (null where it does not resolve); returns how many resolved. Called by
/// emcv::gl::context after making a context current: the pointers then belong to that context's platform.
std::size_t load_gl_functions(gl_get_proc_address get);

/// Entry points in the table (those of <GL/glcorearb.h>).
std::size_t gl_function_count() noexcept;

}  // namespace emcv::gl::detail
