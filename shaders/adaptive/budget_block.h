// SPDX-License-Identifier: MIT
// shaders/adaptive/budget_block.h — the budget's storage block (emcv/port/budget.h's EmcvBudgetBlock) as the
// adaptive passes see it; for the samples pass (EMCV_BUDGET_GROUP_THREADS defined), the per-workgroup histogram
// its pixels are added to and the solve that its last workgroup runs on the frame's histogram.
#ifndef EMCV_ADAPTIVE_BUDGET_BLOCK_H
#define EMCV_ADAPTIVE_BUDGET_BLOCK_H

#include "emcv/port/bindings.h"
#include "emcv/port/history.h"
#include "adaptive/bindings.h"

layout(std430, EMCV_LAYOUT_BINDING(EMCV_ADAPTIVE_BUDGET)) buffer Budget {
    EmcvBudgetBlock budget;
};

#if defined(EMCV_BUDGET_GROUP_THREADS)
// The solve, run by the samples pass's last workgroup (EMCV_BUDGET_GROUP_THREADS threads, a power of two that
// divides EMCV_BUDGET_BINS): the bisection on lambda's bit pattern of sum_i clamp(lambda sigma_i, N_MIN, N_MAX)
// = B (histogram pixels + sub-pixel pixels), its sums in the fixed pairwise tree over the 256 bins that
// emcv::budget_solve follows in C++ (the same bits). Each thread holds EMCV_BUDGET_BINS / threads bins and adds
// the tree's first levels itself (bin t with t + 128, then with t + 64, ...), the rest in shared memory.
#define EMCV_BUDGET_BINS_PER_THREAD (EMCV_BUDGET_BINS / EMCV_BUDGET_GROUP_THREADS)
shared float emcv_budget_partial[EMCV_BUDGET_GROUP_THREADS];
shared bool emcv_budget_last_group;
// The workgroup's own histogram: its pixels meet in shared memory, and only its non-empty bins reach the
// frame's histogram (a tile's 64 pixels fall in a few bins: a few global atomics instead of two per pixel).
shared uint emcv_budget_group_count[EMCV_BUDGET_BINS];
shared uint emcv_budget_group_fraction[EMCV_BUDGET_BINS];
shared uint emcv_budget_group_zero;
shared uint emcv_budget_group_default;

/// Empties the workgroup's histogram; the caller's next barrier() precedes the first emcv_budget_add.
void emcv_budget_group_clear(uint thread) {
    for (uint k = 0u; k < uint(EMCV_BUDGET_BINS_PER_THREAD); ++k) {
        emcv_budget_group_count[thread + k * uint(EMCV_BUDGET_GROUP_THREADS)] = 0u;
        emcv_budget_group_fraction[thread + k * uint(EMCV_BUDGET_GROUP_THREADS)] = 0u;
    }
    if (thread == 0u) {
        emcv_budget_group_zero = 0u;
        emcv_budget_group_default = 0u;
    }
}

/// Adds one SSS pixel's per-sample variance (or its no-variance / no-samples code, history.h) to the
/// workgroup's histogram (emcv::budget_add in C++ adds to the frame's at once: the sums are the same integers).
void emcv_budget_add(float sigma2) {
    if (sigma2 == emcv_history_no_samples()) {
        atomicAdd(emcv_budget_group_zero, 1u);
    } else if (!(sigma2 >= 0.0f)) {
        atomicAdd(emcv_budget_group_default, 1u);
    } else {
        float sigma = sqrt(sigma2);
        uint bin = emcv_budget_bin(sigma);
        atomicAdd(emcv_budget_group_count[bin], 1u);
        atomicAdd(emcv_budget_group_fraction[bin], emcv_budget_fraction(sigma));
    }
}

/// The bins' sum in the tree's order: `value` holds thread t's bins t, t + threads, t + 2 threads, ...
float emcv_budget_tree_sum(uint thread, float value[EMCV_BUDGET_BINS_PER_THREAD]) {
    for (uint width = uint(EMCV_BUDGET_BINS_PER_THREAD); width > 1u; width /= 2u)
        for (uint k = 0u; k < width / 2u; ++k) value[k] = value[k] + value[k + width / 2u];
    emcv_budget_partial[thread] = value[0];
    barrier();
    for (uint stride = uint(EMCV_BUDGET_GROUP_THREADS) / 2u; stride > 0u; stride /= 2u) {
        if (thread < stride) emcv_budget_partial[thread] = emcv_budget_partial[thread] + emcv_budget_partial[thread + stride];
        barrier();
    }
    float total = emcv_budget_partial[0];
    barrier();  // everyone has read the total before the next sum overwrites it
    return total;
}

/// Called by every thread of every workgroup of the samples pass once its pixels are in the histogram (uniform
/// control flow: it has barriers). The last workgroup to arrive reads the histogram and clears it (atomic
/// exchanges: the other workgroups' atomics are visible to atomics), solves lambda for the burley pass and
/// resets the block for the next frame.
void emcv_budget_finish_group(uint thread, uint groups) {
    barrier();  // every pixel of the workgroup is in its histogram
    for (uint k = 0u; k < uint(EMCV_BUDGET_BINS_PER_THREAD); ++k) {
        uint bin = thread + k * uint(EMCV_BUDGET_GROUP_THREADS);
        if (emcv_budget_group_count[bin] > 0u) {
            atomicAdd(budget.bin_count[bin], emcv_budget_group_count[bin]);
            atomicAdd(budget.bin_fraction[bin], emcv_budget_group_fraction[bin]);
        }
    }
    if (thread == 0u) {
        if (emcv_budget_group_zero > 0u) atomicAdd(budget.zero_pixels, emcv_budget_group_zero);
        if (emcv_budget_group_default > 0u) atomicAdd(budget.default_pixels, emcv_budget_group_default);
    }
    memoryBarrierBuffer();  // this thread's histogram atomics are done before its workgroup counts as finished
    barrier();
    if (thread == 0u) emcv_budget_last_group = atomicAdd(budget.finished_groups, 1u) == groups - 1u;
    barrier();
    if (!emcv_budget_last_group) return;  // the same for the whole workgroup

    uint count[EMCV_BUDGET_BINS_PER_THREAD];
    float bin_sum[EMCV_BUDGET_BINS_PER_THREAD];
    float counted[EMCV_BUDGET_BINS_PER_THREAD];
    for (uint k = 0u; k < uint(EMCV_BUDGET_BINS_PER_THREAD); ++k) {
        uint bin = thread + k * uint(EMCV_BUDGET_GROUP_THREADS);
        count[k] = atomicExchange(budget.bin_count[bin], 0u);
        bin_sum[k] = emcv_budget_bin_sum(bin, count[k], atomicExchange(budget.bin_fraction[bin], 0u));
        counted[k] = float(count[k]);
    }
    // The histogram's pixel count (exact in float below 2^24 pixels; the C++ adds the same integers).
    float histogram_pixels = emcv_budget_tree_sum(thread, counted);
    uint zero_pixels = atomicOr(budget.zero_pixels, 0u);
    EMCV_PRECISE float planned = float(EMCV_HISTORY_SPP_BUDGET) * float(uint(histogram_pixels) + zero_pixels);
    float n_min = float(EMCV_HISTORY_N_MIN), n_max = float(EMCV_HISTORY_N_MAX);
    uint low = emcv_budget_lambda_low_bits(), high = emcv_budget_lambda_high_bits();
    for (int step = 0; step < EMCV_BUDGET_SOLVE_STEPS; ++step) {
        uint middle = low + (high - low) / 2u;
        float samples[EMCV_BUDGET_BINS_PER_THREAD];
        for (uint k = 0u; k < uint(EMCV_BUDGET_BINS_PER_THREAD); ++k)
            samples[k] = emcv_budget_bin_samples(emcv_bits_float(middle), bin_sum[k], count[k], n_min, n_max);
        if (emcv_budget_tree_sum(thread, samples) < planned) low = middle; else high = middle;
    }
    if (thread == 0u) {
        budget.lambda = emcv_bits_float(high);
        budget.planned = planned;
        atomicExchange(budget.default_pixels, 0u);
        atomicExchange(budget.zero_pixels, 0u);
        atomicExchange(budget.finished_groups, 0u);
    }
}
#endif  // defined(EMCV_BUDGET_GROUP_THREADS)

#endif  // #ifndef EMCV_ADAPTIVE_BUDGET_BLOCK_H
