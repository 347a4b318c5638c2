// SPDX-License-Identifier: MIT
// emcv::demo::render_options: what a renderer is made with besides the scene and the method.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "resolve.hpp"
#include "timing.hpp"

namespace emcv::demo {

enum class tonemap_operator { aces, reinhard };

struct render_options {
    int width = 128;
    int height = 128;
    std::uint32_t seed = 1;  ///< decorrelates the per-pixel, per-frame sample rotations
    /// Draw Burley radii with SPVG's approximate inverse CDF (port/burley.h) instead of the exact one; the
    /// exact pdf is evaluated either way. Applies to burley-N, reference and the adaptive methods.
    bool approximate_inverse_cdf = false;
    tonemap_operator tonemap = tonemap_operator::aces;
    float exposure = 1.0f;  ///< linear radiance is multiplied by this before the tonemap
    timing timing_mode = timing::wall;  ///< the clock of frame_stats' pass times (timing.hpp)
    /// The temporal resolve after the composite (resolve.hpp). The renderer's default is the raw frame; the
    /// command lines default to taa, what an engine shows.
    resolve_mode resolve = resolve_mode::none;
    /// The camera moves by taa_jitter(frame) (view.hpp) every frame so that the resolve accumulates an
    /// anti-aliased image; only under resolve taa, never for the reference.
    bool jitter = false;
    /// Tunables of the port headers (`--define NAME=VALUE`, validated by demo/render/tunables.hpp), passed
    /// to every shader as `#define NAME VALUE`.
    std::vector<std::pair<std::string, std::string>> defines;
    /// Where the GLSL passes and the port headers are read from at run time. Empty: $EMCV_SHADER_DIR /
    /// $EMCV_INCLUDE_DIR when set, else the source tree (compile definitions of emcv_demo_render).
    std::filesystem::path shader_dir;
    std::filesystem::path include_dir;
};

}  // namespace emcv::demo
