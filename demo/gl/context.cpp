// SPDX-License-Identifier: MIT
// Order of attempts follows Magnum's WindowlessEglApplication: EGL_EXT_platform_device
// (device picked by index), then EGL_MESA_platform_surfaceless, then OSMesa, then a GLFW window on request.
// The EGL display is never eglTerminate()d: it is a process-wide singleton shared with other users.
// Once a platform's context is current, gl.hpp's entry points are loaded from that platform's resolver.
#include "context.hpp"

#include "gl.hpp"
#include "osmesa_platform.hpp"

#include <EGL/egl.h>
#include <EGL/eglext.h>

#ifdef EMCV_GL_HAVE_GLFW
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#endif

#include <cstdlib>
#include <sstream>

// LeakSanitizer: Mesa keeps some allocations until exit (driver caches, LLVM; libOSMesa also after a failed
// OSMesaCreateContextAttribs): suppress reports whose stack goes through Mesa's libraries only, for every
// program linking emcv_gl (tests, emcv-glinfo, the demo). LSan stays on for emcv's code; harmless without
// sanitizers. Defined here because this file is linked into every such program.
// AddressSanitizer: GCC 12's runtime (Debian 12) guesses from a dynamic TLS block's address alone whether it has a
// pre-2.25 glibc header, and when a block lands on that offset by chance it records a bogus range that
// LeakSanitizer's tracer then scans: "Tracer caught signal 11" in ScanRangeForPointers at exit, about once in
// a few hundred GL runs (Mesa and LLVM are dlopen'd with dynamic TLS). Not intercepting __tls_get_addr avoids
// it; LSan still scans static TLS and every thread's stack. ASAN_OPTIONS from the environment are applied after
// these. Harmless without sanitizers.
extern "C" const char* __asan_default_options() { return "intercept_tls_get_addr=0"; }

extern "C" const char* __lsan_default_suppressions() {
    return "leak:libEGL_mesa\nleak:libgallium\nleak:libglapi\nleak:swrast_dri\nleak:libLLVM\nleak:libGLX_mesa\n"
           "leak:libOSMesa\nleak:libglfw\nleak:libX11\n";
}

namespace emcv::gl {
namespace {

const char* egl_error_name(EGLint e) {
    switch (e) {
        case EGL_SUCCESS: return "EGL_SUCCESS";
        case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
        case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
        case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
        case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
        case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
        case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
        case EGL_BAD_CURRENT_SURFACE: return "EGL_BAD_CURRENT_SURFACE";
        case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
        case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
        case EGL_BAD_NATIVE_PIXMAP: return "EGL_BAD_NATIVE_PIXMAP";
        case EGL_BAD_NATIVE_WINDOW: return "EGL_BAD_NATIVE_WINDOW";
        case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
        case EGL_BAD_SURFACE: return "EGL_BAD_SURFACE";
        case EGL_CONTEXT_LOST: return "EGL_CONTEXT_LOST";
        default: return "unknown EGL error";
    }
}

std::string egl_fail(const char* call) { return std::string(call) + ": " + egl_error_name(eglGetError()); }

/// Token-boundary match in a space-separated extension string (not a bare strstr).
bool has_extension(const char* list, const std::string& name) {
    if (!list) return false;
    std::istringstream in(list);
    std::string tok;
    while (in >> tok)
        if (tok == name) return true;
    return false;
}

/// Why one attempt failed; `display_missing` marks failures that mean "nothing to render with here".
struct attempt_failure {
    std::string reason;
    bool display_missing;
};

int env_int(const char* name, int fallback) {
    const char* v = std::getenv(name);
    if (!v || !*v) return fallback;
    char* end = nullptr;
    const long x = std::strtol(v, &end, 10);
    if (*end != '\0') throw std::invalid_argument(std::string(name) + "=" + v + " is not an integer");
    return static_cast<int>(x);
}

detail::gl_proc egl_proc(const char* name) { return reinterpret_cast<detail::gl_proc>(eglGetProcAddress(name)); }
#ifdef EMCV_GL_HAVE_GLFW
detail::gl_proc glfw_proc(const char* name) { return reinterpret_cast<detail::gl_proc>(glfwGetProcAddress(name)); }
#endif
detail::gl_proc osmesa_proc(const char* name) { return detail::osmesa_session::get_proc_address(name); }

/// Loads gl.hpp's table from `get` for the context just made current and checks that it reaches the context:
/// glGetString(GL_VERSION) answers and glCreateBuffers (GL 4.5 direct state access) names a buffer.
/// Returns "" or why not.
std::string load_and_probe(detail::gl_get_proc_address get) {
    const std::size_t resolved = detail::load_gl_functions(get);
    if (!glGetString || !glCreateBuffers || !glDeleteBuffers || !glDispatchCompute)
        return "GL entry points do not resolve (" + std::to_string(resolved) + " of " +
               std::to_string(detail::gl_function_count()) + ")";
    if (!glGetString(GL_VERSION)) return "glGetString(GL_VERSION) returned NULL: GL calls do not reach the context";
    GLuint probe = 0;
    glCreateBuffers(1, &probe);
    if (probe == 0) return "glCreateBuffers (GL 4.5 direct state access) does not reach the context";
    glDeleteBuffers(1, &probe);
    return {};
}

}  // namespace

const char* platform_name(platform p) noexcept {
    switch (p) {
        case platform::egl_device: return "device";
        case platform::egl_surfaceless: return "surfaceless";
        case platform::osmesa: return "osmesa";
        case platform::glfw_window: return "window";
    }
    return "?";
}

bool platform_built(platform p) noexcept {
    switch (p) {
        case platform::osmesa: return detail::osmesa_built();
        case platform::glfw_window:
#ifdef EMCV_GL_HAVE_GLFW
            return true;
#else
            return false;
#endif
        default: return true;
    }
}

std::vector<platform> parse_platforms(const std::string& list) {
    std::vector<platform> out;
    std::istringstream in(list);
    std::string item;
    while (std::getline(in, item, ',')) {
        if (item == "device") out.push_back(platform::egl_device);
        else if (item == "surfaceless") out.push_back(platform::egl_surfaceless);
        else if (item == "osmesa") out.push_back(platform::osmesa);
        else if (item == "window") out.push_back(platform::glfw_window);
        else if (item == "none" || item.empty()) continue;
        else
            throw std::invalid_argument("unknown GL platform '" + item +
                                        "' (expected device, surfaceless, osmesa, window or none)");
    }
    return out;
}

struct context::impl {
    platform used = platform::egl_device;
    std::string fallback_log;
    EGLDisplay display = EGL_NO_DISPLAY;
    EGLContext egl_context = EGL_NO_CONTEXT;
#ifdef EMCV_GL_HAVE_GLFW
    GLFWwindow* window = nullptr;
#endif
    std::unique_ptr<detail::osmesa_session> osmesa;

    ~impl() {
        osmesa.reset();
        if (egl_context != EGL_NO_CONTEXT) {
            eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
            eglDestroyContext(display, egl_context);
        }
#ifdef EMCV_GL_HAVE_GLFW
        if (window) {
            glfwDestroyWindow(window);
            glfwTerminate();
        }
#endif
    }

    /// Creates a core context of the requested version on an initialised display (no config, no surface).
    std::string make_egl_context(EGLDisplay dpy, const context_options& o) {
        EGLint major = 0, minor = 0;
        if (!eglInitialize(dpy, &major, &minor)) return egl_fail("eglInitialize");
        const char* ext = eglQueryString(dpy, EGL_EXTENSIONS);
        if (!has_extension(ext, "EGL_KHR_no_config_context") || !has_extension(ext, "EGL_KHR_surfaceless_context"))
            return "display lacks EGL_KHR_no_config_context or EGL_KHR_surfaceless_context";
        if (!eglBindAPI(EGL_OPENGL_API)) return egl_fail("eglBindAPI(EGL_OPENGL_API)");
        const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION, o.major,
                                  EGL_CONTEXT_MINOR_VERSION, o.minor,
                                  EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                  EGL_CONTEXT_OPENGL_DEBUG, o.debug ? EGL_TRUE : EGL_FALSE,
                                  EGL_NONE};
        EGLContext c = eglCreateContext(dpy, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attribs);
        if (c == EGL_NO_CONTEXT) {
            std::ostringstream m;
            m << "no OpenGL " << o.major << "." << o.minor << " core context (" << egl_fail("eglCreateContext")
              << ", EGL " << major << "." << minor << ")";
            return m.str();
        }
        if (!eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, c)) {
            const std::string r = egl_fail("eglMakeCurrent");
            eglDestroyContext(dpy, c);
            return r;
        }
        const std::string probe = load_and_probe(egl_proc);
        if (!probe.empty()) {
            eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
            eglDestroyContext(dpy, c);
            return probe;
        }
        display = dpy;
        egl_context = c;
        return {};
    }

    attempt_failure try_device(const context_options& o) {
        const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
        if (!client) return {"no EGL client extensions (" + egl_fail("eglQueryString") + "; no EGL vendor?)", true};
        if (!has_extension(client, "EGL_EXT_platform_device") ||
            !(has_extension(client, "EGL_EXT_device_enumeration") || has_extension(client, "EGL_EXT_device_base")))
            return {"EGL_EXT_platform_device / EGL_EXT_device_enumeration not supported", true};
        auto query_devices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
        auto get_display =
            reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
        if (!query_devices || !get_display) return {"eglQueryDevicesEXT / eglGetPlatformDisplayEXT missing", true};
        EGLDeviceEXT devices[16];
        EGLint count = 0;
        if (!query_devices(16, devices, &count)) return {egl_fail("eglQueryDevicesEXT"), true};
        if (count == 0) return {"no EGL device", true};
        const int index = o.device_index >= 0 ? o.device_index : env_int("EMCV_EGL_DEVICE", 0);
        if (index >= count)
            return {"device index " + std::to_string(index) + " out of range (" + std::to_string(count) +
                        " device(s))",
                    false};
        EGLDisplay dpy = get_display(EGL_PLATFORM_DEVICE_EXT, devices[index], nullptr);
        if (dpy == EGL_NO_DISPLAY) return {egl_fail("eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT)"), true};
        std::string r = make_egl_context(dpy, o);
        if (!r.empty()) return {"device " + std::to_string(index) + ": " + r, false};
        return {{}, false};
    }

    attempt_failure try_surfaceless(const context_options& o) {
        const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
        if (!client) return {"no EGL client extensions (" + egl_fail("eglQueryString") + "; no EGL vendor?)", true};
        if (!has_extension(client, "EGL_MESA_platform_surfaceless"))
            return {"EGL_MESA_platform_surfaceless not supported", true};
        auto get_display =
            reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
        if (!get_display) return {"eglGetPlatformDisplayEXT missing", true};
        EGLDisplay dpy = get_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        if (dpy == EGL_NO_DISPLAY) return {egl_fail("eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA)"), true};
        std::string r = make_egl_context(dpy, o);
        if (!r.empty()) return {r, false};
        return {{}, false};
    }

    attempt_failure try_osmesa(const context_options& o) {
        auto session = std::make_unique<detail::osmesa_session>();
        bool library_missing = false;
        std::string r = session->create(o.major, o.minor, library_missing);
        if (r.empty()) r = load_and_probe(osmesa_proc);
        if (!r.empty()) return {r, library_missing};
        osmesa = std::move(session);
        return {{}, false};
    }

    attempt_failure try_window(const context_options& o) {
#ifdef EMCV_GL_HAVE_GLFW
        if (!glfwInit()) {
            const char* d = nullptr;
            glfwGetError(&d);
            return {std::string("glfwInit failed: ") + (d ? d : "unknown error"), true};
        }
        glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, o.major);
        glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, o.minor);
        glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
        glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
        glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, o.debug ? GLFW_TRUE : GLFW_FALSE);
        window = glfwCreateWindow(o.window_width, o.window_height, "emcv", nullptr, nullptr);
        if (!window) {
            const char* d = nullptr;
            glfwGetError(&d);
            glfwTerminate();
            return {std::string("glfwCreateWindow failed: ") + (d ? d : "unknown error"), false};
        }
        glfwMakeContextCurrent(window);
        std::string r = load_and_probe(glfw_proc);
        if (!r.empty()) return {r, false};
        return {{}, false};
#else
        (void)o;
        return {"built without GLFW", true};
#endif
    }
};

context::context(context_options o) : p_(std::make_unique<impl>()) {
    if (o.platforms.empty()) {
        const char* env = std::getenv("EMCV_GL_PLATFORMS");
        if (env)
            o.platforms = parse_platforms(env);
        else
            o.platforms = {platform::egl_device, platform::egl_surfaceless, platform::osmesa};
    }
    if (o.major == 0) {
        o.major = 4;
        o.minor = 5;
        if (const char* v = std::getenv("EMCV_GL_VERSION")) {
            int ma = 0, mi = 0;
            char dot = 0;
            std::istringstream in(v);
            if (!(in >> ma >> dot >> mi) || dot != '.' || ma < 1)
                throw std::invalid_argument(std::string("EMCV_GL_VERSION=") + v + " is not of the form 4.5");
            o.major = ma;
            o.minor = mi;
        }
    }
    std::ostringstream log;
    bool all_missing = true;
    for (platform pf : o.platforms) {
        attempt_failure f;
        switch (pf) {
            case platform::egl_device: f = p_->try_device(o); break;
            case platform::egl_surfaceless: f = p_->try_surfaceless(o); break;
            case platform::osmesa: f = p_->try_osmesa(o); break;
            case platform::glfw_window: f = p_->try_window(o); break;
        }
        if (f.reason.empty()) {
            p_->used = pf;
            p_->fallback_log = log.str();
            return;
        }
        all_missing = all_missing && f.display_missing;
        log << "\n  " << platform_name(pf) << ": " << f.reason;
    }
    std::ostringstream msg;
    msg << "cannot create an OpenGL " << o.major << "." << o.minor << " core context; platforms tried:";
    if (o.platforms.empty()) msg << " none (EMCV_GL_PLATFORMS names no platform)";
    msg << log.str();
    throw context_error(msg.str(), all_missing);
}

context::~context() = default;
context::context(context&&) noexcept = default;
context& context::operator=(context&&) noexcept = default;

platform context::used_platform() const noexcept { return p_->used; }
const std::string& context::fallback_log() const noexcept { return p_->fallback_log; }

static std::string gl_string(GLenum name) {
    const GLubyte* s = glGetString(name);
    return s ? reinterpret_cast<const char*>(s) : "";
}
std::string context::vendor() const { return gl_string(GL_VENDOR); }
std::string context::renderer() const { return gl_string(GL_RENDERER); }
std::string context::version() const { return gl_string(GL_VERSION); }

bool context::present() {
#ifdef EMCV_GL_HAVE_GLFW
    if (p_->window) {
        glfwSwapBuffers(p_->window);
        glfwPollEvents();
        return !glfwWindowShouldClose(p_->window);
    }
#endif
    return true;
}

}  // namespace emcv::gl
