// SPDX-License-Identifier: MIT
// The history's per-sample variance on an analytic stream (supp. Eq. 25-27): each pixel's frame output is
// x_t = mu + the mean of N_t Gaussian samples of standard deviation s, N_t varying from frame to frame; pushed
// as a batch of N_t (sampling_update), emcv_history_sigma2_moving (spvg) and emcv_history_sigma2_cv (cv, with a
// constant G) estimate s^2; pushed plainly (one sample per frame, the port's emcv_moving_stats_push) they
// estimate s^2 E[1/N], the variance of the output rather than of one sample.
//
// The expectation, exactly. Per pixel, with e_t = mu_t - mu the EMA mean's error and V_t = Var(e_t):
//   first push (r = 1): mu_0 = x_0, C_0 = 0, V_0 = s^2 / N_0;
//   then d_t = x_t - mu_(t-1) has E[d_t^2] = s^2 / N_t + V_(t-1), and the port's step C' = (1 - eta)(C + eta n d^2)
//   (n = N_t for a batch push, 1 for a plain one) gives E[C_t] = (1 - eta)(E[C_(t-1)] + eta n_t E[d_t^2]),
//   V_t = (1 - eta)^2 V_(t-1) + eta^2 s^2 / N_t.
// The test runs this recursion in double on each pixel's own N sequence: the mean of the expectations is
// what the mean of the estimates must match, warm-up included. In steady state with N i.i.d. it reduces to
//   batch: unbias * (1 - eta) E[N d^2] = s^2 (1 + eta (E[N] E[1/N] - 1) / 2)     (= s^2 for a constant N)
//   plain: s^2 E[1/N]
// (V_inf = eta s^2 E[1/N] / (2 - eta); unbias = (2 - eta) / (2 (1 - eta))): the batch push is exact for a
// constant N and over-states by eta (E[N] E[1/N] - 1) / 2 when N jumps from frame to frame (the mean's lag noise
// is multiplied by this frame's N) -- 11% for spvg (eta 0.2) with N uniform over 1..32, 2.7% for cv.
//
// The bound. C_T = sum_k w_k X_(T-k) with X = n d^2 and weights w_k = (1 - eta) eta (1 - eta)^k, so
// Var(C) / E[C]^2 ~ (sum w_k^2 / (sum w_k)^2) relvar(X) = eta / (2 - eta) relvar(X), with d Gaussian given N:
// E[X^2] = 3 m_N^2, m_N = E[X | N], so relvar(X) = 3 E[m_N^2] / E[m_N]^2 - 1 (2 for a constant N). Averaging P
// independent pixels divides the variance by P. The O(eta) correlation of successive d (they share the mean's
// error) is not in this; the 6-sigma margin covers it.
#include <catch2/catch_test_macros.hpp>

#include <cmath>
#include <cstdint>
#include <vector>

#include <emcv/adaptive_sampling.hpp>

#include "policy_support.hpp"

namespace per_sample_variance_tests {  // one namespace per file: the unity build (the sanitize preset) joins files

namespace {

using emcv_policy_test::gaussian_source;

constexpr std::size_t width = 64, pixels = width * width;
constexpr int frames = 400;  // (1 - 0.05)^400 ~ 1e-9: every estimator is past its warm-up
constexpr double s = 0.1, mu = 0.5;

enum class schedule { constant16, alternating4_32, uniform1_32 };

int batch_size(schedule k, gaussian_source& rng, int t) {
    switch (k) {
        case schedule::constant16: return 16;
        case schedule::alternating4_32: return t % 2 == 0 ? 4 : 32;
        case schedule::uniform1_32: return rng.integer(1, 32);
    }
    return 1;
}

/// E[1/N] and E[N] of a schedule over a long run (all three are stationary).
void schedule_moments(schedule k, double& mean_n, double& mean_inv_n) {
    switch (k) {
        case schedule::constant16: mean_n = 16, mean_inv_n = 1.0 / 16; return;
        case schedule::alternating4_32: mean_n = 18, mean_inv_n = (0.25 + 1.0 / 32) / 2; return;
        case schedule::uniform1_32: {
            mean_n = 16.5, mean_inv_n = 0;
            for (int n = 1; n <= 32; ++n) mean_inv_n += 1.0 / n / 32;
            return;
        }
    }
}

struct run_result {
    double estimate = 0;     // mean over pixels of the estimator's sigma^2
    double expectation = 0;  // mean over pixels of its exact expectation (the recursion above)
    double steady = 0;       // the steady-state closed form
    double bound = 0;        // 6 standard deviations of the pixel mean
};

/// One estimator over the analytic stream. batch: the library's sampling_update (a batch of N_t); otherwise the
/// port's plain push of the output.
run_result run(emcv::sampling_estimator estimator, schedule k, bool batch, std::uint64_t seed) {
    emcv::sampling_params p;
    p.estimator = estimator;
    const double eta = emcv::sampling_eta(p);
    const bool cv = estimator == emcv::sampling_estimator::cv;
    std::vector<emcv::port::EmcvMovingStats> moving(pixels, emcv::port::emcv_moving_stats_init());
    std::vector<emcv::port::EmcvEmcm2> emcm(pixels, emcv::port::emcv_emcm2_init());
    std::vector<double> ec(pixels, 0.0), v(pixels, 0.0);
    std::vector<float> f(pixels), g(pixels, 0.25f);  // G: a constant control (C_GG = 0, alpha = 0)
    std::vector<int> n(pixels);
    gaussian_source rng(seed);
    for (int t = 0; t < frames; ++t) {
        for (std::size_t i = 0; i < pixels; ++i) {
            n[i] = batch_size(k, rng, t);
            const double var_out = s * s / n[i];  // the mean of N_t samples: exactly N(mu, s^2 / N_t)
            f[i] = static_cast<float>(mu + std::sqrt(var_out) * rng.normal());
            const double push_n = batch ? n[i] : 1.0;
            if (t == 0) {
                ec[i] = 0.0, v[i] = var_out;
            } else {
                ec[i] = (1 - eta) * (ec[i] + eta * push_n * (var_out + v[i]));
                v[i] = (1 - eta) * (1 - eta) * v[i] + eta * eta * var_out;
            }
            if (!batch) emcv::port::emcv_moving_stats_push(moving[i], f[i], static_cast<float>(eta));
        }
        if (batch && cv) emcv::sampling_update(p, emcm.data(), pixels, width, nullptr, f.data(), g.data(), n.data());
        else if (batch) emcv::sampling_update(p, moving.data(), pixels, width, nullptr, f.data(), g.data(), n.data());
    }
    std::vector<float> sigma2(pixels);
    if (cv) emcv::sampling_sigma2(p, emcm.data(), pixels, nullptr, sigma2.data());
    else emcv::sampling_sigma2(p, moving.data(), pixels, nullptr, sigma2.data());
    run_result r;
    const double unbias = (2 - eta) / (2 * (1 - eta));
    for (std::size_t i = 0; i < pixels; ++i) {
        r.estimate += sigma2[i] / double(pixels);
        r.expectation += ec[i] * unbias / double(pixels);
    }
    double en = 0, einv = 0;
    schedule_moments(k, en, einv);
    const double v_inf = eta * s * s * einv / (2 - eta);
    r.steady = batch ? s * s * (1 + eta * (en * einv - 1) / 2) : s * s * einv;
    if (k == schedule::alternating4_32) {
        // Not i.i.d.: a 2-periodic steady state. V after an N = 4 frame (V_a) and after an N = 32 one (V_b):
        // V_a = q V_b + eta^2 s^2 / 4, V_b = q V_a + eta^2 s^2 / 32 with q = (1 - eta)^2; the N = 4 push sees
        // V_b and the N = 32 push V_a, and the last frame (t = 399) pushed N = 32:
        // E[C_odd] (1 - q) = (1 - eta) eta ((1 - eta) X_4 + X_32), X_N = n (s^2 / N + V_before).
        const double q = (1 - eta) * (1 - eta), e2 = eta * eta * s * s;
        const double va = (e2 / 4 + q * e2 / 32) / (1 - q * q), vb = (e2 / 32 + q * e2 / 4) / (1 - q * q);
        const double x4 = (batch ? 4 : 1) * (s * s / 4 + vb), x32 = (batch ? 32 : 1) * (s * s / 32 + va);
        r.steady = (1 - eta) * eta * ((1 - eta) * x4 + x32) / (1 - q) * (2 - eta) / (2 * (1 - eta));
    }
    // relvar(X) = 3 E[m^2] / E[m]^2 - 1 with m_N = s^2 + N V_inf (batch) or s^2 / N + V_inf (plain), over the
    // schedule's N distribution
    double em = 0, em2 = 0;
    const int support[] = {16, 4, 32};
    auto add = [&](int nn, double weight) {
        const double m = batch ? s * s + nn * v_inf : s * s / nn + v_inf;
        em += weight * m, em2 += weight * m * m;
    };
    if (k == schedule::constant16) add(support[0], 1.0);
    else if (k == schedule::alternating4_32) add(support[1], 0.5), add(support[2], 0.5);
    else
        for (int nn = 1; nn <= 32; ++nn) add(nn, 1.0 / 32);
    const double relvar_x = 3 * em2 / (em * em) - 1;
    r.bound = 6 * r.expectation * std::sqrt(eta / (2 - eta) * relvar_x / double(pixels));
    return r;
}

const char* name(schedule k) {
    return k == schedule::constant16 ? "N = 16" : k == schedule::alternating4_32 ? "N = 4, 32, 4, ..." : "N ~ U{1..32}";
}

}  // namespace

TEST_CASE("batch pushes estimate the per-sample variance: s^2 for a constant N, plus the mean's lag term when N_t jumps") {
    std::uint64_t seed = 11;
    for (const schedule k : {schedule::constant16, schedule::alternating4_32, schedule::uniform1_32}) {
        for (const auto e : {emcv::sampling_estimator::spvg, emcv::sampling_estimator::cv}) {
            const run_result r = run(e, k, true, seed++);
            INFO(name(k) << (e == emcv::sampling_estimator::cv ? ", cv" : ", spvg") << ": estimate " << r.estimate
                         << ", expectation " << r.expectation << ", steady state " << r.steady << ", s^2 " << s * s
                         << ", bound " << r.bound);
            CHECK(std::fabs(r.estimate - r.expectation) <= r.bound);
            // the recursion has reached the closed-form steady state; with N drawn at random the pixels' own N
            // sequences scatter it, by less than the estimate's own scatter (Var E[C | N] <= Var C)
            CHECK(std::fabs(r.expectation - r.steady) <= (k == schedule::uniform1_32 ? r.bound : 1e-3 * s * s));
            // a constant N: no lag term, the estimate is s^2 itself
            if (k == schedule::constant16) CHECK(std::fabs(r.estimate - s * s) <= r.bound);
        }
    }
}

TEST_CASE("plain pushes (no N_t scaling) estimate the output's variance, s^2 E[1/N], not the per-sample one") {
    std::uint64_t seed = 101;
    for (const schedule k : {schedule::constant16, schedule::uniform1_32}) {
        const run_result plain = run(emcv::sampling_estimator::spvg, k, false, seed++);
        double en = 0, einv = 0;
        schedule_moments(k, en, einv);
        INFO(name(k) << ": plain estimate " << plain.estimate << ", s^2 E[1/N] " << s * s * einv);
        CHECK(std::fabs(plain.estimate - plain.expectation) <= plain.bound);
        CHECK(std::fabs(plain.expectation - plain.steady) <= (k == schedule::uniform1_32 ? plain.bound : 1e-3 * s * s));
        CHECK(plain.estimate < 0.2 * s * s);  // off by E[1/N] = 1/16 or 0.127
    }
}

}  // namespace per_sample_variance_tests
