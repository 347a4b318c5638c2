// SPDX-License-Identifier: MIT
// cv-notex's update (port::emcv_history_push_notex, which sampling_update calls for cv-notex) on an analytic
// stream: 32x32 pixels, N = 16 samples a frame of standard deviation s = 0.1 around f = G + 0.05, G = 0.25
// (static), eta = sampling_eta (cv-notex's 0.2), 200 frames: every history is mature (count eta >= 1) and its
// sigma^2, the unbiased moving variance of the residual r = f - G (alpha = 1), estimates s^2.
//   unexplained step  f jumps by 20 s / sqrt(N) with G unchanged: r moves by e with N e^2 ~ 400 s^2 > 25 sigma^2,
//            so the frame enters with weight n' = 25 sigma^2 / e^2 and its comoment term is eta n' e^2 =
//            25 eta sigma^2, sigma^2 = unbias C (unbias = (2 - eta) / (2 (1 - eta))): C' = (1 - eta)(C + 25 eta
//            unbias C), a rise of exactly (1 - eta)(1 + 25 eta unbias) = 5.3 at eta 0.2 on every pixel, up to float
//            rounding, and the mean restarts at r. The plain batch push (port::emcv_moving_stats_push_batch, what
//            cv-notex did before) adds eta N e^2 ~ 400 eta s^2: a rise of (1 - eta)(1 + 400 eta unbias s^2 /
//            sigma^2) ~ 72, and its mean lags the new level for 1 / eta frames more, each read as noise.
//   explained step   f and G step by the same amount: r does not move, nothing is clipped, and sigma^2 after the
//            step is what the same frame pushed plainly gives, bit for bit.
//   no change        over the warm-up, a move beyond 5 sigma of Gaussian noise is rare (the estimate's own noise
//            makes it likelier than the normal tail's 6e-7); the mean sigma^2 stays within 5% of s^2.
#include <catch2/catch_test_macros.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include <emcv/adaptive_sampling.hpp>

#include "policy_support.hpp"

namespace notex_changes_tests {  // one namespace per file: the unity build (the sanitize preset) joins files

namespace {

constexpr std::size_t width = 32, pixels = width * width;
constexpr int warm_up = 200, n_samples = 16;
constexpr double s = 0.1, offset = 0.05, g_before = 0.25;

struct notex_stream {
    emcv::sampling_params p;
    std::vector<emcv::port::EmcvMovingStats> states =
        std::vector<emcv::port::EmcvMovingStats>(pixels, emcv::port::emcv_moving_stats_init());
    std::vector<float> f = std::vector<float>(pixels), g = std::vector<float>(pixels);
    std::vector<int> n = std::vector<int>(pixels, n_samples);
    emcv_policy_test::gaussian_source rng{43};

    notex_stream() { p.estimator = emcv::sampling_estimator::cv_notex; }

    /// One frame: f = G + offset + step + the mean of N samples of standard deviation s.
    void frame(double g_value, double step) {
        for (std::size_t i = 0; i < pixels; ++i) {
            g[i] = static_cast<float>(g_value);
            f[i] = static_cast<float>(g_value + offset + step + s * rng.normal() / std::sqrt(double(n_samples)));
        }
        emcv::sampling_update(p, states.data(), pixels, width, nullptr, f.data(), g.data(), n.data());
    }

    std::vector<float> sigma2() const {
        std::vector<float> out(pixels);
        emcv::sampling_sigma2(p, states.data(), pixels, nullptr, out.data());
        return out;
    }

    /// The states after pushing this frame's (f, G) plainly, from `from`.
    std::vector<emcv::port::EmcvMovingStats> plain_push(std::vector<emcv::port::EmcvMovingStats> from) const {
        const float eta = emcv::sampling_eta(p);
        for (std::size_t i = 0; i < pixels; ++i)
            emcv::port::emcv_moving_stats_push_batch(from[i], f[i] - g[i], eta, float(n_samples));
        return from;
    }
};

}  // namespace

using emcv_policy_test::mean_of;

TEST_CASE("cv-notex's update: a residual jump raises sigma^2 by the 5-sigma weight only and restarts the mean") {
    notex_stream st;
    for (int t = 0; t < warm_up; ++t) st.frame(g_before, 0.0);
    const double eta = emcv::sampling_eta(st.p);
    REQUIRE(st.states[0].count * eta >= 1.0);
    const std::vector<float> before = st.sigma2();
    const double mean_before = mean_of(before);
    INFO("sigma^2 before the step " << mean_before << ", s^2 " << s * s);
    REQUIRE(std::fabs(mean_before / (s * s) - 1) < 0.05);  // no change: the test rarely fires, sigma^2 unbiased

    const std::vector<emcv::port::EmcvMovingStats> was = st.states;
    const double step = 20 * s / std::sqrt(double(n_samples));
    st.frame(g_before, step);
    const std::vector<float> after = st.sigma2();
    std::vector<emcv::port::EmcvMovingStats> plain = st.plain_push(was);
    std::vector<float> after_plain(pixels);
    emcv::sampling_sigma2(st.p, plain.data(), pixels, nullptr, after_plain.data());

    std::size_t restarted = 0;
    for (std::size_t i = 0; i < pixels; ++i)
        if (st.states[i].mean == st.f[i] - st.g[i]) ++restarted;
    emcv_policy_test::check_clipped_jump(before, after, after_plain, restarted, eta, s, [&] {
        st.frame(g_before, step);  // the next frame at the new level: noise around the restarted mean
        return st.sigma2();
    });
}

TEST_CASE("cv-notex's update: a step of f and G by the same amount is no change (alpha = 1)") {
    notex_stream st;
    for (int t = 0; t < warm_up; ++t) st.frame(g_before, 0.0);
    const std::vector<emcv::port::EmcvMovingStats> was = st.states;
    st.frame(2 * g_before, 0.0);  // f and G both rise by g_before: r = offset + noise as before
    const std::vector<emcv::port::EmcvMovingStats> plain = st.plain_push(was);
    for (std::size_t i = 0; i < pixels; ++i) {
        INFO("pixel " << i);
        CHECK(st.states[i].mean == plain[i].mean);
        CHECK(st.states[i].variance == plain[i].variance);
        CHECK(st.states[i].count == plain[i].count);
    }
}

}  // namespace notex_changes_tests
