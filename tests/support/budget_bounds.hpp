// SPDX-License-Identifier: MIT
// The budget's bounds that the tests of its spending derive (the policy tests on the library's plan, the adaptive
// tests on the renderer's passes): how far the histogram's solve may leave the shares' sum from the plan, and
// how far the stochastic rounding may leave the counts' sum from the shares'.
#pragma once

#include <cmath>
#include <cstdint>

#include <emcv/adaptive_sampling.hpp>

namespace emcv_test {

/// The most the solve at `lambda` over histogram h may miss sum_i clamp(lambda sigma_i, n_min, n_max) = planned
/// (the shares of h's pixels against `planned`, B times its histogram and zero pixels): a bin straddling a clamp
/// c (lambda lo_b < c < lambda hi_b) is clamped as a whole, which moves its sum by at most count_b c (hi_b / lo_b
/// - 1) (the pixels beyond c lie within the bin's width of it); each pixel's sigma is known to 2^-13 of itself
/// (10 mantissa bits, taken at the middle of the step); the bisection ends on adjacent floats (2^-23 of lambda,
/// 2^-20 with margin).
inline double budget_solve_bound(const emcv::budget_histogram& h, float lambda, const emcv::sampling_params& p,
                                 double planned) {
    double bound = planned * (0x1.0p-13 + 0x1.0p-20);
    for (std::uint32_t b = 0; b < EMCV_BUDGET_BINS; ++b) {
        const double octave = std::ldexp(1.0, EMCV_BUDGET_SIGMA_LOW_EXPONENT + int(b / 8));
        const double lo = octave * (1 + (b % 8) / 8.0), hi = lo + octave / 8;
        for (const double c : {double(p.n_min), double(p.n_max)})
            if (lambda * lo < c && c < lambda * hi) bound += h.bin_count[b] * c * (hi / lo - 1);
    }
    return bound;
}

/// One pixel's share of the budget from its variance code, as emcv_history_count_budget rounds it: 0 for a pixel
/// that takes no samples, B (at most n_max) for one without a variance yet, else clamp(lambda sigma, n_min, n_max).
inline float budget_share_of(float sigma2, float lambda, const emcv::sampling_params& p) {
    if (sigma2 == emcv::port::emcv_history_no_samples()) return 0.0f;
    if (!(sigma2 >= 0.0f)) return std::fmin(p.budget, float(p.n_max));
    return emcv::port::emcv_budget_share(lambda, std::sqrt(sigma2), float(p.n_min), float(p.n_max));
}

/// The counts against the shares they were rounded from. N_i = floor(x_i) + [u_i < frac(x_i)] with u_i uniform
/// and independent across pixels is x_i plus a centred Bernoulli of variance frac (1 - frac) <= 1/4, so
///   sum    sum N - sum x has mean 0 and variance v = sum frac (1 - frac) <= P / 4;
///   by quarter  over the pixels whose fraction lies in one quarter of [0, 1), the number rounded up
///          (N_i - floor(x_i)) has mean sum frac and variance sum frac (1 - frac): the rounding goes up as often
///          as each fraction says, not only on average over the frame (plain rounding, which rounds none of the
///          lower quarters up and all of the upper ones, keeps the frame's mean where the fractions spread evenly).
/// The tests allow 5 standard deviations of each (a normal tail of 6e-7 over hundreds of pixels; Chebyshev's 1/25
/// for any count). A count that is neither floor(x_i) nor the next is counted apart (`off`).
struct rounding_sums {
    double shares = 0, counts = 0, variance = 0;
    double quarter_up[4] = {0, 0, 0, 0}, quarter_fraction[4] = {0, 0, 0, 0}, quarter_variance[4] = {0, 0, 0, 0};
    int off = 0;
    void add(float share, int count) {
        const double whole = std::floor(double(share)), frac = double(share) - whole;
        shares += share, counts += count, variance += frac * (1 - frac);
        const int up = count - int(whole);
        if (up != 0 && up != 1) ++off;
        const int q = frac < 0.25 ? 0 : frac < 0.5 ? 1 : frac < 0.75 ? 2 : 3;
        quarter_up[q] += up, quarter_fraction[q] += frac, quarter_variance[q] += frac * (1 - frac);
    }
    double bound() const { return 5 * std::sqrt(variance); }
    double quarter_bound(int q) const { return 5 * std::sqrt(quarter_variance[q]); }
};

}  // namespace emcv_test
