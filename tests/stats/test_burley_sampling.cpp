// The Burley radius samplers of include/emcv/port/burley.h through emcv/testing's chi-square and mean checks:
// the exact inverse CDF draws from the Burley radial pdf (passes against the exact CDF and pdf); SPVG's
// approximation r = d (2 + (c - 2) u) (-ln(1 - u)), c = 2.5715, does not: at 10^6 samples its pdf mismatch is
// rejected by the chi-square test (which is why the renderer evaluates the exact pdf at the radius it returns),
// while with 10^3 samples the mismatch is below what the test can see.
#include <emcv/port/burley.h>
#include <emcv/testing/catch2.hpp>

#include <cmath>
#include <random>

namespace et = emcv::testing;
namespace port = emcv::port;

namespace {

constexpr float shape_d = 0.7f;

// the CDF and pdf in double, straight from the paper (Xie & Olano 2021), section 4 (the port's fp32 versions are checked against
// these in tests/port)
double burley_cdf(double r) {
    const double d = shape_d;
    return r <= 0 ? 0.0 : 1.0 - 0.25 * std::exp(-r / d) - 0.75 * std::exp(-r / (3 * d));
}
double burley_pdf(double r) {
    const double d = shape_d;
    return r < 0 ? 0.0 : (std::exp(-r / d) + std::exp(-r / (3 * d))) / (4 * d);
}

struct radius_sampler {
    std::mt19937 rng;
    std::uniform_real_distribution<float> u{0.0f, 1.0f};
    bool spvg;
    double operator()() {
        const float x = u(rng);
        return spvg ? port::emcv_burley_sample_spvg(x, shape_d) : port::emcv_burley_sample_exact(x, shape_d);
    }
};

}  // namespace

TEST_CASE("Burley exact inverse CDF passes the chi-square test against the CDF and the pdf", "[stats]") {
    // two tests on the same sampler: Sidak over 2 keeps the family's false-positive rate at 1 %
    et::chi2_options o;
    o.test_count = 2;
    EMCV_CHECK_STAT(et::chi2_test_1d_cdf(radius_sampler{std::mt19937(1), {}, false}, burley_cdf, 100, 1000000, o));
    EMCV_CHECK_STAT(
        et::chi2_test_1d_pdf(radius_sampler{std::mt19937(2), {}, false}, burley_pdf, 0.0, 20 * shape_d, 200, 1000000, o));
}

TEST_CASE("SPVG's approximate sampler is rejected against the exact CDF at 10^6 samples", "[stats]") {
    const auto r = et::chi2_test_1d_cdf(radius_sampler{std::mt19937(3), {}, true}, burley_cdf, 100, 1000000);
    INFO(r.message);
    CHECK_FALSE(r.passed);
    CHECK(r.p_value < 1e-12);
    // with 10^3 samples the same mismatch hides in the noise: the test's power grows with the sample count
    EMCV_CHECK_STAT(et::chi2_test_1d_cdf(radius_sampler{std::mt19937(4), {}, true}, burley_cdf, 20, 1000));
}

TEST_CASE("Burley mean radius: E[r] = 2.5 d by t-test, and its Monte Carlo error falls like 1/sqrt(n)", "[stats]") {
    // E[r] = int r p(r) dr = (d^2 + 9 d^2) / (4 d) = 2.5 d; Var[r] = E[r^2] - E[r]^2 = (2 d^2 + 54 d^2) / 4 - 6.25 d^2
    const double mean_r = 2.5 * shape_d;
    radius_sampler exact{std::mt19937(5), {}, false};
    double sum = 0, sum_sq = 0;
    const std::size_t n = 200000;
    for (std::size_t i = 0; i < n; ++i) {
        const double r = exact();
        sum += r, sum_sq += r * r;
    }
    const double mean = sum / static_cast<double>(n);
    const double var = (sum_sq - static_cast<double>(n) * mean * mean) / static_cast<double>(n - 1);
    EMCV_CHECK_STAT(et::t_test_mean(n, mean, var, mean_r));
    EMCV_CHECK_STAT(et::z_test_mean(n, mean, std::sqrt(7.75) * shape_d, mean_r));
    EMCV_CHECK_STAT(et::convergence_test(
        [&](std::size_t count) {
            double s = 0;
            for (std::size_t i = 0; i < count; ++i) s += exact();
            return s / static_cast<double>(count) - mean_r;
        },
        {32, 64, 128, 256, 512, 1024, 2048}));
}
