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

/// The method's per-sample variance from its state (emcv_history_no_variance() before two frames): spvg f's,
/// cv the residual's at the EMCM's alpha, cv-notex the residual's at alpha = 1.
float emcv_adaptive_sigma2(EmcvAdaptiveState s) {
#if defined(EMCV_ADAPTIVE_CV)
    return emcv_history_sigma2_cv(s, EMCV_HISTORY_ETA_EMCM);
#else
    return emcv_history_sigma2_moving(s, EMCV_HISTORY_ETA_MOVING);
#endif
}

/// Whether the pixel's kernel is under a pixel, where the control-variate methods take no samples (spvg never
/// skips: it has no control to stand in for the scattered value).
bool emcv_adaptive_sub_pixel(ivec2 p, uint code) {
#if defined(EMCV_ADAPTIVE_CV) || defined(EMCV_ADAPTIVE_NOTEX)
    vec3 d = emcv_sss_shape_distance(materials[code - 1u].mean_free_path.xyz, texelFetch(gbuffer_albedo, p, 0).xyz);
    float pixels_per_mm = emcv_sss_pixels_per_mm(frame.projection.x, frame.viewport.x, emcv_render_depth(p),
                                                 frame.camera_position.w);
    return emcv_history_sub_pixel(emcv_sss_widest(d), pixels_per_mm);
#else
    return false;
#endif
}

/// The pixel's diffuse as displayed before the tonemap (albedo * irradiance * exposure), as gamma luminance.
float emcv_adaptive_tracked(ivec2 p, vec3 irradiance) {
    vec3 albedo = texelFetch(gbuffer_albedo, p, 0).xyz;
    return emcv_gamma_luminance(albedo * irradiance * frame.background.w);
}

#endif  // #ifndef EMCV_ADAPTIVE_HISTORY_IO_H
