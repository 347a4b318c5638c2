// SPDX-License-Identifier: MIT
// shaders/adaptive/history_io.h — the history images of one adaptive method, chosen by the define the renderer
// passes from the method's row: EMCV_ADAPTIVE_SPVG, EMCV_ADAPTIVE_CV or EMCV_ADAPTIVE_NOTEX, and their load/store in the port's types
// (include/emcv/port/history.h holds the layouts and every formula).
#ifndef EMCV_ADAPTIVE_HISTORY_IO_H
#define EMCV_ADAPTIVE_HISTORY_IO_H

#include "emcv/port/history.h"
#include "emcv/port/sss.h"
#include "adaptive/bindings.h"
#include "adaptive/budget_block.h"
#include "render/burley_taps.h"
#include "render/gbuffer_read.h"

// Coherent: under a quality target the burley pass plans a pixel's history in one thread and, after sorting the
// tile by N, updates it in another (sss_burley.comp.glsl, sort_tile_by_count).
#if defined(EMCV_ADAPTIVE_CV)
layout(rgba32f, EMCV_LAYOUT_IMAGE_BINDING(EMCV_ADAPTIVE_IMG_HISTORY_A)) coherent uniform image2D history_a;
layout(rg32f, EMCV_LAYOUT_IMAGE_BINDING(EMCV_ADAPTIVE_IMG_HISTORY_B)) coherent uniform image2D history_b;
#define EmcvAdaptiveState EmcvEmcm2
#elif defined(EMCV_ADAPTIVE_SPVG) || defined(EMCV_ADAPTIVE_NOTEX)
layout(rgba16f, EMCV_LAYOUT_IMAGE_BINDING(EMCV_ADAPTIVE_IMG_HISTORY_A)) coherent uniform image2D history_a;
#define EmcvAdaptiveState EmcvMovingStats
#else
#error "the renderer defines the method: EMCV_ADAPTIVE_SPVG, EMCV_ADAPTIVE_CV or EMCV_ADAPTIVE_NOTEX (its row of the method table)"
#endif

layout(r32ui, EMCV_LAYOUT_IMAGE_BINDING(EMCV_ADAPTIVE_IMG_SAMPLES)) uniform uimage2D samples_image;

// The statistics' grain (emcv/port/history.h, EMCV_HISTORY_BLOCK): the history, the samples image and every
// count are one texel per K x K block of pixels; an 8x8 tile holds EMCV_ADAPTIVE_TILE_BLOCKS of them.
#if EMCV_HISTORY_BLOCK != 1 && EMCV_HISTORY_BLOCK != 2 && EMCV_HISTORY_BLOCK != 4
#error "EMCV_HISTORY_BLOCK is 1, 2 or 4 (a divisor of the 8x8 SSS tile)"
#endif
#define EMCV_ADAPTIVE_TILE_BLOCKS_SIDE (EMCV_RENDER_TILE_SIZE / EMCV_HISTORY_BLOCK)
#define EMCV_ADAPTIVE_TILE_BLOCKS (EMCV_ADAPTIVE_TILE_BLOCKS_SIDE * EMCV_ADAPTIVE_TILE_BLOCKS_SIDE)
/// Whether this invocation holds one of the tile's blocks: invocation j holds block j (the first TILE_BLOCKS
/// invocations, which lie in the first warps: a GPU skips a warp in which no lane takes the `if`; llvmpipe runs
/// the `if` masked in every 8-lane batch, so there the blocks' arithmetic costs as much at any K:
/// docs/notebook/2026-12-07-block-work-on-llvmpipe.md).
bool emcv_adaptive_holds_block() { return gl_LocalInvocationIndex < uint(EMCV_ADAPTIVE_TILE_BLOCKS); }

/// One block of a tile as its pixels left it in shared memory (emcv_adaptive_block).
struct EmcvAdaptiveBlock {
    ivec2 texel;     ///< its texel of the history and samples images (block grid); (-1, -1) past the tile count
    ivec2 pixel;     ///< its representative: the first scattering pixel in row order (reprojection, surface)
    uint code;       ///< the representative's material code; 0 when none of its pixels scatters
    uint pixels;     ///< its scattering pixels (m)
    bool sub_pixel;  ///< every scattering pixel's kernel is under a pixel: the block takes no samples
};

/// The tile's pixels, at their local index: material code (0: off screen or not scattering) and sub-pixel test
/// (emcv_adaptive_share_pixel), and after sampling their tracked f, G and samples (emcv_adaptive_update_tile).
shared uint tile_pixel_code[EMCV_RENDER_TILE_SIZE * EMCV_RENDER_TILE_SIZE];
shared uint tile_pixel_sub[EMCV_RENDER_TILE_SIZE * EMCV_RENDER_TILE_SIZE];

/// Shares one pixel's code and sub-pixel test at its local index; the caller's barrier() makes them readable.
void emcv_adaptive_share_pixel(uint local, uint code, bool sub_pixel) {
    tile_pixel_code[local] = code;
    tile_pixel_sub[local] = sub_pixel ? 1u : 0u;
}

/// The workgroup's tile origin (its pixel (0, 0)) from pixel p of this invocation before any reordering, or
/// (-1, -1) for a workgroup past the tile count.
ivec2 emcv_adaptive_tile_origin(ivec2 p) { return p.x >= 0 ? p - ivec2(gl_LocalInvocationID.xy) : ivec2(-1); }

/// Block j's position within its tile, in blocks.
ivec2 emcv_adaptive_block_local(uint j) {
    return ivec2(int(j % uint(EMCV_ADAPTIVE_TILE_BLOCKS_SIDE)), int(j / uint(EMCV_ADAPTIVE_TILE_BLOCKS_SIDE)));
}

/// The block grid's size: the viewport divided by K, rounded up.
ivec2 emcv_adaptive_grid() {
    return (ivec2(frame.viewport.xy) + (EMCV_HISTORY_BLOCK - 1)) / EMCV_HISTORY_BLOCK;
}

/// Whether t is a texel of the block grid (at K = 1, emcv_render_on_screen).
bool emcv_adaptive_on_grid(ivec2 t) { return all(greaterThanEqual(t, ivec2(0))) && all(lessThan(t, emcv_adaptive_grid())); }

/// No block (an invocation that holds none).
EmcvAdaptiveBlock emcv_adaptive_no_block() { return EmcvAdaptiveBlock(ivec2(-1), ivec2(-1), 0u, 0u, false); }

/// Block j of the tile at `origin` (emcv_adaptive_tile_origin) from the pixels shared in the tile's arrays: its
/// texel, representative, code, scattering pixels and whether all of them are sub-pixel. At K = 1 the block is
/// the pixel.
EmcvAdaptiveBlock emcv_adaptive_block(uint j, ivec2 origin) {
    ivec2 l = emcv_adaptive_block_local(j);
    EmcvAdaptiveBlock b = emcv_adaptive_no_block();
    if (origin.x < 0) return b;
    b.texel = origin / EMCV_HISTORY_BLOCK + l;
    b.pixel = origin + l * EMCV_HISTORY_BLOCK;
    b.sub_pixel = true;
    for (int dy = 0; dy < EMCV_HISTORY_BLOCK; ++dy) {
        for (int dx = 0; dx < EMCV_HISTORY_BLOCK; ++dx) {
            ivec2 q = l * EMCV_HISTORY_BLOCK + ivec2(dx, dy);
            uint i = uint(q.x + q.y * EMCV_RENDER_TILE_SIZE);
            uint code = tile_pixel_code[i];
            if (code == 0u) continue;
            if (b.pixels == 0u) {
                b.code = code;
                b.pixel = origin + q;
            }
            b.pixels += 1u;
            b.sub_pixel = b.sub_pixel && tile_pixel_sub[i] != 0u;
        }
    }
    if (b.pixels == 0u) b.sub_pixel = false;
    return b;
}

/// A fresh (reset) state.
EmcvAdaptiveState emcv_adaptive_init() {
#if defined(EMCV_ADAPTIVE_CV)
    return emcv_emcm2_init();
#else
    return emcv_moving_stats_init();
#endif
}

/// Decodes raw history texels; false (state reset) when they are poisoned.
bool emcv_adaptive_decode(vec4 a, vec4 b, out EmcvAdaptiveState s) {
#if defined(EMCV_ADAPTIVE_CV)
    return emcv_history_decode_emcm2(a, b.xy, s);
#else
    return emcv_history_decode_stats(a, s);
#endif
}

void emcv_adaptive_store(ivec2 p, EmcvAdaptiveState s) {
#if defined(EMCV_ADAPTIVE_CV)
    imageStore(history_a, p, emcv_history_encode_emcm2_cov(s));
    imageStore(history_b, p, vec4(emcv_history_encode_emcm2_means(s), 0.0f, 0.0f));
#else
    imageStore(history_a, p, emcv_history_encode_stats(s));
#endif
}

/// Stores texels as they were read (a kept history: no second rounding).
void emcv_adaptive_store_raw(ivec2 p, vec4 a, vec4 b) {
    imageStore(history_a, p, a);
#if defined(EMCV_ADAPTIVE_CV)
    imageStore(history_b, p, b);
#endif
}

/// Resampling a reprojected history: adds w times a neighbour's statistics (the means and comoments, not the
/// count) to a running blend (a fresh state, emcv_adaptive_init(), to start: its statistics are 0).
void emcv_adaptive_blend_add(inout EmcvAdaptiveState blend, float w, EmcvAdaptiveState s) {
#if defined(EMCV_ADAPTIVE_CV)
    blend.mean += w * s.mean;
    blend.cov += w * s.cov;
#else
    blend.mean += w * s.mean;
    blend.variance += w * s.variance;
#endif
}

/// The blend's statistics, divided by its weight, into state s (whose count and flags stay).
void emcv_adaptive_blend_finish(inout EmcvAdaptiveState s, EmcvAdaptiveState blend, float weight) {
#if defined(EMCV_ADAPTIVE_CV)
    s.mean = blend.mean / weight;
    s.cov = blend.cov / weight;
#else
    s.mean = blend.mean / weight;
    s.variance = blend.variance / weight;
#endif
}

/// The method's per-sample variance from its state (emcv_history_no_variance() before two frames): spvg f's,
/// cv the residual's at the EMCM's alpha, cv-notex the residual's at alpha = 1.
float emcv_adaptive_sigma2(EmcvAdaptiveState s) {
#if defined(EMCV_ADAPTIVE_CV)
    return emcv_history_sigma2_cv(s, EMCV_HISTORY_ETA_EMCM);
#else
    return emcv_history_sigma2_moving(s, EMCV_HISTORY_ETA_MOVING);
#endif
}

/// The effective frames the method's per-sample variance rests on (emcv_history_effective_frames at its eta).
float emcv_adaptive_effective_frames(EmcvAdaptiveState s) {
#if defined(EMCV_ADAPTIVE_CV)
    return emcv_history_effective_frames(s.count, EMCV_HISTORY_ETA_EMCM);
#else
    return emcv_history_effective_frames(s.count, EMCV_HISTORY_ETA_MOVING);
#endif
}

/// Whether a kernel whose widest channel has shape distance `widest_d` (mm) covers under a pixel at
/// `pixels_per_mm`, where the control-variate methods take no samples (spvg never skips: it has no control to
/// stand in for the scattered value).
bool emcv_adaptive_sub_pixel_kernel(float widest_d, float pixels_per_mm) {
#if defined(EMCV_ADAPTIVE_CV) || defined(EMCV_ADAPTIVE_NOTEX)
    return emcv_history_sub_pixel(widest_d, pixels_per_mm);
#else
    return false;
#endif
}

/// emcv_adaptive_sub_pixel_kernel at scattering pixel p of material `code`, from the taps' setup there.
bool emcv_adaptive_sub_pixel(ivec2 p, uint code) {
    EmcvBurleyPixel px = emcv_render_burley_pixel(p, code);
    return emcv_adaptive_sub_pixel_kernel(px.d_sample, px.pixels_per_mm);
}

/// A pixel's diffuse as displayed before the tonemap (albedo * irradiance * exposure), as gamma luminance: the
/// caller passes the pixel's albedo, read once.
float emcv_adaptive_tracked(vec3 albedo, vec3 irradiance) {
    return emcv_gamma_luminance(albedo * irradiance * frame.background.w);
}

/// The history state of SSS pixel p as this frame's samples pass left it (a poisoned texel decodes as a fresh
/// state).
EmcvAdaptiveState emcv_adaptive_load(ivec2 p) {
#if defined(EMCV_ADAPTIVE_CV)
    vec4 b = imageLoad(history_b, p);
#else
    vec4 b = vec4(0.0f);
#endif
    EmcvAdaptiveState s;
    emcv_adaptive_decode(imageLoad(history_a, p), b, s);
    return s;
}

/// The history update of a block once its samples are taken (the burley pass runs it after its sampling loop;
/// emcv_adaptive_update_tile): pushes this frame's values into the block's state s (emcv_adaptive_load) as the mean
/// of `batch` samples (include/emcv/port/ema.h, *_push_batch: the history estimates the per-sample variance, supp.
/// Eq. 25-27; a block's batch is emcv_history_block_batch) and stores it at the block's texel. f and g are the tracked scattered diffuse as stored for
/// display and the tracked unscattered diffuse (in-frame constant control): gamma-space luminance
/// (emcv_adaptive_tracked).
///   spvg      moving mean/variance of f (eta 0.2)
///   cv        EMCM over (f, G) (eta 0.2), a change the control does not explain clipped (emcv_history_push_cv),
///             then the comoments scaled by `noise_ratio`, the tile's noise test (emcv_history_noise_ratio,
///             emcv_history_rescale_cv)
///   cv-notex  moving mean/variance of r = f - G (alpha = 1, eta 0.2), a change G does not explain clipped as
///             cv's (emcv_history_push_notex)
/// A block that took no samples learns nothing about its noise and is not pushed. A non-finite f or G is
/// refused by the port (state unchanged); a poisoned stored state is reset, never used.
void emcv_adaptive_update(ivec2 texel, EmcvAdaptiveState s, float f, float g, float batch, float noise_ratio) {
    if (batch == 0.0f) return;
#if defined(EMCV_ADAPTIVE_CV)
    emcv_history_push_cv(s, f, g, EMCV_HISTORY_ETA_EMCM, batch);
    emcv_history_rescale_cv(s, noise_ratio);
#elif defined(EMCV_ADAPTIVE_NOTEX)
    emcv_history_push_notex(s, f, g, EMCV_HISTORY_ETA_MOVING, batch);
#else
    emcv_moving_stats_push_batch(s, f, EMCV_HISTORY_ETA_MOVING, batch);
#endif
    emcv_adaptive_store(texel, s);
}

#if defined(EMCV_ADAPTIVE_TILE_UPDATE)
#if defined(EMCV_ADAPTIVE_CV)
// The tile's noise-test pool (emcv_history_noise_add's: sums of term units, of relative-variance units, blocks),
// added to with atomics: fixed-point sums are exact in any order.
shared uint tile_noise_pool[3];
#endif
// The tile's pixels after sampling, at their local index: tracked f and G and the samples taken (0: none).
shared float tile_pixel_f[EMCV_RENDER_TILE_SIZE * EMCV_RENDER_TILE_SIZE];
shared float tile_pixel_g[EMCV_RENDER_TILE_SIZE * EMCV_RENDER_TILE_SIZE];
shared uint tile_pixel_n[EMCV_RENDER_TILE_SIZE * EMCV_RENDER_TILE_SIZE];

/// The history update of the workgroup's 8x8 tile (at `origin`, emcv_adaptive_tile_origin), this invocation's
/// pixel at local index `local` having taken n samples (0 off screen and for pixels that do not scatter), its
/// scattered and unscattered diffuse as the burley pass stored them and its albedo: every invocation calls it, in
/// uniform control flow (it holds barriers). Each pixel's tracked f and g go to the tile; each block
/// (emcv_adaptive_holds_block) takes the means of its pixels that took samples, in row order, as a batch of
/// n m samples (emcv_history_block_batch; at K = 1 the pixel's own f, g and n), and reads its state once. cv: each
/// block's noise-test term before its push (emcv_history_noise_term) and its relative variance
/// (emcv_history_noise_relative), in fixed-point units (emcv_history_noise_units), summed over the tile's blocks
/// that took samples, then the push and the rescale by the pool's ratio (emcv_history_noise_ratio,
/// emcv_adaptive_update); the other methods push as they are.
void emcv_adaptive_update_tile(uint local, ivec2 origin, vec3 scattered, vec3 unscattered, vec3 albedo, uint n) {
    tile_pixel_n[local] = n;
    if (n > 0u) {
        tile_pixel_f[local] = emcv_adaptive_tracked(albedo, scattered);
        tile_pixel_g[local] = emcv_adaptive_tracked(albedo, unscattered);
    }
#if defined(EMCV_ADAPTIVE_CV)
    if (gl_LocalInvocationIndex < 3u) tile_noise_pool[gl_LocalInvocationIndex] = 0u;
#endif
    memoryBarrierShared();
    barrier();
    EmcvAdaptiveState s = emcv_adaptive_init();
    ivec2 texel = ivec2(-1);
    float f = 0.0f;
    float g = 0.0f;
    float batch = 0.0f;
    if (emcv_adaptive_holds_block()) {
        uint j = gl_LocalInvocationIndex;
        ivec2 l = emcv_adaptive_block_local(j);
        texel = origin / EMCV_HISTORY_BLOCK + l;
        EMCV_PRECISE float sum_f = 0.0f;
        EMCV_PRECISE float sum_g = 0.0f;
        uint pixels = 0u;
        uint taken = 0u;
        for (int dy = 0; dy < EMCV_HISTORY_BLOCK; ++dy) {
            for (int dx = 0; dx < EMCV_HISTORY_BLOCK; ++dx) {
                ivec2 q = l * EMCV_HISTORY_BLOCK + ivec2(dx, dy);
                uint i = uint(q.x + q.y * EMCV_RENDER_TILE_SIZE);
                if (tile_pixel_n[i] == 0u) continue;
                sum_f += tile_pixel_f[i];
                sum_g += tile_pixel_g[i];
                taken = tile_pixel_n[i];  // the block's N: every pixel of a block takes the same
                pixels += 1u;
            }
        }
        if (pixels > 0u && origin.x >= 0) {
            EMCV_PRECISE float mean_f = sum_f / float(pixels);
            EMCV_PRECISE float mean_g = sum_g / float(pixels);
            f = mean_f;
            g = mean_g;
            batch = emcv_history_block_batch(taken, pixels);
            s = emcv_adaptive_load(texel);
        }
#if defined(EMCV_ADAPTIVE_CV)
        float term = batch > 0.0f ? emcv_history_noise_term(s, f, g, EMCV_HISTORY_ETA_EMCM, batch) : emcv_history_no_variance();
        uvec3 own = uvec3(0u);
        emcv_history_noise_add(own, term, emcv_history_noise_relative(max(batch, 1.0f)));
        if (own.z != 0u) {
            atomicAdd(tile_noise_pool[0], own.x);
            atomicAdd(tile_noise_pool[1], own.y);
            atomicAdd(tile_noise_pool[2], own.z);
        }
#endif
    }
#if defined(EMCV_ADAPTIVE_CV)
    memoryBarrierShared();
    barrier();
    uvec3 pool = uvec3(tile_noise_pool[0], tile_noise_pool[1], tile_noise_pool[2]);
    if (emcv_adaptive_holds_block()) emcv_adaptive_update(texel, s, f, g, batch, emcv_history_noise_ratio(pool));
#else
    if (emcv_adaptive_holds_block()) emcv_adaptive_update(texel, s, f, g, batch, 1.0f);
#endif
}
#endif

#endif  // #ifndef EMCV_ADAPTIVE_HISTORY_IO_H
