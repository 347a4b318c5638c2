// SPDX-License-Identifier: MIT
// The package tests' OpenGL engines (gl_consumer, budget_consumer) take a headless EGL context and build their
// compute programs as an engine would: no emcv GL code. Exit status 77 (CTest's SKIP_RETURN_CODE) where there is no EGL display, unless
// EMCV_REQUIRE_GL=1 makes that a failure.
#ifndef EMCV_TESTS_PACKAGE_EGL_HEADLESS_H
#define EMCV_TESTS_PACKAGE_EGL_HEADLESS_H

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/glcorearb.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace consumer {

constexpr int kSkip = 77;

inline int no_display(const char* why) {
    const char* require = std::getenv("EMCV_REQUIRE_GL");
    const bool required = require != nullptr && std::strcmp(require, "1") == 0;
    std::printf("%s: %s\n", required ? "error (EMCV_REQUIRE_GL=1)" : "skipped: no EGL display", why);
    return required ? 1 : kSkip;
}

inline bool has_extension(const char* list, const char* name) {
    if (list == nullptr) return false;
    const std::size_t n = std::strlen(name);
    for (const char* p = std::strstr(list, name); p != nullptr; p = std::strstr(p + n, name))
        if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
    return false;
}

/// A display: Mesa's surfaceless platform, else the first EGL device, else the default display.
inline EGLDisplay open_display() {
    const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    auto get_platform_display =
        reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
    EGLint major = 0, minor = 0;
    if (get_platform_display && has_extension(client, "EGL_MESA_platform_surfaceless")) {
        EGLDisplay d = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        if (d != EGL_NO_DISPLAY && eglInitialize(d, &major, &minor)) return d;
    }
    auto query_devices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    if (get_platform_display && query_devices && has_extension(client, "EGL_EXT_platform_device")) {
        EGLDeviceEXT device{};
        EGLint count = 0;
        if (query_devices(1, &device, &count) && count > 0) {
            EGLDisplay d = get_platform_display(EGL_PLATFORM_DEVICE_EXT, device, nullptr);
            if (d != EGL_NO_DISPLAY && eglInitialize(d, &major, &minor)) return d;
        }
    }
    EGLDisplay d = eglGetDisplay(EGL_DEFAULT_DISPLAY);
    if (d != EGL_NO_DISPLAY && eglInitialize(d, &major, &minor)) return d;
    return EGL_NO_DISPLAY;
}

template <class F>
F load(const char* name) {
    F f = reinterpret_cast<F>(eglGetProcAddress(name));
    if (f == nullptr) {
        std::printf("FAILED: eglGetProcAddress(\"%s\") returned null\n", name);
        std::exit(1);
    }
    return f;
}
#define CONSUMER_GL(type, name) const auto name = consumer::load<type>(#name)

/// A current OpenGL 4.5 core context without a surface on `display`, or EGL_NO_CONTEXT after printing why (`skip`:
/// the display lacks the extensions, so the caller returns no_display's status).
inline EGLContext make_context(EGLDisplay display, bool& skip) {
    skip = false;
    const char* extensions = eglQueryString(display, EGL_EXTENSIONS);
    if (!has_extension(extensions, "EGL_KHR_no_config_context") ||
        !has_extension(extensions, "EGL_KHR_surfaceless_context") || !eglBindAPI(EGL_OPENGL_API)) {
        skip = true;
        return EGL_NO_CONTEXT;
    }
    const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                                 EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    EGLContext context = eglCreateContext(display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes);
    if (context == EGL_NO_CONTEXT || !eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
        std::printf("FAILED: no OpenGL 4.5 core context on the EGL display (0x%x)\n", eglGetError());
        return EGL_NO_CONTEXT;
    }
    return context;
}

/// Opens a display and makes a GL 4.5 core context current on it: 0 on success, else the exit status the test
/// returns (no_display's, or 1 when a display that has the extensions gives no context).
inline int start(EGLDisplay& display, EGLContext& context) {
    display = open_display();
    if (display == EGL_NO_DISPLAY) return no_display("no surfaceless, device or default EGL display initialises");
    bool skip = false;
    context = make_context(display, skip);
    if (skip) return no_display("the display lacks EGL_KHR_no_config_context or EGL_KHR_surfaceless_context");
    return context == EGL_NO_CONTEXT ? 1 : 0;
}

/// The compute program of `source` (one glShaderSource string) in the current context, or 0 after printing the
/// compiler's or the linker's log under `name`.
inline GLuint compile_compute(const std::string& source, const std::string& name) {
    CONSUMER_GL(PFNGLCREATESHADERPROC, glCreateShader);
    CONSUMER_GL(PFNGLSHADERSOURCEPROC, glShaderSource);
    CONSUMER_GL(PFNGLCOMPILESHADERPROC, glCompileShader);
    CONSUMER_GL(PFNGLGETSHADERIVPROC, glGetShaderiv);
    CONSUMER_GL(PFNGLGETSHADERINFOLOGPROC, glGetShaderInfoLog);
    CONSUMER_GL(PFNGLDELETESHADERPROC, glDeleteShader);
    CONSUMER_GL(PFNGLCREATEPROGRAMPROC, glCreateProgram);
    CONSUMER_GL(PFNGLATTACHSHADERPROC, glAttachShader);
    CONSUMER_GL(PFNGLLINKPROGRAMPROC, glLinkProgram);
    CONSUMER_GL(PFNGLGETPROGRAMIVPROC, glGetProgramiv);
    CONSUMER_GL(PFNGLGETPROGRAMINFOLOGPROC, glGetProgramInfoLog);
    const char* text = source.c_str();
    const GLuint shader = glCreateShader(GL_COMPUTE_SHADER);
    glShaderSource(shader, 1, &text, nullptr);
    glCompileShader(shader);
    GLint ok = GL_FALSE;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    std::vector<char> log(1 << 15);
    if (!ok) {
        glGetShaderInfoLog(shader, static_cast<GLsizei>(log.size()), nullptr, log.data());
        std::printf("FAILED: %s does not compile:\n%s\n", name.c_str(), log.data());
        glDeleteShader(shader);
        return 0;
    }
    const GLuint program = glCreateProgram();
    glAttachShader(program, shader);
    glLinkProgram(program);
    glDeleteShader(shader);  // freed with the program
    glGetProgramiv(program, GL_LINK_STATUS, &ok);
    if (!ok) {
        glGetProgramInfoLog(program, static_cast<GLsizei>(log.size()), nullptr, log.data());
        std::printf("FAILED: %s does not link:\n%s\n", name.c_str(), log.data());
        return 0;
    }
    return program;
}

}  // namespace consumer

#endif  // EMCV_TESTS_PACKAGE_EGL_HEADLESS_H
