// SPDX-License-Identifier: MIT
// Shadow pass, vertex stage: one light's view-projection (orthographic for directional, perspective for spot).
#version 450 core

#include "render/objects.h"

layout(std140, EMCV_LAYOUT_BINDING(EMCV_RENDER_PASS)) uniform Pass {
    EmcvPassBlock pass;  // ints.x: light index
};

layout(location = EMCV_RENDER_ATTRIB_POSITION) in vec3 in_position;
layout(location = EMCV_RENDER_ATTRIB_OBJECT) in uint in_object;

void main() {
    gl_Position = lights[pass.ints.x].shadow_view_proj * (objects[in_object].model * vec4(in_position, 1.0f));
}
