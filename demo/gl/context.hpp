// SPDX-License-Identifier: MIT
// emcv::gl::context — an OpenGL 4.5 core context without a window (EGL device, EGL surfaceless), or with one
// on request (GLFW). EGL types stay in context.cpp (pimpl).
#pragma once

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace emcv::gl {

enum class platform { egl_device, egl_surfaceless, osmesa, glfw_window };

/// "device", "surfaceless", "osmesa", "window".
const char* platform_name(platform p) noexcept;

/// False for osmesa without -DEMCV_WITH_OSMESA=ON and for window without GLFW; true otherwise.
bool platform_built(platform p) noexcept;

/// Context creation failed. what() lists every platform tried and why each failed.
class context_error : public std::runtime_error {
public:
    context_error(const std::string& what, bool no_display)
        : std::runtime_error(what), no_display_(no_display) {}
    /// True when no platform could even open a display (no EGL vendor, no device, no X server): the case in
    /// which tests report "skipped: no EGL display" instead of failing.
    bool no_display() const noexcept { return no_display_; }

private:
    bool no_display_;
};

struct context_options {
    /// Platforms tried in order. Empty: $EMCV_GL_PLATFORMS (comma list of device, surfaceless, osmesa, window;
    /// "none" for no platform at all), else device, surfaceless, osmesa.
    std::vector<platform> platforms;
    /// EGL device index for the device platform; -1: $EMCV_EGL_DEVICE, else 0.
    int device_index = -1;
    /// Requested core version; 0: $EMCV_GL_VERSION ("4.5" form), else 4.5.
    int major = 0;
    int minor = 0;
    bool debug = true;  ///< request a debug context (KHR_debug output works either way on Mesa)
    int window_width = 640;
    int window_height = 480;
};

/// Parses "device,surfaceless" into platforms; throws std::invalid_argument naming an unknown entry.
std::vector<platform> parse_platforms(const std::string& list);

class context {
public:
    /// Creates and makes current the first platform that works. Throws context_error.
    explicit context(context_options options = {});
    ~context();
    context(context&&) noexcept;
    context& operator=(context&&) noexcept;
    context(const context&) = delete;
    context& operator=(const context&) = delete;

    platform used_platform() const noexcept;
    /// Notes from platforms tried before the one that worked (empty when the first one worked).
    const std::string& fallback_log() const noexcept;
    /// GL_VENDOR, GL_RENDERER, GL_VERSION of the current context.
    std::string vendor() const;
    std::string renderer() const;
    std::string version() const;
    /// Swaps buffers for a window context; no-op otherwise. Returns false once the window should close.
    bool present();

private:
    struct impl;
    std::unique_ptr<impl> p_;
};

}  // namespace emcv::gl
