// SPDX-License-Identifier: MIT
// G-buffer pass, fragment stage: linear view depth (R32F) signed with whether the material scatters (positive:
// it does; negative: it does not; 0 stays the background's), world normal, albedo with its texture, material
// code (index + 1; 0 stays the background's) and motion in pixels from the previous frame. The sign lets an SSS
// sample test its point and read its depth with one fetch (gbuffer_read.h, emcv_render_scattering_depth).
#version 450 core

#include "render/frame.h"

layout(EMCV_LAYOUT_BINDING(EMCV_RENDER_TEX_ALBEDO_MAP)) uniform sampler2D albedo_map;

layout(location = 0) in vec3 v_normal;
layout(location = 1) in vec2 v_uv;
layout(location = 2) in float v_view_depth;
layout(location = 3) in vec4 v_clip;
layout(location = 4) in vec4 v_prev_clip;
layout(location = 5) flat in uint v_material;

layout(location = 0) out float out_depth;
layout(location = 1) out vec4 out_normal;
layout(location = 2) out vec4 out_albedo;
layout(location = 3) out uint out_material;
layout(location = 4) out vec2 out_motion;

void main() {
    vec3 n = normalize(v_normal);
    if (!gl_FrontFacing) n = -n;  // open meshes (planes) seen from behind
    bool scatters = int(materials[v_material].albedo.w) == EMCV_RENDER_MATERIAL_SSS;
    out_depth = scatters ? v_view_depth : -v_view_depth;
    out_normal = vec4(n, 0.0f);
    out_albedo = vec4(materials[v_material].albedo.xyz * texture(albedo_map, v_uv).xyz, 1.0f);
    out_material = v_material + 1u;
    vec2 ndc = v_clip.xy / v_clip.w;
    vec2 prev_ndc = v_prev_clip.xy / v_prev_clip.w;
    // Less the change of the camera's jitter: the motion of the surface in the unjittered view, 0 for a still
    // camera (what the resolve's history of the pixel reprojects with).
    out_motion = (ndc - prev_ndc) * 0.5f * frame.viewport.xy - (frame.jitter.xy - frame.jitter.zw);
}
