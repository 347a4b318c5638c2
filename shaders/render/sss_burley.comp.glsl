// SPDX-License-Identifier: MIT
// Burley screen-space SSS over the SSS tiles (indirect dispatch): N samples per scattering pixel drawn with the
// widest channel, weighted per channel, sum(w L) / sum(w) (docs/frame.md; the taps in render/burley_taps.h, which
// the resolve's guide shares). Every formula is from include/emcv/port/sss.h. N is the frame's fixed count
// (burley-N, reference). Built for an adaptive method (the renderer defines its EMCV_ADAPTIVE_* from the method
// table, adaptive/history_io.h), the pass takes the pixel's own N and, after its sampling loop, pushes the result
// into the pixel's history (emcv_adaptive_update_tile): sampling and history update are one dispatch. Under a
// quality target N needs only the pixel's tile, and the pass plans it itself first (the history reprojected and
// pooled as in adaptive/samples.h): counting, sampling and update in one dispatch, as many passes as burley-N. In
// budget mode N comes from the adaptive-samples pass before it and the frame's lambda, which the solve pass after
// that one solved (adaptive/budget_solve.comp.glsl).
// Once every pixel's N is known the tile hands its pixels to its threads in order of N (sort_tile_by_count), so
// that a warp (or a CPU's SIMD batch) loops over pixels of like N instead of waiting on its largest. For cv the
// tile's noise test runs between sampling and update (adaptive/history_io.h). Where the temporal resolve reads it
// (EMCV_RENDER_FLAG_SSS_NOISE), it stores beside the estimate (alpha) this frame's noise of it, emcv_sss_noise.
#version 450 core

#include "emcv/port/sss.h"
#include "render/burley_taps.h"
#include "render/gbuffer_read.h"
#include "render/tiles.h"
#include "emcv/port/bindings.h"

#if defined(EMCV_ADAPTIVE_SPVG) || defined(EMCV_ADAPTIVE_CV) || defined(EMCV_ADAPTIVE_NOTEX)
#define EMCV_BURLEY_ADAPTIVE 1
// Budget mode, a frame between two updates of a still view and still lights (EMCV_ADAPTIVE_REUSE_PLAN,
// frame_planner): the pass samples with the counts the last update planned (the samples image and lambda as that
// pass left them, rounded afresh) and neither updates the history nor plans: docs/renderer.md, "Updating one
// frame in M".
#if defined(EMCV_ADAPTIVE_REUSE_PLAN) && defined(EMCV_ADAPTIVE_PLAN_NEXT)
#error "sss_burley: a frame that reuses the plan does not plan the next frame"
#endif
#if !defined(EMCV_ADAPTIVE_REUSE_PLAN)
#define EMCV_BURLEY_UPDATES 1
#define EMCV_ADAPTIVE_TILE_UPDATE 1  // emcv_adaptive_update_tile and its shared memory
#endif
// Budget mode, the next frame showing this frame's view (EMCV_ADAPTIVE_PLAN_NEXT): after its update the pass
// plans the next frame's N as that frame's samples pass would (plan_next_frame); the solve pass follows.
#include "adaptive/samples.h"
#endif

layout(local_size_x = EMCV_RENDER_TILE_SIZE, local_size_y = EMCV_RENDER_TILE_SIZE) in;

#if defined(EMCV_BURLEY_UPDATES)
// Read back by the history update: the value as stored (binary16), which is what the display shows.
layout(rgba16f, EMCV_LAYOUT_IMAGE_BINDING(EMCV_RENDER_IMG_SSS_OUT)) uniform image2D out_scattered;
#else
layout(rgba16f, EMCV_LAYOUT_IMAGE_BINDING(EMCV_RENDER_IMG_SSS_OUT)) writeonly uniform image2D out_scattered;
#endif
layout(r32ui, EMCV_LAYOUT_IMAGE_BINDING(EMCV_RENDER_IMG_COUNT)) writeonly uniform uimage2D out_count;

shared uint tile_sample_sum;
shared uint tile_sample_max;
#if defined(EMCV_BURLEY_UPDATES)
// What the history update of this invocation's pixel reads after the tile's noise test, and the planning of the
// next frame after it (scatter leaves them: every G-buffer value read once).
vec3 pending_scattered = vec3(0.0f);
vec3 pending_unscattered = vec3(0.0f);
vec3 pending_albedo = vec3(0.0f);
uint pending_code = 0u;  // 0: off screen, or the pixel does not scatter
bool pending_sub_pixel = false;
#endif

#if defined(EMCV_BURLEY_ADAPTIVE)
uint planned_count = 0u;  // quality target: this invocation's N, planned at the top of main (emcv_adaptive_quality_count)
ivec2 tile_origin = ivec2(-1);  // the tile's pixel (0, 0) (emcv_adaptive_tile_origin), set at the top of main
uint assigned_count = 0u;  // the N of the pixel this invocation samples (sort_tile_by_count)
uint assigned_local = 0u;  // that pixel's local index in the tile (sort_tile_by_count)
// The tile's counting sort by N, over as many keys as the tile has pixels: per key its pixels' count, then its
// first slot; each slot's pixel (local index); each pixel's N.
#define SORT_KEYS (EMCV_RENDER_TILE_SIZE * EMCV_RENDER_TILE_SIZE)
shared uint sort_offset[SORT_KEYS];
shared uint sort_pixel[SORT_KEYS];
shared uint sort_count[SORT_KEYS];

/// The pixel's N, its block's: under a quality target the one planned at the top of main
/// (emcv_adaptive_quality_count); in budget mode from the samples pass's variance and the solved lambda
/// (emcv_adaptive_budget_count).
uint adaptive_count(ivec2 p) {
    return emcv_history_budget_mode() ? emcv_adaptive_budget_count(p, frame.counters.x, frame.counters.y) : planned_count;
}

/// Hands the tile's pixels to its threads in order of N: this invocation's pixel p (its own on entry, 0 samples
/// where it is off screen or does not scatter) becomes the one of the tile's sorted order at its own index, and
/// assigned_count that pixel's N. A warp runs as long as its largest N: sorted, each warp (each of llvmpipe's
/// SIMD batches) holds pixels of like N, and the pixels that take none come first. A counting sort over SORT_KEYS
/// keys (N scaled monotonically onto them: EMCV_HISTORY_N_MAX may exceed them), the order within a key as the
/// atomics fall: what a pixel's samples and history update compute does not depend on the thread that runs them,
/// so the image is the same bit for bit. A block's history is planned, updated and read back by the invocation
/// that holds the block (emcv_adaptive_holds_block), whichever pixels the sort hands out.
/// Every invocation calls it, in uniform control flow.
void sort_tile_by_count(inout ivec2 p) {
    uint here = gl_LocalInvocationIndex;
    uint own = 0u;
    if (emcv_render_on_screen(p) && emcv_render_scatters(emcv_render_material_code(p))) own = adaptive_count(p);
    sort_offset[here] = 0u;
    sort_count[here] = own;
    barrier();
    uint key = min(uint(float(own) * (float(SORT_KEYS - 1) / float(EMCV_HISTORY_N_MAX)) + 0.5f), uint(SORT_KEYS - 1));
    atomicAdd(sort_offset[key], 1u);
    barrier();
    if (here == 0u) {  // exclusive prefix sum: each key's first slot
        uint first = 0u;
        for (uint k = 0u; k < uint(SORT_KEYS); ++k) {
            uint count = sort_offset[k];
            sort_offset[k] = first;
            first += count;
        }
    }
    barrier();
    sort_pixel[atomicAdd(sort_offset[key], 1u)] = here;
    barrier();
    uint taken = sort_pixel[here];
    assigned_count = sort_count[taken];
    assigned_local = taken;
    // Workgroups past the tile count hold (-1, -1) everywhere (emcv_render_tile_pixel): they stay off screen.
    if (p.x >= 0)
        p += ivec2(int(taken % uint(EMCV_RENDER_TILE_SIZE)), int(taken / uint(EMCV_RENDER_TILE_SIZE))) -
             ivec2(gl_LocalInvocationID.xy);
}
#endif

#if defined(EMCV_ADAPTIVE_PLAN_NEXT)
/// Budget mode, when the next frame shows this frame's view (the renderer builds the pass with
/// EMCV_ADAPTIVE_PLAN_NEXT then: frame_planner): the next frame's samples pass would reproject every history to its
/// own texel, keep it as this pass stored it, and pool, shrink and histogram the variances over the same tiles.
/// So this pass does that now, from the history it has just stored (emcv_adaptive_stored_sigma2), and the solve
/// pass after it solves the next frame's lambda (adaptive/budget_solve.comp.glsl: after the whole dispatch, so
/// every workgroup has read this frame's lambda). The next frame records no samples pass, and its burley pass reads
/// the samples image and the budget block as that pass and its solve would have left them, bit for bit. Each
/// invocation shares the pixel it sampled (sort_tile_by_count, local index assigned_local); the blocks' invocations
/// plan. Every invocation calls it, in uniform control flow.
void plan_next_frame() {
    emcv_adaptive_share_pixel(assigned_local, pending_code, pending_sub_pixel);
    barrier();
    EmcvAdaptiveBlock blk = emcv_adaptive_no_block();
    float own = emcv_history_no_samples();
    if (emcv_adaptive_holds_block()) {
        uint j = gl_LocalInvocationIndex;
        float frames;
        blk = emcv_adaptive_block(j, tile_origin);
        own = emcv_adaptive_stored_sigma2(blk, frames);
        emcv_adaptive_share_sigma2(j, own, blk.code, frames);
    }
    barrier();
    if (emcv_adaptive_holds_block()) {
        uint j = gl_LocalInvocationIndex;
        if (blk.code != 0u) emcv_adaptive_allocate(j, blk, own);
    }
}
#endif

/// Scatters pixel p; returns the samples it took (0 off screen and for non-scattering pixels).
uint scatter(ivec2 p) {
    if (!emcv_render_on_screen(p)) return 0u;
    uint code = emcv_render_material_code(p);
    if (!emcv_render_scatters(code)) return 0u;

    EmcvBurleyPixel px = emcv_render_burley_pixel(p, code);
    bool approximate = (frame.counters.w & EMCV_RENDER_FLAG_APPROXIMATE_CDF) != 0u;
    vec2 rotation = emcv_sss_rotation(uint(p.x), uint(p.y), frame.counters.x, frame.counters.y);
#if defined(EMCV_BURLEY_ADAPTIVE)
    uint n = assigned_count;
#else
    uint n = uint(frame.sss.x);
#endif

    vec3 sum_wl = vec3(0.0f);
    vec3 sum_w = vec3(0.0f);
    // emcv_sss_noise's sums, kept only where the resolve reads the noise (no resolve, jitter, the reference: not).
    bool keeps_noise = (frame.counters.w & EMCV_RENDER_FLAG_SSS_NOISE) != 0u;
    vec3 sum_w2 = vec3(0.0f), sum_w2l = vec3(0.0f), sum_w2l2 = vec3(0.0f);
    for (uint i = 0u; i < n; ++i) {
        vec3 w, l;
        // Off-screen and non-scattering samples get weight 0 (docs/frame.md).
        if (!emcv_render_burley_tap(p, px, i, rotation, approximate, w, l)) continue;
        sum_w += w;
        sum_wl += w * l;
        if (keeps_noise) {
            vec3 w2 = w * w;
            sum_w2 += w2;
            sum_w2l += w2 * l;
            sum_w2l2 += w2 * l * l;
        }
    }
    vec3 centre = texelFetch(lit_diffuse, p, 0).xyz;
    vec3 scattered = emcv_render_burley_estimate(sum_wl, sum_w, centre);
    // This frame's noise beside the estimate (its alpha, which the composite does not read): the resolve narrows
    // its clip box to it (docs/frame.md, "Temporal resolve").
    float noise = keeps_noise ? emcv_sss_noise(sum_w, sum_w2, sum_w2l, sum_w2l2, scattered, n) : 1.0f;
    imageStore(out_scattered, p, vec4(scattered, noise));
    imageStore(out_count, p, uvec4(n));
#if defined(EMCV_BURLEY_UPDATES)
    // The invocation reads its own store back: the binary16 value the display shows (and the separate update
    // pass this replaced used to read); main pushes it once the tile's noise test is done.
    pending_scattered = imageLoad(out_scattered, p).xyz;
    pending_unscattered = centre;
    pending_albedo = px.albedo;
    pending_code = code;
    pending_sub_pixel = emcv_adaptive_sub_pixel_kernel(px.d_sample, px.pixels_per_mm);
#endif
    return n;
}

void main() {
    if (gl_LocalInvocationIndex == 0u) {
        tile_sample_sum = 0u;
        tile_sample_max = 0u;
    }
    barrier();
    ivec2 p = emcv_render_tile_pixel();
#if defined(EMCV_BURLEY_ADAPTIVE)
    tile_origin = emcv_adaptive_tile_origin(p);
    if (!emcv_history_budget_mode()) {
        emcv_adaptive_share_pixel_of(p);
        planned_count = emcv_adaptive_quality_count(tile_origin);
    }
    sort_tile_by_count(p);
#endif
    uint n = scatter(p);
#if defined(EMCV_BURLEY_UPDATES)
    emcv_adaptive_update_tile_diffuse(assigned_local, tile_origin, pending_scattered, pending_unscattered, pending_albedo, n);
#endif
    // Sample statistics reduced per tile in shared memory, then one global atomic per tile (not per pixel).
    atomicAdd(tile_sample_sum, n);
    atomicMax(tile_sample_max, n);
    barrier();
    if (gl_LocalInvocationIndex == 0u) {
        atomicAdd(stats.sample_sum, tile_sample_sum);
        atomicMax(stats.sample_max, tile_sample_max);
    }
#if defined(EMCV_ADAPTIVE_PLAN_NEXT)
    plan_next_frame();
#endif
}
