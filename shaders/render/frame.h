// SPDX-License-Identifier: MIT
// shaders/render/frame.h — the renderer's frame, light and material blocks as the GLSL passes declare them;
// their structs are defined once for C++ and GLSL in render/blocks.h.
#ifndef EMCV_RENDER_FRAME_H
#define EMCV_RENDER_FRAME_H

#include "emcv/port/bindings.h"
#include "render/bindings.h"
#include "render/blocks.h"

layout(std140, EMCV_LAYOUT_BINDING(EMCV_RENDER_FRAME)) uniform Frame {
    EmcvFrameBlock frame;
};

layout(std430, EMCV_LAYOUT_BINDING(EMCV_RENDER_LIGHTS)) readonly buffer Lights {
    EmcvLight lights[];
};

layout(std430, EMCV_LAYOUT_BINDING(EMCV_RENDER_MATERIALS)) readonly buffer Materials {
    EmcvMaterial materials[];
};

/// True when the G-buffer's material code (index + 1, 0 = background) names a scattering material.
bool emcv_render_scatters(uint material_code) {
    return material_code != 0u &&
           int(materials[material_code - 1u].albedo.w) == EMCV_RENDER_MATERIAL_SSS;
}

/// Linear view depth z of a pixel centre -> world position (the G-buffer stores z, > 0 in front).
vec3 emcv_render_world_position(ivec2 pixel, float z) {
    // The pixel's centre less the camera's jitter: where the surface it shows lies in the unjittered view.
    vec2 ndc = (vec2(pixel) + 0.5f - frame.jitter.xy) * frame.viewport.zw * 2.0f - 1.0f;
    vec4 view_position = vec4(ndc.x * z / frame.projection.x, ndc.y * z / frame.projection.y, -z, 1.0f);
    return (frame.inv_view * view_position).xyz;
}

#endif  // #ifndef EMCV_RENDER_FRAME_H
