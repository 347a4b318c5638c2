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

/// The history update of SSS pixel p once its samples are taken (the burley pass runs it after its sampling
/// loop; emcv_adaptive_update_tile): pushes this frame's values into the pixel's state s (emcv_adaptive_load) as
/// the mean of the n samples the pixel took (include/emcv/port/ema.h, *_push_batch: the history estimates the
/// per-sample variance, supp. Eq. 25-27) and stores it. f and g are the tracked scattered diffuse as stored for
/// display and the tracked unscattered diffuse (in-frame constant control): gamma-space luminance
/// (emcv_adaptive_tracked).
///   spvg      moving mean/variance of f (eta 0.2)
///   cv        EMCM over (f, G) (eta 0.2), a change the control does not explain clipped (emcv_history_push_cv),
///             then the comoments scaled by `noise_ratio`, the tile's noise test (emcv_history_noise_ratio,
///             emcv_history_rescale_cv)
///   cv-notex  moving mean/variance of r = f - G (alpha = 1, eta 0.2), a change G does not explain clipped as
///             cv's (emcv_history_push_notex)
/// A pixel that took no samples learns nothing about its noise and is not pushed. A non-finite f or G is
/// refused by the port (state unchanged); a poisoned stored state is reset, never used.
void emcv_adaptive_update(ivec2 p, EmcvAdaptiveState s, float f, float g, uint n, float noise_ratio) {
    if (n == 0u) return;
#if defined(EMCV_ADAPTIVE_CV)
    emcv_history_push_cv(s, f, g, EMCV_HISTORY_ETA_EMCM, float(n));
    emcv_history_rescale_cv(s, noise_ratio);
#elif defined(EMCV_ADAPTIVE_NOTEX)
    emcv_history_push_notex(s, f, g, EMCV_HISTORY_ETA_MOVING, float(n));
#else
    emcv_moving_stats_push_batch(s, f, EMCV_HISTORY_ETA_MOVING, float(n));
#endif
    emcv_adaptive_store(p, s);
}

#if defined(EMCV_ADAPTIVE_TILE_UPDATE)
#if defined(EMCV_ADAPTIVE_CV)
// The tile's noise-test pool (emcv_history_noise_add's: sums of term units, of relative-variance units, pixels),
// added to with atomics: fixed-point sums are exact in any order.
shared uint tile_noise_pool[3];
#endif

/// The history update of the workgroup's 8x8 tile, pixel p of material `code` having taken n samples (0 off
/// screen and for pixels that do not scatter), its scattered and unscattered diffuse as the burley pass stored
/// them and its albedo: every invocation calls it, in uniform control flow (cv's noise test holds barriers). The state, f and
/// g are read once. cv: each pixel's noise-test term before its push (emcv_history_noise_term) and its relative
/// variance (emcv_history_noise_relative), in fixed-point units (emcv_history_noise_units), summed over the tile's
/// pixels that took samples, then the push and the rescale by the pool's ratio (emcv_history_noise_ratio,
/// emcv_adaptive_update); the other methods push as they are.
void emcv_adaptive_update_tile(ivec2 p, vec3 scattered, vec3 unscattered, vec3 albedo, uint n) {
    EmcvAdaptiveState s = emcv_adaptive_init();
    float f = 0.0f;
    float g = 0.0f;
    if (n > 0u) {
        s = emcv_adaptive_load(p);
        f = emcv_adaptive_tracked(albedo, scattered);
        g = emcv_adaptive_tracked(albedo, unscattered);
    }
#if defined(EMCV_ADAPTIVE_CV)
    if (gl_LocalInvocationIndex < 3u) tile_noise_pool[gl_LocalInvocationIndex] = 0u;
    memoryBarrierShared();
    barrier();
    float term = n > 0u ? emcv_history_noise_term(s, f, g, EMCV_HISTORY_ETA_EMCM, float(n)) : emcv_history_no_variance();
    uvec3 own = uvec3(0u);
    emcv_history_noise_add(own, term, emcv_history_noise_relative(float(max(n, 1u))));
    if (own.z != 0u) {
        atomicAdd(tile_noise_pool[0], own.x);
        atomicAdd(tile_noise_pool[1], own.y);
        atomicAdd(tile_noise_pool[2], own.z);
    }
    memoryBarrierShared();
    barrier();
    uvec3 pool = uvec3(tile_noise_pool[0], tile_noise_pool[1], tile_noise_pool[2]);
    emcv_adaptive_update(p, s, f, g, n, emcv_history_noise_ratio(pool));
#else
    emcv_adaptive_update(p, s, f, g, n, 1.0f);
#endif
}
#endif

#endif  // #ifndef EMCV_ADAPTIVE_HISTORY_IO_H
