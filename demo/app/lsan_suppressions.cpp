// SPDX-License-Identifier: MIT
// LeakSanitizer (the `sanitize` preset): Mesa keeps driver caches and LLVM state until exit. Reports whose
// stack goes through Mesa's libraries (or GLFW/X11 under --window) only are suppressed; LSan stays on for
// emcv's code. The same list as tests/gpu/gl_test_support.cpp, for the emcv-demo process. Unused otherwise.
extern "C" const char* __lsan_default_suppressions();
extern "C" const char* __lsan_default_suppressions() {
    return "leak:libEGL_mesa\nleak:libgallium\nleak:libglapi\nleak:swrast_dri\nleak:libLLVM\nleak:libGLX_mesa\n"
           "leak:libglfw\nleak:libX11\n";
}
