// SPDX-License-Identifier: MIT
// Only this file sees <GL/osmesa.h> (and through it <GL/gl.h>); see osmesa_platform.hpp.
#include "osmesa_platform.hpp"

#ifdef EMCV_GL_HAVE_OSMESA
#include <GL/osmesa.h>
#include <dlfcn.h>
#endif

namespace emcv::gl::detail {

#ifdef EMCV_GL_HAVE_OSMESA
namespace {

/// The libOSMesa entry points we call, resolved once with dlsym. The library is never dlclose()d: Mesa keeps
/// per-process state (LLVM, glapi) that does not survive unloading.
struct osmesa_api {
    void* library = nullptr;
    std::string error;
    decltype(&OSMesaCreateContextAttribs) create_context_attribs = nullptr;
    decltype(&OSMesaMakeCurrent) make_current = nullptr;
    decltype(&OSMesaDestroyContext) destroy_context = nullptr;
    decltype(&OSMesaGetProcAddress) get_proc_address = nullptr;

    osmesa_api() {
        for (const char* name : {"libOSMesa.so.8", "libOSMesa.so.6", "libOSMesa.so"}) {
            library = dlopen(name, RTLD_NOW | RTLD_LOCAL);
            if (library) break;
        }
        if (!library) {
            const char* e = dlerror();
            error = std::string("libOSMesa not found (Mesa 25.1 and later no longer ship it): ") + (e ? e : "dlopen failed");
            return;
        }
        create_context_attribs = reinterpret_cast<decltype(create_context_attribs)>(dlsym(library, "OSMesaCreateContextAttribs"));
        make_current = reinterpret_cast<decltype(make_current)>(dlsym(library, "OSMesaMakeCurrent"));
        destroy_context = reinterpret_cast<decltype(destroy_context)>(dlsym(library, "OSMesaDestroyContext"));
        get_proc_address = reinterpret_cast<decltype(get_proc_address)>(dlsym(library, "OSMesaGetProcAddress"));
        if (!create_context_attribs || !make_current || !destroy_context || !get_proc_address)
            error = "libOSMesa lacks OSMesaCreateContextAttribs, OSMesaMakeCurrent, OSMesaDestroyContext or "
                    "OSMesaGetProcAddress (older than Mesa 11.2?)";
    }
};

osmesa_api& api() {
    static osmesa_api instance;
    return instance;
}

}  // namespace

bool osmesa_built() noexcept { return true; }

std::string osmesa_session::create(int major, int minor, bool& library_missing) {
    osmesa_api& a = api();
    library_missing = a.library == nullptr;
    if (!a.error.empty()) return a.error;
    const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 0,
                           OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                           OSMESA_CONTEXT_MAJOR_VERSION, major,
                           OSMESA_CONTEXT_MINOR_VERSION, minor, 0};
    OSMesaContext c = a.create_context_attribs(attribs, nullptr);
    if (!c)
        return "no OpenGL " + std::to_string(major) + "." + std::to_string(minor) +
               " core context (OSMesaCreateContextAttribs failed)";
    // The default framebuffer is a small RGBA8 buffer; rendering goes to framebuffer objects.
    constexpr int side = 16;
    buffer_.assign(side * side * 4, 0);
    if (!a.make_current(c, buffer_.data(), GL_UNSIGNED_BYTE, side, side)) {
        a.destroy_context(c);
        return "OSMesaMakeCurrent failed";
    }
    context_ = c;
    return {};
}

osmesa_proc osmesa_session::get_proc_address(const char* name) {
    return api().get_proc_address ? reinterpret_cast<osmesa_proc>(api().get_proc_address(name)) : nullptr;
}

osmesa_session::~osmesa_session() {
    if (!context_) return;
    osmesa_api& a = api();
    a.make_current(nullptr, nullptr, GL_UNSIGNED_BYTE, 0, 0);
    a.destroy_context(static_cast<OSMesaContext>(context_));
}

#else

bool osmesa_built() noexcept { return false; }
std::string osmesa_session::create(int, int, bool& library_missing) {
    library_missing = true;
    return "not built (<GL/osmesa.h> not found at configure time; Debian: libosmesa6-dev)";
}
osmesa_proc osmesa_session::get_proc_address(const char*) { return nullptr; }
osmesa_session::~osmesa_session() = default;

#endif

}  // namespace emcv::gl::detail
