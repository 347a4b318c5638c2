// SPDX-License-Identifier: MIT
// shaders/adaptive/budget_block.h — the budget's storage block (emcv/port/budget.h's EmcvBudgetBlock) as the
// adaptive passes and the burley pass see it, and the one function that adds a pixel to its histogram.
#ifndef EMCV_ADAPTIVE_BUDGET_BLOCK_H
#define EMCV_ADAPTIVE_BUDGET_BLOCK_H

#include "emcv/port/bindings.h"
#include "emcv/port/history.h"
#include "adaptive/bindings.h"

layout(std430, EMCV_LAYOUT_BINDING(EMCV_ADAPTIVE_BUDGET)) buffer Budget {
    EmcvBudgetBlock budget;
};

/// Adds one SSS pixel's per-sample variance (or its no-variance / no-samples code, history.h) to this frame's
/// histogram, which sss-adaptive-budget solves before the burley pass spends it.
void emcv_budget_add(float sigma2) {
    if (sigma2 == emcv_history_no_samples()) {
        atomicAdd(budget.zero_pixels, 1u);
    } else if (!(sigma2 >= 0.0f)) {
        atomicAdd(budget.default_pixels, 1u);
    } else {
        float sigma = sqrt(sigma2);
        uint bin = emcv_budget_bin(sigma);
        atomicAdd(budget.bin_count[bin], 1u);
        atomicAdd(budget.bin_fraction[bin], emcv_budget_fraction(sigma));
    }
}

#endif  // #ifndef EMCV_ADAPTIVE_BUDGET_BLOCK_H
