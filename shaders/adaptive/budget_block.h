// SPDX-License-Identifier: MIT
// shaders/adaptive/budget_block.h — the renderer's side of the installed module module/emcv_adaptive_budget.glsl:
// its budget block at the renderer's binding (adaptive/bindings.h). The solve pass (adaptive/budget_solve.comp.glsl)
// defines EMCV_BUDGET_GROUP_THREADS before including it.
#ifndef EMCV_ADAPTIVE_BUDGET_BLOCK_H
#define EMCV_ADAPTIVE_BUDGET_BLOCK_H

#include "emcv/port/bindings.h"
#include "emcv/port/history.h"
#include "adaptive/bindings.h"

layout(std430, EMCV_LAYOUT_BINDING(EMCV_ADAPTIVE_BUDGET)) buffer Budget {
    EmcvBudgetBlock budget;
};
#define EMCV_APP_BUDGET budget
#include "module/emcv_adaptive_budget.glsl"

#endif  // #ifndef EMCV_ADAPTIVE_BUDGET_BLOCK_H
