// weighted_covariance and running_covariance against the two-pass long-double definitions.
#include <emcv/running_covariance.hpp>
#include <emcv/weighted_covariance.hpp>

#include <catch2/catch_test_macros.hpp>
#include <catch2/generators/catch_generators.hpp>

#include <limits>
#include <random>

#include "../support/reference.hpp"

using emcv_test::kTolerance;
using emcv_test::real;

namespace {

template <std::size_t N>
std::vector<std::array<double, N>> correlated_stream(std::mt19937_64& rng, std::size_t n, double offset) {
    std::normal_distribution<double> normal(0.0, 1.0);
    std::vector<std::array<double, N>> xs(n);
    for (auto& x : xs) {
        const double common = normal(rng);
        for (std::size_t k = 0; k < N; ++k)
            x[k] = offset * static_cast<double>(k + 1) + common * 0.7 + normal(rng) * static_cast<double>(k + 1);
    }
    return xs;
}

template <class Estimator, std::size_t N>
void require_matches(const Estimator& e, const emcv_test::reference_moments<N>& ref) {
    REQUIRE(emcv_test::scaled_error(e.total_weight(), ref.total_weight, ref.total_weight) <= kTolerance);
    for (std::size_t a = 0; a < N; ++a) {
        const real sd = std::sqrt(ref.covariance[a][a]);
        INFO("mean " << a << ": " << e.mean(a) << " vs " << static_cast<double>(ref.mean[a]));
        REQUIRE(emcv_test::scaled_error(e.mean(a), ref.mean[a], std::fabs(ref.mean[a]) + sd) <= kTolerance);
        for (std::size_t b = 0; b < N; ++b) {
            // plus the absolute floor of any covariance computed from double inputs: eps (|mu_a| + sd_a)(|mu_b| + sd_b)
            const real floor = std::numeric_limits<double>::epsilon() *
                               (std::fabs(ref.mean[a]) + std::sqrt(ref.covariance[a][a])) *
                               (std::fabs(ref.mean[b]) + std::sqrt(ref.covariance[b][b]));
            const real scale = std::sqrt(ref.covariance[a][a] * ref.covariance[b][b]) + floor;
            INFO("cov " << a << "," << b << ": " << e.covariance(a, b) << " vs "
                        << static_cast<double>(ref.covariance[a][b]));
            REQUIRE(emcv_test::scaled_error(e.covariance(a, b), ref.covariance[a][b], scale) <= kTolerance);
        }
    }
}

}  // namespace

TEST_CASE("weighted_covariance equals the two-pass weighted covariance for any weights and decays",
          "[weighted_covariance]") {
    const auto length = GENERATE(1u, 2u, 7u, 64u, 1000u);
    const auto seed = GENERATE(1u, 2u, 3u);
    std::mt19937_64 rng(seed * 7919u + length);
    std::uniform_real_distribution<double> weight_dist(0.05, 10.0);
    std::uniform_real_distribution<double> decay_dist(0.5, 1.0);
    const auto xs = correlated_stream<3>(rng, length, 5.0);

    std::vector<real> weight(length), decay(length);
    emcv::weighted_covariance<double, 3> e;
    const std::size_t checks = std::min<std::size_t>(length, 25);
    for (std::size_t n = 0; n < length; ++n) {
        weight[n] = weight_dist(rng);
        decay[n] = n % 5 == 4 ? 1.0 : decay_dist(rng);  // mix fixed (West 1979) and decaying steps
        REQUIRE(e.push(xs[n], static_cast<double>(weight[n]), static_cast<double>(decay[n])));
        if ((n + 1) % (length / checks) == 0 || n + 1 == length) {
            // decay_0 multiplies an empty history; it does not rescale sample 0
            auto w = emcv_test::effective_weights(weight, decay, n + 1);
            require_matches(e, emcv_test::two_pass<3>(xs, w, n + 1));
        }
    }
    REQUIRE(e.count() == length);
}

TEST_CASE("weighted_covariance: zero weights add nothing and decay 0 forgets everything",
          "[weighted_covariance]") {
    emcv::weighted_covariance<double, 2> e;
    e.push({1.0, 2.0}, 2.0);
    e.push({3.0, -1.0}, 1.0);
    const auto before = e.state();
    e.push({100.0, 100.0}, 0.0);  // weight 0, decay 1: only the count moves
    REQUIRE(e.mean() == before.mean);
    REQUIRE(e.covariance(0, 1) == before.covariance[1]);
    REQUIRE(e.count() == 3);

    e.push({5.0, 6.0}, 1.0, 0.0);  // decay 0: the new sample is all there is
    REQUIRE(e.mean(0) == 5.0);
    REQUIRE(e.mean(1) == 6.0);
    REQUIRE(e.variance(0) == 0.0);
    REQUIRE(e.total_weight() == 1.0);

    e.push({7.0, 7.0}, 0.0, 0.0);  // no weight left anywhere: the estimator is empty again
    REQUIRE(e.total_weight() == 0.0);
    REQUIRE(e.variance(0) == 0.0);
}

TEST_CASE("weighted_covariance stores a symmetric matrix and restores from its state", "[weighted_covariance]") {
    std::mt19937_64 rng(42);
    const auto xs = correlated_stream<4>(rng, 200, -3.0);
    emcv::weighted_covariance<double, 4> e;
    for (const auto& x : xs) e.push(x, 1.5, 0.97);
    const auto m = e.covariance_matrix();
    for (std::size_t a = 0; a < 4; ++a)
        for (std::size_t b = 0; b < 4; ++b) REQUIRE(m[a][b] == m[b][a]);

    emcv::weighted_covariance<double, 4> restored(e.state());
    e.push(xs[0], 2.0, 0.9);
    restored.push(xs[0], 2.0, 0.9);
    REQUIRE(restored.state().covariance == e.state().covariance);
    REQUIRE(restored.mean() == e.mean());
}

TEST_CASE("running_covariance equals the two-pass population and sample covariance", "[running_covariance]") {
    const auto length = GENERATE(2u, 3u, 50u, 5000u);
    std::mt19937_64 rng(length);
    const auto xs = correlated_stream<2>(rng, length, 1e3);
    emcv::running_covariance<double, 2> e;
    for (const auto& x : xs) e.push(x);
    const std::vector<real> ones(length, 1.0L);
    const auto ref = emcv_test::two_pass<2>(xs, ones, length);
    require_matches(e, ref);
    const real n = static_cast<real>(length);
    for (std::size_t a = 0; a < 2; ++a)
        for (std::size_t b = 0; b < 2; ++b) {
            const real unbiased = ref.covariance[a][b] * n / (n - 1);
            const real scale = std::sqrt(ref.covariance[a][a] * ref.covariance[b][b]) * n / (n - 1);
            REQUIRE(emcv_test::scaled_error(e.sample_covariance(a, b), unbiased, scale) <= kTolerance);
        }
    REQUIRE(e.count() == length);
    REQUIRE(e.total_weight() == static_cast<double>(length));
}

TEST_CASE("running_covariance: fewer than two samples", "[running_covariance]") {
    emcv::running_covariance<float, 1> e;
    REQUIRE(e.variance(0) == 0.0f);
    REQUIRE(e.sample_variance(0) == 0.0f);
    e.push(3.0f);
    REQUIRE(e.mean(0) == 3.0f);
    REQUIRE(e.variance(0) == 0.0f);
    REQUIRE(e.sample_variance(0) == 0.0f);  // documented: 0 while n < 2
    e.push(5.0f);
    REQUIRE(e.variance(0) == 1.0f);
    REQUIRE(e.sample_variance(0) == 2.0f);
}

TEST_CASE("every scalar type compiles and agrees on a small exact stream", "[weighted_covariance]") {
    // 1, 2, 3, 4: mean 2.5, population variance 1.25 -- exact in binary floating point for all three types.
    emcv::running_covariance<float, 1> f;
    emcv::running_covariance<double, 1> d;
    emcv::running_covariance<long double, 1> l;
    for (int i = 1; i <= 4; ++i) {
        f.push(static_cast<float>(i));
        d.push(static_cast<double>(i));
        l.push(static_cast<long double>(i));
    }
    REQUIRE(f.mean(0) == 2.5f);
    REQUIRE(d.mean(0) == 2.5);
    REQUIRE(l.mean(0) == 2.5L);
    REQUIRE(f.variance(0) == 1.25f);
    REQUIRE(d.variance(0) == 1.25);
    REQUIRE(l.variance(0) == 1.25L);
}
