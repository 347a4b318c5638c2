// SPDX-License-Identifier: MIT
#include "resolve.hpp"

namespace emcv::demo {

std::optional<resolve_mode> parse_resolve(std::string_view text) {
    if (text == "none") return resolve_mode::none;
    if (text == "taa") return resolve_mode::taa;
    return std::nullopt;
}

resolve_mode parse_resolve_flag(std::string_view value) {
    if (const std::optional<resolve_mode> r = parse_resolve(value)) return *r;
    throw resolve_error("--resolve: expected none or taa, got '" + std::string(value) + "'");
}

const char* resolve_name(resolve_mode r) { return r == resolve_mode::taa ? "taa" : "none"; }

std::string resolve_label(resolve_mode r, bool jitter) {
    return std::string(resolve_name(r)) + (r == resolve_mode::taa && jitter ? "+jitter" : "");
}

std::string resolve_flag_help() {
    return "  --resolve MODE      what is shown after the composite: taa (default: the temporal resolve pass,\n"
           "                      reprojected history, YCoCg variance clipping, exponential blend; every method\n"
           "                      but the reference) or none (the raw frame; no resolve pass is recorded)\n"
           "  --jitter            with --resolve taa: move the camera by a sub-pixel Halton (2, 3) offset each\n"
           "                      frame (8 phases), so that the resolve accumulates an anti-aliased image (not\n"
           "                      the reference, which stays the converged point-sampled image)\n";
}

void check_jitter_flag(bool jitter, resolve_mode r) {
    if (jitter && r != resolve_mode::taa)
        throw resolve_error("--jitter: needs --resolve taa (the jitter is what the resolve accumulates; the raw frame "
                            "alone would only move)");
}

}  // namespace emcv::demo
