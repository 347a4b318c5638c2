// SPDX-License-Identifier: MIT
/// \file
/// emcv/port/budget.h — spending a fixed mean sample budget B per SSS pixel where the noise is, in the shared
/// C++/GLSL dialect (fp32): N_i proportional to the per-sample standard deviation sigma_i.
//
// ABOUT      Over pixels i with per-sample variances sigma_i^2 and counts N_i the frame's mean squared error is
//            (1/P) sum sigma_i^2 / N_i; for a fixed total sum N_i = P B it is smallest at N_i = B sigma_i / E[sigma]
//            (Lagrange / Neyman allocation, docs/renderer.md "Per-sample variance and the two modes"), E[sigma]^2 / B against
//            uniform sampling's E[sigma^2] / B. With a floor n_min and a cap n_max the counts are
//                N_i = clamp(lambda sigma_i, n_min, n_max)
//            with lambda the scale that makes their sum the budget, found by bisection over a histogram of
//            sigma, written and solved in the frame that spends it (between the adaptive-samples pass and the
//            burley pass). Counts are rounded stochastically (floor(x) + [u < frac(x)]) so that the mean is
//            exact in expectation.
//            The histogram: EMCV_BUDGET_BINS bins, 8 per octave of sigma from 2^-24 to 2^8, split on the
//            float's bits (no transcendental: the CPU and the GPU bin alike, bit for bit). Each bin keeps the
//            count and the sum of the next 10 mantissa bits, so that its sum of sigma is known to 2^-13 of
//            sigma (32-bit sums up to 4M pixels per bin).
//            Beside it the block keeps a histogram of the pooled variances before the shrinkage (raw_count) and
//            their sum of 1 / frames, from which the solve stores the next frame's prior (mean_sigma2,
//            between_variance; port/history.h, emcv_history_frame_prior).
//            The solve (emcv::budget_solve in C++, one workgroup's dispatch on the GPU,
//            shaders/module/emcv_adaptive_budget.glsl) searches the bit pattern of lambda (positive floats order as
//            their bits) for the smallest whose total, the bins added in bin order, reaches the plan: C++ by
//            bisection, the GPU 64 candidates a round; the total is monotone, so both give the same lambda.
// USAGE      uint bin = emcv_budget_bin(sigma); count[bin] += 1; fraction[bin] += emcv_budget_fraction(sigma);
//            ... lambda = solve(...);  int n = emcv_budget_round(emcv_budget_share(lambda, sigma, 1, 64), u);
#ifndef EMCV_PORT_BUDGET_H
#define EMCV_PORT_BUDGET_H

#include "port.h"
#include "hash.h"

EMCV_PORT_BEGIN

/// Bins of the sigma histogram: 8 per octave over [2^-24, 2^8) (32 octaves).
#define EMCV_BUDGET_BINS 256
/// The lowest bin's lower edge, 2^-24: a sigma under it (0 included) counts as that edge, where every
/// budget within [n_min, n_max] puts it at n_min anyway.
#define EMCV_BUDGET_SIGMA_LOW_EXPONENT (-24)
/// Bisection steps of lambda's bit pattern: the search range holds under 2^29 patterns
/// (emcv_budget_lambda_low_bits), so 32 halvings end on adjacent floats.
#define EMCV_BUDGET_SOLVE_STEPS 32

/// The histogram and the solved scale (storage buffer; the same struct in C++). Each member is 4 bytes, so
/// std430 and C++ lay it out alike.
struct EmcvBudgetBlock {
    float lambda;         ///< the scale this frame's burley pass spends with (written by the solve)
    float planned;        ///< the total the solve aimed at: B (histogram pixels + zero_pixels)
    uint default_pixels;  ///< pixels without a variance yet (they take B, outside the solve; diagnostic)
    uint zero_pixels;     ///< pixels that take no samples (sub-pixel kernels): their share goes to the others
    /// Solves run since the block was created (the solve adds 1 after resetting the histogram; wraps at 2^32):
    /// a diagnostic that a frame's histogram was solved once, not a count any formula reads.
    uint solves;
    uint bin_count[EMCV_BUDGET_BINS];     ///< pixels per bin
    uint bin_fraction[EMCV_BUDGET_BINS];  ///< sum of the 10 mantissa bits under the bin's 3
    /// Histogram of the pooled per-sample variance before shrinkage (its sqrt binned as sigma), pixels with a
    /// variance only: the frame statistics the next frame shrinks towards (emcv_history_shrink_sigma2).
    uint raw_count[EMCV_BUDGET_BINS];
    uint raw_inverse_frames;  ///< sum over those pixels of 1 / (pooled effective frames), in units of 2^-10
    float mean_sigma2;        ///< last frame's mean pooled sigma^2 over pixels with a variance (0: none yet)
    float between_variance;   ///< last frame's spread of the true sigma^2 across pixels (tau^2), >= 0
};

#ifdef __cplusplus
/// The float's bits (GLSL floatBitsToUint).
EMCV_FN uint emcv_float_bits(float x) { return glm::floatBitsToUint(x); }
/// The float with these bits (GLSL uintBitsToFloat).
EMCV_FN float emcv_bits_float(uint x) { return glm::uintBitsToFloat(x); }
#else
uint emcv_float_bits(float x) { return floatBitsToUint(x); }
float emcv_bits_float(uint x) { return uintBitsToFloat(x); }
#endif

/// sigma's octave counted from 2^-24: negative under the range (0 and NaN included), read off the float's
/// exponent bits.
EMCV_FN int emcv_budget_octave(float sigma) {
    if (!(sigma >= 1.0f / 16777216.0f)) return -1;
    return int(emcv_float_bits(sigma) >> 23u) - 127 - EMCV_BUDGET_SIGMA_LOW_EXPONENT;
}

/// The histogram bin of sigma >= 0: 8 octave + the top 3 mantissa bits, clamped to the range.
EMCV_FN uint emcv_budget_bin(float sigma) {
    int octave = emcv_budget_octave(sigma);
    if (octave < 0) return 0u;
    if (octave >= EMCV_BUDGET_BINS / 8) return uint(EMCV_BUDGET_BINS - 1);
    return uint(octave) * 8u + ((emcv_float_bits(sigma) >> 20u) & 7u);
}

/// The 10 mantissa bits under the bin's 3 (0 under the range, 1023 above it): where sigma lies in its bin.
EMCV_FN uint emcv_budget_fraction(float sigma) {
    int octave = emcv_budget_octave(sigma);
    if (octave < 0) return 0u;
    if (octave >= EMCV_BUDGET_BINS / 8) return 1023u;
    return (emcv_float_bits(sigma) >> 10u) & 1023u;
}

/// The sum of sigma over a bin from its count and fraction sum: each pixel at its bin's lower edge plus its
/// fraction (taken at the middle of its 2^-10 step, the truncation's expectation) of the bin's width.
EMCV_FN float emcv_budget_bin_sum(uint bin, uint count, uint fraction_sum) {
    // lower edge 2^(low + bin/8) (1 + (bin%8)/8), width 2^(low + bin/8) / 8: both exact floats
    float octave_base = emcv_bits_float(uint(int(bin / 8u) + EMCV_BUDGET_SIGMA_LOW_EXPONENT + 127) << 23u);
    EMCV_PRECISE float edge = octave_base * (1.0f + float(bin % 8u) * 0.125f);
    EMCV_PRECISE float within = (float(fraction_sum) + 0.5f * float(count)) * (1.0f / 1024.0f);
    EMCV_PRECISE float sum = float(count) * edge + within * (octave_base * 0.125f);
    return sum;
}

/// One bin's samples at scale lambda: clamp(lambda sum, n_min count, n_max count) (exact when all the bin's
/// pixels lie on one side of a clamp; within 1/8 octave of it otherwise).
EMCV_FN float emcv_budget_bin_samples(float lambda, float bin_sum, uint count, float n_min, float n_max) {
    EMCV_PRECISE float linear = lambda * bin_sum;
    return clamp(linear, n_min * float(count), n_max * float(count));
}

/// The bisection's bounds on lambda's bit pattern: lambda = N / sigma in [2^-10, 2^34] covers sigma from
/// 2^-24 to 2^8 against counts from 2^-2 (under any floor) to 2^10 (N_MAX's range). The span holds 44 2^23 <
/// 2^29 patterns, so EMCV_BUDGET_SOLVE_STEPS halvings end on adjacent floats.
EMCV_FN uint emcv_budget_lambda_low_bits() { return uint(127 - 10) << 23u; }
/// The upper bound's bit pattern, 2^34 (see emcv_budget_lambda_low_bits).
EMCV_FN uint emcv_budget_lambda_high_bits() { return uint(127 + 34) << 23u; }

/// A pixel's real-valued share: clamp(lambda sigma, n_min, n_max).
EMCV_FN float emcv_budget_share(float lambda, float sigma, float n_min, float n_max) {
    EMCV_PRECISE float x = lambda * sigma;
    return clamp(x, n_min, n_max);
}

/// Stochastic rounding of x >= 0 with u uniform in [0, 1): floor(x) + [u < frac(x)], exact in expectation.
EMCV_FN int emcv_budget_round(float x, float u) {
    float whole = floor(x);
    return int(whole) + (u < x - whole ? 1 : 0);
}

/// The uniform number that rounds a pixel's share: a hash of (pixel, frame, seed) salted apart from the SSS
/// pass's sample rotation (port/sss.h), so that the rounding and the samples are independent.
EMCV_FN float emcv_budget_u(uint pixel_x, uint pixel_y, uint frame, uint seed) {
    uint h = emcv_pcg(pixel_y ^ emcv_pcg(pixel_x ^ emcv_pcg(seed ^ emcv_pcg(frame ^ 0x5bd1e995u))));
    return emcv_uint_to_unit_float(h);
}

EMCV_PORT_END

#endif  // #ifndef EMCV_PORT_BUDGET_H
