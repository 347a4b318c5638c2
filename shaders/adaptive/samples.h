// SPDX-License-Identifier: MIT
// shaders/adaptive/samples.h — what decides an adaptive method's N at an SSS pixel, for the two programs that
// plan counts (the renderer defines the method's EMCV_ADAPTIVE_* from its row of the method table): each SSS pixel
// fetches last frame's history at its reprojected position (motion vectors; the texel there decides, its
// statistics resampled bilinearly over the texels of the same surface), keeps it only when the position is on
// screen and the surface is the same (material, depth, normal: emcv_history_reusable) and the texel is not
// poisoned, writes that state (or a fresh one) into this frame's history, and shares its per-sample variance with
// its tile, where it is pooled over its 3x3 neighbours of the same material (emcv_adaptive_tile_sigma2).
//   adaptive/samples.comp.glsl  budget mode: the samples pass before the burley pass (the frame's histogram and
//                               its solve need every pixel's variance before any pixel's N)
//   render/sss_burley.comp.glsl quality target: at the top of the method's burley program, which then samples
//                               and updates the history in the same dispatch (N needs only the pixel's tile)
#ifndef EMCV_ADAPTIVE_SAMPLES_H
#define EMCV_ADAPTIVE_SAMPLES_H

#include "adaptive/history_io.h"
#include "render/tiles.h"

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

/// A scattering pixel's per-sample variance (or code) from its history state s (no samples where its kernel is
/// under a pixel, `sub_pixel`), and the effective frames it rests on: what emcv_adaptive_own_sigma2 and
/// emcv_adaptive_stored_sigma2 return.
float emcv_adaptive_state_sigma2(bool sub_pixel, EmcvAdaptiveState s, out float frames) {
    frames = emcv_adaptive_effective_frames(s);
    return sub_pixel ? emcv_history_no_samples() : emcv_adaptive_sigma2(s);
}

/// p's material code where p is on screen and scatters, else 0.
uint emcv_adaptive_scattering_code(ivec2 p) {
    if (!emcv_render_on_screen(p)) return 0u;
    uint code = emcv_render_material_code(p);
    return emcv_render_scatters(code) ? code : 0u;
}

/// This pixel's own per-sample variance (or its code) from its kept or fresh history, and the effective frames
/// it rests on; 0 material for pixels that do not scatter (and their history reset: nothing stale is ever
/// reprojected from there).
float emcv_adaptive_own_sigma2(ivec2 p, out uint code, out float frames) {
    code = emcv_adaptive_scattering_code(p);
    frames = 0.0f;
    if (code == 0u) {
        // the burley pass skips these pixels before any count
        if (emcv_render_on_screen(p)) emcv_adaptive_store(p, emcv_adaptive_init());
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
    return emcv_adaptive_state_sigma2(emcv_adaptive_sub_pixel(p, code), s, frames);
}

#if defined(EMCV_ADAPTIVE_PLAN_NEXT)
/// The next frame's own per-sample variance (or code) at p and its effective frames, read from the history this
/// frame's burley pass just stored at p, for a next frame that shows the same view (the burley pass plans it,
/// sss_burley.comp.glsl): there the next frame's samples pass would find each pixel's history at its own texel
/// (reprojection the identity, the surface the same), decode it and keep it as stored, so this is what it would
/// return, bit for bit, without the pass. A poisoned texel is reset as that pass resets it. `code` (0: off screen
/// or not scattering, whose history was reset when the view last changed and stays so) and `sub_pixel` are what
/// the burley pass found at p this frame, which the next frame's G-buffer repeats.
float emcv_adaptive_stored_sigma2(ivec2 p, uint code, bool sub_pixel, out float frames) {
    frames = 0.0f;
    if (code == 0u) return emcv_history_no_samples();
#if defined(EMCV_ADAPTIVE_CV)
    vec4 b = imageLoad(history_b, p);  // this invocation's own store: ordered after it
#else
    vec4 b = vec4(0.0f);
#endif
    EmcvAdaptiveState s;
    if (!emcv_adaptive_decode(imageLoad(history_a, p), b, s)) emcv_adaptive_store(p, s);
    return emcv_adaptive_state_sigma2(sub_pixel, s, frames);
}
#endif

/// Stores a pixel's per-sample variance (or code), material code and effective frames in the tile's shared
/// arrays at the pixel's local index `here`, for emcv_adaptive_pooled_sigma2. Every invocation calls it, in
/// uniform control flow: it ends on the barrier after which the tile's variances are readable.
void emcv_adaptive_share_sigma2(uint here, float own, uint code, float frames) {
    tile_sigma2[here] = own;
    tile_frames[here] = frames;
    tile_code[here] = code;
    barrier();
}

/// Shares pixel p's own per-sample variance with its tile (emcv_adaptive_own_sigma2, whose history store it
/// makes) and returns it, with p's material code (0: nothing to plan) and the effective frames it rests on.
/// Every invocation of the workgroup calls it, in uniform control flow: it ends on the barrier after which the
/// tile's variances are readable (emcv_adaptive_pooled_sigma2).
float emcv_adaptive_tile_sigma2(ivec2 p, out uint code, out float frames) {
    float own = emcv_adaptive_own_sigma2(p, code, frames);
    emcv_adaptive_share_sigma2(gl_LocalInvocationIndex, own, code, frames);
    return own;
}

/// The per-sample variance a frame's allocation reads at scattering pixel p (material `code`, its own variance
/// `own`), pooled over the pixel's 3x3 neighbours of the same material within its tile (emcv/port/history.h,
/// emcv_history_pool_sigma2): one pixel's estimate rests on about 1 / eta frames of a heavy-tailed residual, and
/// its neighbours see nearly the same noise. `l`: the pixel's position within its tile. `pooled_frames`: the
/// effective frames of the pooled estimate (emcv_history_pool_frames), which budget mode's shrinkage reads. After
/// emcv_adaptive_share_sigma2.
float emcv_adaptive_pooled_sigma2(ivec2 l, float own, uint code, out float pooled_frames) {
    float sum = 0.0f;
    uint count = 0u;
    float inverse_frames = 0.0f;
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
    pooled_frames = emcv_history_pool_frames(count, inverse_frames);
    return emcv_history_pool_sigma2(own, sum, count);
}

#if defined(EMCV_BUDGET_GROUP_THREADS)
/// Writes what the burley pass takes at scattering pixel p (tile position l, own variance `own`, material
/// `code`), after emcv_adaptive_share_sigma2: in budget mode the pooled variance, shrunk, into the samples image
/// and the workgroup's histograms, from which the last workgroup solves lambda (emcv_budget_finish_group); built
/// with a quality target (tests), N. The samples pass runs it for this frame, the burley pass that plans the next
/// frame for that one (sss_burley.comp.glsl).
void emcv_adaptive_allocate(ivec2 p, ivec2 l, float own, uint code) {
    float frames;
    float sigma2 = emcv_adaptive_pooled_sigma2(l, own, code, frames);
    if (emcv_history_budget_mode()) {
        // The burley pass turns sigma into N once lambda is solved from this frame's histogram: the image
        // carries the variance (or its code) until then.
        // Shrunk towards the previous frame's mean by how much the pooled estimate knows (emcv/port/history.h,
        // emcv_history_shrink_sigma2); the estimate before shrinkage feeds the next frame's prior.
        emcv_budget_add_raw(sigma2, frames);
        sigma2 = emcv_history_shrink_sigma2(sigma2, frames, budget.mean_sigma2, budget.between_variance,
                                            emcv_history_spend_relative_variance());
        emcv_budget_add(sigma2);
        imageStore(samples_image, p, uvec4(floatBitsToUint(sigma2)));
    } else {
        imageStore(samples_image, p, uvec4(uint(emcv_history_count_target(sigma2))));
    }
}
#endif

#endif  // #ifndef EMCV_ADAPTIVE_SAMPLES_H
