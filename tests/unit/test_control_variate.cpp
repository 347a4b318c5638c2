// cv_coefficient, the residual policies, batch_mean_covariance and sample_count.
#include <emcv/batch_means.hpp>
#include <emcv/control_variate.hpp>
#include <emcv/running_covariance.hpp>
#include <emcv/sample_count.hpp>

#include <catch2/catch_approx.hpp>
#include <catch2/catch_test_macros.hpp>
#include <catch2/matchers/catch_matchers_string.hpp>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "../support/reference.hpp"

TEST_CASE("cv_coefficient is Cov/Var with a guard that falls back to no control variate", "[cv]") {
    REQUIRE(emcv::cv_coefficient(0.5, 2.0) == 0.25);
    REQUIRE(emcv::cv_coefficient(-3.0f, 1.5f) == -2.0f);
    // guard: alpha = 0 (residual = f, which can only over-state the variance the sampler needs)
    REQUIRE(emcv::cv_coefficient(1.0, 0.0) == 0.0);
    REQUIRE(emcv::cv_coefficient(1.0, -1e-3) == 0.0);
    REQUIRE(emcv::cv_coefficient(1.0, std::numeric_limits<double>::denorm_min()) == 0.0);
    REQUIRE(emcv::cv_coefficient(1.0, std::nan("")) == 0.0);
    REQUIRE(emcv::cv_coefficient(std::nan(""), 1.0) == 0.0);
    REQUIRE(emcv::cv_coefficient(1.0, std::numeric_limits<double>::infinity()) == 0.0);
    REQUIRE(emcv::cv_coefficient(1e300, 1e-300) == 0.0);  // overflow
    REQUIRE(emcv::cv_coefficient(2e-30f, 1e-30f) == 2.0f);  // small but normal: a real coefficient
    // a relative floor for a control of known scale
    const double floor = emcv::variance_floor(100.0, 1e-6);
    REQUIRE(std::fabs(floor - 1e-8) <= 1e-8 * 1e-15);
    REQUIRE(emcv::cv_coefficient(1e-9, 1e-9, floor) == 0.0);
    REQUIRE(emcv::cv_coefficient(1e-7, 1e-7, floor) == 1.0);
}

TEST_CASE("residual policies apply the coefficient of the previous frame", "[cv]") {
    using emcv::residual_policy;
    const emcv::cv_frame<double> f1{2.0, 1.0, 0.5, 0.3, 0.1};
    const emcv::cv_frame<double> f2{3.0, 2.0, 1.5, 0.2, 0.4};

    emcv::control_variate<double> none(residual_policy::none);
    REQUIRE(none.push(f1) == 2.0);
    REQUIRE(none.push(f2) == 3.0);
    REQUIRE(none.alpha() == 0.0);

    emcv::control_variate<double> sf(residual_policy::single_frame);
    REQUIRE(sf.push(f1) == 2.0);  // alpha_0 = 0
    REQUIRE(sf.alpha() == 0.3 / 0.1);
    REQUIRE(sf.push(f2) == 3.0 - (0.3 / 0.1) * 2.0);
    REQUIRE(sf.alpha() == 0.5);

    emcv::control_variate<double> ema(residual_policy::single_frame_ema, 0.05, 0.25);
    ema.push(f1);
    REQUIRE(ema.alpha() == 0.3 / 0.1);  // the first alpha seeds the EMA
    ema.push(f2);
    REQUIRE(std::fabs(ema.alpha() - (0.75 * 3.0 + 0.25 * 0.5)) < 1e-15);

    // The emcm_* coefficient against the two-pass weighted covariance of the (f, g) frame means under the
    // geometric weights of Eq. 18 (long double, independent of the recurrence): alpha = C_fg / C_gg, 0 while
    // C_gg = 0 (one frame seen).
    emcv::control_variate<double> sampled(residual_policy::emcm_sampled, 0.5);
    emcv::control_variate<double> constant(residual_policy::emcm_constant, 0.5);
    const emcv::cv_frame<double> f3{2.5, 3.0, 1.0, 0.1, 0.2};  // off the line through f1 and f2
    const std::vector<emcv::cv_frame<double>> frames{f1, f2, f3, f1, f2, f3};
    std::vector<std::array<double, 2>> seen;
    double alpha_expected = 0;
    for (const auto& fr : frames) {
        INFO("frame " << seen.size());
        REQUIRE(std::fabs(sampled.residual(fr) - (fr.f - alpha_expected * fr.g)) <= 1e-12);
        REQUIRE(std::fabs(constant.residual(fr) - (fr.f - alpha_expected * fr.g_expected)) <= 1e-12);
        sampled.update(fr);
        constant.update(fr);
        seen.push_back({fr.f, fr.g});
        const auto ref = emcv_test::two_pass<2>(seen, emcv_test::geometric_weights(0.5, seen.size()), seen.size());
        alpha_expected = ref.covariance[1][1] > 0 ? static_cast<double>(ref.covariance[0][1] / ref.covariance[1][1]) : 0.0;
        REQUIRE(std::fabs(sampled.alpha() - alpha_expected) <= 1e-12 * (1 + std::fabs(alpha_expected)));
        REQUIRE(sampled.alpha() == constant.alpha());  // same EMCM, same alpha (Table 1's ResHat_EMCM)
    }
    REQUIRE(std::fabs(alpha_expected) > 0.05);  // a real coefficient (2/21 here), not the guard's 0
    REQUIRE(sampled.alpha() != 0.0);
    sampled.reset();
    REQUIRE(sampled.alpha() == 0.0);
    REQUIRE(sampled.frame_covariance().count() == 0);
}

TEST_CASE("an optimal coefficient minimises the residual variance (Eq. 29-31)", "[cv]") {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    emcv::running_covariance<double, 2> c;
    std::vector<std::array<double, 2>> xs(20000);
    for (auto& x : xs) {
        const double y = u(rng);
        x = {1.0 / (1.0 + y), 1.0 - y};  // the toy's f and g
        c.push(x);
    }
    const double alpha = emcv::cv_coefficient(c.covariance(0, 1), c.variance(1));
    auto residual_variance = [&](double a) {
        emcv::running_covariance<double, 1> r;
        for (const auto& x : xs) r.push(emcv::cv_residual(x[0], a, x[1]));
        return r.variance(0);
    };
    REQUIRE(residual_variance(alpha) < residual_variance(alpha * 0.9));
    REQUIRE(residual_variance(alpha) < residual_variance(alpha * 1.1));
    REQUIRE(residual_variance(alpha) < 0.05 * residual_variance(0.0));
}

TEST_CASE("batch_mean_covariance divides by the batch size (Eq. 27)", "[batch]") {
    REQUIRE(emcv::batch_mean_covariance(1.6, 16) == 0.1);
    REQUIRE(emcv::batch_mean_covariance(3.0f, 1) == 3.0f);
    REQUIRE_THROWS_WITH(emcv::batch_mean_covariance(1.0, 0),
                        Catch::Matchers::ContainsSubstring("batch size n = 0 must be at least 1"));
}

TEST_CASE("sample_count clamps variance / target and rounds up (SPVG)", "[samples]") {
    REQUIRE(emcv::sample_count(1e-3, 1e-4, 8, 64) == 10);
    REQUIRE(emcv::sample_count(1.05e-3, 1e-4, 8, 64) == 11);  // 10.5 -> 11 samples
    REQUIRE(emcv::sample_count(1.0, 1e-4, 8, 64) == 64);
    REQUIRE(emcv::sample_count(0.0, 1e-4, 8, 64) == 8);
    REQUIRE(emcv::sample_count(0.0, 1e-4, 0, 64) == 0);  // sub-pixel / static: no samples at all
    REQUIRE(emcv::sample_count(-1.0, 1e-4, 0, 64) == 0);
    REQUIRE(emcv::sample_count(std::nan(""), 1e-4, 8, 64) == 64);  // broken history: sample fully
    REQUIRE(emcv::sample_count(std::numeric_limits<float>::infinity(), 1e-4f, 8, 64) == 64);
    REQUIRE(emcv::sample_count(5e-4f, 1e-4f, 8, 8) == 8);
}

TEST_CASE("sample_count_true_distribution follows Unreal's formula", "[samples]") {
    // g = 1e-4, eta = 0.2 -> n_est = 1e-4 * 9 = 9e-4; N = var * n_est / target - n_est
    const double n_est = 1e-4 * (2.0 / 0.2 - 1.0);
    const double var = 2.0;
    const double expected = var * n_est / 1e-4 - n_est;  // 17.9991
    REQUIRE(emcv::sample_count_true_distribution(var, 1e-4, 0.2, 1e-4, 0, 64) ==
            static_cast<int>(std::ceil(expected)));
    REQUIRE(emcv::sample_count_true_distribution(0.0, 1e-4, 0.2, 1e-4, 0, 64) == 0);
}

TEST_CASE("sample_count_true_distribution subtracts n_est: exactly representable cases", "[samples]") {
    // Every operand and intermediate below is a small dyadic rational, so the arithmetic is exact in float and
    // double and the ceiling cannot hide a missing term: with and without "- n_est" the counts differ.
    //   g = 0.5, eta = 0.5: n_est = 0.5 (2/0.5 - 1) = 1.5;  var 2, target 0.5: 2 * 1.5 / 0.5 - 1.5 = 4.5 -> 5 (not 6)
    REQUIRE(emcv::sample_count_true_distribution(2.0, 0.5, 0.5, 0.5, 0, 64) == 5);
    REQUIRE(emcv::sample_count_true_distribution(2.0f, 0.5f, 0.5f, 0.5f, 0, 64) == 5);
    //   g = 1, eta = 1: n_est = 1;  var 4, target 1: 4 - 1 = 3 exactly -> 3 (not 4)
    REQUIRE(emcv::sample_count_true_distribution(4.0, 1.0, 1.0, 1.0, 0, 64) == 3);
    //   g = 2, eta = 0.25: n_est = 2 * 7 = 14;  var 0.75, target 0.5: 0.75 * 14 / 0.5 - 14 = 7 -> 7 (not 21)
    REQUIRE(emcv::sample_count_true_distribution(0.75, 2.0, 0.25, 0.5, 0, 64) == 7);
    //   g = 2, eta = 1: n_est = 2;  var 0.5, target 1: 0.5 * 2 - 2 = -1, clamped to n_min = 0 (not 1)
    REQUIRE(emcv::sample_count_true_distribution(0.5, 2.0, 1.0, 1.0, 0, 64) == 0);
}

TEST_CASE("sample_count rejects a meaningless budget", "[samples]") {
    using Catch::Matchers::ContainsSubstring;
    REQUIRE_THROWS_WITH(emcv::sample_count(1.0, 0.0, 8, 64), ContainsSubstring("target variance"));
    REQUIRE_THROWS_WITH(emcv::sample_count(1.0, std::nan(""), 8, 64), ContainsSubstring("target variance"));
    REQUIRE_THROWS_WITH(emcv::sample_count(1.0, 1e-4, -1, 64), ContainsSubstring("n_min = -1 must be >= 0"));
    REQUIRE_THROWS_WITH(emcv::sample_count(1.0, 1e-4, 65, 64), ContainsSubstring("n_min = 65 must not exceed n_max = 64"));
    REQUIRE_THROWS_WITH(emcv::sample_count_true_distribution(1.0, 1.0, 0.0, 1e-4, 8, 64),
                        ContainsSubstring("eta = 0 must lie in (0, 1]"));
}

TEST_CASE("control_variate computes every alpha with its variance floor", "[cv]") {
    // Var(G) = 1e-7 against Cov(f, G) = 1: without a floor alpha = 1e7, a coefficient divided out of a
    // variance at the noise level; a floor above Var(G) turns the control variate off (alpha = 0).
    const emcv::cv_frame<double> tiny_control{1.0, 1.0, 1.0, 1.0, 1e-7};
    for (auto policy : {emcv::residual_policy::single_frame, emcv::residual_policy::single_frame_ema}) {
        emcv::control_variate<double> unfloored(policy, 0.05, 1.0);
        unfloored.update(tiny_control);
        REQUIRE(unfloored.alpha() == Catch::Approx(1e7));
        emcv::control_variate<double> floored(policy, 0.05, 1.0, 1e-6);
        REQUIRE(floored.var_floor() == 1e-6);
        floored.update(tiny_control);
        REQUIRE(floored.alpha() == 0.0);
    }
    // emcm_sampled, eta 0.5: frame means (f, g) = (0, 0) then (1, sqrt(1e-7)): Cov = 0.25 d d^T, so
    // C_GG = 2.5e-8 and alpha = C_fG / C_GG = 1 / sqrt(1e-7) without a floor
    const double dg = std::sqrt(1e-7);
    for (double floor : {0.0, 1e-6}) {
        emcv::control_variate<double> cv(emcv::residual_policy::emcm_sampled, 0.5, 0.05, floor);
        cv.update({0.0, 0.0, 0.0, 0.0, 0.0});
        cv.update({1.0, dg, dg, 0.0, 0.0});
        if (floor == 0.0) REQUIRE(cv.alpha() == Catch::Approx(1.0 / dg));
        else REQUIRE(cv.alpha() == 0.0);
    }
}

TEST_CASE("a broken history samples fully; a NaN floor turns the control variate off", "[samples][cv]") {
    const double nan = std::nan(""), inf = std::numeric_limits<double>::infinity();
    // sample_count_true_distribution: a NaN (or Inf) per-sample history makes n_est and the count NaN -> n_max,
    // as a NaN variance does in sample_count (more samples, never fewer, when the history is broken)
    REQUIRE(emcv::sample_count_true_distribution(2.0, nan, 0.5, 0.5, 1, 48) == 48);
    REQUIRE(emcv::sample_count_true_distribution(0.0, nan, 0.5, 0.5, 1, 48) == 48);
    REQUIRE(emcv::sample_count_true_distribution(2.0, inf, 0.5, 0.5, 1, 48) == 48);
    REQUIRE(emcv::sample_count_true_distribution(0.0, inf, 0.5, 0.5, 1, 48) == 48);  // 0 * Inf is NaN
    REQUIRE(emcv::sample_count_true_distribution(nan, 0.5, 0.5, 0.5, 1, 48) == 48);
    // cv_coefficient: no variance is "above" a NaN floor, so alpha = 0 (the residual is f itself)
    REQUIRE(emcv::cv_coefficient(0.5, 2.0, nan) == 0.0);
    REQUIRE(emcv::cv_coefficient(0.5f, 2.0f, std::nanf("")) == 0.0f);
    REQUIRE(emcv::cv_coefficient(0.5, 2.0, 1.0) == 0.25);  // while a finite floor below var_g lets it through
}
