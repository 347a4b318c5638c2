// SPDX-License-Identifier: MIT
// emcv/testing/chi2_test.hpp — chi-square goodness-of-fit of a sampler against its CDF or pdf, after
// Mitsuba's chi2 tests (mitsuba/python/chi2.py): histogram the samples, integrate the pdf over each bin for
// the expected counts, pool the cells expected to receive fewer than `min_expected` samples (sorted by
// expectation, smallest first), and compare sum (O - E)^2 / E with the chi-square distribution of
// (cells - 1) degrees of freedom; p = Q(dof / 2, chi2 / 2). A sample landing in a cell of zero expectation
// rejects outright, and so does a non-finite sample (its own message: how many, the first value and draw).
// `test_count` > 1: Sidak correction over a family of tests. A rejection lists the cells with the largest
// contributions to chi2 in its message; chi2_options::histogram_csv writes every cell as CSV, which
// scripts/plot_chi2.py turns into a PNG (docs/testing.md).
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
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>
#include <string>
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
    std::size_t worst_cells = 5;    ///< a rejection lists this many cells, largest contribution to chi2 first
    std::string histogram_csv{};    ///< when not empty: every cell is written to this file as CSV (each run)
};

/// Where one cell of a chi-square histogram lies, for its message and its CSV row.
struct chi2_cell {
    /// What the cell is: a bin of the binned region, the mass outside it, or a caller's cell (chi2_test).
    enum class kind { bin, outside, cell };
    kind type = kind::cell;  ///< what the cell is
    double x_lo = 0;         ///< bin: lower edge in x (may be -inf for chi2_test_1d_cdf's first bin)
    double x_hi = 0;         ///< bin: upper edge in x (may be +inf for chi2_test_1d_cdf's last bin)
    double y_lo = 0;         ///< bin of chi2_test_2d_pdf: lower edge in y
    double y_hi = 0;         ///< bin of chi2_test_2d_pdf: upper edge in y
    bool two_d = false;      ///< the y edges are meaningful (chi2_test_2d_pdf)
};

namespace detail {

/// "x in [a, b)", "(x, y) in [a, b) x [c, d)", "outside [lo, hi)" or "cell i": where cell i lies.
inline std::string describe_cell(const std::vector<chi2_cell>& cells, std::size_t i) {
    std::ostringstream m;
    if (cells.empty() || cells[i].type == chi2_cell::kind::cell) {
        m << "cell " << i;
    } else if (cells[i].type == chi2_cell::kind::outside) {
        m << "outside the binned region";
    } else if (cells[i].two_d) {
        m << "(x, y) in [" << cells[i].x_lo << ", " << cells[i].x_hi << ") x [" << cells[i].y_lo << ", "
          << cells[i].y_hi << ")";
    } else {
        m << "x in [" << cells[i].x_lo << ", " << cells[i].x_hi << ")";
    }
    return m.str();
}

/// Writes one row per cell: cell,kind,x_lo,x_hi,y_lo,y_hi,observed,expected,contribution,pooled
/// (contribution (O - E)^2 / E of an unpooled cell; pooled cells count together, their column is empty).
inline void write_histogram_csv(const std::string& path, const std::vector<double>& observed,
                                const std::vector<double>& expected, const std::vector<chi2_cell>& cells,
                                const std::vector<bool>& is_pooled) {
    std::ofstream out(path);
    if (!out) throw std::invalid_argument("emcv::testing::chi2_test: cannot write histogram_csv '" + path + "'");
    out << std::setprecision(17) << "cell,kind,x_lo,x_hi,y_lo,y_hi,observed,expected,contribution,pooled\n";
    for (std::size_t i = 0; i < observed.size(); ++i) {
        const chi2_cell c = cells.empty() ? chi2_cell{} : cells[i];
        const char* kind_name =
            c.type == chi2_cell::kind::bin ? "bin" : (c.type == chi2_cell::kind::outside ? "outside" : "cell");
        out << i << ',' << kind_name << ',';
        if (c.type == chi2_cell::kind::bin) out << c.x_lo << ',' << c.x_hi << ',';
        else out << ",,";
        if (c.type == chi2_cell::kind::bin && c.two_d) out << c.y_lo << ',' << c.y_hi << ',';
        else out << ",,";
        out << observed[i] << ',' << expected[i] << ',';
        if (!is_pooled[i] && expected[i] > 0.0)
            out << (observed[i] - expected[i]) * (observed[i] - expected[i]) / expected[i];
        out << ',' << (is_pooled[i] ? 1 : 0) << '\n';
    }
    if (!out) throw std::invalid_argument("emcv::testing::chi2_test: cannot write histogram_csv '" + path + "'");
}

/// One entry of a rejection's list: a cell (or the pool) and its share of chi2.
struct chi2_contribution {
    std::string where;
    double observed, expected, contribution;
};

/// The test proper, with the cells' places for the message and the CSV (cells empty: a caller's histogram).
inline test_result chi2_test_cells(const std::vector<double>& observed, const std::vector<double>& expected,
                                   const std::vector<chi2_cell>& places, const chi2_options& o) {
    const double level = sidak_alpha(o.alpha, o.test_count);
    if (observed.size() != expected.size() || observed.empty())
        throw std::invalid_argument("emcv::testing::chi2_test: observed and expected need the same non-zero size");
    std::vector<std::size_t> order(expected.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return expected[a] < expected[b]; });

    double chi2 = 0.0, pooled_expected = 0.0, pooled_observed = 0.0;
    std::size_t cells = 0, pooled = 0;
    std::vector<bool> is_pooled(expected.size(), false);
    std::vector<chi2_contribution> contributions;
    for (std::size_t i : order) {
        const double e = expected[i], obs = observed[i];
        if (!(e >= 0.0) || !std::isfinite(e))
            throw std::invalid_argument("emcv::testing::chi2_test: expected counts must be finite and >= 0");
        if (e == 0.0 && obs > 0.0) {
            std::ostringstream m;
            m << obs << " samples in " << describe_cell(places, i)
              << " whose expected count is 0 (sampler outside the pdf's support)";
            return make_result("chi-square", m.str(), std::numeric_limits<double>::infinity(), 0.0, level);
        }
        if (e < o.min_expected || (pooled_expected > 0.0 && pooled_expected < o.min_expected)) {
            if (e > 0.0) ++pooled;
            pooled_expected += e;
            pooled_observed += obs;
            is_pooled[i] = true;
        } else {
            const double c = (obs - e) * (obs - e) / e;
            chi2 += c;
            ++cells;
            contributions.push_back({describe_cell(places, i), obs, e, c});
        }
    }
    if (pooled_expected > 0.0) {
        const double c = (pooled_observed - pooled_expected) * (pooled_observed - pooled_expected) / pooled_expected;
        chi2 += c;
        ++cells;
        contributions.push_back(
            {"the " + std::to_string(pooled) + " pooled cells", pooled_observed, pooled_expected, c});
    }
    if (!o.histogram_csv.empty()) write_histogram_csv(o.histogram_csv, observed, expected, places, is_pooled);
    std::ostringstream m;
    m << "chi2 = " << chi2 << " over " << cells << " cells (" << pooled << " pooled into one)";
    if (cells < 2)
        throw std::invalid_argument("emcv::testing::chi2_test: fewer than 2 cells after pooling: more samples needed");
    const double dof = static_cast<double>(cells - 1);
    m << ", " << cells - 1 << " dof";
    test_result r = make_result("chi-square", m.str(), chi2, chi2_survival(chi2, dof), level);
    if (!r.passed && o.worst_cells > 0) {
        std::stable_sort(contributions.begin(), contributions.end(),
                         [](const chi2_contribution& a, const chi2_contribution& b) {
                             return a.contribution > b.contribution;
                         });
        const std::size_t shown = std::min(o.worst_cells, contributions.size());
        std::ostringstream cells_text;
        cells_text << "\n  largest contributions to chi2 (" << shown << " of " << contributions.size()
                   << " cells):\n    "
                   << std::left << std::setw(32) << "cell" << std::right << std::setw(10) << "observed"
                   << std::setw(10) << "expected" << std::setw(11) << "(O-E)^2/E";
        for (std::size_t k = 0; k < shown; ++k) {
            const chi2_contribution& c = contributions[k];
            cells_text << "\n    " << std::left << std::setw(32) << c.where << std::right << std::setw(10)
                       << c.observed << std::setw(10) << c.expected << std::setw(11) << std::setprecision(4)
                       << c.contribution << std::setprecision(6);
        }
        r.message += cells_text.str();
    }
    if (!o.histogram_csv.empty()) r.message += "\n  histogram written to " + o.histogram_csv;
    return r;
}

}  // namespace detail

/// The chi-square test proper on per-cell observed and expected counts (equal sizes, expected >= 0); cells are
/// named by their index in the message and the CSV.
inline test_result chi2_test(const std::vector<double>& observed, const std::vector<double>& expected,
                             const chi2_options& o = {}) {
    return detail::chi2_test_cells(observed, expected, {}, o);
}

namespace detail {

/// Counts the non-finite values a sampler returned and remembers the first (value and 1-based draw).
struct non_finite_samples {
    std::size_t count = 0;       ///< non-finite draws so far
    std::size_t first_draw = 0;  ///< 1-based index of the first one
    std::string first_value;     ///< its text: "nan", "inf", "(0.5, nan)"

    /// Records draw `draw` (1-based) whose text is `value`.
    void add(std::size_t draw, const std::string& value) {
        if (count++ == 0) {
            first_draw = draw;
            first_value = value;
        }
    }
    /// The rejection: "sampler returned 3 non-finite samples (first: nan at draw 17 of 1000)".
    test_result result(std::size_t draws, const chi2_options& o) const {
        std::ostringstream m;
        m << "sampler returned " << count << " non-finite sample" << (count == 1 ? "" : "s") << " (first: "
          << first_value << " at draw " << first_draw << " of " << draws << ")";
        return make_result("chi-square", m.str(), std::numeric_limits<double>::infinity(), 0.0,
                           sidak_alpha(o.alpha, o.test_count));
    }
};

/// A double as text for the non-finite message ("nan", "-inf", "0.25").
inline std::string sample_text(double x) {
    std::ostringstream m;
    m << x;
    return m.str();
}

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
    std::vector<double> observed(bins, 0.0);
    detail::non_finite_samples non_finite;
    for (std::size_t i = 0; i < sample_count; ++i) {
        const double x = static_cast<double>(sample());
        if (!std::isfinite(x)) {
            non_finite.add(i + 1, detail::sample_text(x));
            continue;
        }
        observed[static_cast<std::size_t>(std::upper_bound(edges.begin(), edges.end(), x) - edges.begin())] += 1.0;
    }
    if (non_finite.count > 0) return non_finite.result(sample_count, o);
    // expected counts from the CDF at the edges actually found (equal to n / bins up to the bisection)
    std::vector<double> expected(bins, 0.0);
    std::vector<chi2_cell> places(bins);
    for (std::size_t k = 0; k < bins; ++k) {
        places[k].type = chi2_cell::kind::bin;
        places[k].x_lo = k == 0 ? -std::numeric_limits<double>::infinity() : edges[k - 1];
        places[k].x_hi = k + 1 < bins ? edges[k] : std::numeric_limits<double>::infinity();
    }
    double previous = 0.0;
    for (std::size_t k = 0; k < bins; ++k) {
        const double next = k + 1 < bins ? static_cast<double>(cdf(edges[k])) : 1.0;
        expected[k] = std::max(0.0, next - previous) * static_cast<double>(sample_count);
        previous = next;
    }
    return detail::chi2_test_cells(observed, expected, places, o);
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
    std::vector<double> observed(bins + 1, 0.0), expected(bins + 1, 0.0);  // + the outside cell
    std::vector<chi2_cell> places(bins + 1);
    double inside = 0.0;
    for (std::size_t k = 0; k < bins; ++k) {
        const double a = lo + width * static_cast<double>(k);
        const double mass = detail::simpson(pdf, a, a + width, o.simpson_steps);
        expected[k] = mass * n;
        inside += mass;
        places[k].type = chi2_cell::kind::bin;
        places[k].x_lo = a;
        places[k].x_hi = k + 1 < bins ? a + width : hi;
    }
    expected[bins] = detail::outside_mass(inside) * n;
    places[bins].type = chi2_cell::kind::outside;
    detail::non_finite_samples non_finite;
    for (std::size_t i = 0; i < sample_count; ++i) {
        const double x = static_cast<double>(sample());
        if (!std::isfinite(x)) non_finite.add(i + 1, detail::sample_text(x));
        else if (x < lo || x >= hi) observed[bins] += 1.0;
        else observed[std::min(bins - 1, static_cast<std::size_t>((x - lo) / width))] += 1.0;
    }
    if (non_finite.count > 0) return non_finite.result(sample_count, o);
    return detail::chi2_test_cells(observed, expected, places, o);
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
    std::vector<double> observed(cells + 1, 0.0), expected(cells + 1, 0.0);  // + the outside cell
    std::vector<chi2_cell> places(cells + 1);
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
            chi2_cell& place = places[j * bins_x + i];
            place.type = chi2_cell::kind::bin;
            place.two_d = true;
            place.x_lo = ax;
            place.x_hi = i + 1 < bins_x ? ax + wx : x1;
            place.y_lo = ay;
            place.y_hi = j + 1 < bins_y ? ay + wy : y1;
        }
    expected[cells] = detail::outside_mass(inside) * n;
    places[cells].type = chi2_cell::kind::outside;
    detail::non_finite_samples non_finite;
    for (std::size_t s = 0; s < sample_count; ++s) {
        const auto p = sample();
        const double x = static_cast<double>(p[0]), y = static_cast<double>(p[1]);
        if (!std::isfinite(x) || !std::isfinite(y))
            non_finite.add(s + 1, "(" + detail::sample_text(x) + ", " + detail::sample_text(y) + ")");
        else if (x < x0 || x >= x1 || y < y0 || y >= y1) observed[cells] += 1.0;
        else {
            const std::size_t i = std::min(bins_x - 1, static_cast<std::size_t>((x - x0) / wx));
            const std::size_t j = std::min(bins_y - 1, static_cast<std::size_t>((y - y0) / wy));
            observed[j * bins_x + i] += 1.0;
        }
    }
    if (non_finite.count > 0) return non_finite.result(sample_count, o);
    return detail::chi2_test_cells(observed, expected, places, o);
}

}  // namespace emcv::testing
