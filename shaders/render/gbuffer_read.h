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
layout(EMCV_LAYOUT_BINDING(EMCV_RENDER_TEX_MOTION)) uniform sampler2D gbuffer_motion;

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

/// Where p's centre was in the previous frame, in pixels (the motion target holds current - previous): what the
/// passes that keep a history (the adaptive samples pass, the resolve) reproject from.
vec2 emcv_render_previous_position(ivec2 p) { return vec2(p) + 0.5f - texelFetch(gbuffer_motion, p, 0).xy; }
/// Where the surface point that p's centre shows this frame (the camera's jitter included) was shown in the
/// previous frame, in pixels: the position of the adaptive history, which holds statistics of that point. Without
/// jitter it is emcv_render_previous_position.
vec2 emcv_render_previous_sample_position(ivec2 p) {
    return emcv_render_previous_position(p) - (frame.jitter.xy - frame.jitter.zw);
}
/// The view depth that the surface seen at p (view depth z) had in the previous frame: its clip w under the
/// previous camera (objects do not move in the scene model). A history texel whose stored depth differs from it
/// shows another surface.
float emcv_render_previous_depth(ivec2 p, float z) {
    return (frame.prev_view_proj * vec4(emcv_render_world_position(p, z), 1.0f)).w;
}

#endif  // #ifndef EMCV_RENDER_GBUFFER_READ_H
