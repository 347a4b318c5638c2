// SPDX-License-Identifier: MIT
// emcv_adaptive_plan.glsl — installed GPU module (share/emcv/module): what decides an adaptive method's N at its
// pixels, one 8x8 tile per workgroup (emcv_adaptive_history.glsl's blocks): each block of K x K pixels
// (EMCV_HISTORY_BLOCK; a pixel at K = 1) fetches last frame's history at its reprojected position (the texel there
// decides, its statistics resampled bilinearly over the texels of the same surface), keeps it only when the
// position is on screen and the surface is the same (material, depth, normal: emcv_history_reusable) and the
// texel is not poisoned, writes that state (or a fresh one) into this frame's history, and shares its per-sample
// variance with its tile, where it is pooled over its 3x3 neighbouring blocks of the same material
// (emcv_adaptive_tile_sigma2). emcv_adaptive_allocate then writes what the sampling pass takes: in budget mode
// the shrunk variance, added to the frame's histogram (emcv_adaptive_budget.glsl); under a quality target, N.
// The renderer runs it in budget mode as its own pass before the sampling pass (adaptive/samples.comp.glsl: the
// histogram and its solve need every pixel's variance before any pixel's N), and under a quality target at the
// top of the sampling pass (render/sss_burley.comp.glsl).
//
// Include after emcv_adaptive_history.glsl and emcv_adaptive_budget.glsl. No resources: besides those modules'
// functions, the application defines the emcv_app_* functions declared below over its own G-buffer.
#ifndef EMCV_ADAPTIVE_PLAN_H
#define EMCV_ADAPTIVE_PLAN_H

#include "module/emcv_adaptive_history.glsl"
#include "module/emcv_adaptive_budget.glsl"

// What the application supplies (prototypes).
/// Where pixel p's sample position was in the previous frame, in pixels (motion vectors; a pixel's centre is
/// p + 0.5).
vec2 emcv_app_previous_position(ivec2 p);
/// The view depth the surface seen at p had in the previous frame (under the previous camera).
float emcv_app_expected_previous_depth(ivec2 p);
/// This frame's world normal at p.
vec3 emcv_app_normal(ivec2 p);
/// Last frame's material index + 1 (0: background), linear view depth and world normal at pixel q (on screen).
uint emcv_app_previous_material(ivec2 q);
float emcv_app_previous_depth(ivec2 q);
vec3 emcv_app_previous_normal(ivec2 q);
/// Stores what the sampling pass reads at a block's texel: in budget mode the shrunk per-sample variance as its
/// float bits (or a code, emcv/port/history.h), under a quality target N.
void emcv_app_store_plan(ivec2 texel, uint value);
/// Loads what emcv_app_store_plan stored at a texel (budget mode: the sampling pass reads it).
uint emcv_app_load_plan(ivec2 texel);

/// Whether last frame's pixel q shows the surface pixel p shows now (emcv_history_reusable; false off screen).
bool emcv_adaptive_same_surface(ivec2 q, uint material, float expected_prev_depth, vec3 normal) {
    if (!emcv_adaptive_on_screen(q)) return false;
    return emcv_history_reusable(material, emcv_app_previous_material(q), expected_prev_depth,
                                 emcv_app_previous_depth(q), normal, emcv_app_previous_normal(q));
}

/// Last frame's history for block `blk` in s, or false (disoccluded, off-screen, first frame, poisoned). The
/// block's representative pixel p decides: the previous pixel q under p's previous position must show p's surface
/// (the surface test); the block's centre, moved as p moved, falls in last frame's texel `texel` of the block grid
/// (q's own texel at K = 1), which must decode and gives the count. Its means and comoments are then resampled at
/// that position: bilinear over the 2x2 texels around it that show this surface (tested at the pixel of each that
/// lies where q lies in its own) and hold a valid history of at least one frame. A point-sampled history would be
/// the surface point up to half a texel away, and under a moving camera that offset's signal difference would
/// enter the next frame's residual as noise every frame (docs/renderer.md). `resampled` is false
/// where the position is a texel centre (a still camera): then `a` and `b` hold the texel as stored, copied
/// without a second rounding (llvmpipe's float -> half store truncates; measured 2 ulps of drift against one
/// rounding).
bool emcv_adaptive_reproject(EmcvAdaptiveBlock blk, out vec4 a, out vec4 b, out EmcvAdaptiveState s,
                             out bool resampled) {
    a = vec4(0.0f, 0.0f, 0.0f, 0.0f);
    b = vec4(0.0f, 0.0f, 0.0f, 0.0f);
    s = emcv_adaptive_init();
    resampled = false;
    ivec2 p = blk.pixel;
    vec2 previous = emcv_app_previous_position(p);
    ivec2 q = ivec2(floor(previous));
    float expected_prev_depth = emcv_app_expected_previous_depth(p);
    vec3 normal = emcv_app_normal(p);
    if (!emcv_adaptive_same_surface(q, blk.code, expected_prev_depth, normal)) return false;
    // The block's centre (p + 0.5 - offset - 0.5 + K / 2 in pixels, offset = p - K texel) moved as p moved, in
    // the block grid's texel-centre coordinates: exactly `previous - 0.5` at K = 1.
    vec2 x = (previous - vec2(p - blk.texel * EMCV_HISTORY_BLOCK) - 0.5f) / float(EMCV_HISTORY_BLOCK);
    ivec2 texel = EMCV_HISTORY_BLOCK == 1 ? q : ivec2(floor(x + 0.5f));
    if (!emcv_adaptive_on_grid(texel)) return false;
    a = emcv_app_history_previous_a(texel);
    b = emcv_adaptive_previous_b(texel);
    if (!emcv_adaptive_decode(a, b, s)) return false;
    ivec2 base = ivec2(floor(x));
    vec2 t = x - vec2(base);
    if (all(equal(t, vec2(0.0f, 0.0f))) || s.count < 1u) return true;
    EmcvAdaptiveState blend = emcv_adaptive_init();
    float weight = 0.0f;
    for (int k = 0; k < 4; ++k) {
        ivec2 o = ivec2(k & 1, k >> 1);
        float w = (o.x == 1 ? t.x : 1.0f - t.x) * (o.y == 1 ? t.y : 1.0f - t.y);
        ivec2 r = base + o;
        if (w == 0.0f) continue;
        EmcvAdaptiveState neighbour = s;  // `texel` itself: tested and decoded above
        if (any(notEqual(r, texel)) &&
            (!emcv_adaptive_on_grid(r) ||
             !emcv_adaptive_same_surface(q + (r - texel) * EMCV_HISTORY_BLOCK, blk.code, expected_prev_depth, normal) ||
             !emcv_adaptive_decode(emcv_app_history_previous_a(r), emcv_adaptive_previous_b(r), neighbour) ||
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
/// The invocation that stored the block's update reads it: from its registers where the layout's texels read back
/// bit for bit (emcv_adaptive_as_stored; 24 B a block fewer), else from the texels.
float emcv_adaptive_stored_sigma2(EmcvAdaptiveBlock blk, out float frames) {
    frames = 0.0f;
    if (blk.code == 0u) return emcv_history_no_samples();
    EmcvAdaptiveState s;
    bool decoded;
#if EMCV_ADAPTIVE_HISTORY_EXACT && defined(EMCV_ADAPTIVE_TILE_UPDATE)
    if (emcv_adaptive_updated_known) {
        s = emcv_adaptive_updated_state;
        decoded = emcv_adaptive_as_stored(s);
    } else
#endif
    {
        // this invocation's own stores: ordered after them
        decoded = emcv_adaptive_decode(emcv_app_history_load_a(blk.texel), emcv_adaptive_load_b(blk.texel), s);
    }
    if (!decoded) emcv_adaptive_store(blk.texel, s);
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
            if (any(lessThan(q, ivec2(0, 0))) ||
                any(greaterThanEqual(q, ivec2(EMCV_ADAPTIVE_TILE_BLOCKS_SIDE, EMCV_ADAPTIVE_TILE_BLOCKS_SIDE))))
                continue;
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
        sigma2 = emcv_history_shrink_sigma2(sigma2, frames, EMCV_APP_BUDGET.mean_sigma2, EMCV_APP_BUDGET.between_variance,
                                            emcv_history_spend_relative_variance());
        emcv_budget_add(sigma2, blk.pixels);
        emcv_app_store_plan(blk.texel, floatBitsToUint(sigma2));
    } else {
        emcv_app_store_plan(blk.texel, uint(emcv_history_count_target(sigma2)));
    }
}

// Quality target: each block's N, planned by the invocation that holds the block (emcv_adaptive_quality_count).
shared uint tile_planned[EMCV_ADAPTIVE_TILE_BLOCKS];

/// Quality target, at the top of the sampling pass: reprojects the tile's block histories into this frame's, pools
/// their per-sample variances over the tile and plans each block's N = the count that brings it to the target
/// (emcv_history_count_target). Returns the N of this invocation's pixel (its local id's block). Every invocation
/// calls it, in uniform control flow, after sharing its pixel (emcv_adaptive_share_pixel; the tile's variances
/// meet behind barriers).
uint emcv_adaptive_quality_count(ivec2 origin) {
    EmcvAdaptiveBlock blk;
    float own, frames;
    emcv_adaptive_tile_sigma2(origin, blk, own, frames);
    if (emcv_adaptive_holds_block()) {
        uint j = gl_LocalInvocationIndex;
        float pooled_frames;
        tile_planned[j] = blk.code == 0u ? 0u
                        : uint(emcv_history_count_target(emcv_adaptive_pooled_sigma2(j, own, blk.code, pooled_frames)));
    }
    barrier();
    ivec2 l = ivec2(gl_LocalInvocationID.xy) / EMCV_HISTORY_BLOCK;
    return tile_planned[l.x + l.y * EMCV_ADAPTIVE_TILE_BLOCKS_SIDE];
}

/// Budget mode, in the sampling pass after the solve: pixel p's N = clamp(lambda sigma) from its block's planned
/// variance (emcv_app_load_plan) and the lambda the solve found from the same frame's variances, rounded with the
/// block's number (emcv_budget_u over the block's texel, the frame's index and seed: every pixel of a block takes
/// the same N).
uint emcv_adaptive_budget_count(ivec2 p, uint frame_index, uint seed) {
    ivec2 texel = p / EMCV_HISTORY_BLOCK;
    float u = emcv_budget_u(uint(texel.x), uint(texel.y), frame_index, seed);
    return uint(emcv_history_count_spend(uintBitsToFloat(emcv_app_load_plan(texel)), EMCV_APP_BUDGET.lambda, u));
}

#endif  // #ifndef EMCV_ADAPTIVE_PLAN_H
