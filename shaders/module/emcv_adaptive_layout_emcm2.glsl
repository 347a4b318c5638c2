// SPDX-License-Identifier: MIT
// emcv_adaptive_layout_emcm2.glsl — cv's history layout (EMCV_ADAPTIVE_CV; the library's history_layout::emcm2):
// the EMCM over (f, G) (emcv/port/ema.h) in two texels per pixel or block, texel A (C_ff, C_fG, C_GG, count) in
// RGBA32F and texel B (mean_f, mean_G) in RG32F, and what only this layout does: the means' second texel, the
// tile's noise test before the push. emcv_adaptive_history.glsl includes it, or emcv_adaptive_layout_moving.glsl,
// which implements the same functions; every formula is the port's (emcv/port/history.h). No resources: the
// application's emcv_app_history_* functions (emcv_adaptive_history.glsl) load and store the texels.
#ifndef EMCV_ADAPTIVE_LAYOUT_H
#define EMCV_ADAPTIVE_LAYOUT_H

#define EMCV_ADAPTIVE_HISTORY_TEXELS 2            // texels A and B per pixel or block
#define EMCV_ADAPTIVE_HISTORY_FORMAT_A rgba32f    // the image formats the application binds them with
#define EMCV_ADAPTIVE_HISTORY_FORMAT_B rg32f
#define EmcvAdaptiveState EmcvEmcm2
#define EMCV_ADAPTIVE_ETA EMCV_HISTORY_ETA_EMCM  // the EMCM's weight
#define EMCV_ADAPTIVE_NOISE_TEST 1               // the tile's noise test before the push (below)
#define EMCV_ADAPTIVE_HISTORY_EXACT 1            // 32-bit texels: a stored state reads back as emcv_adaptive_as_stored

/// A fresh (reset) state.
EmcvAdaptiveState emcv_adaptive_init() { return emcv_emcm2_init(); }

/// Decodes raw history texels; false (state reset) when they are poisoned.
bool emcv_adaptive_decode(vec4 a, vec4 b, out EmcvAdaptiveState s) { return emcv_history_decode_emcm2(a, b.xy, s); }

void emcv_adaptive_store(ivec2 p, EmcvAdaptiveState s) {
    emcv_app_history_store_a(p, emcv_history_encode_emcm2_cov(s));
    emcv_app_history_store_b(p, vec4(emcv_history_encode_emcm2_means(s), 0.0f, 0.0f));
}

/// The state a load of what emcv_adaptive_store(p, s) stored decodes to (its texels read back bit for bit:
/// 32-bit formats), computed without the load; false (s reset) where that decode would find it poisoned.
bool emcv_adaptive_as_stored(inout EmcvAdaptiveState s) {
    return emcv_adaptive_decode(emcv_history_encode_emcm2_cov(s), vec4(emcv_history_encode_emcm2_means(s), 0.0f, 0.0f), s);
}

/// Stores texels as they were read (a kept history: no second rounding).
void emcv_adaptive_store_raw(ivec2 p, vec4 a, vec4 b) {
    emcv_app_history_store_a(p, a);
    emcv_app_history_store_b(p, b);
}

/// This frame's second texel at p (the means).
vec4 emcv_adaptive_load_b(ivec2 p) { return emcv_app_history_load_b(p); }

/// Last frame's second texel at q.
vec4 emcv_adaptive_previous_b(ivec2 q) { return emcv_app_history_previous_b(q); }

/// Resampling a reprojected history: adds w times a neighbour's means and comoments (not the count) to a running
/// blend (a fresh state, emcv_adaptive_init(), to start: its statistics are 0).
void emcv_adaptive_blend_add(inout EmcvAdaptiveState blend, float w, EmcvAdaptiveState s) {
    blend.mean += w * s.mean;
    blend.cov += w * s.cov;
}

/// The blend's statistics, divided by its weight, into state s (whose count and flags stay).
void emcv_adaptive_blend_finish(inout EmcvAdaptiveState s, EmcvAdaptiveState blend, float weight) {
    s.mean = blend.mean / weight;
    s.cov = blend.cov / weight;
}

/// The residual's per-sample variance at the EMCM's alpha (emcv_history_no_variance() before two frames).
float emcv_adaptive_sigma2(EmcvAdaptiveState s) { return emcv_history_sigma2_cv(s, EMCV_ADAPTIVE_ETA); }

/// Whether a kernel whose widest channel has shape distance `widest_d` (mm) covers under a pixel at
/// `pixels_per_mm`: there the control stands in for the scattered value and the block takes no samples.
bool emcv_adaptive_sub_pixel_kernel(float widest_d, float pixels_per_mm) {
    return emcv_history_sub_pixel(widest_d, pixels_per_mm);
}

/// The push of a block's batch (emcv_history_push_cv: a change the control does not explain clipped), then its
/// comoments scaled by the tile's noise test (emcv_history_rescale_cv).
void emcv_adaptive_push(inout EmcvAdaptiveState s, float f, float g, float batch, float noise_ratio) {
    emcv_history_push_cv(s, f, g, EMCV_ADAPTIVE_ETA, batch);
    emcv_history_rescale_cv(s, noise_ratio);
}

#if defined(EMCV_ADAPTIVE_TILE_UPDATE)
// The tile's noise-test pool (emcv_history_noise_add's: sums of term units, of relative-variance units, blocks),
// added to with atomics: fixed-point sums are exact in any order.
shared uint tile_noise_pool[3];

/// Clears the tile's pool (local invocation index `local`; the caller's barrier follows).
void emcv_adaptive_noise_clear(uint local) {
    if (local < 3u) tile_noise_pool[local] = 0u;
}

/// Adds a block's noise-test term before its push (emcv_history_noise_term) and the term's relative variance to
/// the tile's pool, where it has one (a history as old as its memory, a batch taken).
void emcv_adaptive_noise_add(EmcvAdaptiveState s, float f, float g, float batch) {
    float term = batch > 0.0f ? emcv_history_noise_term(s, f, g, EMCV_ADAPTIVE_ETA, batch) : emcv_history_no_variance();
    uvec3 own = uvec3(0u, 0u, 0u);
    emcv_history_noise_add(own, term, emcv_history_noise_relative(max(batch, 1.0f)));
    if (own.z != 0u) {
        EMCV_ATOMIC_ADD(tile_noise_pool[0], own.x);
        EMCV_ATOMIC_ADD(tile_noise_pool[1], own.y);
        EMCV_ATOMIC_ADD(tile_noise_pool[2], own.z);
    }
}

/// The ratio the tile's blocks scale their comoments by (emcv_history_noise_ratio), after the pool's barrier.
float emcv_adaptive_noise_ratio() {
    return emcv_history_noise_ratio(uvec3(tile_noise_pool[0], tile_noise_pool[1], tile_noise_pool[2]));
}
#endif

#endif  // #ifndef EMCV_ADAPTIVE_LAYOUT_H
