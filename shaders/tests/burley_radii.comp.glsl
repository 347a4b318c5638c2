// SPDX-License-Identifier: MIT
// Burley radii exactly as the renderer's sss-burley pass draws them (include/emcv/port/sss.h): invocation k is
// pixel (k mod 1024, k / 1024) of one frame and takes that pixel's sample k mod 64; tests/render's chi-square
// compares the radii with the port's CDF (emcv_burley_cdf).
#version 450 core

#include "emcv/port/bindings.h"
#include "emcv/port/sss.h"
#include "render/bindings.h"

layout(local_size_x = EMCV_WORKGROUP_SIZE_X) in;

layout(std140, EMCV_LAYOUT_BINDING(EMCV_RENDER_TEST_PARAMS)) uniform RadiiParams {
    uvec4 counts;  // samples, seed, frame, approximate (0 exact inverse CDF, 1 SPVG)
    vec4 shape;    // x: shape distance d (mm)
} params;

layout(std430, EMCV_LAYOUT_BINDING(EMCV_RENDER_TEST_OUTPUT)) writeonly buffer Radii {
    float radii[];
};

void main() {
    uint k = gl_GlobalInvocationID.x;
    if (k >= params.counts.x) return;
    vec2 rotation = emcv_sss_rotation(k % 1024u, k / 1024u, params.counts.z, params.counts.y);
    vec2 u = emcv_sss_sample_uv(k % 64u, rotation);
    radii[k] = emcv_sss_sample_radius(u.x, params.shape.x, params.counts.w != 0u);
}
