// SPDX-License-Identifier: MIT
// shaders/adaptive/history_io.h — the renderer's side of the installed module module/emcv_adaptive_history.glsl
// (the history of the adaptive method whose define the renderer passes from its row of the method table,
// EMCV_ADAPTIVE_SPVG, EMCV_ADAPTIVE_CV or EMCV_ADAPTIVE_NOTEX): the module's emcv_app_* functions over the
// renderer's history images and textures (adaptive/bindings.h), the samples image, and what the renderer itself
// computes per pixel (the sub-pixel test from the Burley taps, the tracked values from its exposure). The module
// is the one implementation; this file is the reference integration of it.
#ifndef EMCV_ADAPTIVE_HISTORY_IO_H
#define EMCV_ADAPTIVE_HISTORY_IO_H

#include "emcv/port/bindings.h"
#include "emcv/port/sss.h"
#include "adaptive/bindings.h"
#include "render/burley_taps.h"
#include "render/gbuffer_read.h"

#define EMCV_ADAPTIVE_TILE_SIZE EMCV_RENDER_TILE_SIZE
#include "module/emcv_adaptive_history.glsl"

// This frame's history (coherent: under a quality target the burley pass plans a block's history and updates it
// in the invocation that holds the block, after the tile's sort hands the pixels out, sss_burley.comp.glsl) and
// last frame's, in the layout's formats.
layout(EMCV_ADAPTIVE_HISTORY_FORMAT_A, EMCV_LAYOUT_IMAGE_BINDING(EMCV_ADAPTIVE_IMG_HISTORY_A)) coherent uniform image2D history_a;
layout(EMCV_LAYOUT_BINDING(EMCV_ADAPTIVE_TEX_HISTORY_PREV_A)) uniform sampler2D history_prev_a;
vec4 emcv_app_history_load_a(ivec2 t) { return imageLoad(history_a, t); }
void emcv_app_history_store_a(ivec2 t, vec4 v) { imageStore(history_a, t, v); }
vec4 emcv_app_history_previous_a(ivec2 t) { return texelFetch(history_prev_a, t, 0); }
#if EMCV_ADAPTIVE_HISTORY_TEXELS == 2
layout(EMCV_ADAPTIVE_HISTORY_FORMAT_B, EMCV_LAYOUT_IMAGE_BINDING(EMCV_ADAPTIVE_IMG_HISTORY_B)) coherent uniform image2D history_b;
layout(EMCV_LAYOUT_BINDING(EMCV_ADAPTIVE_TEX_HISTORY_PREV_B)) uniform sampler2D history_prev_b;
vec4 emcv_app_history_load_b(ivec2 t) { return imageLoad(history_b, t); }
void emcv_app_history_store_b(ivec2 t, vec4 v) { imageStore(history_b, t, v); }
vec4 emcv_app_history_previous_b(ivec2 t) { return texelFetch(history_prev_b, t, 0); }
#endif

ivec2 emcv_app_viewport_size() { return ivec2(frame.viewport.xy); }

layout(r32ui, EMCV_LAYOUT_IMAGE_BINDING(EMCV_ADAPTIVE_IMG_SAMPLES)) uniform uimage2D samples_image;

/// emcv_adaptive_sub_pixel_kernel at scattering pixel p of material `code`, from the taps' setup there.
bool emcv_adaptive_sub_pixel(ivec2 p, uint code) {
    EmcvBurleyPixel px = emcv_render_burley_pixel(p, code);
    return emcv_adaptive_sub_pixel_kernel(px.d_sample, px.pixels_per_mm);
}

/// A pixel's diffuse as displayed before the tonemap (albedo * irradiance * exposure), as gamma luminance: the
/// tracked value of emcv_adaptive_update_tile (the caller passes the pixel's albedo, read once).
float emcv_adaptive_tracked(vec3 albedo, vec3 irradiance) {
    return emcv_gamma_luminance(albedo * irradiance * frame.background.w);
}

#if defined(EMCV_ADAPTIVE_TILE_UPDATE)
/// emcv_adaptive_update_tile from a pixel's scattered and unscattered diffuse as the burley pass stored them and
/// its albedo (tracked by emcv_adaptive_tracked where it took samples).
void emcv_adaptive_update_tile_diffuse(uint local, ivec2 origin, vec3 scattered, vec3 unscattered, vec3 albedo,
                                       uint n) {
    float f = 0.0f;
    float g = 0.0f;
    if (n > 0u) {
        f = emcv_adaptive_tracked(albedo, scattered);
        g = emcv_adaptive_tracked(albedo, unscattered);
    }
    emcv_adaptive_update_tile(local, origin, f, g, n);
}
#endif

#endif  // #ifndef EMCV_ADAPTIVE_HISTORY_IO_H
