// emcm, ewma_covariance and moving_stats: the exponential moving special cases of the one recurrence.
#include <emcv/emcm.hpp>
#include <emcv/ewma_covariance.hpp>
#include <emcv/moving_stats.hpp>
#include <emcv/weighted_covariance.hpp>

#include <catch2/catch_test_macros.hpp>
#include <catch2/generators/catch_generators.hpp>

#include <random>

#include "../support/reference.hpp"

using emcv_test::kTolerance;
using emcv_test::real;

namespace {

std::vector<std::array<double, 2>> stream(std::uint64_t seed, std::size_t n) {
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> normal(0.0, 1.0);
    std::vector<std::array<double, 2>> xs(n);
    for (auto& x : xs) {
        const double f = normal(rng);
        x = {10.0 + f, -4.0 + 0.6 * f + 0.8 * normal(rng)};
    }
    return xs;
}

}  // namespace

TEST_CASE("emcm equals the weighted covariance under geometric weights (Eq. 18 21 24)", "[emcm]") {
    const double eta = GENERATE(1.0, 0.5, 0.2, 0.05, 1e-3);
    const std::size_t length = GENERATE(std::size_t{1}, std::size_t{2}, std::size_t{30}, std::size_t{700});
    const auto xs = stream(static_cast<std::uint64_t>(length) + 17, length);
    emcv::emcm<double, 2> e(eta);
    for (std::size_t n = 0; n < length; ++n) {
        e.push(xs[n]);
        if (n % 37 != 0 && n + 1 != length) continue;
        const auto w = emcv_test::geometric_weights(eta, n + 1);
        const auto ref = emcv_test::two_pass<2>(xs, w, n + 1);
        REQUIRE(e.total_weight() == 1.0);
        for (std::size_t a = 0; a < 2; ++a) {
            const real sd = std::sqrt(ref.covariance[a][a]);
            INFO("eta " << eta << " n " << n << " mean " << a);
            REQUIRE(emcv_test::scaled_error(e.mean(a), ref.mean[a], std::fabs(ref.mean[a]) + sd) <= kTolerance);
            for (std::size_t b = 0; b < 2; ++b) {
                // once every weight is geometric the reference's own spread can be 0 (eta = 1): compare absolutely
                const real scale = std::max(std::sqrt(ref.covariance[a][a] * ref.covariance[b][b]), real(1e-300));
                REQUIRE(emcv_test::scaled_error(e.covariance(a, b), ref.covariance[a][b],
                                                ref.covariance[a][a] > 0 ? scale : 1) <= kTolerance);
            }
        }
    }
}

TEST_CASE("weighted_covariance pushed with weight eta and decay 1 - eta is the geometric-weight covariance", "[emcm]") {
    // The push(x, w, decay) route to Eq. 21's weights, checked against the two-pass long-double weighted
    // covariance with the weights of Eq. 18 (not against emcm, which shares its recurrence).
    const double eta = 0.05;
    const auto xs = stream(5, 500);
    emcv::weighted_covariance<double, 2> w;
    for (std::size_t n = 0; n < xs.size(); ++n) {
        if (n == 0)
            w.push(xs[n], 1.0, 1.0);  // the seed
        else
            w.push(xs[n], eta, 1.0 - eta);
    }
    const auto ref = emcv_test::two_pass<2>(xs, emcv_test::geometric_weights(eta, xs.size()), xs.size());
    REQUIRE(std::fabs(w.total_weight() - 1.0) <= 1e-13);
    for (std::size_t a = 0; a < 2; ++a) {
        const real sd = std::sqrt(ref.covariance[a][a]);
        REQUIRE(emcv_test::scaled_error(w.mean(a), ref.mean[a], std::fabs(ref.mean[a]) + sd) <= kTolerance);
        for (std::size_t b = 0; b < 2; ++b)
            REQUIRE(emcv_test::scaled_error(w.covariance(a, b), ref.covariance[a][b],
                                            std::sqrt(ref.covariance[a][a] * ref.covariance[b][b])) <= kTolerance);
    }
}

TEST_CASE("the expansion identities behind Eq. 21 hold step by step (supp. Eq. 12-16)", "[emcm]") {
    // With d = x_n - mu_{n-1} and geometric weights (W = 1):
    //   Eq. 12  mu_n - mu_{n-1} = eta d
    //   Eq. 13  x_n - mu_n = (1 - eta) d
    //   Eq. 14  sum_{i<n} w_{n,i} (x_i - mu_n)(y_i - nu_n)
    //             = (1 - eta) [Cov_{n-1} + (mu_{n-1} - mu_n)(nu_{n-1} - nu_n)]   (the cross terms vanish)
    //   Eq. 15  the new sample's term: eta (x_n - mu_n)(y_n - nu_n) = eta (1 - eta)^2 d_x d_y
    //   Eq. 16  sum: (1 - eta) Cov_{n-1} + (1 - eta) eta^2 d_x d_y + eta (1 - eta)^2 d_x d_y
    //             = (1 - eta) Cov_{n-1} + eta (1 - eta) d_x d_y               (= Eq. 21)
    // Each side is computed independently: the left sides by brute force over the stored samples.
    const double eta = 0.1;
    const auto xs = stream(99, 60);
    emcv::emcm<double, 2> e(eta);
    e.push(xs[0]);
    for (std::size_t n = 1; n < xs.size(); ++n) {
        const auto mu_prev = e.mean();
        const double cov_prev = e.covariance(0, 1);
        const double dx = xs[n][0] - mu_prev[0], dy = xs[n][1] - mu_prev[1];
        e.push(xs[n]);
        const auto mu = e.mean();
        const double tol = 1e-12 * (1 + std::fabs(mu[0]) + std::fabs(mu[1]));
        REQUIRE(std::fabs((mu[0] - mu_prev[0]) - eta * dx) <= tol);           // Eq. 12
        REQUIRE(std::fabs((xs[n][0] - mu[0]) - (1 - eta) * dx) <= tol);      // Eq. 13

        const auto w = emcv_test::geometric_weights(eta, n + 1);
        real old_terms = 0;
        for (std::size_t i = 0; i < n; ++i)
            old_terms += w[i] * (xs[i][0] - static_cast<real>(mu[0])) * (xs[i][1] - static_cast<real>(mu[1]));
        const real eq14 = (1 - eta) * (cov_prev + (mu_prev[0] - mu[0]) * (mu_prev[1] - mu[1]));
        const real new_term = w[n] * (xs[n][0] - static_cast<real>(mu[0])) * (xs[n][1] - static_cast<real>(mu[1]));
        const real eq15 = eta * (1 - eta) * (1 - eta) * dx * dy;
        const real scale = 1e-11 * (std::fabs(cov_prev) + std::fabs(dx * dy) + 1);
        REQUIRE(std::fabs(old_terms - eq14) <= scale);                          // Eq. 14
        REQUIRE(std::fabs(new_term - eq15) <= scale);                           // Eq. 15
        REQUIRE(std::fabs(e.covariance(0, 1) - (eq14 + eq15)) <= scale);        // Eq. 16 = Eq. 21
    }
}

TEST_CASE("EWMA covariance (Eq. 22) is EMCM / (1 - eta) at every step", "[ewma]") {
    const double eta = GENERATE(0.5, 0.2, 0.05);
    const auto xs = stream(3, 400);
    emcv::emcm<double, 2> e(eta);
    emcv::ewma_covariance<double, 2> w(eta);
    for (const auto& x : xs) {
        e.push(x);
        w.push(x);
        REQUIRE(w.mean() == e.mean());
        for (std::size_t a = 0; a < 2; ++a)
            for (std::size_t b = 0; b < 2; ++b)
                REQUIRE(std::fabs(w.covariance(a, b) - e.covariance(a, b) / (1 - eta)) <=
                        1e-13 * std::sqrt(w.variance(a) * w.variance(b)));
    }
}

TEST_CASE("EWMA with eta = 1 keeps only the last squared step and EMCM with eta = 1 forgets everything", "[ewma]") {
    emcv::ewma_covariance<double, 1> w(1.0);
    emcv::emcm<double, 1> e(1.0);
    for (double x : {1.0, 4.0, 2.0}) {
        w.push(x);
        e.push(x);
    }
    REQUIRE(w.variance(0) == 4.0);  // (2 - 4)^2
    REQUIRE(e.variance(0) == 0.0);
    REQUIRE(e.mean(0) == 2.0);
}

TEST_CASE("moving_stats follows SPVG's history update (UE UpdateQualityVariance form)", "[moving_stats]") {
    // The UE form, run independently in long double: mu' = (1 - a) mu + a x, var' = (1 - a) var + a (1 - a) (x - mu)^2,
    // seeded with mu = x_0, var = 0. Relative agreement to 1e-12 at every step.
    const double a = 0.2;
    emcv::moving_stats<double> m(a);
    const auto xs = stream(8, 100);
    real mu = xs[0][0], var = 0;
    m.push(xs[0][0]);
    for (std::size_t n = 1; n < xs.size(); ++n) {
        const real x = xs[n][0];
        var = (1 - a) * var + a * (1 - a) * (x - mu) * (x - mu);
        mu = (1 - a) * mu + a * x;
        m.push(xs[n][0]);
        INFO("step " << n);
        REQUIRE(std::fabs(m.mean() - mu) <= 1e-12 * (std::fabs(mu) + 1));
        REQUIRE(std::fabs(m.variance() - var) <= 1e-12 * (var + 1e-300));
    }
    REQUIRE(m.count() == xs.size());
    m.reset();
    REQUIRE(m.count() == 0);
    REQUIRE(m.variance() == 0.0);
}

TEST_CASE("the first sample seeds the mean with zero covariance", "[emcm]") {
    emcv::emcm<float, 3> e(0.05f);
    e.push({1.0f, -2.0f, 1e6f});
    REQUIRE(e.mean() == std::array<float, 3>{1.0f, -2.0f, 1e6f});
    for (std::size_t a = 0; a < 3; ++a)
        for (std::size_t b = 0; b < 3; ++b) REQUIRE(e.covariance(a, b) == 0.0f);
    REQUIRE(e.count() == 1);
}
