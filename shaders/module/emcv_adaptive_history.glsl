// SPDX-License-Identifier: MIT
// emcv_adaptive_history.glsl — installed GPU module (share/emcv/module): the history of one adaptive method, chosen
// by one define (EMCV_ADAPTIVE_CV, EMCV_ADAPTIVE_SPVG or EMCV_ADAPTIVE_NOTEX): its layout
// (emcv_adaptive_layout_emcm2.glsl or _moving.glsl, chosen below), the K x K blocks of an 8x8 tile, and the history
// update of a tile after sampling (EMCV_ADAPTIVE_TILE_UPDATE; emcv/port/history.h holds every formula). Compute
// stage, one workgroup of EMCV_ADAPTIVE_TILE_SIZE^2 invocations per tile.
//
// It declares no resources: the application defines the emcv_app_* functions declared below (anywhere in the
// shader; they are prototypes here) over its own images, and must have its own bindings. The renderer's
// definitions are shaders/adaptive/history_io.h; docs/integration.md, section 3, lists the order.
#ifndef EMCV_ADAPTIVE_HISTORY_H
#define EMCV_ADAPTIVE_HISTORY_H

#include "emcv/port/history.h"
#include "module/emcv_adaptive_language.glsl"

// The tile's side in pixels, the workgroup's size in each dimension. Range: 8 (a multiple of 4, so that every K
// divides it; the renderer's SSS tiles are 8x8).
#ifndef EMCV_ADAPTIVE_TILE_SIZE
#define EMCV_ADAPTIVE_TILE_SIZE 8
#endif

// What the application supplies (prototypes: define them before or after including this module).
// The history of this frame and last frame, at a texel of the block grid (a pixel at K = 1): texel A, and for a
// two-texel layout (EMCV_ADAPTIVE_HISTORY_TEXELS == 2) texel B, in the formats EMCV_ADAPTIVE_HISTORY_FORMAT_A / _B.
// The application binds this frame's history as images (read and written, `coherent`) and last frame's as
// textures (read), and swaps them each frame.
vec4 emcv_app_history_load_a(ivec2 texel);
vec4 emcv_app_history_load_b(ivec2 texel);
void emcv_app_history_store_a(ivec2 texel, vec4 value);
void emcv_app_history_store_b(ivec2 texel, vec4 value);
vec4 emcv_app_history_previous_a(ivec2 texel);
vec4 emcv_app_history_previous_b(ivec2 texel);
/// The viewport in pixels (the block grid is its size divided by K, rounded up).
ivec2 emcv_app_viewport_size();

// The history layout of the method, the one place that chooses between them: EmcvAdaptiveState, its weight
// EMCV_ADAPTIVE_ETA, its texels and formats, whether it has the noise test (EMCV_ADAPTIVE_NOISE_TEST), and the
// functions every pass calls (init, decode, store, blend, sigma2, the sub-pixel test, the push and the noise-test
// hooks).
#if defined(EMCV_ADAPTIVE_CV)
#include "module/emcv_adaptive_layout_emcm2.glsl"
#elif defined(EMCV_ADAPTIVE_SPVG) || defined(EMCV_ADAPTIVE_NOTEX)
#include "module/emcv_adaptive_layout_moving.glsl"
#else
#error "define the method: EMCV_ADAPTIVE_SPVG, EMCV_ADAPTIVE_CV or EMCV_ADAPTIVE_NOTEX (the renderer: its row of the method table)"
#endif

/// The effective frames a history's per-sample variance rests on (emcv_history_effective_frames at its layout's
/// eta).
float emcv_adaptive_effective_frames(EmcvAdaptiveState s) {
    return emcv_history_effective_frames(s.count, EMCV_ADAPTIVE_ETA);
}

// The statistics' grain (emcv/port/history.h, EMCV_HISTORY_BLOCK): the history, the samples image and every
// count are one texel per K x K block of pixels; an 8x8 tile holds EMCV_ADAPTIVE_TILE_BLOCKS of them.
#if EMCV_HISTORY_BLOCK != 1 && EMCV_HISTORY_BLOCK != 2 && EMCV_HISTORY_BLOCK != 4
#error "EMCV_HISTORY_BLOCK is 1, 2 or 4 (a divisor of the 8x8 SSS tile)"
#endif
#define EMCV_ADAPTIVE_TILE_BLOCKS_SIDE (EMCV_ADAPTIVE_TILE_SIZE / EMCV_HISTORY_BLOCK)
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
shared uint tile_pixel_code[EMCV_ADAPTIVE_TILE_SIZE * EMCV_ADAPTIVE_TILE_SIZE];
shared uint tile_pixel_sub[EMCV_ADAPTIVE_TILE_SIZE * EMCV_ADAPTIVE_TILE_SIZE];

/// Shares one pixel's code and sub-pixel test at its local index; the caller's barrier() makes them readable.
void emcv_adaptive_share_pixel(uint local, uint code, bool sub_pixel) {
    tile_pixel_code[local] = code;
    tile_pixel_sub[local] = sub_pixel ? 1u : 0u;
}

/// The workgroup's tile origin (its pixel (0, 0)) from pixel p of this invocation before any reordering, or
/// (-1, -1) for a workgroup past the tile count.
ivec2 emcv_adaptive_tile_origin(ivec2 p) { return p.x >= 0 ? p - ivec2(gl_LocalInvocationID.xy) : ivec2(-1, -1); }

/// Block j's position within its tile, in blocks.
ivec2 emcv_adaptive_block_local(uint j) {
    return ivec2(int(j % uint(EMCV_ADAPTIVE_TILE_BLOCKS_SIDE)), int(j / uint(EMCV_ADAPTIVE_TILE_BLOCKS_SIDE)));
}

/// The block grid's size: the viewport divided by K, rounded up.
ivec2 emcv_adaptive_grid() {
    return (emcv_app_viewport_size() + (EMCV_HISTORY_BLOCK - 1)) / EMCV_HISTORY_BLOCK;
}

/// Whether p lies in [0, size).
bool emcv_adaptive_inside(ivec2 p, ivec2 size) {
    return all(greaterThanEqual(p, ivec2(0, 0))) && all(lessThan(p, size));
}
/// Whether pixel p is on screen.
bool emcv_adaptive_on_screen(ivec2 p) { return emcv_adaptive_inside(p, emcv_app_viewport_size()); }
/// Whether t is a texel of the block grid (at K = 1, emcv_adaptive_on_screen).
bool emcv_adaptive_on_grid(ivec2 t) { return emcv_adaptive_inside(t, emcv_adaptive_grid()); }

/// No block (an invocation that holds none).
EmcvAdaptiveBlock emcv_adaptive_no_block() {
    EmcvAdaptiveBlock b;
    b.texel = ivec2(-1, -1);
    b.pixel = ivec2(-1, -1);
    b.code = 0u;
    b.pixels = 0u;
    b.sub_pixel = false;
    return b;
}

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
            uint i = uint(q.x + q.y * EMCV_ADAPTIVE_TILE_SIZE);
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

/// The history state of SSS pixel p as this frame's samples pass left it (a poisoned texel decodes as a fresh
/// state).
EmcvAdaptiveState emcv_adaptive_load(ivec2 p) {
    EmcvAdaptiveState s;
    emcv_adaptive_decode(emcv_app_history_load_a(p), emcv_adaptive_load_b(p), s);
    return s;
}

/// The history update of a block once its samples are taken (the burley pass runs it after its sampling loop;
/// emcv_adaptive_update_tile): pushes this frame's values into the block's state s (emcv_adaptive_load) as the mean
/// of `batch` samples (include/emcv/port/ema.h, *_push_batch: the history estimates the per-sample variance, supp.
/// Eq. 25-27; a block's batch is emcv_history_block_batch) and stores it at the block's texel. f and g are the
/// tracked values: the scattered diffuse as displayed and the unscattered diffuse (the in-frame constant
/// control), each as the gamma luminance of albedo * irradiance * exposure (emcv_gamma_luminance).
///   spvg      moving mean/variance of f (eta 0.2)
///   cv        EMCM over (f, G) (eta 0.2), a change the control does not explain clipped (emcv_history_push_cv),
///             then the comoments scaled by `noise_ratio`, the tile's noise test (emcv_history_noise_ratio,
///             emcv_history_rescale_cv)
///   cv-notex  moving mean/variance of r = f - G (alpha = 1, eta 0.2), a change G does not explain clipped as
///             cv's (emcv_history_push_notex)
/// A block that took no samples learns nothing about its noise and is not pushed (returns false; true once s,
/// pushed, is stored). A non-finite f or G is refused by the port (state unchanged); a poisoned stored state is
/// reset, never used.
bool emcv_adaptive_update(ivec2 texel, inout EmcvAdaptiveState s, float f, float g, float batch, float noise_ratio) {
    if (batch == 0.0f) return false;
    emcv_adaptive_push(s, f, g, batch, noise_ratio);
    emcv_adaptive_store(texel, s);
    return true;
}

#if defined(EMCV_ADAPTIVE_TILE_UPDATE)
// What emcv_adaptive_update_tile stored at this invocation's block, where it stored one (updated_known): a pass
// that reads the block's history back after its update (the next frame's plan, emcv_adaptive_stored_sigma2)
// takes it from here where the layout's texels read back bit for bit (EMCV_ADAPTIVE_HISTORY_EXACT) instead of
// loading the texels again. The state has no initialiser: it is read only where updated_known is true (and
// glslang's HLSL front end refuses a global initialised by a call).
EMCV_STATIC EmcvAdaptiveState emcv_adaptive_updated_state;
EMCV_STATIC bool emcv_adaptive_updated_known = false;

// The tile's pixels after sampling, at their local index: tracked f and G and the samples taken (0: none).
shared float tile_pixel_f[EMCV_ADAPTIVE_TILE_SIZE * EMCV_ADAPTIVE_TILE_SIZE];
shared float tile_pixel_g[EMCV_ADAPTIVE_TILE_SIZE * EMCV_ADAPTIVE_TILE_SIZE];
shared uint tile_pixel_n[EMCV_ADAPTIVE_TILE_SIZE * EMCV_ADAPTIVE_TILE_SIZE];

/// The history update of the workgroup's 8x8 tile (at `origin`, emcv_adaptive_tile_origin), this invocation's
/// pixel at local index `local` having taken n samples (0 off screen and for pixels that do not scatter) and
/// given its tracked f and g (emcv_adaptive_update; read only where n > 0): every invocation calls it, in
/// uniform control flow (it holds barriers). Each pixel's tracked f and g go to the tile; each block
/// (emcv_adaptive_holds_block) takes the means of its pixels that took samples, in row order, as a batch of
/// n m samples (emcv_history_block_batch; at K = 1 the pixel's own f, g and n), and reads its state once. cv: each
/// block's noise-test term before its push (emcv_history_noise_term) and its relative variance
/// (emcv_history_noise_relative), in fixed-point units (emcv_history_noise_units), summed over the tile's blocks
/// that took samples, then the push and the rescale by the pool's ratio (emcv_history_noise_ratio,
/// emcv_adaptive_update); the other methods push as they are.
void emcv_adaptive_update_tile(uint local, ivec2 origin, float tracked_f, float tracked_g, uint n) {
    tile_pixel_n[local] = n;
    if (n > 0u) {
        tile_pixel_f[local] = tracked_f;
        tile_pixel_g[local] = tracked_g;
    }
    emcv_adaptive_noise_clear(gl_LocalInvocationIndex);
    memoryBarrierShared();
    barrier();
    EmcvAdaptiveState s = emcv_adaptive_init();
    ivec2 texel = ivec2(-1, -1);
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
                uint i = uint(q.x + q.y * EMCV_ADAPTIVE_TILE_SIZE);
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
        emcv_adaptive_noise_add(s, f, g, batch);  // cv's noise test (layout_emcm2.h); the others add nothing
    }
#if EMCV_ADAPTIVE_NOISE_TEST
    memoryBarrierShared();
    barrier();  // the tile's noise pool is complete
#endif
    if (emcv_adaptive_holds_block()) {
        emcv_adaptive_updated_known = emcv_adaptive_update(texel, s, f, g, batch, emcv_adaptive_noise_ratio());
        emcv_adaptive_updated_state = s;
    }
}
#endif

#endif  // #ifndef EMCV_ADAPTIVE_HISTORY_H
