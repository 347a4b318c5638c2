// SPDX-License-Identifier: MIT
// shaders/render/gbuffer_read.h — the G-buffer and lighting targets as textures read with texelFetch.
#ifndef EMCV_RENDER_GBUFFER_READ_H
#define EMCV_RENDER_GBUFFER_READ_H

#include "render/frame.h"

layout(EMCV_LAYOUT_BINDING(EMCV_RENDER_TEX_DEPTH)) uniform sampler2D gbuffer_depth;
layout(EMCV_LAYOUT_BINDING(EMCV_RENDER_TEX_NORMAL)) uniform sampler2D gbuffer_normal;
layout(EMCV_LAYOUT_BINDING(EMCV_RENDER_TEX_ALBEDO)) uniform sampler2D gbuffer_albedo;
layout(EMCV_LAYOUT_BINDING(EMCV_RENDER_TEX_MATERIAL)) uniform usampler2D gbuffer_material;
layout(EMCV_LAYOUT_BINDING(EMCV_RENDER_TEX_DIFFUSE)) uniform sampler2D lit_diffuse;
layout(EMCV_LAYOUT_BINDING(EMCV_RENDER_TEX_SPECULAR)) uniform sampler2D lit_specular;

bool emcv_render_on_screen(ivec2 p) {
    return p.x >= 0 && p.y >= 0 && p.x < int(frame.viewport.x) && p.y < int(frame.viewport.y);
}

uint emcv_render_material_code(ivec2 p) { return texelFetch(gbuffer_material, p, 0).x; }
/// Linear view depth at p (0 for the background). The G-buffer stores it signed with the scatter flag.
float emcv_render_depth(ivec2 p) { return abs(texelFetch(gbuffer_depth, p, 0).x); }
/// The depth at q if q is on screen and its material scatters, else 0 (what an SSS sample needs of the point it
/// lands on, in one fetch: the G-buffer's depth is positive exactly where the material scatters).
float emcv_render_scattering_depth(ivec2 q) {
    if (!emcv_render_on_screen(q)) return 0.0f;
    return max(texelFetch(gbuffer_depth, q, 0).x, 0.0f);
}

#endif  // #ifndef EMCV_RENDER_GBUFFER_READ_H
