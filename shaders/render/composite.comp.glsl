// SPDX-License-Identifier: MIT
// Composite and tonemap: albedo * (scattered diffuse at SSS pixels when the SSS pass ran, else the lighting's
// diffuse) + specular (post-scatter texturing, docs/frame.md), the background elsewhere; then the scene's
// exposure, the tonemap and the sRGB encoding of include/emcv/port/tonemap.h.
#version 450 core

#include "emcv/port/tonemap.h"
#include "render/gbuffer_read.h"

layout(local_size_x = EMCV_RENDER_TILE_SIZE, local_size_y = EMCV_RENDER_TILE_SIZE) in;

layout(EMCV_LAYOUT_BINDING(EMCV_RENDER_TEX_SSS_IN)) uniform sampler2D scattered;
layout(rgba16f, EMCV_LAYOUT_IMAGE_BINDING(EMCV_RENDER_IMG_LINEAR)) writeonly uniform image2D out_linear;
layout(rgba8, EMCV_LAYOUT_IMAGE_BINDING(EMCV_RENDER_IMG_DISPLAY)) writeonly uniform image2D out_display;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (!emcv_render_on_screen(p)) return;
    uint code = emcv_render_material_code(p);
    vec3 color = frame.background.xyz;
    if (code != 0u) {
        bool sss_ran = (frame.counters.w & EMCV_RENDER_FLAG_SSS_RAN) != 0u;
        vec3 diffuse = (sss_ran && emcv_render_scatters(code)) ? texelFetch(scattered, p, 0).xyz
                                                               : texelFetch(lit_diffuse, p, 0).xyz;
        color = texelFetch(gbuffer_albedo, p, 0).xyz * diffuse + texelFetch(lit_specular, p, 0).xyz;
    }
    imageStore(out_linear, p, vec4(color, 1.0f));
    imageStore(out_display, p, vec4(emcv_display_encode(color * frame.background.w, int(frame.ambient.w)), 1.0f));
}
