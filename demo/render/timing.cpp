// SPDX-License-Identifier: MIT
#include "timing.hpp"

namespace emcv::demo {

std::optional<timing_request> parse_timing(std::string_view text) {
    if (text == "auto") return timing_request::automatic;
    if (text == "wall") return timing_request::wall;
    if (text == "gpu") return timing_request::gpu;
    return std::nullopt;
}

timing_request parse_timing_flag(std::string_view value) {
    if (const std::optional<timing_request> t = parse_timing(value)) return *t;
    throw timing_error("--timing: expected auto, wall or gpu, got '" + std::string(value) + "'");
}

bool is_software_renderer(std::string_view gl_renderer) {
    for (std::string_view name : {"llvmpipe", "softpipe", "SwiftShader", "Software Rasterizer"})
        if (gl_renderer.find(name) != std::string_view::npos) return true;
    return false;
}

timing resolve_timing(timing_request request, std::string_view gl_renderer) {
    switch (request) {
        case timing_request::wall: return timing::wall;
        case timing_request::gpu: return timing::gpu;
        case timing_request::automatic: break;
    }
    return is_software_renderer(gl_renderer) ? timing::wall : timing::gpu;
}

const char* timing_name(timing t) { return t == timing::gpu ? "gpu" : "wall"; }

std::string timing_description(timing t, std::string_view gl_renderer) {
    const bool software = is_software_renderer(gl_renderer);
    if (t == timing::gpu)
        return software ? "GPU timestamps at every pass boundary (a software renderer: its compute passes may read 0)"
                        : "GPU timestamps at every pass boundary";
    return software ? "wall clock, glFinish at every pass boundary (a software renderer: this measures its CPU work, "
                      "not GPU time)"
                    : "wall clock, glFinish at every pass boundary (includes the driver's submission; --timing gpu "
                      "gives GPU time)";
}

std::string timing_flag_help() {
    return "  --timing CLOCK      clock of the pass times: auto (default: gpu on a hardware renderer, wall on a\n"
           "                      software one such as llvmpipe), gpu (GL timestamps at every pass boundary,\n"
           "                      read back frames later) or wall (glFinish and the steady clock at each one)\n";
}

}  // namespace emcv::demo
