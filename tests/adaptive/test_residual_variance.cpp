// SPDX-License-Identifier: MIT
// The residual variance that drives the cv method's sample count (docs/renderer.md):
//   Var(f - alpha G) = C_ff - 2 alpha C_fG + alpha^2 C_GG,   min over alpha = C_ff - C_fG^2 / C_GG   (Eq. 29-31)
// checked against an independent evaluation: the EMCM is the geometric-weighted covariance about the current
// mean (supp. Eq. 24), so the weighted variance of f_i - alpha G_i, taken two-pass in long double over the
// stored stream and minimised over alpha by a scan, must equal what the helpers compute from the EMCM state.
// The port's fp32 twins (include/emcv/port/cv.h) must equal the C++ float instances bit for bit.
#include <catch2/catch_approx.hpp>
#include <catch2/catch_test_macros.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include <emcv/control_variate.hpp>
#include <emcv/emcm.hpp>
#include <emcv/moving_stats.hpp>
#include <emcv/port/cv.h>
#include <emcv/port/ema.h>
#include <emcv/port/hash.h>

namespace {

struct pair_fg {
    double f, g;
};

/// A light that switches and flickers, f = k G + noise: the shape of an SSS pixel's (f, G) stream.
std::vector<pair_fg> stream(std::uint32_t seed, std::size_t n) {
    std::vector<pair_fg> xs;
    for (std::uint32_t i = 0; i < n; ++i) {
        const double u = emcv::port::emcv_uint_to_unit_float(emcv::port::emcv_pcg(seed * 7919u + i)) - 0.5;
        const double light = (i % 17 < 5 ? 1.0 : 0.3) + 0.1 * std::sin(0.3 * i);
        const double g = 0.6 * light;
        xs.push_back({0.85 * g + 0.05 * light * u, g});
    }
    return xs;
}

/// Weighted variance of f - alpha G about its weighted mean, weights of an EMCM after the stream (the first
/// sample seeds: weight (1-eta)^(n-1); sample i >= 1: eta (1-eta)^(n-1-i)), two-pass in long double.
long double weighted_residual_variance(const std::vector<pair_fg>& xs, long double eta, long double alpha) {
    const std::size_t n = xs.size();
    std::vector<long double> w(n);
    for (std::size_t i = 0; i < n; ++i)
        w[i] = (i == 0 ? 1.0L : eta) * std::pow(1.0L - eta, static_cast<long double>(n - 1 - i));
    long double mean = 0, total = 0;
    for (std::size_t i = 0; i < n; ++i) {
        mean += w[i] * (xs[i].f - alpha * xs[i].g);
        total += w[i];
    }
    mean /= total;
    long double var = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const long double d = (xs[i].f - alpha * xs[i].g) - mean;
        var += w[i] * d * d;
    }
    return var / total;
}

std::uint32_t bits(float x) {
    std::uint32_t b;
    std::memcpy(&b, &x, sizeof b);
    return b;
}

}  // namespace

TEST_CASE("the EMCM residual variance is the minimum over alpha of the weighted variance of f - alpha G") {
    for (const double eta : {0.05, 0.1, 0.2}) {
        for (std::uint32_t seed = 1; seed <= 3; ++seed) {
            INFO("eta " << eta << " seed " << seed);
            const auto xs = stream(seed, 200);
            emcv::emcm<double, 2> fg(eta);
            for (const pair_fg& x : xs) fg.push({x.f, x.g});

            // Independent minimum: scan alpha, then refine by golden section on the long-double evaluation.
            long double lo = -5.0L, hi = 5.0L;
            for (int it = 0; it < 200; ++it) {
                const long double a = lo + (hi - lo) * 0.381966L, b = lo + (hi - lo) * 0.618034L;
                if (weighted_residual_variance(xs, eta, a) < weighted_residual_variance(xs, eta, b)) hi = b;
                else lo = a;
            }
            const long double alpha_min = 0.5L * (lo + hi);
            const double v_min = static_cast<double>(weighted_residual_variance(xs, eta, alpha_min));

            const double alpha = emcv::cv_coefficient(fg.covariance(0, 1), fg.variance(1));
            CHECK(alpha == Catch::Approx(static_cast<double>(alpha_min)).epsilon(1e-6));
            CHECK(emcv::cv_optimal_residual_variance(fg) == Catch::Approx(v_min).epsilon(1e-9));
            // The general form at that alpha, and at alpha = 1 against the two-pass evaluation.
            CHECK(emcv::cv_residual_variance(fg.variance(0), fg.covariance(0, 1), fg.variance(1), alpha) ==
                  Catch::Approx(v_min).epsilon(1e-9));
            CHECK(emcv::cv_residual_variance(fg.variance(0), fg.covariance(0, 1), fg.variance(1), 1.0) ==
                  Catch::Approx(static_cast<double>(weighted_residual_variance(xs, eta, 1.0L))).epsilon(1e-9));
            // The minimum is a real reduction here: f follows G.
            CHECK(emcv::cv_optimal_residual_variance(fg) < 0.1 * fg.variance(0));
        }
    }
}

TEST_CASE("Var(f - alpha G) from the EMCM equals a moving variance of the residual stream at a fixed alpha") {
    // By linearity of the recurrence (supp. Eq. 21), the EMCM's quadratic form at a fixed alpha is the
    // moving variance of r = f - alpha G with the same eta: a second estimator fed other numbers.
    const auto xs = stream(11, 300);
    for (const double alpha : {0.0, 0.5, 1.0, 1.7}) {
        emcv::emcm<double, 2> fg(0.1);
        emcv::moving_stats<double> r(0.1);
        for (const pair_fg& x : xs) {
            fg.push({x.f, x.g});
            r.push(x.f - alpha * x.g);
        }
        INFO("alpha " << alpha);
        CHECK(emcv::cv_residual_variance(fg.variance(0), fg.covariance(0, 1), fg.variance(1), alpha) ==
              Catch::Approx(r.variance()).epsilon(1e-10));
    }
}

TEST_CASE("the residual variance guards: constant control, rounding below zero, NaN") {
    // A constant G (static light): C_GG = 0, alpha's guard gives 0 and the variance is C_ff.
    emcv::emcm<float, 2> fg(0.05f);
    for (int i = 0; i < 50; ++i) fg.push({0.5f + 0.01f * static_cast<float>(i % 3), 0.7f});
    REQUIRE(fg.variance(1) == 0.0f);
    CHECK(emcv::cv_optimal_residual_variance(fg) == fg.variance(0));
    // Perfect correlation with rounding: C_fG^2 / C_GG slightly above C_ff must not give a negative variance.
    CHECK(emcv::cv_optimal_residual_variance(1.0f, 1.0000001f, 1.0f) == 0.0f);
    CHECK(emcv::cv_residual_variance(1.0f, 1.0000001f, 1.0f, 1.0f) == 0.0f);
    // A broken state stays broken (the sample count then takes n_max), never becomes a quiet 0.
    const float nan = std::numeric_limits<float>::quiet_NaN();
    CHECK(std::isnan(emcv::cv_optimal_residual_variance(nan, 0.1f, 0.2f)));
    CHECK(std::isnan(emcv::cv_residual_variance(nan, 0.1f, 0.2f, 0.5f)));
}

TEST_CASE("the port's residual variances equal the C++ float instances bit for bit") {
    const auto xs = stream(5, 120);
    emcv::emcm<float, 2> cpp(0.05f);
    emcv::port::EmcvEmcm2 gpu = emcv::port::emcv_emcm2_init();
    for (const pair_fg& x : xs) {
        const float f = static_cast<float>(x.f), g = static_cast<float>(x.g);
        cpp.push({f, g});
        emcv::port::emcv_emcm2_push(gpu, glm::vec2(f, g), 0.05f);
        CHECK(bits(emcv::port::emcv_cv_optimal_residual_variance_emcm2(gpu)) ==
              bits(emcv::cv_optimal_residual_variance(cpp)));
        for (const float alpha : {0.0f, 0.85f, 1.0f})
            CHECK(bits(emcv::port::emcv_cv_residual_variance(gpu.cov.x, gpu.cov.y, gpu.cov.z, alpha)) ==
                  bits(emcv::cv_residual_variance(cpp.variance(0), cpp.covariance(0, 1), cpp.variance(1), alpha)));
    }
    CHECK(emcv::port::emcv_cv_optimal_residual_variance(1.0f, 1.0000001f, 1.0f) == 0.0f);
    CHECK(std::isnan(emcv::port::emcv_cv_optimal_residual_variance(std::nanf(""), 0.1f, 0.2f)));
}
