// SPDX-License-Identifier: MIT
// emcv::demo::frame_stats: what one rendered frame reports (times per pass, samples per SSS pixel).
#pragma once

#include <cstddef>
#include <string_view>
#include <vector>

namespace emcv::demo {

struct pass_time {
    /// The pass's name as in pass_list; points into the renderer's own names (valid while the renderer lives),
    /// so a frame's statistics cost no allocation.
    std::string_view name;
    double ms = 0.0;
};

/// frame_ms is the sum of the frame's pass times (GL_TIME_ELAPSED queries cannot nest, and every GPU command
/// of a frame is inside one pass); sss_ms is the sum of the sss-* passes.
struct frame_stats {
    int frame = 0;
    double sss_ms = 0.0;    ///< sum of the sss-* passes (0 when none was recorded)
    double frame_ms = 0.0;  ///< sum of every pass of the frame
    /// Samples per SSS pixel that made this frame's image (burley-N: N; separable: 2 * taps; reference:
    /// its count, also on frames that reuse it; diffuse: 0). Counted on the GPU over the SSS pixels.
    double mean_spp = 0.0;
    int max_spp = 0;
    std::size_t sss_pixels = 0;      ///< visible pixels with a scattering material (0 if no SSS pass ran)
    bool reference_reused = false;   ///< reference: inputs unchanged, last frame's result shown again
    std::vector<pass_time> passes;   ///< in recording order, named as in pass_list
};

}  // namespace emcv::demo
