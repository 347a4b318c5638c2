// SPDX-License-Identifier: MIT
// shaders/adaptive/bindings.h — binding slots of the adaptive passes (spvg, cv, cv-notex), read by the host
// (demo/render/adaptive, C++) and the GLSL passes. They use the slots render/bindings.h leaves free (18, 19,
// 26-28; image units 2-4, see render/bindings.h) and the renderer's own slots for what they share with it
// (G-buffer, lighting, motion, the SSS output bound at EMCV_RENDER_TEX_SSS_IN, the tile list).
#ifndef EMCV_ADAPTIVE_BINDINGS_H
#define EMCV_ADAPTIVE_BINDINGS_H

#include "render/bindings.h"

// Textures read with texelFetch: last frame's history and G-buffer (the reprojection source)
#define EMCV_ADAPTIVE_TEX_HISTORY_PREV_A 18   // spvg, cv-notex: RGBA16F stats; cv: RGBA32F (C_ff, C_fG, C_GG, count)
#define EMCV_ADAPTIVE_TEX_HISTORY_PREV_B 19   // cv: RG32F (mean_f, mean_G); unused otherwise
#define EMCV_ADAPTIVE_TEX_PREV_DEPTH 26       // last frame's linear view depth (R32F)
#define EMCV_ADAPTIVE_TEX_PREV_NORMAL 27      // last frame's world normal (RGBA16F)
#define EMCV_ADAPTIVE_TEX_PREV_MATERIAL 28    // last frame's material index + 1 (R8UI)

// Buffers
// storage: the budget's sigma histogram and solved scale (emcv/port/budget.h). The separable kernels' slot: no
// frame runs a separable pass and an adaptive one, and each adaptive pass binds it before its dispatch.
#define EMCV_ADAPTIVE_BUDGET EMCV_RENDER_KERNELS

// Images: this frame's history (written by adaptive-samples, updated in place by the adaptive burley pass) and N
#define EMCV_ADAPTIVE_IMG_SAMPLES 2           // samples per pixel for the burley pass (R32UI)
#define EMCV_ADAPTIVE_IMG_HISTORY_A 3
#define EMCV_ADAPTIVE_IMG_HISTORY_B 4

#endif  // #ifndef EMCV_ADAPTIVE_BINDINGS_H
