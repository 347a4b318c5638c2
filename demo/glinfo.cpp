// SPDX-License-Identifier: MIT
// emcv-glinfo: creates the emcv OpenGL 4.5 context and prints vendor, renderer, version and the platform used.
//   emcv-glinfo [--platform device|surfaceless|osmesa] [--window] [--device N]
// --device N picks the N-th EGL device (from 0) and, without --platform, tries only the device platform: an
// index that does not exist is an error, never a silent fall-back to surfaceless.
// Exit status: 0 on success, 1 when no context could be created or a GL error was reported, 2 on bad usage.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "gl/context.hpp"
#include "gl/debug.hpp"

namespace {

int usage(const char* why) {
    std::fprintf(stderr, "emcv-glinfo: %s\nusage: emcv-glinfo [--platform device|surfaceless|osmesa] [--window] [--device N]\n", why);
    return 2;
}

/// A device index: 1 to 9 decimal digits (no sign, no suffix, so it fits an int); -1 for anything else.
int parse_device_index(const std::string& text) {
    if (text.empty() || text.size() > 9 || !std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; }))
        return -1;
    return std::stoi(text);
}

}  // namespace

int main(int argc, char** argv) {
    emcv::gl::context_options options;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        try {
            if ((a == "--platform" || a == "--device") && i + 1 >= argc) {
                return usage((a + " needs a value").c_str());
            } else if (a == "--platform") {
                options.platforms = emcv::gl::parse_platforms(argv[++i]);
                if (options.platforms.empty()) return usage("--platform needs a platform name");
            } else if (a == "--window") {
                options.platforms = {emcv::gl::platform::glfw_window};
            } else if (a == "--device") {
                const std::string value = argv[++i];
                options.device_index = parse_device_index(value);
                if (options.device_index < 0)
                    return usage(("--device needs a device index 0, 1, ..., got '" + value + "'").c_str());
            } else if (a == "--help" || a == "-h") {
                return usage("prints the OpenGL context emcv gets");
            } else {
                return usage(("unknown argument '" + a + "'").c_str());
            }
        } catch (const std::exception& e) {
            return usage(e.what());
        }
    }
    if (options.device_index >= 0) {
        if (options.platforms.empty()) options.platforms = {emcv::gl::platform::egl_device};
        if (std::find(options.platforms.begin(), options.platforms.end(), emcv::gl::platform::egl_device) ==
            options.platforms.end())
            return usage("--device applies to the device platform only");
    }
    try {
        emcv::gl::context ctx(options);
        emcv::gl::debug_messenger debug;
        std::printf("platform: %s\nvendor:   %s\nrenderer: %s\nversion:  %s\n",
                    emcv::gl::platform_name(ctx.used_platform()), ctx.vendor().c_str(), ctx.renderer().c_str(),
                    ctx.version().c_str());
        if (!ctx.fallback_log().empty()) std::printf("platforms that failed first:%s\n", ctx.fallback_log().c_str());
        return debug.exit_status();
    } catch (const std::exception& e) {
        std::fprintf(stderr, "emcv-glinfo: %s\n", e.what());
        return 1;
    }
}
