// SPDX-License-Identifier: MIT
// Budget mode, pass 2 of 4: one workgroup solves lambda from the frame's histogram (emcv_adaptive_budget.hlsl).
#define EMCV_BUDGET_GROUP_THREADS 64
#include "app.hlsl"

[numthreads(EMCV_BUDGET_GROUP_THREADS, 1, 1)]
void main(uint3 group_thread_id : SV_GroupThreadID, uint group_index : SV_GroupIndex)
{
    emcv_hlsl_set_invocation(group_thread_id, group_index);
    emcv_budget_solve(group_index);
}
