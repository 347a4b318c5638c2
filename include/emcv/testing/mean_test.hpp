// SPDX-License-Identifier: MIT
// emcv/testing/mean_test.hpp — does a Monte Carlo mean agree with its expected value?
//   t_test_mean: two-sided one-sample Student t-test, t = (mean - expected) / sqrt(s^2 / n), n - 1 dof
//                (exact for Gaussian samples, asymptotically exact for any finite-variance samples);
//   z_test_mean: the same with a known standard deviation sigma, z = (mean - expected) / (sigma / sqrt(n)).
// A correct estimator is rejected with probability alpha (the false-positive rate the caller chooses);
// `test_count` > 1 applies the Sidak correction so that alpha holds for the whole family of tests.
#pragma once

#include <cmath>
#include <cstddef>
#include <limits>
#include <sstream>
#include <string>

#include "distributions.hpp"
#include "result.hpp"

namespace emcv::testing {

/// t-test of a mean of `count` samples with unbiased sample variance `sample_variance` against `expected`.
inline test_result t_test_mean(std::size_t count, double mean, double sample_variance, double expected,
                               double alpha = 0.01, std::size_t test_count = 1) {
    const double level = sidak_alpha(alpha, test_count);
    if (count < 2) throw std::invalid_argument("emcv::testing::t_test_mean: needs at least 2 samples");
    std::ostringstream details;
    details << "mean " << mean << " vs expected " << expected << " over " << count << " samples (s^2 = " << sample_variance
            << ")";
    if (!std::isfinite(mean) || !std::isfinite(sample_variance) || !(sample_variance >= 0.0))
        return detail::make_result("t-test", details.str() + ", not finite", std::nan(""), 0.0, level);
    const double diff = mean - expected;
    double t = 0.0, p = 1.0;
    if (sample_variance > 0.0) {
        t = diff / std::sqrt(sample_variance / static_cast<double>(count));
        p = student_t_two_sided_p(t, static_cast<double>(count - 1));
    } else if (diff != 0.0) {  // no spread at all, and the wrong value: certain rejection
        t = std::copysign(std::numeric_limits<double>::infinity(), diff);
        p = 0.0;
    }
    details << ", t = " << t << " with " << count - 1 << " dof";
    return detail::make_result("t-test", details.str(), t, p, level);
}

/// z-test of a mean of `count` samples of known standard deviation `sigma` against `expected`.
inline test_result z_test_mean(std::size_t count, double mean, double sigma, double expected, double alpha = 0.01,
                               std::size_t test_count = 1) {
    const double level = sidak_alpha(alpha, test_count);
    if (count < 1) throw std::invalid_argument("emcv::testing::z_test_mean: needs at least 1 sample");
    if (!(sigma > 0.0) || std::isinf(sigma))
        throw std::invalid_argument("emcv::testing::z_test_mean: sigma must be positive and finite");
    std::ostringstream details;
    details << "mean " << mean << " vs expected " << expected << " over " << count << " samples (sigma = " << sigma << ")";
    if (!std::isfinite(mean))
        return detail::make_result("z-test", details.str() + ", not finite", std::nan(""), 0.0, level);
    const double z = (mean - expected) / (sigma / std::sqrt(static_cast<double>(count)));
    details << ", z = " << z;
    return detail::make_result("z-test", details.str(), z, std::erfc(std::fabs(z) / std::sqrt(2.0)), level);
}

/// t-test of a scalar accumulator with count(), mean(0) and sample_variance(0), e.g.
/// emcv::running_covariance<double, 1>.
template <class Accumulator>
auto t_test_mean(const Accumulator& acc, double expected, double alpha = 0.01, std::size_t test_count = 1)
    -> decltype(acc.count(), acc.mean(0), acc.sample_variance(0), test_result{}) {
    return t_test_mean(static_cast<std::size_t>(acc.count()), static_cast<double>(acc.mean(0)),
                       static_cast<double>(acc.sample_variance(0)), expected, alpha, test_count);
}

}  // namespace emcv::testing
