// SPDX-License-Identifier: MIT
// An engine's side of emcv's installed GPU modules (<prefix>/share/emcv/module): its own bindings, budget block
// (EMCV_APP_BUDGET) and emcv_app_* functions. A still camera over one flat surface: a pixel's previous position is
// the pixel, the surface test passes where the material matches. The includer puts `#version 450 core`, the
// method's define (EMCV_ADAPTIVE_CV, _SPVG or _NOTEX) and EMCV_HISTORY_SPP_BUDGET first.
#include "emcv/port/history.h"

layout(std430, binding = 0) buffer AppBudget { EmcvBudgetBlock app_budget; };
#define EMCV_APP_BUDGET app_budget
layout(std140, binding = 1) uniform AppFrame {
    uvec4 app_frame;  // frame index, seed, width, height
};

#include "module/emcv_adaptive_plan.glsl"

// This frame's history (images) and last frame's (textures), in the layout's formats; swapped every frame.
layout(EMCV_ADAPTIVE_HISTORY_FORMAT_A, binding = 2) coherent uniform image2D app_history_a;
layout(binding = 6) uniform sampler2D app_previous_a;
vec4 emcv_app_history_load_a(ivec2 t) { return imageLoad(app_history_a, t); }
void emcv_app_history_store_a(ivec2 t, vec4 v) { imageStore(app_history_a, t, v); }
vec4 emcv_app_history_previous_a(ivec2 t) { return texelFetch(app_previous_a, t, 0); }
#if EMCV_ADAPTIVE_HISTORY_TEXELS == 2
layout(EMCV_ADAPTIVE_HISTORY_FORMAT_B, binding = 3) coherent uniform image2D app_history_b;
layout(binding = 7) uniform sampler2D app_previous_b;
vec4 emcv_app_history_load_b(ivec2 t) { return imageLoad(app_history_b, t); }
void emcv_app_history_store_b(ivec2 t, vec4 v) { imageStore(app_history_b, t, v); }
vec4 emcv_app_history_previous_b(ivec2 t) { return texelFetch(app_previous_b, t, 0); }
#endif

// The plan (budget mode: each block's shrunk variance as float bits) and the samples each pixel took.
layout(r32ui, binding = 4) coherent uniform uimage2D app_plan;
layout(r32ui, binding = 5) coherent uniform uimage2D app_taken;
// The surface's material id (0: does not scatter), the same in every frame.
layout(binding = 8) uniform usampler2D app_material;

ivec2 emcv_app_viewport_size() { return ivec2(app_frame.zw); }
vec2 emcv_app_previous_position(ivec2 p) { return vec2(p) + 0.5f; }  // a still camera
float emcv_app_expected_previous_depth(ivec2 p) { return 1.0f; }
vec3 emcv_app_normal(ivec2 p) { return vec3(0.0f, 0.0f, 1.0f); }
uint emcv_app_previous_material(ivec2 q) { return texelFetch(app_material, q, 0).x; }
float emcv_app_previous_depth(ivec2 q) { return 1.0f; }
vec3 emcv_app_previous_normal(ivec2 q) { return vec3(0.0f, 0.0f, 1.0f); }
void emcv_app_store_plan(ivec2 t, uint v) { imageStore(app_plan, t, uvec4(v)); }
uint emcv_app_load_plan(ivec2 t) { return imageLoad(app_plan, t).x; }

/// Whether p's kernel is under a pixel (the layout's test, at 1 pixel/mm): the last column's widest d is 0.01 mm.
bool app_sub_pixel(ivec2 p) { return emcv_adaptive_sub_pixel_kernel(p.x == int(app_frame.z) - 1 ? 0.01f : 1.0f, 1.0f); }

/// Pixel p's material id, 0 off screen.
uint app_code(ivec2 p) { return emcv_adaptive_on_screen(p) ? texelFetch(app_material, p, 0).x : 0u; }
