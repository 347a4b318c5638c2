// The false-positive rate of each check of emcv/testing, measured: 2000 independent data sets (seeds) drawn
// from exactly the hypothesis under test, each tested at alpha = 0.05 and alpha = 0.01.
//
// Bound: if a check's true rate is alpha, the number of rejections K among M = 2000 independent seeds is
// Binomial(M, alpha), mean M alpha, sd sqrt(M alpha (1 - alpha)). We require |K - M alpha| <= 5 sd:
//   alpha = 0.05: 100 +- 48.7, so K in [52, 148] (both sides bite: a check that never rejects fails too);
//   alpha = 0.01:  20 +- 22.2, so K in [0, 42].
// A correct check fails this with probability ~6e-7 (normal approximation of the binomial, M alpha >= 20).
// The chi-square and convergence tests are asymptotic; the setups below keep them in their regime
// (>= 100 expected per cell; Gaussian errors), and the band would catch a rate off by a factor of 1.5 at 0.05.
#include <emcv/testing/catch2.hpp>

#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <random>

namespace et = emcv::testing;

namespace {

constexpr std::size_t seeds = 2000;

/// Runs `check(seed, alpha)` over the seeds at both levels and checks the binomial band for each.
void check_rate(const std::function<et::test_result(std::mt19937_64&, double)>& check) {
    for (double alpha : {0.05, 0.01}) {
        std::size_t rejected = 0;
        for (std::size_t s = 0; s < seeds; ++s) {
            std::mt19937_64 rng(0x5eed0000u + s);
            if (!check(rng, alpha).passed) ++rejected;
        }
        const double m = static_cast<double>(seeds), expected = m * alpha;
        const double sd = std::sqrt(m * alpha * (1 - alpha));
        INFO("alpha " << alpha << ": " << rejected << " of " << seeds << " rejected, expected " << expected << " +- "
                      << 5 * sd);
        CHECK(std::fabs(static_cast<double>(rejected) - expected) <= 5 * sd);
    }
}

}  // namespace

TEST_CASE("t-test: false-positive rate on Gaussian samples of the expected mean") {
    check_rate([](std::mt19937_64& rng, double alpha) {
        std::normal_distribution<double> normal(1.5, 3.0);
        double sum = 0, sum_sq = 0;
        const std::size_t n = 30;
        for (std::size_t i = 0; i < n; ++i) {
            const double x = normal(rng);
            sum += x, sum_sq += x * x;
        }
        const double mean = sum / n, var = (sum_sq - n * mean * mean) / (n - 1);
        return et::t_test_mean(n, mean, var, 1.5, alpha);
    });
}

TEST_CASE("z-test: false-positive rate on exponential samples (CLT regime, n = 400)") {
    check_rate([](std::mt19937_64& rng, double alpha) {
        std::exponential_distribution<double> expo(2.0);
        double sum = 0;
        for (int i = 0; i < 400; ++i) sum += expo(rng);
        return et::z_test_mean(400, sum / 400, 0.5, 0.5, alpha);
    });
}

TEST_CASE("chi-square 1-D by CDF: false-positive rate") {
    check_rate([](std::mt19937_64& rng, double alpha) {
        std::exponential_distribution<double> expo(1.0);
        auto cdf = [](double x) { return x <= 0 ? 0.0 : -std::expm1(-x); };
        return et::chi2_test_1d_cdf([&] { return expo(rng); }, cdf, 20, 2000, {alpha});
    });
}

TEST_CASE("chi-square 1-D by pdf, with pooled tails: false-positive rate") {
    check_rate([](std::mt19937_64& rng, double alpha) {
        std::normal_distribution<double> normal(0.0, 1.0);
        auto pdf = [](double x) { return std::exp(-0.5 * x * x) / std::sqrt(2.0 * 3.14159265358979323846); };
        return et::chi2_test_1d_pdf([&] { return normal(rng); }, pdf, -4.0, 4.0, 20, 4000, {alpha});
    });
}

TEST_CASE("chi-square 2-D by pdf: false-positive rate") {
    check_rate([](std::mt19937_64& rng, double alpha) {
        std::uniform_real_distribution<double> u(0.0, 1.0);
        // density 4 x y on the unit square, sampled by inversion: x = sqrt(u1), y = sqrt(u2)
        auto sample = [&] { return std::array<double, 2>{std::sqrt(u(rng)), std::sqrt(u(rng))}; };
        return et::chi2_test_2d_pdf(sample, [](double x, double y) { return 4 * x * y; }, {0, 1, 0, 1}, 6, 6, 4000,
                                    {alpha});
    });
}

TEST_CASE("convergence: false-positive rate for a Gaussian Monte Carlo mean") {
    check_rate([](std::mt19937_64& rng, double alpha) {
        std::normal_distribution<double> normal(0.0, 1.0);
        auto error = [&](std::size_t n) {
            double s = 0;
            for (std::size_t i = 0; i < n; ++i) s += normal(rng);
            return s / static_cast<double>(n);
        };
        et::convergence_options o;
        o.alpha = alpha;
        o.replicates = 32;
        return et::convergence_test(error, {4, 8, 16, 32, 64, 128}, o);
    });
}
