// SPDX-License-Identifier: MIT
#include "frame_constants.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "pass_list.hpp"
#include "render/bindings.h"

namespace emcv::demo {

void frame_constants::upload(const gpu_resources& r, const scene& s, const method& m, const render_options& o,
                             int frame, const view_matrices& v, bool sss_shown, bool sss_passes, bool sss_noise,
                             const std::vector<float>& light_scale) {
    const float width = float(r.width), height = float(r.height);
    frame_.view = v.view;
    frame_.proj = v.proj;
    frame_.view_proj = v.view_proj;
    frame_.prev_view_proj = has_previous_ ? prev_view_proj_ : v.view_proj;
    const glm::vec2 prev_jitter = has_previous_ ? prev_jitter_ : v.jitter;
    frame_.jitter = glm::vec4(v.jitter, prev_jitter);
    frame_.inv_view = glm::inverse(v.view);
    frame_.camera_position = glm::vec4(v.position, s.mm_per_unit);
    frame_.viewport = glm::vec4(width, height, 1.0f / width, 1.0f / height);
    frame_.projection = glm::vec4(v.proj[0][0], v.proj[1][1], s.view.near_plane, s.view.far_plane);
    frame_.background = glm::vec4(s.background, o.exposure);
    frame_.ambient = glm::vec4(s.ambient, o.tonemap == tonemap_operator::aces ? 0.0f : 1.0f);
    std::uint32_t flags = 0;
    if (sss_shown) flags |= EMCV_RENDER_FLAG_SSS_RAN;
    if (o.approximate_inverse_cdf) flags |= EMCV_RENDER_FLAG_APPROXIMATE_CDF;
    if (sss_passes) flags |= EMCV_RENDER_FLAG_SSS_TILES;
    if (v.jittered) flags |= EMCV_RENDER_FLAG_JITTER;
    if (sss_noise) flags |= EMCV_RENDER_FLAG_SSS_NOISE;
    frame_.counters = glm::uvec4(static_cast<std::uint32_t>(frame), o.seed, static_cast<std::uint32_t>(s.lights.size()), flags);
    // The burley pass takes the method's fixed count; an adaptive method's own burley program (built with its
    // EMCV_ADAPTIVE_* define, adaptive::history) takes N per pixel from the adaptive-samples pass instead.
    const method_row& row = row_of(m);
    const int fixed = row.passes() == sss_passes::burley ? m.samples : 0;
    frame_.sss = glm::ivec4(fixed, 0, static_cast<int>(s.materials.size()), 0);
    glNamedBufferSubData(r.frame_ubo.id(), 0, sizeof frame_, &frame_);

    for (std::size_t i = 0; i < s.lights.size(); ++i) {
        const light& l = s.lights[i];
        gpu::light_block& b = lights_[i];
        const float kind = l.type == light::kind::directional ? float(EMCV_RENDER_LIGHT_DIRECTIONAL)
                           : l.type == light::kind::point     ? float(EMCV_RENDER_LIGHT_POINT)
                                                              : float(EMCV_RENDER_LIGHT_SPOT);
        b.radiance = glm::vec4(l.color * l.intensity.at(frame) * light_scale[i], kind);
        const auto layer = std::find(r.shadow_lights.begin(), r.shadow_lights.end(), i);
        // A dark light's layer was not rendered this frame (pass list): never read it.
        const float shadow_layer = layer == r.shadow_lights.end() || !light_shines(l, frame)
                                       ? -1.0f
                                       : float(layer - r.shadow_lights.begin());
        b.position = glm::vec4(l.position, shadow_layer);
        b.direction = glm::vec4(glm::normalize(l.direction), std::cos(glm::radians(l.outer_cone_degrees)));
        const float texel = shadow_texel_world(l, r.world_bounds, shadow_resolution);
        b.cone = glm::vec4(std::cos(glm::radians(l.inner_cone_degrees)), 1.5f * texel, 5e-4f, 0.0f);
        b.shadow_view_proj = shadow_layer >= 0.0f ? shadow_view_proj(l, r.world_bounds) : glm::mat4(1.0f);
    }
    if (!lights_.empty()) {
        glNamedBufferSubData(r.lights_ssbo.id(), 0, static_cast<GLsizeiptr>(lights_.size() * sizeof(gpu::light_block)),
                             lights_.data());
    }
}

}  // namespace emcv::demo
