// SPDX-License-Identifier: MIT
// Burley screen-space SSS over the SSS tiles (indirect dispatch): N samples per scattering pixel drawn with the
// widest channel, weighted per channel, sum(w L) / sum(w) (docs/frame.md). Every formula is from
// include/emcv/port/sss.h. N is the frame's fixed count (burley-N, reference) or, for the adaptive methods,
// the pixel's own (below).
#version 450 core

#include "emcv/port/sss.h"
#include "render/gbuffer_read.h"
#include "render/tiles.h"
#include "emcv/port/bindings.h"
#include "emcv/port/history.h"
#include "adaptive/bindings.h"

layout(local_size_x = EMCV_RENDER_TILE_SIZE, local_size_y = EMCV_RENDER_TILE_SIZE) in;

layout(rgba16f, EMCV_LAYOUT_IMAGE_BINDING(EMCV_RENDER_IMG_SSS_OUT)) writeonly uniform image2D out_scattered;
layout(r32ui, EMCV_LAYOUT_IMAGE_BINDING(EMCV_RENDER_IMG_COUNT)) writeonly uniform uimage2D out_count;
// Adaptive methods (frame.sss.y = 1): N per pixel from the adaptive-samples pass (shaders/adaptive); in budget
// mode that pass leaves the per-sample variance and N = clamp(lambda sigma) is taken here, with the lambda that
// sss-adaptive-budget solved from the same frame's variances.
layout(r32ui, EMCV_LAYOUT_IMAGE_BINDING(EMCV_ADAPTIVE_IMG_SAMPLES)) readonly uniform uimage2D adaptive_samples;

// Budget mode's scale lambda: the first member of the budget block (emcv/port/budget.h, EmcvBudgetBlock) that
// sss-adaptive-budget solved this frame. Declared alone, 4 bytes: without a budget the slot holds another buffer
// (the separable kernels', never read then), and a block larger than the bound buffer is undefined behaviour even
// unread (llvmpipe's LeakSanitizer run crashed at exit with the whole block declared here).
layout(std430, EMCV_LAYOUT_BINDING(EMCV_ADAPTIVE_BUDGET)) readonly buffer BudgetScale {
    float lambda;
} budget_scale;

shared uint tile_sample_sum;
shared uint tile_sample_max;

/// The adaptive methods' N at p (see above).
uint adaptive_count(ivec2 p) {
    uint stored = imageLoad(adaptive_samples, p).x;
    if (!emcv_history_budget_mode()) return stored;
    float u = emcv_budget_u(uint(p.x), uint(p.y), frame.counters.x, frame.counters.y);
    return uint(emcv_history_count_spend(uintBitsToFloat(stored), budget_scale.lambda, u));
}

/// Scatters pixel p; returns the samples it took (0 off screen and for non-scattering pixels).
uint scatter(ivec2 p) {
    if (!emcv_render_on_screen(p)) return 0u;
    uint code = emcv_render_material_code(p);
    if (!emcv_render_scatters(code)) return 0u;

    vec3 d = emcv_sss_shape_distance(materials[code - 1u].mean_free_path.xyz, texelFetch(gbuffer_albedo, p, 0).xyz);
    float d_sample = emcv_sss_widest(d);
    float z = emcv_render_depth(p);
    float mm_per_unit = frame.camera_position.w;
    float pixels_per_mm = emcv_sss_pixels_per_mm(frame.projection.x, frame.viewport.x, z, mm_per_unit);
    bool approximate = (frame.counters.w & EMCV_RENDER_FLAG_APPROXIMATE_CDF) != 0u;
    vec2 rotation = emcv_sss_rotation(uint(p.x), uint(p.y), frame.counters.x, frame.counters.y);
    uint n = frame.sss.y != 0 ? adaptive_count(p) : uint(frame.sss.x);

    vec3 sum_wl = vec3(0.0f);
    vec3 sum_w = vec3(0.0f);
    for (uint i = 0u; i < n; ++i) {
        vec2 u = emcv_sss_sample_uv(i, rotation);
        float r = emcv_sss_sample_radius(u.x, d_sample, approximate);
        vec2 offset = emcv_sss_offset_pixels(r, u.y, pixels_per_mm);
        ivec2 q = ivec2(floor(vec2(p) + 0.5f + offset));
        // Off-screen and non-scattering samples get weight 0 (docs/frame.md).
        if (!emcv_render_on_screen(q) || !emcv_render_scatters(emcv_render_material_code(q))) continue;
        float dz_mm = (emcv_render_depth(q) - z) * mm_per_unit;
        vec3 w = emcv_sss_weight(r, emcv_sss_depth_aware_radius(r, dz_mm), d, d_sample);
        sum_w += w;
        sum_wl += w * texelFetch(lit_diffuse, q, 0).xyz;
    }
    vec3 centre = texelFetch(lit_diffuse, p, 0).xyz;
    // A channel with no accepted sample keeps the unscattered value (the pixel's own irradiance).
    vec3 scattered = mix(centre, sum_wl / max(sum_w, vec3(1e-30f)), greaterThan(sum_w, vec3(0.0f)));
    imageStore(out_scattered, p, vec4(scattered, 1.0f));
    imageStore(out_count, p, uvec4(n));
    return n;
}

void main() {
    if (gl_LocalInvocationIndex == 0u) {
        tile_sample_sum = 0u;
        tile_sample_max = 0u;
    }
    barrier();
    uint n = scatter(emcv_render_tile_pixel());
    // Sample statistics reduced per tile in shared memory, then one global atomic per tile (not per pixel).
    atomicAdd(tile_sample_sum, n);
    atomicMax(tile_sample_max, n);
    barrier();
    if (gl_LocalInvocationIndex == 0u) {
        atomicAdd(stats.sample_sum, tile_sample_sum);
        atomicMax(stats.sample_max, tile_sample_max);
    }
}
