// SPDX-License-Identifier: MIT
// Budget mode, pass 4 of 4: the tile's history update after sampling (emcv_adaptive_update_tile), from each pixel's
// tracked f and G and the samples it took. Built with EMCV_ADAPTIVE_PLAN_NEXT it then plans the next frame from the
// history it has just stored, as the renderer's burley pass does under a still view (emcv_adaptive_stored_sigma2).
#define EMCV_ADAPTIVE_TILE_UPDATE 1
#include "app.hlsl"

StructuredBuffer<float2> app_tracked : register(t3);  // (f, G) per pixel, row by row

[numthreads(EMCV_ADAPTIVE_TILE_SIZE, EMCV_ADAPTIVE_TILE_SIZE, 1)]
void main(uint3 id : SV_DispatchThreadID, uint3 group_thread_id : SV_GroupThreadID, uint group_index : SV_GroupIndex)
{
    emcv_hlsl_set_invocation(group_thread_id, group_index);
    int2 p = int2(id.xy);
    uint code = app_code(p);
    uint n = code != 0u ? app_taken[p] : 0u;
    float2 fg = n > 0u ? app_tracked[id.y * app_frame.z + id.x] : float2(0.0f, 0.0f);
    int2 origin = emcv_adaptive_tile_origin(p);
    emcv_adaptive_update_tile(group_index, origin, fg.x, fg.y, n);
#if defined(EMCV_ADAPTIVE_PLAN_NEXT)
    emcv_adaptive_share_pixel(group_index, code, code != 0u && app_sub_pixel(p));
    GroupMemoryBarrierWithGroupSync();
    EmcvAdaptiveBlock blk = emcv_adaptive_no_block();
    float own = emcv_history_no_samples();
    if (emcv_adaptive_holds_block()) {
        float frames;
        blk = emcv_adaptive_block(group_index, origin);
        own = emcv_adaptive_stored_sigma2(blk, frames);
        emcv_adaptive_share_sigma2(group_index, own, blk.code, frames);
    }
    GroupMemoryBarrierWithGroupSync();
    if (emcv_adaptive_holds_block() && blk.code != 0u) emcv_adaptive_allocate(group_index, blk, own);
#endif
}
