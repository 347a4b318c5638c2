// SPDX-License-Identifier: MIT
// tests/hlsl/consumer.comp.hlsl: an engine's compute kernel on the installed HLSL module, as docs/porting.md
// ("HLSL") describes it: it #includes emcv_port.hlsl (twice: the include guard holds), declares its own
// resources (structured buffers of the port's structs, a cbuffer holding two of them, an image) and calls port
// functions. check_hlsl.py compiles it with glslang's HLSL front end and reads the layouts back from its SPIR-V.
#include "emcv_port.hlsl"
#include "emcv_port.hlsl"

StructuredBuffer<float> irradiance : register(t0);
RWStructuredBuffer<EmcvEmcm2> covariance : register(u0);      // cv's state, per pixel
RWStructuredBuffer<EmcvMovingStats> residual : register(u1);  // spvg's state, per pixel
RWStructuredBuffer<EmcvBudgetBlock> budget : register(u2);    // one block
RWTexture2D<float4> history_cov : register(u3);
cbuffer Frame : register(b0)
{
    uint4 frame_seed_width_height;  // (frame, seed, width, height)
    float4 camera;                  // (P00, viewport width, mm per world unit, view depth)
    EmcvEmcm2 prior_state;          // the port's structs in a cbuffer (Direct3D cbuffer packing)
    EmcvMovingStats prior_stats;
};

[numthreads(EMCV_WORKGROUP_SIZE_X, 1, 1)]
void main(uint3 id : SV_DispatchThreadID)
{
    const uint width = frame_seed_width_height.z;
    const uint index = id.y * width + id.x;
    const uint frame_index = frame_seed_width_height.x;
    const uint seed = frame_seed_width_height.y;
    const float g = irradiance[index];
    EmcvEmcm2 cov = covariance[index];
    if (!emcv_emcm2_valid(cov)) cov = prior_state;
    const float sigma2 = emcv_history_sigma2_cv(cov, EMCV_HISTORY_ETA_EMCM);
    const float u_round = emcv_budget_u(id.x, id.y, frame_index, seed);
    const int n = emcv_history_count_quality(sigma2, EMCV_HISTORY_TARGET, EMCV_HISTORY_N_MIN, EMCV_HISTORY_N_MAX);
    const float2 rotation = emcv_sss_rotation(id.x, id.y, frame_index, seed);
    float f = 0.0f;
    for (int i = 0; i < n; ++i) {
        const float2 u = emcv_sss_sample_uv(uint(i), rotation);
        f += emcv_burley_profile(emcv_sss_sample_radius(u.x, 1.0f, (i & 1) == 1), 1.0f) * g;
    }
    f /= float(max(n, 1));
    emcv_history_push_cv(cov, f, g, EMCV_HISTORY_ETA_EMCM, float(max(n, 1)));
    covariance[index] = cov;
    EmcvMovingStats stats = residual[index];
    if (!emcv_moving_stats_valid(stats)) stats = prior_stats;
    emcv_moving_stats_push(stats, emcv_cv_residual(f, emcv_cv_coefficient_emcm2(cov), g), EMCV_HISTORY_ETA_MOVING);
    residual[index] = stats;
    const uint bin = emcv_budget_bin(sqrt(max(emcv_cv_optimal_residual_variance_emcm2(cov), 0.0f)));
    InterlockedAdd(budget[0].bin_count[bin], 1u);
    InterlockedAdd(budget[0].raw_count[bin], u_round < 0.5f ? 1u : 0u);
    history_cov[id.xy] = emcv_history_encode_emcm2_cov(cov) * camera.w;
}
