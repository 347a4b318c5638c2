// SPDX-License-Identifier: MIT
// Test probe (tests/adaptive/test_history_gpu.cpp): the history update that the adaptive burley pass runs after
// its sampling loop (emcv_adaptive_update_tile, adaptive/history_io.h), fed with given values instead: the scattered
// diffuse from a texture and the samples taken from an image, so that the GPU's estimators can be compared with
// the C++ ones on chosen streams.
#version 450 core

#define EMCV_ADAPTIVE_TILE_UPDATE 1
#include "adaptive/history_io.h"
#include "render/tiles.h"

layout(local_size_x = EMCV_RENDER_TILE_SIZE, local_size_y = EMCV_RENDER_TILE_SIZE) in;

layout(EMCV_LAYOUT_BINDING(EMCV_RENDER_TEX_SSS_IN)) uniform sampler2D scattered_diffuse;
layout(r32ui, EMCV_LAYOUT_IMAGE_BINDING(EMCV_RENDER_IMG_COUNT)) readonly uniform uimage2D taken_samples;

void main() {
    ivec2 p = emcv_render_tile_pixel();
    // Every invocation reaches the update (cv's noise test holds a barrier); pixels that do not scatter take 0.
    uint code = emcv_render_on_screen(p) ? emcv_render_material_code(p) : 0u;
    bool scatters = code != 0u && emcv_render_scatters(code);
    uint n = scatters ? imageLoad(taken_samples, p).x : 0u;
    vec3 scattered = scatters ? texelFetch(scattered_diffuse, p, 0).xyz : vec3(0.0f);
    vec3 unscattered = scatters ? texelFetch(lit_diffuse, p, 0).xyz : vec3(0.0f);
    vec3 albedo = scatters ? texelFetch(gbuffer_albedo, p, 0).xyz : vec3(0.0f);
    emcv_adaptive_update_tile_diffuse(gl_LocalInvocationIndex, emcv_adaptive_tile_origin(p), scattered, unscattered, albedo, n);
}
