// SPDX-License-Identifier: MIT
// Under a quality target (emcv_port.hlsl translated with EMCV_HISTORY_SPP_BUDGET 0, its default): each pixel's N
// at the top of the sampling pass, from its tile's reprojected and pooled histories (emcv_adaptive_quality_count).
#include "app.hlsl"

[numthreads(EMCV_ADAPTIVE_TILE_SIZE, EMCV_ADAPTIVE_TILE_SIZE, 1)]
void main(uint3 id : SV_DispatchThreadID, uint3 group_thread_id : SV_GroupThreadID, uint group_index : SV_GroupIndex)
{
    emcv_hlsl_set_invocation(group_thread_id, group_index);
    int2 p = int2(id.xy);
    uint code = app_share_pixel(p, group_index);
    uint n = emcv_adaptive_quality_count(emcv_adaptive_tile_origin(p));
    if (code != 0u) app_taken[p] = n;
}
