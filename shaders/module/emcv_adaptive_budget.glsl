// SPDX-License-Identifier: MIT
// emcv_adaptive_budget.glsl — installed GPU module (share/emcv/module): budget mode's storage block
// (emcv/port/budget.h's EmcvBudgetBlock) as the adaptive passes use it: the frame's histogram that the planning
// passes add their blocks to (emcv_budget_add), and, where EMCV_BUDGET_GROUP_THREADS is defined (the solve pass's
// one workgroup), the solve on that histogram, which also stores the next frame's shrinkage prior from the
// histogram of the unshrunk variances (emcv_history_frame_prior).
//
// No resources: the application declares a std430 buffer holding one EmcvBudgetBlock (zeroed once, before the
// first frame) and defines EMCV_APP_BUDGET as that block, before including this module, e.g.
//   layout(std430, binding = 5) buffer Budget { EmcvBudgetBlock budget; };
//   #define EMCV_APP_BUDGET budget
#ifndef EMCV_ADAPTIVE_BUDGET_H
#define EMCV_ADAPTIVE_BUDGET_H

#include "emcv/port/history.h"
#include "module/emcv_adaptive_language.glsl"

#if !defined(EMCV_APP_BUDGET)
#error "define EMCV_APP_BUDGET as the application's EmcvBudgetBlock (a std430 buffer member) before this module"
#endif

/// Adds a block's per-sample variance (or its no-variance / no-samples code, history.h) to the frame's histogram,
/// once for each of its `pixels` scattering pixels (every pixel of a block takes the block's N: the budget counts
/// pixels, emcv/port/history.h, emcv_history_block_batch): global atomics, integer sums that are the same in any
/// order, so the histogram is emcv::budget_add's in C++ (a pixel at a time) bit for bit. A block adds its own
/// (a tile holds 4 of them at K = 4, 16 at K = 2): no workgroup histogram to clear and flush, which on llvmpipe
/// cost every workgroup a walk over all the bins.
void emcv_budget_add(float sigma2, uint pixels) {
    if (sigma2 == emcv_history_no_samples()) {
        EMCV_ATOMIC_ADD(EMCV_APP_BUDGET.zero_pixels, pixels);
    } else if (!(sigma2 >= 0.0f)) {
        EMCV_ATOMIC_ADD(EMCV_APP_BUDGET.default_pixels, pixels);
    } else {
        float sigma = sqrt(sigma2);
        uint bin = emcv_budget_bin(sigma);
        EMCV_ATOMIC_ADD(EMCV_APP_BUDGET.bin_count[bin], pixels);
        EMCV_ATOMIC_ADD(EMCV_APP_BUDGET.bin_fraction[bin], pixels * emcv_budget_fraction(sigma));
    }
}

/// Adds a block's pooled variance before shrinkage and its pooled effective frames, once for each of its `pixels`,
/// to the statistics the next frame shrinks towards (a code, or no frames, adds nothing; emcv::budget_add_raw in
/// C++, a pixel at a time).
void emcv_budget_add_raw(float sigma2, float frames, uint pixels) {
    if (!(sigma2 >= 0.0f) || !(frames > 0.0f)) return;
    EMCV_ATOMIC_ADD(EMCV_APP_BUDGET.raw_count[emcv_budget_bin(sqrt(sigma2))], pixels);
    EMCV_ATOMIC_ADD(EMCV_APP_BUDGET.raw_inverse_frames, pixels * emcv_history_inverse_frames_units(frames));
}

#if defined(EMCV_BUDGET_GROUP_THREADS)
// The solve, run by the solve pass's one workgroup (EMCV_BUDGET_GROUP_THREADS threads, a power of two that
// divides EMCV_BUDGET_BINS): the smallest bit pattern of lambda in the open interval between
// emcv_budget_lambda_low_bits and _high_bits whose planned samples sum_i clamp(lambda sigma_i, N_MIN, N_MAX),
// added over the bins in bin order, reach B (histogram pixels + sub-pixel pixels), the high bound when none
// does: what emcv::budget_solve's bisection finds in C++ (the same bits). The total is monotone in lambda, so
// instead of bisecting (one barrier-bound reduction per halving) every thread evaluates one of `threads`
// candidates over all the bins each round, which narrows the interval 65-fold: five rounds and a last one.
#define EMCV_BUDGET_BINS_PER_THREAD (EMCV_BUDGET_BINS / EMCV_BUDGET_GROUP_THREADS)
// The frame's bins as the solve reads them (counts, and sums of sigma as float bits).
shared uint emcv_budget_group_count[EMCV_BUDGET_BINS];
shared uint emcv_budget_group_fraction[EMCV_BUDGET_BINS];
shared uint emcv_budget_group_zero;
shared vec3 emcv_budget_moments[EMCV_BUDGET_GROUP_THREADS];  // per thread, for the next frame's prior
shared vec2 emcv_budget_prior;                                   // (mean, tau^2), stored with lambda
shared uint emcv_budget_group_default;
shared uint emcv_budget_below;  // candidates of the round whose total falls short of the plan
shared uint emcv_budget_nonempty;  // the frame's non-empty bins, packed in bin order at the front of the arrays

/// The frame's planned samples at scale lambda: the non-empty bins added in bin order (the empty ones would add
/// exactly 0).
float emcv_budget_total(float lambda, float n_min, float n_max) {
    EMCV_PRECISE float total = 0.0f;
    for (uint i = 0u; i < emcv_budget_nonempty; ++i)
        total += emcv_budget_bin_samples(lambda, uintBitsToFloat(emcv_budget_group_fraction[i]),
                                         emcv_budget_group_count[i], n_min, n_max);
    return total;
}

/// The solve, one workgroup of EMCV_BUDGET_GROUP_THREADS threads dispatched after the pass whose blocks added to
/// the frame's histogram (the renderer's adaptive/budget_solve.comp.glsl; a memory barrier orders it after their
/// atomics): reads the frame's histogram and clears it, solves lambda for the burley pass that spends it,
/// stores the next frame's prior and resets the block's counters. Every thread calls it (it has barriers).
void emcv_budget_solve(uint thread) {
    // The frame's bins into shared memory: count, and the bin's sum of sigma (as bits, in the fraction array);
    // then the non-empty ones packed in bin order at the front (a frame fills a few tens of the 256).
    for (uint k = 0u; k < uint(EMCV_BUDGET_BINS_PER_THREAD); ++k) {
        uint bin = thread + k * uint(EMCV_BUDGET_GROUP_THREADS);
        uint count, fraction;
        EMCV_ATOMIC_EXCHANGE(EMCV_APP_BUDGET.bin_count[bin], 0u, count);
        EMCV_ATOMIC_EXCHANGE(EMCV_APP_BUDGET.bin_fraction[bin], 0u, fraction);
        emcv_budget_group_count[bin] = count;
        emcv_budget_group_fraction[bin] = floatBitsToUint(emcv_budget_bin_sum(bin, count, fraction));
    }
    if (thread == 0u) EMCV_ATOMIC_EXCHANGE(EMCV_APP_BUDGET.zero_pixels, 0u, emcv_budget_group_zero);
    {  // the next frame's prior (emcv_history_frame_prior): each thread's bins, then thread 0 adds the threads
        vec3 moments = vec3(0.0f, 0.0f, 0.0f);
        for (uint k = 0u; k < uint(EMCV_BUDGET_BINS_PER_THREAD); ++k) {
            uint bin = thread + k * uint(EMCV_BUDGET_GROUP_THREADS);
            uint raw_count;
            EMCV_ATOMIC_EXCHANGE(EMCV_APP_BUDGET.raw_count[bin], 0u, raw_count);
            moments = emcv_history_moments_add(moments, bin, raw_count);
        }
        emcv_budget_moments[thread] = moments;
    }
    barrier();
    if (thread == 0u) {
        vec3 moments = vec3(0.0f, 0.0f, 0.0f);
        for (uint t = 0u; t < uint(EMCV_BUDGET_GROUP_THREADS); ++t) moments += emcv_budget_moments[t];
        uint raw_inverse_frames;
        EMCV_ATOMIC_EXCHANGE(EMCV_APP_BUDGET.raw_inverse_frames, 0u, raw_inverse_frames);
        emcv_budget_prior = emcv_history_frame_prior(moments, raw_inverse_frames,
                                                     emcv_history_spend_relative_variance());
    }
    barrier();
    uint histogram_pixels = 0u;
    if (thread == 0u) {
        uint stored = 0u;
        for (uint bin = 0u; bin < uint(EMCV_BUDGET_BINS); ++bin) {
            uint count = emcv_budget_group_count[bin];
            if (count == 0u) continue;
            emcv_budget_group_count[stored] = count;  // stored <= bin: never overwrites a bin not yet read
            emcv_budget_group_fraction[stored] = emcv_budget_group_fraction[bin];
            ++stored;
            histogram_pixels += count;
        }
        emcv_budget_nonempty = stored;
        emcv_budget_group_default = histogram_pixels;  // handed to the other threads
    }
    barrier();
    histogram_pixels = emcv_budget_group_default;
    EMCV_PRECISE float planned = float(EMCV_HISTORY_SPP_BUDGET) * float(histogram_pixels + emcv_budget_group_zero);
    float n_min = float(EMCV_HISTORY_N_MIN), n_max = float(EMCV_HISTORY_N_MAX);
    uint low = emcv_budget_lambda_low_bits(), high = emcv_budget_lambda_high_bits();
    while (high - low > 1u) {  // the same bounds in every thread: uniform
        uint step = max((high - low) / uint(EMCV_BUDGET_GROUP_THREADS + 1), 1u);
        if (thread == 0u) emcv_budget_below = 0u;
        barrier();
        uint candidate = low + step * (thread + 1u);  // increasing with the thread; never past 2^32 (see above)
        if (candidate < high && emcv_budget_total(emcv_bits_float(candidate), n_min, n_max) < planned)
            EMCV_ATOMIC_ADD(emcv_budget_below, 1u);
        barrier();
        uint below = emcv_budget_below;  // the total is monotone: the first `below` candidates fall short
        barrier();                       // everyone has read it before the next round clears it
        uint next_high = low + step * (below + 1u);
        if (below > 0u) low = low + step * below;
        if (next_high < high) high = next_high;
    }
    if (thread == 0u) {
        EMCV_APP_BUDGET.lambda = emcv_bits_float(high);
        EMCV_APP_BUDGET.planned = planned;
        EMCV_APP_BUDGET.mean_sigma2 = emcv_budget_prior.x;
        EMCV_APP_BUDGET.between_variance = emcv_budget_prior.y;
        uint default_pixels;  // not read: the exchange clears the counter
        EMCV_ATOMIC_EXCHANGE(EMCV_APP_BUDGET.default_pixels, 0u, default_pixels);
        EMCV_APP_BUDGET.solves += 1u;
    }
}
#endif  // defined(EMCV_BUDGET_GROUP_THREADS)

#endif  // #ifndef EMCV_ADAPTIVE_BUDGET_H
