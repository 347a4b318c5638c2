// SPDX-License-Identifier: MIT
// shaders/adaptive/samples.h — what decides an adaptive method's N at an SSS pixel, for the two programs that
// plan counts (the renderer defines the method's EMCV_ADAPTIVE_* from its row of the method table): each block of
// K x K pixels (EMCV_HISTORY_BLOCK; a pixel at K = 1) fetches last frame's history at its reprojected position
// (motion vectors; the texel there decides, its statistics resampled bilinearly over the texels of the same
// surface), keeps it only when the position is on screen and the surface is the same (material, depth, normal:
// emcv_history_reusable) and the texel is not poisoned, writes that state (or a fresh one) into this frame's
// history, and shares its per-sample variance with its tile, where it is pooled over its 3x3 neighbouring blocks
// of the same material (emcv_adaptive_tile_sigma2).
//   adaptive/samples.comp.glsl  budget mode: the samples pass before the burley pass (the frame's histogram and
//                               its solve need every pixel's variance before any pixel's N)
//   render/sss_burley.comp.glsl quality target: at the top of the method's burley program, which then samples
//                               and updates the history in the same dispatch (N needs only the pixel's tile)
#ifndef EMCV_ADAPTIVE_SAMPLES_H
#define EMCV_ADAPTIVE_SAMPLES_H

#include "adaptive/history_io.h"
#include "render/tiles.h"

layout(EMCV_LAYOUT_BINDING(EMCV_ADAPTIVE_TEX_HISTORY_PREV_A)) uniform sampler2D history_prev_a;
layout(EMCV_LAYOUT_BINDING(EMCV_ADAPTIVE_TEX_PREV_DEPTH)) uniform sampler2D prev_depth;
layout(EMCV_LAYOUT_BINDING(EMCV_ADAPTIVE_TEX_PREV_NORMAL)) uniform sampler2D prev_normal;
layout(EMCV_LAYOUT_BINDING(EMCV_ADAPTIVE_TEX_PREV_MATERIAL)) uniform usampler2D prev_material;

/// Whether last frame's pixel q shows the surface pixel p shows now (emcv_history_reusable; false off screen).
bool emcv_adaptive_same_surface(ivec2 q, uint material, float expected_prev_depth, vec3 normal) {
    if (!emcv_render_on_screen(q)) return false;
    return emcv_history_reusable(material, texelFetch(prev_material, q, 0).x, expected_prev_depth,
                                 abs(texelFetch(prev_depth, q, 0).x), normal, texelFetch(prev_normal, q, 0).xyz);
}

/// Last frame's history for block `blk` in s, or false (disoccluded, off-screen, first frame, poisoned). The
/// block's representative pixel p decides: the previous pixel q under p's previous position must show p's surface
/// (the surface test); the block's centre, moved as p moved, falls in last frame's texel `texel` of the block grid
/// (q's own texel at K = 1), which must decode and gives the count. Its means and comoments are then resampled at
/// that position: bilinear over the 2x2 texels around it that show this surface (tested at the pixel of each that
/// lies where q lies in its own) and hold a valid history of at least one frame. A point-sampled history would be
/// the surface point up to half a texel away, and under a moving camera that offset's signal difference would
/// enter the next frame's residual as noise every frame (docs/renderer.md, "Reprojection"). `resampled` is false
/// where the position is a texel centre (a still camera): then `a` and `b` hold the texel as stored, copied
/// without a second rounding (llvmpipe's float -> half store truncates; measured 2 ulps of drift against one
/// rounding).
bool emcv_adaptive_reproject(EmcvAdaptiveBlock blk, out vec4 a, out vec4 b, out EmcvAdaptiveState s,
                             out bool resampled) {
    a = vec4(0.0f);
    b = vec4(0.0f);
    s = emcv_adaptive_init();
    resampled = false;
    ivec2 p = blk.pixel;
    vec2 previous = emcv_render_previous_sample_position(p);
    ivec2 q = ivec2(floor(previous));
    float expected_prev_depth = emcv_render_previous_depth(p, emcv_render_depth(p));
    vec3 normal = texelFetch(gbuffer_normal, p, 0).xyz;
    if (!emcv_adaptive_same_surface(q, blk.code, expected_prev_depth, normal)) return false;
    // The block's centre (p + 0.5 - offset - 0.5 + K / 2 in pixels, offset = p - K texel) moved as p moved, in
    // the block grid's texel-centre coordinates: exactly `previous - 0.5` at K = 1.
    vec2 x = (previous - vec2(p - blk.texel * EMCV_HISTORY_BLOCK) - 0.5f) / float(EMCV_HISTORY_BLOCK);
    ivec2 texel = EMCV_HISTORY_BLOCK == 1 ? q : ivec2(floor(x + 0.5f));
    if (!emcv_adaptive_on_grid(texel)) return false;
    a = texelFetch(history_prev_a, texel, 0);
    b = emcv_adaptive_previous_b(texel);
    if (!emcv_adaptive_decode(a, b, s)) return false;
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
        EmcvAdaptiveState neighbour = s;  // `texel` itself: tested and decoded above
        if (r != texel && (!emcv_adaptive_on_grid(r) ||
                           !emcv_adaptive_same_surface(q + (r - texel) * EMCV_HISTORY_BLOCK, blk.code,
                                                       expected_prev_depth, normal) ||
                           !emcv_adaptive_decode(texelFetch(history_prev_a, r, 0), emcv_adaptive_previous_b(r), neighbour) ||
                           neighbour.count < 1u))
            continue;
        emcv_adaptive_blend_add(blend, w, neighbour);
        weight += w;
    }
    // `texel` is one of the four (the nearest, weight >= 1/4) and passed both tests: weight > 0.
    emcv_adaptive_blend_finish(s, blend, weight);
    resampled = true;
    return true;
}

// The blocks of this 8x8 tile: their per-sample variance (or code), material and effective frames, for the 3x3
// pooling below.
shared float tile_sigma2[EMCV_ADAPTIVE_TILE_BLOCKS];
shared uint tile_code[EMCV_ADAPTIVE_TILE_BLOCKS];
shared float tile_frames[EMCV_ADAPTIVE_TILE_BLOCKS];  // effective frames of each variance

/// A scattering block's per-sample variance (or code) from its history state s (no samples where every
/// scattering pixel's kernel is under a pixel, `sub_pixel`), and the effective frames it rests on: what
/// emcv_adaptive_own_sigma2 and emcv_adaptive_stored_sigma2 return.
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

/// Shares pixel p's material code (0: off screen or not scattering) and sub-pixel test with its tile, at its
/// local index: what emcv_adaptive_block reads once the caller's barrier() has followed.
void emcv_adaptive_share_pixel_of(ivec2 p) {
    uint code = emcv_adaptive_scattering_code(p);
    emcv_adaptive_share_pixel(gl_LocalInvocationIndex, code, code != 0u && emcv_adaptive_sub_pixel(p, code));
}

/// Block `blk`'s own per-sample variance (or its code) from its kept or fresh history, stored into this frame's
/// history, and the effective frames it rests on; a block none of whose pixels scatters has its history reset
/// (nothing stale is ever reprojected from there) and takes no samples.
float emcv_adaptive_own_sigma2(EmcvAdaptiveBlock blk, out float frames) {
    frames = 0.0f;
    if (blk.code == 0u) {
        // the burley pass skips these pixels before any count
        if (emcv_adaptive_on_grid(blk.texel)) emcv_adaptive_store(blk.texel, emcv_adaptive_init());
        return emcv_history_no_samples();
    }
    vec4 a, b;
    EmcvAdaptiveState s;
    bool resampled;
    if (emcv_adaptive_reproject(blk, a, b, s, resampled) && !resampled) {
        emcv_adaptive_store_raw(blk.texel, a, b);
    } else {
        emcv_adaptive_store(blk.texel, s);  // resampled, or a fresh state
    }
    return emcv_adaptive_state_sigma2(blk.sub_pixel, s, frames);
}

#if defined(EMCV_ADAPTIVE_PLAN_NEXT)
/// The next frame's own per-sample variance (or code) of block `blk` and its effective frames, read from the
/// history this frame's burley pass just stored at its texel, for a next frame that shows the same view (the
/// burley pass plans it, sss_burley.comp.glsl): there the next frame's samples pass would find each block's
/// history at its own texel (reprojection the identity, the surface the same), decode it and keep it as stored,
/// so this is what it would return, bit for bit, without the pass. A poisoned texel is reset as that pass resets
/// it. The block's code (0: no pixel on screen scatters, whose history was reset when the view last changed and
/// stays so) and sub-pixel test are what the burley pass found this frame, which the next frame's G-buffer repeats.
/// The invocation that stored the block's update reads it.
float emcv_adaptive_stored_sigma2(EmcvAdaptiveBlock blk, out float frames) {
    frames = 0.0f;
    if (blk.code == 0u) return emcv_history_no_samples();
    // this invocation's own stores: ordered after them
    EmcvAdaptiveState s;
    if (!emcv_adaptive_decode(imageLoad(history_a, blk.texel), emcv_adaptive_load_b(blk.texel), s))
        emcv_adaptive_store(blk.texel, s);
    return emcv_adaptive_state_sigma2(blk.sub_pixel, s, frames);
}
#endif

/// Stores block j's per-sample variance (or code), material code and effective frames in the tile's shared
/// arrays, for emcv_adaptive_pooled_sigma2 after the caller's barrier().
void emcv_adaptive_share_sigma2(uint j, float own, uint code, float frames) {
    tile_sigma2[j] = own;
    tile_frames[j] = frames;
    tile_code[j] = code;
}

/// The per-sample variance a frame's allocation reads at scattering block j (material `code`, its own variance
/// `own`), pooled over the block's 3x3 neighbours of the same material within its tile (emcv/port/history.h,
/// emcv_history_pool_sigma2): one block's estimate rests on about 1 / eta frames of a heavy-tailed residual, and
/// its neighbours see nearly the same noise. `pooled_frames`: the effective frames of the pooled estimate
/// (emcv_history_pool_frames), which budget mode's shrinkage reads. After emcv_adaptive_share_sigma2 and a barrier.
float emcv_adaptive_pooled_sigma2(uint j, float own, uint code, out float pooled_frames) {
    ivec2 l = emcv_adaptive_block_local(j);
    float sum = 0.0f;
    uint count = 0u;
    float inverse_frames = 0.0f;
    for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
            ivec2 q = l + ivec2(dx, dy);
            if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, ivec2(EMCV_ADAPTIVE_TILE_BLOCKS_SIDE)))) continue;
            uint i = uint(q.x + q.y * EMCV_ADAPTIVE_TILE_BLOCKS_SIDE);
            if (tile_code[i] != code) continue;
            emcv_history_pool_add_frames(inverse_frames, tile_sigma2[i], tile_frames[i]);
            emcv_history_pool_add(sum, count, tile_sigma2[i]);
        }
    }
    pooled_frames = emcv_history_pool_frames(count, inverse_frames);
    return emcv_history_pool_sigma2(own, sum, count);
}

/// Plans the tile's blocks from this frame's reprojected histories, every invocation calling it in uniform control
/// flow after emcv_adaptive_share_pixel_of (it holds barriers): each block's own variance (emcv_adaptive_own_sigma2,
/// whose store it makes) shared with the tile; afterwards emcv_adaptive_pooled_sigma2 may read the tile. Returns,
/// in the invocations that hold a block (emcv_adaptive_holds_block), that block, its own variance and frames.
void emcv_adaptive_tile_sigma2(ivec2 origin, out EmcvAdaptiveBlock blk, out float own, out float frames) {
    barrier();  // the tile's pixels are shared
    own = emcv_history_no_samples();
    frames = 0.0f;
    blk = emcv_adaptive_no_block();
    if (emcv_adaptive_holds_block()) {
        uint j = gl_LocalInvocationIndex;
        blk = emcv_adaptive_block(j, origin);
        own = emcv_adaptive_own_sigma2(blk, frames);
        emcv_adaptive_share_sigma2(j, own, blk.code, frames);
    }
    barrier();  // the tile's variances are readable
}

/// Writes what the burley pass takes at scattering block j (`blk`, own variance `own`), after
/// emcv_adaptive_share_sigma2: in budget mode the pooled variance, shrunk, into the samples image at the block's
/// texel and, weighted by its pixels, into the frame's histograms (emcv_budget_add) for the solve pass; built with
/// a quality target (tests), N. The samples pass runs it
/// for this frame, the burley pass that plans the next frame for that one (sss_burley.comp.glsl).
void emcv_adaptive_allocate(uint j, EmcvAdaptiveBlock blk, float own) {
    float frames;
    float sigma2 = emcv_adaptive_pooled_sigma2(j, own, blk.code, frames);
    if (emcv_history_budget_mode()) {
        // The burley pass turns sigma into N once lambda is solved from this frame's histogram: the image
        // carries the variance (or its code) until then.
        // Shrunk towards the previous frame's mean by how much the pooled estimate knows (emcv/port/history.h,
        // emcv_history_shrink_sigma2); the estimate before shrinkage feeds the next frame's prior.
        emcv_budget_add_raw(sigma2, frames, blk.pixels);
        sigma2 = emcv_history_shrink_sigma2(sigma2, frames, budget.mean_sigma2, budget.between_variance,
                                            emcv_history_spend_relative_variance());
        emcv_budget_add(sigma2, blk.pixels);
        imageStore(samples_image, blk.texel, uvec4(floatBitsToUint(sigma2)));
    } else {
        imageStore(samples_image, blk.texel, uvec4(uint(emcv_history_count_target(sigma2))));
    }
}

#endif  // #ifndef EMCV_ADAPTIVE_SAMPLES_H
