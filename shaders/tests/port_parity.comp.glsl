// SPDX-License-Identifier: MIT
// Runs the shared port (include/emcv/port) over the parity streams, one invocation per pixel; the CPU side of
// tests/gpu/test_port_parity.cpp runs the same headers and compares the buffers element by element.
#version 450 core

#include "emcv/port/bindings.h"
#include "emcv/port/ema.h"
#include "emcv/port/cv.h"
#include "emcv/port/samples.h"
#include "emcv/port/burley.h"
#include "emcv/port/resolve.h"
#include "tests/parity_bindings.h"
#include "tests/parity_stream.h"

layout(local_size_x = EMCV_WORKGROUP_SIZE_X) in;

layout(std140, EMCV_LAYOUT_BINDING(EMCV_BINDING_PARITY_PARAMS)) uniform ParityParams {
    uvec4 counts;    // (pixels, updates, seed, unused)
    vec4 weights;    // (eta_cov, eta_res, target variance, Burley d)
    ivec4 budget;    // (n_min, n_max, unused, unused)
} params;

layout(std430, EMCV_LAYOUT_BINDING(EMCV_BINDING_PARITY_OUTPUT)) writeonly buffer ParityOutput {
    vec4 results[];
};

void main() {
    uint pixel = gl_GlobalInvocationID.x;
    if (pixel >= params.counts.x) return;
    uint updates = params.counts.y;
    EmcvEmcm2 cov = emcv_emcm2_init();
    EmcvMovingStats res = emcv_moving_stats_init();
    vec2 last = vec2(0.0f);
    for (uint k = 0u; k < updates; ++k) {
        vec2 x = emcv_parity_sample(pixel, k, updates, params.counts.z);
        float alpha = emcv_cv_coefficient_emcm2(cov);  // alpha_{t-1}
        emcv_moving_stats_push(res, emcv_cv_residual(x.x, alpha, x.y), params.weights.y);
        emcv_emcm2_push(cov, x, params.weights.x);
        last = x;
    }
    float q = res.variance / params.weights.z;
    int n = emcv_sample_count(res.variance, params.weights.z, params.budget.x, params.budget.y);
    float u = emcv_uint_to_unit_float(emcv_pcg(pixel + 7u));
    float d = params.weights.w;
    float r_exact = emcv_burley_sample_exact(u, d);
    uint base = pixel * uint(EMCV_PARITY_OUTPUT_VEC4S);
    results[base + 0u] = vec4(cov.mean, cov.cov.x, cov.cov.y);
    results[base + 1u] = vec4(cov.cov.z, emcv_cv_coefficient_emcm2(cov), res.mean, res.variance);
    results[base + 2u] = vec4(float(n), uintBitsToFloat(cov.count), uintBitsToFloat(cov.rejected), q);
    results[base + 3u] = vec4(r_exact, emcv_burley_sample_spvg(u, d), emcv_burley_cdf(r_exact, d),
                              emcv_burley_pdf(r_exact, d));
    // The resolve's guide (resolve.h) on the stream's statistics as centred sums, values and history, the sums
    // scaled by 2^-(pixel % 32) (exact) so that they span the slope's half-step floor.
    float scale = exp2(-float(pixel % 32u));
    vec3 slope = emcv_resolve_guide_slope(scale * vec3(cov.cov.z, cov.cov.x, res.variance),
                                          scale * vec3(cov.cov.y, -cov.cov.y, res.variance * cov.mean.x), 9.0f);
    vec3 moved = emcv_resolve_guided_history(vec3(cov.mean, res.mean), slope, vec3(last, q),
                                             vec3(cov.mean.y, cov.mean.x, res.variance));
    results[base + 4u] = vec4(slope.x, slope.z, moved.x, moved.z);
    // The weight the guide's change asks of the blend (resolve.h), on the same sums and change, over n = 1, 9 and
    // 81 values and at half the change (exact).
    vec3 guide_sums = scale * vec3(cov.cov.z, cov.cov.x, res.variance);
    vec3 change = vec3(last, q) - vec3(cov.mean.y, cov.mean.x, res.variance);
    results[base + 5u] = vec4(emcv_resolve_guide_weight(change, guide_sums, 1.0f),
                              emcv_resolve_guide_weight(change, guide_sums, 9.0f),
                              emcv_resolve_guide_weight(change, guide_sums, 81.0f),
                              emcv_resolve_guide_weight(0.5f * change, guide_sums, 9.0f));
}
