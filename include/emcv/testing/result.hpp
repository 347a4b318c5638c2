// SPDX-License-Identifier: MIT
// emcv::testing::test_result — what every statistical check of emcv/testing returns: the verdict, the test
// statistic, the p-value and the significance level it was compared with, and a message that says all of it.
#pragma once

#include <cmath>
#include <cstddef>
#include <sstream>
#include <stdexcept>
#include <string>

namespace emcv::testing {

/// The outcome of one statistical test: verdict, statistic, p-value, level and a message.
struct test_result {
    bool passed = false;   ///< p_value >= alpha: no evidence against the hypothesis at this level
    double statistic = 0;  ///< t, z, chi-square or the fitted convergence order (see the message)
    double p_value = 0;    ///< probability, under the hypothesis, of a statistic at least this extreme
    double alpha = 0;      ///< significance level actually used (after the Sidak correction)
    std::string message;   ///< the test, its statistic, p-value, alpha and verdict on one line; a rejected
                           ///< chi-square adds its worst cells on the lines below (docs/testing.md)

    /// True when the test passed (`passed`).
    explicit operator bool() const noexcept { return passed; }
};

/// Sidak correction: the per-test level that keeps the family-wise false-positive rate at `alpha` over
/// `test_count` independent tests, 1 - (1 - alpha)^(1 / test_count) (computed without cancellation).
inline double sidak_alpha(double alpha, std::size_t test_count) {
    if (!(alpha > 0.0 && alpha < 1.0)) throw std::invalid_argument("emcv::testing: alpha must lie in (0, 1)");
    if (test_count == 0) throw std::invalid_argument("emcv::testing: test_count must be at least 1");
    return -std::expm1(std::log1p(-alpha) / static_cast<double>(test_count));
}

namespace detail {

/// Fills in the verdict and a message "<what>: <details>, p = ..., alpha = ...: passed|REJECTED".
inline test_result make_result(const std::string& what, const std::string& details, double statistic,
                               double p_value, double alpha) {
    test_result r;
    r.statistic = statistic;
    r.p_value = p_value;
    r.alpha = alpha;
    r.passed = std::isfinite(statistic) && p_value >= alpha;
    std::ostringstream m;
    m << what << ": " << details << ", p = " << p_value << ", alpha = " << alpha << (r.passed ? ": passed" : ": REJECTED");
    r.message = m.str();
    return r;
}

}  // namespace detail
}  // namespace emcv::testing
