// SPDX-License-Identifier: MIT
// shaders/adaptive/budget.comp.glsl — the sss-adaptive-budget pass (budget mode only, one workgroup): solves the
// scale lambda with sum_i clamp(lambda sigma_i, N_MIN, N_MAX) = B (histogram pixels + sub-pixel pixels) over the
// sigma histogram this frame's adaptive-samples pass wrote (emcv/port/budget.h), then clears the histogram for
// the next frame; the burley pass spends lambda right after. Pixels without a variance take B each outside the solve; sub-pixel pixels take 0
// and leave their share to the others, so the frame spends B per SSS pixel. The bisection runs on lambda's bit
// pattern and sums the bins in a fixed pairwise tree, as emcv::budget_solve does in C++ (the same bits).
#version 450 core

#include "emcv/port/bindings.h"

#include "adaptive/budget_block.h"

layout(local_size_x = EMCV_BUDGET_BINS) in;

shared float partial[EMCV_BUDGET_BINS];
shared uint pixels[EMCV_BUDGET_BINS];

void main() {
    uint bin = gl_LocalInvocationIndex;
    uint count = budget.bin_count[bin];
    float bin_sum = emcv_budget_bin_sum(bin, count, budget.bin_fraction[bin]);
    float n_min = float(EMCV_HISTORY_N_MIN), n_max = float(EMCV_HISTORY_N_MAX);

    // The histogram's pixel count, the same tree as the sums below.
    pixels[bin] = count;
    barrier();
    for (uint stride = uint(EMCV_BUDGET_BINS) / 2u; stride > 0u; stride /= 2u) {
        if (bin < stride) pixels[bin] += pixels[bin + stride];
        barrier();
    }
    uint histogram_pixels = pixels[0];
    EMCV_PRECISE float planned = float(EMCV_HISTORY_SPP_BUDGET) * float(histogram_pixels + budget.zero_pixels);

    uint low = emcv_budget_lambda_low_bits(), high = emcv_budget_lambda_high_bits();
    for (int step = 0; step < EMCV_BUDGET_SOLVE_STEPS; ++step) {
        uint middle = low + (high - low) / 2u;
        partial[bin] = emcv_budget_bin_samples(emcv_bits_float(middle), bin_sum, count, n_min, n_max);
        barrier();
        for (uint stride = uint(EMCV_BUDGET_BINS) / 2u; stride > 0u; stride /= 2u) {
            if (bin < stride) partial[bin] = partial[bin] + partial[bin + stride];
            barrier();
        }
        float total = partial[0];
        barrier();  // everyone has read the total before the next step overwrites it
        if (total < planned) low = middle; else high = middle;
    }
    if (bin == 0u) {
        budget.lambda = emcv_bits_float(high);
        budget.planned = planned;
        budget.default_pixels = 0u;
        budget.zero_pixels = 0u;
    }
    budget.bin_count[bin] = 0u;
    budget.bin_fraction[bin] = 0u;
}
