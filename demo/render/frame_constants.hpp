// SPDX-License-Identifier: MIT
// The frame's constants on the GPU: the frame block (camera, viewport, counters, the method's sample mode) and
// the lights at this frame, uploaded once per frame before the first pass.
#pragma once

#include <vector>

#include "gpu_types.hpp"
#include "method.hpp"
#include "render_options.hpp"
#include "resources.hpp"
#include "scene/scene.hpp"
#include "view.hpp"

namespace emcv::demo {

class frame_constants {
public:
    explicit frame_constants(const scene& s) : lights_(s.lights.size()) {}

    /// Fills and uploads the frame block and the light blocks. `sss_shown`: the composite reads the scattered
    /// diffuse (an SSS pass ran, or the reference shows its held result). `sss_passes`: SSS passes run this
    /// frame (the lighting pass lists their tiles). `sss_noise`: the resolve reads the burley pass's noise
    /// (frame_planner::resolves_sss_noise). `light_scale`: one factor per light.
    void upload(const gpu_resources& r, const scene& s, const method& m, const render_options& o, int frame,
                const view_matrices& v, bool sss_shown, bool sss_passes, bool sss_noise,
                const std::vector<float>& light_scale);
    /// The next frame's motion vectors start from the camera of the frame uploaded last.
    void end_frame(const view_matrices& v) {
        prev_view_proj_ = v.view_proj;
        prev_jitter_ = v.jitter;
        has_previous_ = true;
    }

private:
    gpu::frame_block frame_{};
    std::vector<gpu::light_block> lights_;
    glm::mat4 prev_view_proj_{1.0f};
    glm::vec2 prev_jitter_{0.0f};
    bool has_previous_ = false;
};

}  // namespace emcv::demo
