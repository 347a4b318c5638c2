// SPDX-License-Identifier: MIT
// shaders/adaptive/history_io.h — the history images of one adaptive method, chosen by the define the renderer
// passes from the method's row: EMCV_ADAPTIVE_SPVG, EMCV_ADAPTIVE_CV or EMCV_ADAPTIVE_NOTEX, and their load/store in the port's types
// (include/emcv/port/history.h holds the layouts and every formula).
#ifndef EMCV_ADAPTIVE_HISTORY_IO_H
#define EMCV_ADAPTIVE_HISTORY_IO_H

#include "emcv/port/history.h"
#include "adaptive/bindings.h"
#include "render/gbuffer_read.h"

#if defined(EMCV_ADAPTIVE_CV)
layout(rgba32f, EMCV_LAYOUT_IMAGE_BINDING(EMCV_ADAPTIVE_IMG_HISTORY_A)) uniform image2D history_a;
layout(rg32f, EMCV_LAYOUT_IMAGE_BINDING(EMCV_ADAPTIVE_IMG_HISTORY_B)) uniform image2D history_b;
#define EmcvAdaptiveState EmcvEmcm2
#elif defined(EMCV_ADAPTIVE_SPVG) || defined(EMCV_ADAPTIVE_NOTEX)
layout(rgba16f, EMCV_LAYOUT_IMAGE_BINDING(EMCV_ADAPTIVE_IMG_HISTORY_A)) uniform image2D history_a;
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

/// The method's sample count from its state.
int emcv_adaptive_count(EmcvAdaptiveState s) {
#if defined(EMCV_ADAPTIVE_CV)
    return emcv_history_count_cv(s);
#elif defined(EMCV_ADAPTIVE_NOTEX)
    return emcv_history_count_notex(s);
#else
    return emcv_history_count_spvg(s);
#endif
}

/// The pixel's diffuse as displayed before the tonemap (albedo * irradiance * exposure), as gamma luminance.
float emcv_adaptive_tracked(ivec2 p, vec3 irradiance) {
    vec3 albedo = texelFetch(gbuffer_albedo, p, 0).xyz;
    return emcv_gamma_luminance(albedo * irradiance * frame.background.w);
}

#endif  // #ifndef EMCV_ADAPTIVE_HISTORY_IO_H
