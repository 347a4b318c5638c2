// SPDX-License-Identifier: MIT
// emcv_adaptive_layout_moving.glsl — the moving-statistics history layout (EMCV_ADAPTIVE_SPVG, EMCV_ADAPTIVE_NOTEX;
// the library's history_layout::moving_stats): a moving mean and variance of one scalar (emcv/port/ema.h) in one
// RGBA16F texel A per pixel or block, for spvg (the scalar is f) and cv-notex (the residual f - G, alpha = 1).
// emcv_adaptive_history.glsl includes it, or emcv_adaptive_layout_emcm2.glsl, which implements the same functions;
// every formula is the port's (emcv/port/history.h). It has no second texel and no noise test (the hooks below
// do nothing). No resources: the application's emcv_app_history_*_a functions load and store the texel.
#ifndef EMCV_ADAPTIVE_LAYOUT_H
#define EMCV_ADAPTIVE_LAYOUT_H

#define EMCV_ADAPTIVE_HISTORY_TEXELS 1            // texel A only
#define EMCV_ADAPTIVE_HISTORY_FORMAT_A rgba16f    // the image format the application binds it with
#define EmcvAdaptiveState EmcvMovingStats
#define EMCV_ADAPTIVE_ETA EMCV_HISTORY_ETA_MOVING  // the moving statistics' weight
#define EMCV_ADAPTIVE_NOISE_TEST 0                 // no noise test: the hooks below do nothing
#define EMCV_ADAPTIVE_HISTORY_EXACT 0              // binary16 texels: a stored state is read back to know it

/// A fresh (reset) state.
EmcvAdaptiveState emcv_adaptive_init() { return emcv_moving_stats_init(); }

/// Decodes a raw history texel (b unused); false (state reset) when it is poisoned.
bool emcv_adaptive_decode(vec4 a, vec4 b, out EmcvAdaptiveState s) { return emcv_history_decode_stats(a, s); }

void emcv_adaptive_store(ivec2 p, EmcvAdaptiveState s) { emcv_app_history_store_a(p, emcv_history_encode_stats(s)); }

/// Stores the texel as it was read (a kept history: no second rounding).
void emcv_adaptive_store_raw(ivec2 p, vec4 a, vec4 b) { emcv_app_history_store_a(p, a); }

/// No second texel: zeros.
vec4 emcv_adaptive_load_b(ivec2 p) { return vec4(0.0f, 0.0f, 0.0f, 0.0f); }
vec4 emcv_adaptive_previous_b(ivec2 q) { return vec4(0.0f, 0.0f, 0.0f, 0.0f); }

/// Resampling a reprojected history: adds w times a neighbour's mean and variance (not the count) to a running
/// blend (a fresh state, emcv_adaptive_init(), to start: its statistics are 0).
void emcv_adaptive_blend_add(inout EmcvAdaptiveState blend, float w, EmcvAdaptiveState s) {
    blend.mean += w * s.mean;
    blend.variance += w * s.variance;
}

/// The blend's statistics, divided by its weight, into state s (whose count and flags stay).
void emcv_adaptive_blend_finish(inout EmcvAdaptiveState s, EmcvAdaptiveState blend, float weight) {
    s.mean = blend.mean / weight;
    s.variance = blend.variance / weight;
}

/// The scalar's per-sample variance (emcv_history_no_variance() before two frames).
float emcv_adaptive_sigma2(EmcvAdaptiveState s) { return emcv_history_sigma2_moving(s, EMCV_ADAPTIVE_ETA); }

/// Whether a kernel whose widest channel has shape distance `widest_d` (mm) covers under a pixel at
/// `pixels_per_mm`, where cv-notex takes no samples (its control stands in for the scattered value); spvg never
/// skips: it has no control to stand in.
bool emcv_adaptive_sub_pixel_kernel(float widest_d, float pixels_per_mm) {
#if defined(EMCV_ADAPTIVE_NOTEX)
    return emcv_history_sub_pixel(widest_d, pixels_per_mm);
#else
    return false;
#endif
}

/// The push of a block's batch: cv-notex the residual f - G with cv's change test at alpha = 1
/// (emcv_history_push_notex), spvg f itself (emcv_moving_stats_push_batch). No noise test: noise_ratio is 1.
void emcv_adaptive_push(inout EmcvAdaptiveState s, float f, float g, float batch, float noise_ratio) {
#if defined(EMCV_ADAPTIVE_NOTEX)
    emcv_history_push_notex(s, f, g, EMCV_ADAPTIVE_ETA, batch);
#else
    emcv_moving_stats_push_batch(s, f, EMCV_ADAPTIVE_ETA, batch);
#endif
}

#if defined(EMCV_ADAPTIVE_TILE_UPDATE)
// No noise test in this layout.
void emcv_adaptive_noise_clear(uint local) {}
void emcv_adaptive_noise_add(EmcvAdaptiveState s, float f, float g, float batch) {}
float emcv_adaptive_noise_ratio() { return 1.0f; }
#endif

#endif  // #ifndef EMCV_ADAPTIVE_LAYOUT_H
