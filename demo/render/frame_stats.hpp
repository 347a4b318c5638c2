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

/// The measured times of one frame's passes (render_options::timing_mode says which clock). frame_ms is
/// the sum of its passes: stamps sit at every pass boundary, so it spans the first pass's start to the last
/// one's end; sss_ms is the sum of the sss-* passes.
struct frame_times {
    int frame = -1;         ///< the frame these times belong to (-1: none measured yet)
    double sss_ms = 0.0;    ///< sum of the sss-* passes (0 when none was recorded)
    double frame_ms = 0.0;  ///< sum of every pass of the frame
    std::vector<pass_time> passes;  ///< in recording order, named as in pass_list
};

struct frame_stats {
    int frame = 0;
    /// The newest measured frame's times: this frame's under the wall clock; under GPU timestamps the newest
    /// frame whose stamps have arrived (a few frames old, times.frame = -1 before the first). Exact per-frame
    /// times: renderer::take_times.
    frame_times times;
    /// Samples per SSS pixel that made this frame's image (burley-N: N; separable: 2 * taps; reference:
    /// its count, also on frames that reuse it; diffuse: 0). Counted on the GPU over the SSS pixels.
    double mean_spp = 0.0;
    int max_spp = 0;
    std::size_t sss_pixels = 0;      ///< visible pixels with a scattering material (0 if no SSS pass ran)
    bool reference_reused = false;   ///< reference: inputs unchanged, last frame's result shown again
};

}  // namespace emcv::demo
