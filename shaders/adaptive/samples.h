// SPDX-License-Identifier: MIT
// shaders/adaptive/samples.h — the renderer's side of the installed module module/emcv_adaptive_plan.glsl (what
// decides an adaptive method's N at its pixels, for the two programs that plan counts): the module's emcv_app_*
// functions over the renderer's G-buffer, last frame's G-buffer (adaptive/bindings.h) and the samples image, and
// what each pixel shares with its tile.
//   adaptive/samples.comp.glsl  budget mode: the samples pass before the burley pass (the frame's histogram and
//                               its solve need every pixel's variance before any pixel's N)
//   render/sss_burley.comp.glsl quality target: at the top of the method's burley program, which then samples
//                               and updates the history in the same dispatch (N needs only the pixel's tile)
#ifndef EMCV_ADAPTIVE_SAMPLES_H
#define EMCV_ADAPTIVE_SAMPLES_H

#include "adaptive/history_io.h"
#include "adaptive/budget_block.h"
#include "render/tiles.h"
#include "module/emcv_adaptive_plan.glsl"

layout(EMCV_LAYOUT_BINDING(EMCV_ADAPTIVE_TEX_PREV_DEPTH)) uniform sampler2D prev_depth;
layout(EMCV_LAYOUT_BINDING(EMCV_ADAPTIVE_TEX_PREV_NORMAL)) uniform sampler2D prev_normal;
layout(EMCV_LAYOUT_BINDING(EMCV_ADAPTIVE_TEX_PREV_MATERIAL)) uniform usampler2D prev_material;

vec2 emcv_app_previous_position(ivec2 p) { return emcv_render_previous_sample_position(p); }
float emcv_app_expected_previous_depth(ivec2 p) { return emcv_render_previous_depth(p, emcv_render_depth(p)); }
vec3 emcv_app_normal(ivec2 p) { return texelFetch(gbuffer_normal, p, 0).xyz; }
uint emcv_app_previous_material(ivec2 q) { return texelFetch(prev_material, q, 0).x; }
float emcv_app_previous_depth(ivec2 q) { return abs(texelFetch(prev_depth, q, 0).x); }  // stored signed
vec3 emcv_app_previous_normal(ivec2 q) { return texelFetch(prev_normal, q, 0).xyz; }
void emcv_app_store_plan(ivec2 texel, uint value) { imageStore(samples_image, texel, uvec4(value)); }
uint emcv_app_load_plan(ivec2 texel) { return imageLoad(samples_image, texel).x; }

/// p's material code where p is on screen and scatters, else 0.
uint emcv_adaptive_scattering_code(ivec2 p) {
    if (!emcv_render_on_screen(p)) return 0u;
    uint code = emcv_render_material_code(p);
    return emcv_render_scatters(code) ? code : 0u;
}

/// Shares pixel p's material code (0: off screen or not scattering) and sub-pixel test with its tile, at its
/// local index: what emcv_adaptive_block reads once the caller's barrier() has followed.
void emcv_adaptive_share_pixel_of(ivec2 p) {
    uint code = emcv_adaptive_scattering_code(p);
    emcv_adaptive_share_pixel(gl_LocalInvocationIndex, code, code != 0u && emcv_adaptive_sub_pixel(p, code));
}

#endif  // #ifndef EMCV_ADAPTIVE_SAMPLES_H
