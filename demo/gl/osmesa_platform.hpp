// SPDX-License-Identifier: MIT
// The OSMesa platform, loaded at run time: libOSMesa is dlopen()ed when the platform is tried, never linked,
// so it cannot shadow GLVND's GL dispatch for the other platforms, and a system without it (Mesa >= 25.1
// removed libOSMesa) still runs everything else. Kept out of context.cpp because <GL/osmesa.h> includes the
// compatibility <GL/gl.h>, which cannot share a translation unit with gl.hpp's function-pointer table.
#pragma once

#include <string>
#include <vector>

namespace emcv::gl::detail {

/// The same type as gl.hpp's gl_proc (gl.hpp itself cannot be included next to <GL/osmesa.h>).
using osmesa_proc = void (*)();

class osmesa_session {
public:
    osmesa_session() = default;
    ~osmesa_session();
    osmesa_session(const osmesa_session&) = delete;
    osmesa_session& operator=(const osmesa_session&) = delete;

    /// Loads libOSMesa, creates an OpenGL major.minor core context with a small RGBA8 default framebuffer and
    /// makes it current. Returns "" on success, else why not; `library_missing` says libOSMesa itself is absent.
    std::string create(int major, int minor, bool& library_missing);
    /// OSMesaGetProcAddress of the loaded library (valid after a successful create()).
    static osmesa_proc get_proc_address(const char* name);

private:
    void* context_ = nullptr;
    std::vector<unsigned char> buffer_;
};

/// True when this build has the OSMesa platform (the header was found at configure time).
bool osmesa_built() noexcept;

}  // namespace emcv::gl::detail
