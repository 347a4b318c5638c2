// A deliberately failing Catch2 test: the sampler draws at rate 1.8 where its CDF says 2, a second sampler
// sometimes returns NaN, and the integrand carries a bias of 0.01. docs/testing.md shows this file and its
// output (tests/testing/failing_example/expected_output.txt, compared with a fresh run by `ctest -L testing`).
#include <emcv/emcv.hpp>
#include <emcv/testing/catch2.hpp>

#include <catch2/catch_test_macros.hpp>

#include <cmath>
#include <random>

TEST_CASE("my sampler draws from its pdf") {
    std::mt19937_64 rng(42);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    auto sample = [&] { return -std::log1p(-u(rng)) / 1.8; };  // the bug: rate 1.8
    auto cdf = [](double x) { return x <= 0.0 ? 0.0 : -std::expm1(-2.0 * x); };
    emcv::testing::chi2_options o;
    o.histogram_csv = "my_sampler_chi2.csv";  // /usr/bin/python3 scripts/plot_chi2.py my_sampler_chi2.csv
    EMCV_CHECK_STAT(emcv::testing::chi2_test_1d_cdf(sample, cdf, 20, 10000, o));

    auto with_nan = [&] {
        const double x = u(rng);
        return x < 1e-3 ? std::nan("") : -std::log1p(-x) / 2.0;
    };
    EMCV_CHECK_STAT(emcv::testing::chi2_test_1d_cdf(with_nan, cdf, 20, 10000));
}

TEST_CASE("my integrator is unbiased") {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    emcv::running_covariance<double, 1> estimate;
    for (int i = 0; i < 10000; ++i) {
        const double x = u(rng);
        estimate.push(x * x + 0.01);  // the bug: + 0.01
    }
    EMCV_CHECK_STAT(emcv::testing::t_test_mean(estimate, 1.0 / 3.0));
}
