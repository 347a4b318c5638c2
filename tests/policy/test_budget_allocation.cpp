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
// And at a fractional budget (the issue "Cheap at equal time": plain rounding passed every test above, whose shares'
// fractions spread evenly, while emcv-demo at --spp-budget 2.5 spent 3.00 in its first two frames, every share B):
//   expected the rounding averages x over its random number: over the grid u = k 2^-16 (values emcv_budget_u
//            takes, spread evenly over [0, 1)), exactly floor(x) + ceil(frac(x) 2^16) / 2^16, x to within 2^-16;
//   frames   plan_frame at B = 2.5 and 5.75 on docs/integration.md's recipe spends B per pixel in every frame,
//            from the first (every history fresh: each share is B itself) on: the shares sum to B P up to the
//            solve's bound above, and the counts to the shares within 5 standard deviations of the rounding,
//            sqrt(sum frac (1 - frac)) <= sqrt(P) / 2; and by quarter of the shares' fractions, the pixels rounded up
//            as many as the fractions say (plain rounding keeps the frame's mean where the fractions spread evenly,
//            as from frame 2 on here, and is off by an eighth to three eighths of each quarter's pixels).
#include <catch2/catch_test_macros.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include <emcv/adaptive_sampling.hpp>

#include "../support/budget_bounds.hpp"
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
    double total = 0;
    const double bound = emcv_test::budget_solve_bound(h, lambda, p, bp);
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

TEST_CASE("the stochastic rounding's expected count over its random number is the share") {
    constexpr int grid = 1 << 16;
    // x's fractions from 0 to 1 - 2^-16, multiples of 2^-16 (exact expectation) and not (within 2^-16), counts
    // from under 1 to n_max's range
    for (const float x : {0.0f, 0.25f, 0.5f, 1.0f, 1.5f, 2.25f, 2.5f, 2.75f, 5.75f, 7.125f, 63.5f, 1.0f - 0x1.0p-16f,
                          0.1f, 2.3f, 5.9f, 40.01f}) {
        INFO("x " << x);
        const double whole = std::floor(double(x)), frac = double(x) - whole;
        double sum = 0;
        int lowest = 1 << 30, highest = -1;
        for (int k = 0; k < grid; ++k) {
            const int n = emcv::port::emcv_budget_round(x, float(k) * 0x1.0p-16f);
            sum += n;
            lowest = std::min(lowest, n), highest = std::max(highest, n);
        }
        const double mean = sum / grid;
        CHECK(mean == whole + std::ceil(frac * grid) / grid);
        CHECK(mean >= double(x));
        CHECK(mean - double(x) < 0x1.0p-16);
        CHECK(lowest == int(whole));                       // floor(x) ...
        CHECK(highest == int(whole) + (frac > 0 ? 1 : 0));  // ... or the next count, never further
    }
}

TEST_CASE("plan_frame spends a fractional budget B per pixel in every frame") {
    constexpr std::size_t side = 64, count = side * side;
    for (const float budget : {2.5f, 5.75f}) {
        emcv::sampling_params p;
        p.estimator = emcv::sampling_estimator::cv;
        p.mode = emcv::sampling_mode::budget;
        p.budget = budget;
        std::vector<emcv::port::EmcvEmcm2> history(count, emcv::port::emcv_emcm2_init());
        std::vector<float> sigma2(count), f(count), g(count);
        std::vector<int> n(count);
        emcv_policy_test::gaussian_source rng(5);
        emcv::budget_prior prior;
        double spent = 0, solves = 0, bernoullis = 0;
        constexpr std::uint32_t frames = 10;
        for (std::uint32_t frame = 0; frame < frames; ++frame) {
            INFO("B " << budget << ", frame " << frame);
            const emcv::frame_plan plan = emcv::plan_frame(p, history.data(), count, side, nullptr, nullptr, frame, 3u,
                                                           sigma2.data(), n.data(), prior);
            // the shares the counts were rounded from: B itself without a variance (frames 0 and 1), else the
            // solve's clamp(lambda sigma, n_min, n_max)
            emcv_test::rounding_sums sums;
            emcv::budget_histogram h = emcv::make_budget_histogram();
            emcv::budget_add(h, sigma2.data(), count);
            for (std::size_t i = 0; i < count; ++i) sums.add(emcv_test::budget_share_of(sigma2[i], plan.lambda, p), n[i]);
            const double sum_x = sums.shares, sum_n = sums.counts, bernoulli = sums.variance;
            const double bp = double(budget) * double(count);
            // every pixel without a variance: each share is B, summed exactly (no solve)
            const double solve = h.default_pixels == count ? 0.0 : emcv_test::budget_solve_bound(h, plan.lambda, p, bp);
            INFO("sum of shares " << sum_x << ", B P " << bp << " (bound " << solve << "); counts " << sum_n
                                  << ", rounding's sd " << std::sqrt(bernoulli));
            CHECK(std::fabs(sum_x - bp) <= solve);
            CHECK(std::fabs(sum_n - sum_x) <= 5 * std::sqrt(bernoulli));
            CHECK(sums.off == 0);
            for (int q = 0; q < 4; ++q) {  // up as often as each fraction says (tests/support/budget_bounds.hpp)
                INFO("fractions in [" << q / 4.0 << ", " << (q + 1) / 4.0 << "): rounded up " << sums.quarter_up[q]
                                      << ", expected " << sums.quarter_fraction[q]);
                CHECK(std::fabs(sums.quarter_up[q] - sums.quarter_fraction[q]) <= sums.quarter_bound(q));
            }
            CHECK(double(plan.samples) == sum_n);
            CHECK(std::fabs(sum_n / double(count) - budget) <= (solve + 5 * std::sqrt(bernoulli)) / double(count));
            spent += sum_n / double(count) / frames, solves += solve, bernoullis += bernoulli;
            // the recipe's field: a gradient of G, the top half's samples 10x noisier
            for (std::size_t i = 0; i < count; ++i) {
                g[i] = 0.2f + 0.6f * float(i % side) / float(side);
                const float spread = i < count / 2 ? 0.5f : 0.05f;
                f[i] = g[i] * (1.0f + spread * float(rng.normal()) / std::sqrt(float(n[i])));
            }
            emcv::sampling_update(p, history.data(), count, side, nullptr, f.data(), g.data(), n.data());
        }
        // the frames' mean: the solves' bounds plus 5 sd of the rounding over all frames (independent u per frame)
        const double bound = (solves + 5 * std::sqrt(bernoullis)) / (double(count) * frames);
        INFO("B " << budget << ": mean spent over " << frames << " frames " << spent << ", bound " << bound);
        CHECK(std::fabs(spent - budget) <= bound);
    }
}

}  // namespace budget_allocation_tests
