// Statistical tests at fixed seeds: the expectation of EMCM, EWMA, moving_stats and running_covariance on
// i.i.d. Gaussian streams matches the values derived in docs/estimators.md ("Expectation on i.i.d. samples"),
// within five standard deviations of the mean over M independent streams.
//
// Derivation used here (docs/estimators.md has it in full). After n + 1 samples the EMCM is the weighted
// covariance about the weighted mean with the normalised geometric weights w_i of Eq. 18, i.e. the quadratic
// form C = x^T A y with A = diag(w) - w w^T. For i.i.d. pairs with covariance matrix S:
//   E[C_xy]   = S_xy (1 - sum w_i^2)
//   Var[C_xy] = (S_xx S_yy + S_xy^2) tr(A^2),  tr(A^2) = sum w^2 - 2 sum w^3 + (sum w^2)^2   (Gaussian)
// The mean of M independent streams has standard deviation sqrt(Var / M); a 5-sigma bound fails by chance
// with probability about 6e-7 (normal approximation, M >= 2000). EWMA = EMCM / (1 - eta) exactly.
// Steady state (n -> inf): sum w^2 -> eta / (2 - eta), so E[EMCM] -> 2 (1 - eta) / (2 - eta) S and
// E[EWMA] -> 2 / (2 - eta) S: EWMA / EMCM -> 1 / (1 - eta).
#include <emcv/emcv.hpp>

#include <catch2/catch_test_macros.hpp>
#include <catch2/generators/catch_generators.hpp>

#include <cmath>
#include <random>
#include <vector>

#include "../support/reference.hpp"

#include <emcv/testing/catch2.hpp>

namespace {

struct gaussian_pair {
    double sxx, syy, sxy;  // covariance matrix S
    std::array<double, 2> operator()(std::mt19937_64& rng, std::normal_distribution<double>& n) const {
        const double a = n(rng), b = n(rng);
        const double lx = std::sqrt(sxx), rho = sxy / std::sqrt(sxx * syy), ly = std::sqrt(syy);
        return {3.0 + lx * a, -1.0 + ly * (rho * a + std::sqrt(1 - rho * rho) * b)};
    }
};

/// Two-sided tail of a 5-sigma normal deviation, erfc(5 / sqrt 2) = 5.7e-7: the level of every check here.
const double five_sigma_alpha = std::erfc(5.0 / std::sqrt(2.0));

struct weight_sums {
    double s2 = 0, tr_a2 = 0;
};

weight_sums sums(double eta, std::size_t count) {
    const auto w = emcv_test::geometric_weights(eta, count);
    long double s2 = 0, s3 = 0;
    for (auto wi : w) {
        s2 += wi * wi;
        s3 += wi * wi * wi;
    }
    return {static_cast<double>(s2), static_cast<double>(s2 - 2 * s3 + s2 * s2)};
}

}  // namespace

TEST_CASE("EMCM and EWMA expectations on i.i.d. streams", "[stats]") {
    const double eta = GENERATE(0.05, 0.2);
    const std::size_t updates = 400, streams = 4000;
    const gaussian_pair dist{2.0, 0.5, 0.6};
    std::mt19937_64 rng(20210517);
    std::normal_distribution<double> normal(0.0, 1.0);

    double emcm_xx = 0, emcm_xy = 0, ewma_xx = 0, ewma_xy = 0;
    for (std::size_t s = 0; s < streams; ++s) {
        emcv::emcm<double, 2> e(eta);
        emcv::ewma_covariance<double, 2> w(eta);
        for (std::size_t n = 0; n < updates; ++n) {
            const auto x = dist(rng, normal);
            e.push(x);
            w.push(x);
        }
        emcm_xx += e.variance(0);
        emcm_xy += e.covariance(0, 1);
        ewma_xx += w.variance(0);
        ewma_xy += w.covariance(0, 1);
    }
    const double m = static_cast<double>(streams);
    emcm_xx /= m, emcm_xy /= m, ewma_xx /= m, ewma_xy /= m;

    const auto ws = sums(eta, updates);
    const double sd_xx = std::sqrt(2 * dist.sxx * dist.sxx * ws.tr_a2 / m);
    const double sd_xy = std::sqrt((dist.sxx * dist.syy + dist.sxy * dist.sxy) * ws.tr_a2 / m);
    const double expected_xx = dist.sxx * (1 - ws.s2), expected_xy = dist.sxy * (1 - ws.s2);
    INFO("eta " << eta << ": EMCM var " << emcm_xx << " expected " << expected_xx << " +- " << sd_xx);
    CHECK(std::fabs(emcm_xx - expected_xx) <= 5 * sd_xx);
    CHECK(std::fabs(emcm_xy - expected_xy) <= 5 * sd_xy);
    CHECK(std::fabs(ewma_xx - expected_xx / (1 - eta)) <= 5 * sd_xx / (1 - eta));
    CHECK(std::fabs(ewma_xy - expected_xy / (1 - eta)) <= 5 * sd_xy / (1 - eta));

    // at 400 updates the transient (1 - eta)^800 is gone: the finite-n value is the steady state
    const double steady = 2 * (1 - eta) / (2 - eta);
    CHECK(std::fabs((1 - ws.s2) - steady) < 1e-12);
    CHECK(std::fabs(ewma_xx / emcm_xx - 1 / (1 - eta)) < 1e-12);
    // and the biases are real: EMCM under-, EWMA over-estimates the variance by more than the noise
    CHECK(dist.sxx - emcm_xx > 5 * sd_xx);
    CHECK(ewma_xx - dist.sxx > 5 * sd_xx);
}

TEST_CASE("moving_stats variance has the EMCM expectation", "[stats]") {
    const double eta = 0.2, sigma2 = 4.0;
    const std::size_t updates = 60, streams = 20000;
    std::mt19937_64 rng(7);
    std::normal_distribution<double> normal(5.0, std::sqrt(sigma2));
    double mean_var = 0;
    for (std::size_t s = 0; s < streams; ++s) {
        emcv::moving_stats<double> m(eta);
        for (std::size_t n = 0; n < updates; ++n) m.push(normal(rng));
        mean_var += m.variance();
    }
    mean_var /= static_cast<double>(streams);
    const auto ws = sums(eta, updates);
    // the same 5-sigma rule as a z-test: one stream's variance estimate has sd sqrt(2 sigma^4 tr(A^2))
    EMCV_CHECK_STAT(emcv::testing::z_test_mean(streams, mean_var, std::sqrt(2 * sigma2 * sigma2 * ws.tr_a2),
                                               sigma2 * (1 - ws.s2), five_sigma_alpha));
}

TEST_CASE("running_covariance's sample covariance is unbiased", "[stats]") {
    // E[s^2] = sigma^2, Var[s^2] = 2 sigma^4 / (n - 1) for Gaussian samples. Small n, where the correction
    // n / (n - 1) is far from a wrong one such as (n + 1) / n: with the population mean E[v] = sigma^2 (n - 1) / n,
    // (n + 1) / n would give E = sigma^2 (n^2 - 1) / n^2, i.e. 0.75 sigma^2 at n = 2 and 0.889 sigma^2 at n = 3,
    // while the 5-sigma window below is 5 sqrt(2 / ((n - 1) M)) sigma^2 = 0.050 and 0.035 sigma^2 at M = 20000.
    const std::size_t n = GENERATE(std::size_t{2}, std::size_t{3}, std::size_t{10});
    const std::size_t streams = 20000;
    const double sigma2 = 2.5;
    std::mt19937_64 rng(99 + n);
    std::normal_distribution<double> normal(-7.0, std::sqrt(sigma2));
    double mean_sample = 0, mean_population = 0;
    for (std::size_t s = 0; s < streams; ++s) {
        emcv::running_covariance<double, 1> r;
        for (std::size_t i = 0; i < n; ++i) r.push(normal(rng));
        mean_sample += r.sample_variance(0);
        mean_population += r.variance(0);
    }
    const double m = static_cast<double>(streams), nd = static_cast<double>(n);
    mean_sample /= m;
    mean_population /= m;
    // one stream's s^2 has sd sigma^2 sqrt(2 / (n - 1)) (Gaussian); z-tests at the 5-sigma level
    const double sd_one = sigma2 * std::sqrt(2.0 / static_cast<double>(n - 1));
    EMCV_CHECK_STAT(emcv::testing::z_test_mean(streams, mean_sample, sd_one, sigma2, five_sigma_alpha));
    // the population covariance carries the (n - 1) / n bias (and its sd is (n - 1) / n times smaller)
    const double shrink = static_cast<double>(n - 1) / static_cast<double>(n);
    EMCV_CHECK_STAT(emcv::testing::z_test_mean(streams, mean_population, sd_one * shrink, sigma2 * shrink,
                                               five_sigma_alpha));
    // where n is small the test tells the right correction from (n + 1) / n: the two expectations lie more
    // than 10 standard errors apart (25 at n = 2, 16 at n = 3)
    const double sd = sd_one / std::sqrt(m);
    if (n <= 3) CHECK(sigma2 - sigma2 * (nd * nd - 1) / (nd * nd) > 10 * sd);
}

TEST_CASE("frame means of n samples have 1/n of the per-sample covariance (Eq. 27)", "[stats]") {
    // The toy's f = 1/(1+y), g = 1-y, y ~ U[0,1]: Cov(f, g) = 1.5 ln 2 - 1, Var(g) = 1/12.
    const std::size_t spp = 16, frames = 40000;
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    emcv::running_covariance<double, 2> means;
    for (std::size_t t = 0; t < frames; ++t) {
        emcv::running_covariance<double, 2> frame;
        for (std::size_t i = 0; i < spp; ++i) {
            const double y = u(rng);
            frame.push({1.0 / (1.0 + y), 1.0 - y});
        }
        means.push(frame.mean());
    }
    const double cov_fg = 1.5 * std::log(2.0) - 1.0, var_g = 1.0 / 12.0;
    const double expected_cov = emcv::batch_mean_covariance(cov_fg, spp);
    const double expected_var = emcv::batch_mean_covariance(var_g, spp);
    // the batch means are nearly Gaussian (CLT over 16 samples); same 5-sigma rule with M = frames,
    // Var[s_gg] ~ 2 var^2 / (M - 1), Var[s_fg] ~ (var_f var_g + cov^2) / (M - 1) <= 2 var_g^2 / (M - 1)
    // because var_f = 1/2 - (ln 2)^2 < var_g here.
    const double sd = std::sqrt(2.0 / static_cast<double>(frames - 1)) * expected_var;
    CHECK(std::fabs(means.sample_covariance(0, 1) - expected_cov) <= 5 * sd);
    CHECK(std::fabs(means.sample_variance(1) - expected_var) <= 5 * sd);
    // and alpha* = Cov/Var = 0.4767 is the same for samples and for frame means. The regression slope over M
    // frames has Var[alpha] ~ (var_f - cov^2 / var_g) / (M var_g) (the 1/n of Eq. 27 cancels).
    const double var_f = 0.5 - std::log(2.0) * std::log(2.0);
    const double sd_alpha = std::sqrt((var_f - cov_fg * cov_fg / var_g) / (static_cast<double>(frames) * var_g));
    const double alpha = emcv::cv_coefficient(means.sample_covariance(0, 1), means.sample_variance(1));
    CHECK(std::fabs(alpha - cov_fg / var_g) <= 5 * sd_alpha);
}
