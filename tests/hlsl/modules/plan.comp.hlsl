// SPDX-License-Identifier: MIT
// Budget mode, pass 1 of 4 (tests/package/budget_consumer/plan.comp.glsl in HLSL): each 8x8 tile reprojects its
// histories, pools their variances, shrinks them and adds them to the frame's histogram (emcv_adaptive_plan.hlsl).
#include "app.hlsl"

[numthreads(EMCV_ADAPTIVE_TILE_SIZE, EMCV_ADAPTIVE_TILE_SIZE, 1)]
void main(uint3 id : SV_DispatchThreadID, uint3 group_thread_id : SV_GroupThreadID, uint group_index : SV_GroupIndex)
{
    emcv_hlsl_set_invocation(group_thread_id, group_index);
    int2 p = int2(id.xy);
    app_share_pixel(p, group_index);
    EmcvAdaptiveBlock blk;
    float own, frames;
    emcv_adaptive_tile_sigma2(emcv_adaptive_tile_origin(p), blk, own, frames);
    if (emcv_adaptive_holds_block() && blk.code != 0u) emcv_adaptive_allocate(group_index, blk, own);
}
