// SPDX-License-Identifier: MIT
// Separable SSS (Jimenez 2015, docs/frame.md): one 1-D pass along pass.ints.xy over the SSS tiles (indirect
// dispatch); run twice (horizontal from the lighting, vertical from the horizontal result). The kernel
// (rgb weights, offset in mm) is built on the CPU per material (demo/render/separable_kernel.cpp). Offsets
// are mapped to pixels with the same pixelsPerMm in x and y (square pixels: no aspect error, docs/frame.md).
// Follow-surface (docs/frame.md): a tap across a depth step s = saturate(|dz| / kernel half-width) is pulled
// to the centre colour; taps off screen or on non-scattering pixels take the centre colour.
#version 450 core

#include "emcv/port/sss.h"
#include "render/gbuffer_read.h"
#include "render/tiles.h"

layout(local_size_x = EMCV_RENDER_TILE_SIZE, local_size_y = EMCV_RENDER_TILE_SIZE) in;

layout(std140, EMCV_LAYOUT_BINDING(EMCV_RENDER_PASS)) uniform Pass {
    EmcvPassBlock pass;  // ints.xy: direction (1, 0) or (0, 1)
};

layout(std430, EMCV_LAYOUT_BINDING(EMCV_RENDER_KERNELS)) readonly buffer Kernels {
    vec4 taps[];   // material * EMCV_RENDER_MAX_SEPARABLE_TAPS + k: rgb weight, w offset in mm; tap 0 is the centre
};

layout(EMCV_LAYOUT_BINDING(EMCV_RENDER_TEX_SSS_IN)) uniform sampler2D source;
layout(rgba16f, EMCV_LAYOUT_IMAGE_BINDING(EMCV_RENDER_IMG_SSS_OUT)) writeonly uniform image2D out_scattered;

void main() {
    ivec2 p = emcv_render_tile_pixel();
    if (!emcv_render_on_screen(p)) return;
    uint code = emcv_render_material_code(p);
    if (!emcv_render_scatters(code)) return;

    EmcvMaterial m = materials[code - 1u];
    int tap_count = int(m.separable.y);
    float half_width_mm = m.separable.x;
    float z = emcv_render_depth(p);
    float mm_per_unit = frame.camera_position.w;
    float pixels_per_mm = emcv_sss_pixels_per_mm(frame.projection.x, frame.viewport.x, z, mm_per_unit);
    vec2 direction = vec2(pass.ints.xy);
    uint base = (code - 1u) * uint(EMCV_RENDER_MAX_SEPARABLE_TAPS);

    vec3 centre = texelFetch(source, p, 0).xyz;
    vec3 result = taps[base].xyz * centre;
    for (int k = 1; k < tap_count; ++k) {
        vec4 tap = taps[base + uint(k)];
        ivec2 q = ivec2(floor(vec2(p) + 0.5f + direction * (tap.w * pixels_per_mm)));
        vec3 c = centre;
        float zq = emcv_render_scattering_depth(q);  // 0: off screen or not scattering
        if (zq != 0.0f) {
            float dz_mm = abs(zq - z) * mm_per_unit;
            c = mix(texelFetch(source, q, 0).xyz, centre, clamp(dz_mm / half_width_mm, 0.0f, 1.0f));
        }
        result += tap.xyz * c;
    }
    imageStore(out_scattered, p, vec4(result, 1.0f));
}
