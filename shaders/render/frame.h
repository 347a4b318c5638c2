// SPDX-License-Identifier: MIT
// shaders/render/frame.h — the renderer's shared resource blocks (GLSL only). The host mirrors each block in
// demo/render/gpu_types.hpp (std140 / std430, vec4 and mat4 members only, so both layouts agree).
#ifndef EMCV_RENDER_FRAME_H
#define EMCV_RENDER_FRAME_H

#include "emcv/port/bindings.h"
#include "render/bindings.h"

layout(std140, EMCV_LAYOUT_BINDING(EMCV_RENDER_FRAME)) uniform Frame {
    mat4 view;
    mat4 proj;
    mat4 view_proj;
    mat4 prev_view_proj;   // the previous frame's (motion vectors)
    mat4 inv_view;
    vec4 camera_position;  // xyz world, w: mm per world unit
    vec4 viewport;         // width, height, 1 / width, 1 / height
    vec4 projection;       // P00, P11, near, far
    vec4 background;       // linear rgb, w: exposure
    vec4 ambient;          // linear rgb irradiance, w: tonemap (0 ACES fitted, 1 Reinhard)
    uvec4 counters;        // frame, seed, light count, flags (EMCV_RENDER_FLAG_*)
    ivec4 sss;             // fixed samples per SSS pixel, adaptive (1: N per pixel from shaders/adaptive), material count, unused
} frame;

struct Light {
    vec4 radiance;    // rgb: colour * intensity(frame), w: kind (EMCV_RENDER_LIGHT_*)
    vec4 position;    // xyz world, w: shadow layer (-1: none)
    vec4 direction;   // xyz: unit direction the light travels, w: cos(outer cone)
    vec4 cone;        // x: cos(inner cone)
    mat4 shadow_view_proj;
};

layout(std430, EMCV_LAYOUT_BINDING(EMCV_RENDER_LIGHTS)) readonly buffer Lights {
    Light lights[];
};

struct Material {
    vec4 albedo;           // linear rgb, w: kind (EMCV_RENDER_MATERIAL_*)
    vec4 mean_free_path;   // rgb mm (sss), w: unused
    vec4 specular;         // x: weight, y: roughness
    vec4 separable;        // x: kernel half-width in mm, y: taps
};

layout(std430, EMCV_LAYOUT_BINDING(EMCV_RENDER_MATERIALS)) readonly buffer Materials {
    Material materials[];
};

/// True when the G-buffer's material code (index + 1, 0 = background) names a scattering material.
bool emcv_render_scatters(uint material_code) {
    return material_code != 0u &&
           int(materials[material_code - 1u].albedo.w) == EMCV_RENDER_MATERIAL_SSS;
}

/// Linear view depth z of a pixel centre -> world position (the G-buffer stores z, > 0 in front).
vec3 emcv_render_world_position(ivec2 pixel, float z) {
    vec2 ndc = (vec2(pixel) + 0.5f) * frame.viewport.zw * 2.0f - 1.0f;
    vec4 view_position = vec4(ndc.x * z / frame.projection.x, ndc.y * z / frame.projection.y, -z, 1.0f);
    return (frame.inv_view * view_position).xyz;
}

#endif  // #ifndef EMCV_RENDER_FRAME_H
