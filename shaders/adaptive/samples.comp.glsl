// SPDX-License-Identifier: MIT
// shaders/adaptive/samples.comp.glsl — the adaptive-samples pass of every adaptive method (the renderer defines the
// method's EMCV_ADAPTIVE_* from its row of the method table): over the SSS tiles, each SSS pixel fetches last
// frame's history at its reprojected position (motion vectors; the texel there decides, its statistics resampled
// bilinearly over the texels of the same surface), keeps it only when the position is on screen and the surface is
// the same (material, depth, normal: emcv_history_reusable) and the texel is not poisoned, writes that state (or a
// fresh one) into this frame's history, and writes what the burley pass takes (EMCV_ADAPTIVE_IMG_SAMPLES) from the
// history's per-sample variance: N under a quality target; under a budget the variance shrunk towards the previous
// frame's mean (emcv_history_shrink_sigma2), as its bits, added to the histogram from which the pass's last
// workgroup solves lambda before the burley pass computes N (emcv/port/budget.h, adaptive/budget_block.h): one
// pass, no solve dispatch of its own.
#version 450 core

#define EMCV_BUDGET_GROUP_THREADS (EMCV_RENDER_TILE_SIZE * EMCV_RENDER_TILE_SIZE)
#include "adaptive/history_io.h"
#include "render/tiles.h"

layout(local_size_x = EMCV_RENDER_TILE_SIZE, local_size_y = EMCV_RENDER_TILE_SIZE) in;

layout(EMCV_LAYOUT_BINDING(EMCV_ADAPTIVE_TEX_HISTORY_PREV_A)) uniform sampler2D history_prev_a;
layout(EMCV_LAYOUT_BINDING(EMCV_ADAPTIVE_TEX_HISTORY_PREV_B)) uniform sampler2D history_prev_b;
layout(EMCV_LAYOUT_BINDING(EMCV_ADAPTIVE_TEX_PREV_DEPTH)) uniform sampler2D prev_depth;
layout(EMCV_LAYOUT_BINDING(EMCV_ADAPTIVE_TEX_PREV_NORMAL)) uniform sampler2D prev_normal;
layout(EMCV_LAYOUT_BINDING(EMCV_ADAPTIVE_TEX_PREV_MATERIAL)) uniform usampler2D prev_material;

/// Last frame's second history texel at q: cv's means; spvg and cv-notex keep one texel and fetch nothing here.
vec4 emcv_adaptive_previous_b(ivec2 q) {
#if defined(EMCV_ADAPTIVE_CV)
    return texelFetch(history_prev_b, q, 0);
#else
    return vec4(0.0f);
#endif
}

/// Whether last frame's texel q shows the surface pixel p shows now (emcv_history_reusable; false off screen).
bool emcv_adaptive_same_surface(ivec2 q, uint material, float expected_prev_depth, vec3 normal) {
    if (!emcv_render_on_screen(q)) return false;
    return emcv_history_reusable(material, texelFetch(prev_material, q, 0).x, expected_prev_depth,
                                 abs(texelFetch(prev_depth, q, 0).x), normal, texelFetch(prev_normal, q, 0).xyz);
}

/// Last frame's history for pixel p in s, or false (disoccluded, off-screen, first frame, poisoned). The texel
/// under p's previous position decides (the surface test, a poisoned texel) and gives the count. Its means and
/// comoments are then resampled at the previous position: bilinear over the 2x2 texels around it that show this
/// surface and hold a valid history of at least one frame. A point-sampled history would be the surface point up to
/// half a pixel away, and under a moving camera that offset's signal difference would enter the next frame's
/// residual as noise every frame (docs/renderer.md, "Reprojection"). `resampled` is false where the position is a
/// texel centre (a still camera): then `a` and `b` hold the texel as stored, copied without a second rounding
/// (llvmpipe's float -> half store truncates; measured 2 ulps of drift against one rounding).
bool emcv_adaptive_reproject(ivec2 p, uint material, out vec4 a, out vec4 b, out EmcvAdaptiveState s,
                             out bool resampled) {
    a = vec4(0.0f);
    b = vec4(0.0f);
    s = emcv_adaptive_init();
    resampled = false;
    vec2 previous = emcv_render_previous_sample_position(p);
    ivec2 q = ivec2(floor(previous));
    float expected_prev_depth = emcv_render_previous_depth(p, emcv_render_depth(p));
    vec3 normal = texelFetch(gbuffer_normal, p, 0).xyz;
    if (!emcv_adaptive_same_surface(q, material, expected_prev_depth, normal)) return false;
    a = texelFetch(history_prev_a, q, 0);
    b = emcv_adaptive_previous_b(q);
    if (!emcv_adaptive_decode(a, b, s)) return false;
    vec2 x = previous - 0.5f;  // in texel-centre coordinates
    ivec2 base = ivec2(floor(x));
    vec2 t = x - vec2(base);
    if (t == vec2(0.0f) || s.count < 1u) return true;
    EmcvAdaptiveState blend = emcv_adaptive_init();
    float weight = 0.0f;
    for (int k = 0; k < 4; ++k) {
        ivec2 o = ivec2(k & 1, k >> 1);
        float w = (o.x == 1 ? t.x : 1.0f - t.x) * (o.y == 1 ? t.y : 1.0f - t.y);
        ivec2 r = base + o;
        if (w == 0.0f) continue;
        EmcvAdaptiveState neighbour = s;  // q itself: tested and decoded above
        if (r != q && (!emcv_adaptive_same_surface(r, material, expected_prev_depth, normal) ||
                       !emcv_adaptive_decode(texelFetch(history_prev_a, r, 0), emcv_adaptive_previous_b(r), neighbour) ||
                       neighbour.count < 1u))
            continue;
        emcv_adaptive_blend_add(blend, w, neighbour);
        weight += w;
    }
    // q is one of the four (the nearest, weight >= 1/4) and passed both tests: weight > 0.
    emcv_adaptive_blend_finish(s, blend, weight);
    resampled = true;
    return true;
}

// The pixels of this 8x8 tile: their per-sample variance (or code) and material, for the 3x3 pooling below.
shared float tile_sigma2[EMCV_RENDER_TILE_SIZE * EMCV_RENDER_TILE_SIZE];
shared uint tile_code[EMCV_RENDER_TILE_SIZE * EMCV_RENDER_TILE_SIZE];
shared float tile_frames[EMCV_RENDER_TILE_SIZE * EMCV_RENDER_TILE_SIZE];  // effective frames of each variance

/// This pixel's own per-sample variance (or its code) from its kept or fresh history, and the effective frames
/// it rests on; 0 material for pixels that do not scatter (and their history reset: nothing stale is ever
/// reprojected from there).
float own_sigma2(ivec2 p, out uint code, out float frames) {
    code = 0u;
    frames = 0.0f;
    if (!emcv_render_on_screen(p)) return emcv_history_no_samples();
    code = emcv_render_material_code(p);
    if (!emcv_render_scatters(code)) {
        emcv_adaptive_store(p, emcv_adaptive_init());
        imageStore(samples_image, p, uvec4(0u));  // the burley pass skips non-scattering pixels before reading
        code = 0u;
        return emcv_history_no_samples();
    }
    vec4 a, b;
    EmcvAdaptiveState s;
    bool resampled;
    if (emcv_adaptive_reproject(p, code, a, b, s, resampled) && !resampled) {
        emcv_adaptive_store_raw(p, a, b);
    } else {
        emcv_adaptive_store(p, s);  // resampled, or a fresh state
    }
    frames = emcv_adaptive_effective_frames(s);
    return emcv_adaptive_sub_pixel(p, code) ? emcv_history_no_samples() : emcv_adaptive_sigma2(s);
}

/// Writes what the burley pass takes at scattering pixel p (see the top of the file).
void allocate(ivec2 p, float own, uint code) {
    // The per-sample variance a frame's allocation reads is pooled over the pixel's 3x3 neighbours of the same
    // material within its tile (emcv/port/history.h, emcv_history_pool_sigma2): one pixel's estimate rests on
    // about 1 / eta frames of a heavy-tailed residual, and its neighbours see nearly the same noise.
    float sum = 0.0f;
    uint count = 0u;
    float inverse_frames = 0.0f;
    ivec2 l = ivec2(gl_LocalInvocationID.xy);
    for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
            ivec2 q = l + ivec2(dx, dy);
            if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, ivec2(EMCV_RENDER_TILE_SIZE)))) continue;
            uint i = uint(q.x + q.y * EMCV_RENDER_TILE_SIZE);
            if (tile_code[i] != code) continue;
            emcv_history_pool_add_frames(inverse_frames, tile_sigma2[i], tile_frames[i]);
            emcv_history_pool_add(sum, count, tile_sigma2[i]);
        }
    }
    float sigma2 = emcv_history_pool_sigma2(own, sum, count);
    if (emcv_history_budget_mode()) {
        // The burley pass turns sigma into N once lambda is solved from this frame's histogram: the image
        // carries the variance (or its code) until then.
        // Shrunk towards the previous frame's mean by how much the pooled estimate knows (emcv/port/history.h,
        // emcv_history_shrink_sigma2); the estimate before shrinkage feeds the next frame's prior.
        float frames = emcv_history_pool_frames(count, inverse_frames);
        emcv_budget_add_raw(sigma2, frames);
        sigma2 = emcv_history_shrink_sigma2(sigma2, frames, budget.mean_sigma2, budget.between_variance,
                                            emcv_history_spend_relative_variance());
        emcv_budget_add(sigma2);
        imageStore(samples_image, p, uvec4(floatBitsToUint(sigma2)));
    } else {
        imageStore(samples_image, p, uvec4(uint(emcv_history_count_target(sigma2))));
    }
}

void main() {
    uint here = gl_LocalInvocationIndex;
    if (emcv_history_budget_mode()) emcv_budget_group_clear(here);  // ordered before any add by the barrier below
    ivec2 p = emcv_render_tile_pixel();
    uint code;
    float frames;
    float own = own_sigma2(p, code, frames);
    tile_sigma2[here] = own;
    tile_frames[here] = frames;
    tile_code[here] = code;
    barrier();
    if (code != 0u) allocate(p, own, code);
    // Budget mode: every workgroup (those past the tile count too) reports; the last one solves lambda.
    if (emcv_history_budget_mode()) emcv_budget_finish_group(here, gl_NumWorkGroups.x * gl_NumWorkGroups.y);
}
