// SPDX-License-Identifier: MIT
// G-buffer pass, vertex stage: world position, normal, uv, linear view depth and both frames' clip positions.
#version 450 core

#include "render/objects.h"

layout(location = EMCV_RENDER_ATTRIB_POSITION) in vec3 in_position;
layout(location = EMCV_RENDER_ATTRIB_NORMAL) in vec3 in_normal;
layout(location = EMCV_RENDER_ATTRIB_UV) in vec2 in_uv;
layout(location = EMCV_RENDER_ATTRIB_OBJECT) in uint in_object;

layout(location = 0) out vec3 v_normal;
layout(location = 1) out vec2 v_uv;
layout(location = 2) out float v_view_depth;
layout(location = 3) out vec4 v_clip;
layout(location = 4) out vec4 v_prev_clip;
layout(location = 5) flat out uint v_material;

void main() {
    EmcvObject o = objects[in_object];
    vec4 world = o.model * vec4(in_position, 1.0f);
    v_normal = (o.normal_matrix * vec4(in_normal, 0.0f)).xyz;
    v_uv = in_uv;
    v_view_depth = -(frame.view * world).z;
    v_clip = frame.view_proj * world;
    // Objects do not move in this scene model (scene.hpp): the previous world position is this one.
    v_prev_clip = frame.prev_view_proj * world;
    v_material = uint(o.material.x);
    gl_Position = v_clip;
}
