// SPDX-License-Identifier: MIT
// tests/adaptive: the tracked scalar (port's emcv_gamma_luminance) of given linear colours, computed on the GPU
// with the same function the adaptive burley pass's history update calls, so the C++ estimators can be fed the GPU's own f and G.
#version 450 core

#include "emcv/port/bindings.h"
#include "emcv/port/history.h"

layout(local_size_x = 64) in;

layout(std430, EMCV_LAYOUT_BINDING(0)) readonly buffer Colours {
    vec4 colours[];
};
layout(std430, EMCV_LAYOUT_BINDING(1)) writeonly buffer Tracked {
    float tracked[];
};

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= uint(colours.length())) return;
    // As emcv_adaptive_tracked: albedo * irradiance * exposure, with the test's albedo 1 and exposure 1.
    tracked[i] = emcv_gamma_luminance(vec3(1.0f) * colours[i].xyz * 1.0f);
}
