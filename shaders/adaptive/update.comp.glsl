// SPDX-License-Identifier: MIT
// shaders/adaptive/update.comp.glsl — the adaptive-update pass of every adaptive method (the renderer defines the
// method's EMCV_ADAPTIVE_* from its row of the method table): after the burley pass, each SSS pixel pushes this
// frame's values into its history as the mean of the N_t samples it took (include/emcv/port/ema.h, *_push_batch:
// the history estimates the per-sample variance, supp. Eq. 25-27): f = the scattered diffuse (the burley
// output), G = the unscattered diffuse (in-frame constant control), both as displayed gamma-space luminance.
//   spvg      moving mean/variance of f (eta 0.2)
//   cv        EMCM over (f, G) (eta 0.2), a change the control does not explain clipped (emcv_history_push_cv)
//   cv-notex  moving mean/variance of r = f - G (alpha = 1, eta 0.2)
// A pixel that took no samples learns nothing about its noise and is not pushed. A non-finite f or G is
// refused by the port (state unchanged); a poisoned stored state is reset, never used.
#version 450 core

#include "adaptive/history_io.h"
#include "render/tiles.h"

layout(local_size_x = EMCV_RENDER_TILE_SIZE, local_size_y = EMCV_RENDER_TILE_SIZE) in;

layout(EMCV_LAYOUT_BINDING(EMCV_RENDER_TEX_SSS_IN)) uniform sampler2D scattered_diffuse;

// The samples each pixel took this frame, as the burley pass wrote them (EMCV_RENDER_IMG_COUNT).
layout(r32ui, EMCV_LAYOUT_IMAGE_BINDING(EMCV_RENDER_IMG_COUNT)) readonly uniform uimage2D taken_samples;

void main() {
    ivec2 p = emcv_render_tile_pixel();
    if (!emcv_render_on_screen(p)) return;
    uint code = emcv_render_material_code(p);
    if (!emcv_render_scatters(code)) return;
#if defined(EMCV_ADAPTIVE_CV)
    vec4 b = imageLoad(history_b, p);
#else
    vec4 b = vec4(0.0f);
#endif
    EmcvAdaptiveState s;
    emcv_adaptive_decode(imageLoad(history_a, p), b, s);  // a poisoned texel decodes as a fresh state
    uint n = imageLoad(taken_samples, p).x;
    if (n > 0u) {
        float f = emcv_adaptive_tracked(p, texelFetch(scattered_diffuse, p, 0).xyz);
        float g = emcv_adaptive_tracked(p, texelFetch(lit_diffuse, p, 0).xyz);
#if defined(EMCV_ADAPTIVE_CV)
        emcv_history_push_cv(s, f, g, EMCV_HISTORY_ETA_EMCM, float(n));
#elif defined(EMCV_ADAPTIVE_NOTEX)
        emcv_moving_stats_push_batch(s, emcv_cv_residual(f, 1.0f, g), EMCV_HISTORY_ETA_MOVING, float(n));
#else
        emcv_moving_stats_push_batch(s, f, EMCV_HISTORY_ETA_MOVING, float(n));
#endif
        emcv_adaptive_store(p, s);
    }
}
