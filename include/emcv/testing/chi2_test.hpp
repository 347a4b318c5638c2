// SPDX-License-Identifier: MIT
// emcv/testing/chi2_test.hpp — chi-square goodness-of-fit of a sampler against its CDF or pdf, after
// Mitsuba's chi2 tests (mitsuba/python/chi2.py): histogram the samples, integrate the pdf over each bin for
// the expected counts, pool the cells expected to receive fewer than `min_expected` samples (sorted by
// expectation, smallest first), and compare sum (O - E)^2 / E with the chi-square distribution of
// (cells - 1) degrees of freedom; p = Q(dof / 2, chi2 / 2). A sample landing in a cell of zero expectation
// (or a non-finite sample) rejects outright. `test_count` > 1: Sidak correction over a family of tests.
//
//   chi2_test_1d_cdf: bins of equal probability, edges F^-1(k / bins) found by bisection on the CDF
//                     (open-ended first and last bins: any support, no pooling needed);
//   chi2_test_1d_pdf: equal-width bins on [lo, hi] plus one cell for the mass outside, pdf by Simpson's rule;
//   chi2_test_2d_pdf: a bins_x x bins_y grid on a rectangle plus the outside cell, pdf by 2-D Simpson's rule;
//   chi2_test:        the test itself, on observed and expected counts the caller made.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "distributions.hpp"
#include "result.hpp"

namespace emcv::testing {

/// Settings of the chi-square goodness-of-fit tests (Mitsuba-style binning and pooling).
struct chi2_options {
    double alpha = 0.01;            ///< family-wise false-positive rate
    std::size_t test_count = 1;     ///< number of tests in the family (Sidak correction)
    double min_expected = 5.0;      ///< cells expected to receive fewer samples are pooled (Cochran's rule)
    std::size_t simpson_steps = 8;  ///< Simpson sub-intervals per bin and axis (even) for the pdf variants
};

/// The chi-square test proper on per-cell observed and expected counts (equal sizes, expected >= 0).
inline test_result chi2_test(const std::vector<double>& observed, const std::vector<double>& expected,
                             const chi2_options& o = {}) {
    const double level = sidak_alpha(o.alpha, o.test_count);
    if (observed.size() != expected.size() || observed.empty())
        throw std::invalid_argument("emcv::testing::chi2_test: observed and expected need the same non-zero size");
    std::vector<std::size_t> order(expected.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return expected[a] < expected[b]; });

    double chi2 = 0.0, pooled_expected = 0.0, pooled_observed = 0.0;
    std::size_t cells = 0, pooled = 0;
    for (std::size_t i : order) {
        const double e = expected[i], obs = observed[i];
        if (!(e >= 0.0) || !std::isfinite(e))
            throw std::invalid_argument("emcv::testing::chi2_test: expected counts must be finite and >= 0");
        if (e == 0.0 && obs > 0.0) {
            std::ostringstream m;
            m << obs << " samples in cell " << i << " whose expected count is 0 (sampler outside the pdf's support)";
            return detail::make_result("chi-square", m.str(), std::numeric_limits<double>::infinity(), 0.0, level);
        }
        if (e < o.min_expected || (pooled_expected > 0.0 && pooled_expected < o.min_expected)) {
            if (e > 0.0) ++pooled;
            pooled_expected += e;
            pooled_observed += obs;
        } else {
            chi2 += (obs - e) * (obs - e) / e;
            ++cells;
        }
    }
    if (pooled_expected > 0.0) {
        chi2 += (pooled_observed - pooled_expected) * (pooled_observed - pooled_expected) / pooled_expected;
        ++cells;
    }
    std::ostringstream m;
    m << "chi2 = " << chi2 << " over " << cells << " cells (" << pooled << " pooled into one)";
    if (cells < 2)
        throw std::invalid_argument("emcv::testing::chi2_test: fewer than 2 cells after pooling: more samples needed");
    const double dof = static_cast<double>(cells - 1);
    m << ", " << cells - 1 << " dof";
    return detail::make_result("chi-square", m.str(), chi2, chi2_survival(chi2, dof), level);
}

namespace detail {

/// Probability outside the binned region, 1 - sum of the bins' masses; below 1e-9 it is taken as exactly 0
/// (what is left is integration rounding), so that samples landing there reject instead of being pooled.
inline double outside_mass(double inside) {
    const double outside = 1.0 - inside;
    return outside < 1e-9 ? 0.0 : outside;
}

inline void check_sample_setup(std::size_t bins, std::size_t sample_count, const chi2_options& o) {
    if (bins < 2) throw std::invalid_argument("emcv::testing: at least 2 bins");
    if (sample_count == 0) throw std::invalid_argument("emcv::testing: sample_count must be positive");
    if (o.simpson_steps < 2 || o.simpson_steps % 2 != 0)
        throw std::invalid_argument("emcv::testing: simpson_steps must be even and >= 2");
}

/// Composite Simpson's rule of f over [a, b] with `steps` (even) sub-intervals.
template <class F>
double simpson(F&& f, double a, double b, std::size_t steps) {
    const double h = (b - a) / static_cast<double>(steps);
    double sum = static_cast<double>(f(a)) + static_cast<double>(f(b));
    for (std::size_t i = 1; i < steps; ++i)
        sum += (i % 2 ? 4.0 : 2.0) * static_cast<double>(f(a + h * static_cast<double>(i)));
    return sum * h / 3.0;
}

/// x with cdf(x) = q, for a non-decreasing cdf: bracket by doubling outward from [-1, 1], then bisect.
template <class Cdf>
double cdf_inverse(Cdf& cdf, double q) {
    double lo = -1.0, hi = 1.0;
    for (int i = 0; i < 1100 && static_cast<double>(cdf(lo)) > q; ++i) lo *= 2.0;
    for (int i = 0; i < 1100 && static_cast<double>(cdf(hi)) < q; ++i) hi *= 2.0;
    for (int i = 0; i < 2200; ++i) {
        const double mid = 0.5 * (lo + hi);
        if (mid <= lo || mid >= hi) break;
        (static_cast<double>(cdf(mid)) < q ? lo : hi) = mid;
    }
    return hi;
}

}  // namespace detail

/// Draws `sample_count` values from `sample()` and tests them against the distribution with CDF `cdf(x)`
/// (non-decreasing, from 0 to 1), in `bins` bins of equal probability.
template <class Sampler, class Cdf>
test_result chi2_test_1d_cdf(Sampler&& sample, Cdf&& cdf, std::size_t bins, std::size_t sample_count,
                             const chi2_options& o = {}) {
    detail::check_sample_setup(bins, sample_count, o);
    std::vector<double> edges(bins - 1);
    for (std::size_t k = 1; k < bins; ++k)
        edges[k - 1] = detail::cdf_inverse(cdf, static_cast<double>(k) / static_cast<double>(bins));
    std::vector<double> observed(bins + 1, 0.0);  // last cell: non-finite samples, expected 0
    for (std::size_t i = 0; i < sample_count; ++i) {
        const double x = static_cast<double>(sample());
        if (!std::isfinite(x)) {
            observed[bins] += 1.0;
            continue;
        }
        observed[static_cast<std::size_t>(std::upper_bound(edges.begin(), edges.end(), x) - edges.begin())] += 1.0;
    }
    // expected counts from the CDF at the edges actually found (equal to n / bins up to the bisection)
    std::vector<double> expected(bins + 1, 0.0);
    double previous = 0.0;
    for (std::size_t k = 0; k < bins; ++k) {
        const double next = k + 1 < bins ? static_cast<double>(cdf(edges[k])) : 1.0;
        expected[k] = std::max(0.0, next - previous) * static_cast<double>(sample_count);
        previous = next;
    }
    return chi2_test(observed, expected, o);
}

/// Draws `sample_count` values from `sample()` and tests them against the density `pdf(x)` (integrating
/// to 1 over its support), histogrammed in `bins` equal bins on [lo, hi] plus one cell for the rest.
template <class Sampler, class Pdf>
test_result chi2_test_1d_pdf(Sampler&& sample, Pdf&& pdf, double lo, double hi, std::size_t bins,
                             std::size_t sample_count, const chi2_options& o = {}) {
    detail::check_sample_setup(bins, sample_count, o);
    if (!(lo < hi) || !std::isfinite(lo) || !std::isfinite(hi))
        throw std::invalid_argument("emcv::testing::chi2_test_1d_pdf: needs finite lo < hi");
    const double width = (hi - lo) / static_cast<double>(bins), n = static_cast<double>(sample_count);
    std::vector<double> observed(bins + 2, 0.0), expected(bins + 2, 0.0);  // + outside, + non-finite
    double inside = 0.0;
    for (std::size_t k = 0; k < bins; ++k) {
        const double a = lo + width * static_cast<double>(k);
        const double mass = detail::simpson(pdf, a, a + width, o.simpson_steps);
        expected[k] = mass * n;
        inside += mass;
    }
    expected[bins] = detail::outside_mass(inside) * n;
    for (std::size_t i = 0; i < sample_count; ++i) {
        const double x = static_cast<double>(sample());
        if (!std::isfinite(x)) observed[bins + 1] += 1.0;
        else if (x < lo || x >= hi) observed[bins] += 1.0;
        else observed[std::min(bins - 1, static_cast<std::size_t>((x - lo) / width))] += 1.0;
    }
    return chi2_test(observed, expected, o);
}

/// 2-D version: `sample()` returns something indexable as [0], [1] (std::array, glm::vec2), `pdf(x, y)` a
/// density on the plane; a bins_x x bins_y grid on [x0, x1] x [y0, y1] plus one cell for the rest.
template <class Sampler, class Pdf>
test_result chi2_test_2d_pdf(Sampler&& sample, Pdf&& pdf, std::array<double, 4> x0_x1_y0_y1, std::size_t bins_x,
                             std::size_t bins_y, std::size_t sample_count, const chi2_options& o = {}) {
    detail::check_sample_setup(std::min(bins_x, bins_y) * 2, sample_count, o);
    const auto [x0, x1, y0, y1] = x0_x1_y0_y1;
    if (!(x0 < x1 && y0 < y1) || !std::isfinite(x0) || !std::isfinite(x1) || !std::isfinite(y0) || !std::isfinite(y1))
        throw std::invalid_argument("emcv::testing::chi2_test_2d_pdf: needs a finite rectangle x0 < x1, y0 < y1");
    const double wx = (x1 - x0) / static_cast<double>(bins_x), wy = (y1 - y0) / static_cast<double>(bins_y);
    const double n = static_cast<double>(sample_count);
    const std::size_t cells = bins_x * bins_y;
    std::vector<double> observed(cells + 2, 0.0), expected(cells + 2, 0.0);
    double inside = 0.0;
    for (std::size_t j = 0; j < bins_y; ++j)
        for (std::size_t i = 0; i < bins_x; ++i) {
            const double ax = x0 + wx * static_cast<double>(i), ay = y0 + wy * static_cast<double>(j);
            const double mass = detail::simpson(
                [&](double y) {
                    return detail::simpson([&](double x) { return static_cast<double>(pdf(x, y)); }, ax, ax + wx,
                                           o.simpson_steps);
                },
                ay, ay + wy, o.simpson_steps);
            expected[j * bins_x + i] = mass * n;
            inside += mass;
        }
    expected[cells] = detail::outside_mass(inside) * n;
    for (std::size_t s = 0; s < sample_count; ++s) {
        const auto p = sample();
        const double x = static_cast<double>(p[0]), y = static_cast<double>(p[1]);
        if (!std::isfinite(x) || !std::isfinite(y)) observed[cells + 1] += 1.0;
        else if (x < x0 || x >= x1 || y < y0 || y >= y1) observed[cells] += 1.0;
        else {
            const std::size_t i = std::min(bins_x - 1, static_cast<std::size_t>((x - x0) / wx));
            const std::size_t j = std::min(bins_y - 1, static_cast<std::size_t>((y - y0) / wy));
            observed[j * bins_x + i] += 1.0;
        }
    }
    return chi2_test(observed, expected, o);
}

}  // namespace emcv::testing
