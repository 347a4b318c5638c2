// SPDX-License-Identifier: MIT
// Budget mode, pass 3 of 4: each pixel's N from its block's plan and the solved lambda (emcv_adaptive_budget_count).
// An engine's sampling loop would take N samples here; this pass stores N.
#include "app.hlsl"

[numthreads(EMCV_ADAPTIVE_TILE_SIZE, EMCV_ADAPTIVE_TILE_SIZE, 1)]
void main(uint3 id : SV_DispatchThreadID, uint3 group_thread_id : SV_GroupThreadID, uint group_index : SV_GroupIndex)
{
    emcv_hlsl_set_invocation(group_thread_id, group_index);
    int2 p = int2(id.xy);
    if (app_code(p) == 0u) return;
    app_taken[p] = emcv_adaptive_budget_count(p, app_frame.x, app_frame.y);
}
