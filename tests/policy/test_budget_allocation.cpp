// SPDX-License-Identifier: MIT
// Budget mode on a synthetic field: 10,000 pixels with sigma log-uniform over three decades [1e-3, 1], plus 500
// sub-pixel pixels (no samples: their share goes to the others) and 100 without a variance (the budget each).
// B = 32, n_min = 1, n_max = 64: the unclamped scale would put lambda sigma over [0.22, 221], so both the floor
// and the cap bind.
//   total    sum_i clamp(lambda sigma_i, n_min, n_max) over the histogram pixels = B (histogram + sub-pixel
//            pixels) up to the histogram's resolution: a bin straddling a clamp boundary c (lambda lo_b < c <
//            lambda hi_b) is clamped as a whole, which moves its sum by at most count_b c (hi_b / lo_b - 1) (the
//            pixels beyond c are within the bin's width of it); each pixel's sigma is known to 2^-13 of itself
//            (10 mantissa bits, taken at the middle of the step); the bisection ends on adjacent floats
//            (2^-23 of lambda). With ~125 pixels a bin (80 bins) that bound is about 0.3% of B P: under 0.5%.
//   ratios   unclamped shares are lambda sigma_i rounded once to float: x_i / x_j = sigma_i / sigma_j to 2^-23.
//   clamps   every count in [n_min, n_max]; a share at or past a clamp is exactly the clamp.
//   rounding N_i = floor(x_i) + [u_i < frac(x_i)], u from the PCG hash: N_i - x_i is a centred Bernoulli, so
//            sum N_i - sum x_i has variance sum frac (1 - frac): within 5 of its standard deviations.
#include <catch2/catch_test_macros.hpp>

#include <cmath>
#include <cstdint>
#include <vector>

#include <emcv/adaptive_sampling.hpp>

#include "policy_support.hpp"

namespace budget_allocation_tests {  // one namespace per file: the unity build (the sanitize preset) joins files

namespace {

constexpr std::size_t field = 10000, sub_pixel = 500, no_variance = 100;
constexpr std::size_t pixels = field + sub_pixel + no_variance, width = 100;  // 106 rows of 100

}  // namespace

TEST_CASE("the budget's lambda spends B per pixel over a log-uniform sigma field, in proportion to sigma") {
    emcv_policy_test::gaussian_source rng(2024);
    emcv::sampling_params p;
    p.mode = emcv::sampling_mode::budget;
    p.budget = 32;
    p.n_min = 1;
    p.n_max = 64;
    std::vector<float> sigma2(pixels);
    for (std::size_t i = 0; i < field; ++i) {  // sigma log-uniform over [1e-3, 1]: sigma^2 over [1e-6, 1]
        const double sigma = std::pow(10.0, -3.0 + 3.0 * rng.uniform());
        sigma2[i] = static_cast<float>(sigma * sigma);
    }
    for (std::size_t i = field; i < field + sub_pixel; ++i) sigma2[i] = emcv::port::emcv_history_no_samples();
    for (std::size_t i = field + sub_pixel; i < pixels; ++i) sigma2[i] = emcv::port::emcv_history_no_variance();

    emcv::budget_histogram h = emcv::make_budget_histogram();
    emcv::budget_add(h, sigma2.data(), pixels);
    REQUIRE(h.zero_pixels == sub_pixel);
    REQUIRE(h.default_pixels == no_variance);
    const float lambda = emcv::budget_solve(p, h);
    const double bp = double(p.budget) * double(field + sub_pixel);

    // total against the derived bound
    double total = 0, bound = bp * (0x1.0p-13 + 0x1.0p-20);
    for (std::uint32_t b = 0; b < EMCV_BUDGET_BINS; ++b) {
        const double octave = std::ldexp(1.0, EMCV_BUDGET_SIGMA_LOW_EXPONENT + int(b / 8));
        const double lo = octave * (1 + (b % 8) / 8.0), hi = lo + octave / 8;
        for (const double c : {double(p.n_min), double(p.n_max)})
            if (lambda * lo < c && c < lambda * hi) bound += h.bin_count[b] * c * (hi / lo - 1);
    }
    std::vector<double> share(pixels);
    for (std::size_t i = 0; i < field; ++i) {
        const double sigma = std::sqrt(sigma2[i]);
        share[i] = std::fmin(std::fmax(lambda * sigma, p.n_min), p.n_max);
        total += share[i];
    }
    INFO("lambda " << lambda << ", sum of shares " << total << ", B P " << bp << ", bound " << bound);
    CHECK(bound < 0.005 * bp);
    CHECK(std::fabs(total - bp) <= bound);

    // ratios of unclamped shares, as the port computes them (emcv_budget_share), against the sigmas
    std::size_t unclamped = 0, at_floor = 0, at_cap = 0;
    float previous_x = 0, previous_sigma = 0;
    for (std::size_t i = 0; i < field; ++i) {
        const float sigma = std::sqrt(sigma2[i]);
        const float x = emcv::port::emcv_budget_share(lambda, sigma, float(p.n_min), float(p.n_max));
        if (double(lambda) * sigma <= p.n_min) {
            CHECK(x == float(p.n_min));
            ++at_floor;
        } else if (double(lambda) * sigma >= p.n_max) {
            CHECK(x == float(p.n_max));
            ++at_cap;
        } else {
            if (previous_x > 0) {
                const double ratio = (double(x) / previous_x) / (double(sigma) / previous_sigma);
                CHECK(std::fabs(ratio - 1) <= 0x1.0p-22);
            }
            previous_x = x, previous_sigma = sigma;
            ++unclamped;
        }
    }
    INFO("at the floor " << at_floor << ", at the cap " << at_cap << ", between " << unclamped);
    CHECK(at_floor > 100);  // both clamps bind on this field
    CHECK(at_cap > 100);

    // the counts as the burley pass takes them, and the stochastic rounding's mean
    std::vector<int> n(pixels);
    const std::uint64_t samples = emcv::sampling_counts(p, sigma2.data(), pixels, width, lambda, 7u, 3u, n.data());
    double sum_n = 0, sum_x = 0, bernoulli = 0;
    for (std::size_t i = 0; i < field; ++i) {
        const float x = emcv::port::emcv_budget_share(lambda, std::sqrt(sigma2[i]), float(p.n_min), float(p.n_max));
        CHECK(n[i] >= p.n_min);
        CHECK(n[i] <= p.n_max);
        CHECK((n[i] == int(std::floor(x)) || n[i] == int(std::floor(x)) + 1));
        const double frac = x - std::floor(x);
        sum_n += n[i], sum_x += x, bernoulli += frac * (1 - frac);
    }
    INFO("sum N " << sum_n << ", sum of shares " << sum_x << ", Bernoulli sd " << std::sqrt(bernoulli));
    CHECK(bernoulli > 100);  // the rounding is exercised
    CHECK(std::fabs(sum_n - sum_x) <= 5 * std::sqrt(bernoulli));
    for (std::size_t i = field; i < field + sub_pixel; ++i) CHECK(n[i] == 0);
    for (std::size_t i = field + sub_pixel; i < pixels; ++i) CHECK(n[i] == 32);  // B, an integer: exact
    CHECK(samples == static_cast<std::uint64_t>(sum_n) + 32u * no_variance);
    // The frame spends B per SSS pixel: the sub-pixel pixels' share went to the others.
    const double mean = double(samples) / double(pixels);
    CHECK(std::fabs(mean - p.budget) <= (bound + 5 * std::sqrt(bernoulli)) / double(pixels));
}

}  // namespace budget_allocation_tests
