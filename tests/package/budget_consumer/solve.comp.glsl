// SPDX-License-Identifier: MIT
// Budget mode, pass 2 of 4: one workgroup solves lambda from the frame's histogram (emcv_adaptive_budget.glsl).
#define EMCV_BUDGET_GROUP_THREADS 64
#include "app.glsl"

layout(local_size_x = EMCV_BUDGET_GROUP_THREADS) in;

void main() { emcv_budget_solve(gl_LocalInvocationIndex); }
