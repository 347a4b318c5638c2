// SPDX-License-Identifier: MIT
// emcv/testing/convergence_test.hpp — does an estimator's error fall like 1 / sqrt(n)?
//
// For each sample count n_k the caller's `error(n)` (estimate minus truth of one fresh estimator that used n
// samples) is drawn R times; MSE_k = mean of the R squared errors. For an unbiased estimator with finite
// variance sigma^2 and Gaussian error (the central limit regime), R MSE_k n_k / sigma^2 ~ chi-square(R), so
//   ln MSE_k = ln sigma^2 - ln n_k + eps_k,   eps_k = ln(chi-square(R) / R),   Var[eps_k] = psi_1(R / 2)
// (psi_1 the trigamma function), independent across k. The least-squares slope b of ln MSE on ln n then has
// mean -2 q (q = expected order, 1/2 for Monte Carlo: -1 for the MSE) and variance psi_1(R / 2) / S_xx, with
// S_xx = sum (ln n_k - mean)^2; z = (b + 2 q) / sd is close to normal (a sum of log-chi-square terms) and the
// test rejects when the two-sided normal p-value is below alpha. The statistic reported is the fitted order
// -b / 2 of the root-mean-square error. A bias, a variance that does not shrink, or correlated samples move b
// away from -1 and are rejected once R and the range of n make sd small enough (the message gives sd).
// Start the sample counts where the error is close to Gaussian (n >= 16 for a mean of skewed samples).
#pragma once

#include <cmath>
#include <cstddef>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "distributions.hpp"
#include "result.hpp"

namespace emcv::testing {

/// Settings of the 1/sqrt(n) convergence check.
struct convergence_options {
    double alpha = 0.01;         ///< false-positive rate
    std::size_t test_count = 1;  ///< Sidak correction over a family of tests
    std::size_t replicates = 64; ///< R: independent estimators per sample count
    double expected_order = 0.5; ///< q: error ~ n^-q
};

template <class ErrorFn>
test_result convergence_test(ErrorFn&& error, const std::vector<std::size_t>& sample_counts,
                             const convergence_options& o = {}) {
    const double level = sidak_alpha(o.alpha, o.test_count);
    if (sample_counts.size() < 2) throw std::invalid_argument("emcv::testing::convergence_test: needs 2 or more sample counts");
    if (o.replicates < 2) throw std::invalid_argument("emcv::testing::convergence_test: needs 2 or more replicates");
    std::vector<double> x, y;
    for (std::size_t n : sample_counts) {
        if (n == 0) throw std::invalid_argument("emcv::testing::convergence_test: sample counts must be positive");
        double sum_sq = 0.0;
        for (std::size_t r = 0; r < o.replicates; ++r) {
            const double e = static_cast<double>(error(n));
            sum_sq += e * e;
        }
        x.push_back(std::log(static_cast<double>(n)));
        y.push_back(std::log(sum_sq / static_cast<double>(o.replicates)));
    }
    double mx = 0.0, my = 0.0;
    for (std::size_t k = 0; k < x.size(); ++k) mx += x[k], my += y[k];
    mx /= static_cast<double>(x.size());
    my /= static_cast<double>(y.size());
    double sxx = 0.0, sxy = 0.0;
    for (std::size_t k = 0; k < x.size(); ++k) {
        sxx += (x[k] - mx) * (x[k] - mx);
        sxy += (x[k] - mx) * (y[k] - my);
    }
    if (!(sxx > 0.0)) throw std::invalid_argument("emcv::testing::convergence_test: sample counts must differ");
    const double slope = sxy / sxx;
    const double sd = std::sqrt(trigamma(0.5 * static_cast<double>(o.replicates)) / sxx);
    const double order = -0.5 * slope, z = (slope + 2.0 * o.expected_order) / sd;
    std::ostringstream m;
    m << "RMS error ~ n^-" << order << " (expected n^-" << o.expected_order << ", sd of the order " << 0.5 * sd
      << ", " << o.replicates << " replicates at " << sample_counts.size() << " sample counts), z = " << z;
    const double p = std::isfinite(z) ? std::erfc(std::fabs(z) / std::sqrt(2.0)) : 0.0;
    return detail::make_result("convergence", m.str(), order, p, level);
}

}  // namespace emcv::testing
