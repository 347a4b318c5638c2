// SPDX-License-Identifier: MIT
// The budget's empirical-Bayes shrinkage of the pooled variance towards the frame's mean (docs/renderer.md,
// "Shrinkage"), against quantities computed here from their definitions, in double:
//   frames   a history of c frames has c - 1 terms n d^2 weighted a^j (a = 1 - eta): its effective frames are
//            (sum w)^2 / sum w^2 of those weights, summed term by term here (1 at c = 2, (2 - eta) / eta late);
//   pool     the mean of P estimates of K_j frames has the sampling variance of P^2 / sum (1 / K_j) frames;
//   weight   the posterior mean w s2 + (1 - w) m with w = tau^2 / (tau^2 + r (m^2 + tau^2) / K): a fresh history
//            (no variance) is allocated m, an old one its own s2 to within (1 - w) |s2 - m|;
//   prior    on a synthetic frame (true sigma^2 log-normal across pixels, each estimate multiplied by a mean-1
//            noise of relative variance r / K) the histogram's statistics recover the true mean and the true
//            spread tau^2 (not the observed one, which the sampling noise inflates), and tau^2 near 0 when the
//            whole spread is noise;
//   plan     plan_frame with a prior shrinks as the weight says and hands the frame's statistics to the next.
#include <catch2/catch_approx.hpp>
#include <catch2/catch_test_macros.hpp>
#include <catch2/matchers/catch_matchers_string.hpp>

#include <cmath>
#include <cstdint>
#include <vector>

#include <emcv/adaptive_sampling.hpp>

#include "policy_support.hpp"

namespace budget_shrink_tests {  // one namespace per file: the unity build (the sanitize preset) joins files

namespace {

namespace port = emcv::port;

/// (sum w)^2 / sum w^2 over the weights a^j, j = 1 .. count - 1, summed one by one.
double effective_frames_by_sum(unsigned count, double eta) {
    double sum = 0, squares = 0, w = 1;
    for (unsigned j = 1; j < count; ++j) {
        w *= 1 - eta;
        sum += w;
        squares += w * w;
    }
    return squares > 0 ? sum * sum / squares : 0;
}

/// The posterior mean of sigma^2 from its definition.
double posterior(double s2, double frames, double mean, double between, double relative) {
    const double sampling = relative * (mean * mean + between) / frames;
    const double w = between / (between + sampling);
    return w * s2 + (1 - w) * mean;
}

emcv::sampling_params budget_params(float b) {
    emcv::sampling_params p;
    p.estimator = emcv::sampling_estimator::spvg;
    p.mode = emcv::sampling_mode::budget;
    p.budget = b;
    return p;
}

}  // namespace

TEST_CASE("a history's effective frames are the weights' (sum w)^2 / sum w^2 over its count - 1 frame terms") {
    CHECK(port::emcv_history_effective_frames(0u, 0.2f) == 0.0f);
    CHECK(port::emcv_history_effective_frames(1u, 0.2f) == 0.0f);
    for (const float eta : {0.05f, 0.2f, 0.5f}) {
        for (const unsigned count : {2u, 3u, 5u, 10u, 40u, 200u}) {
            INFO("eta " << eta << ", count " << count);
            CHECK(port::emcv_history_effective_frames(count, eta) ==
                  Catch::Approx(effective_frames_by_sum(count, double(eta))).epsilon(1e-5));
        }
        // saturation: (2 - eta) / eta, also past the stored count's cap
        CHECK(port::emcv_history_effective_frames(5000u, eta) == Catch::Approx((2.0 - eta) / eta).epsilon(1e-5));
    }
}

TEST_CASE("the pooled estimate's effective frames are P^2 / sum (1 / K_j) over the neighbours with a variance") {
    // One 3x3 image, one material: the centre pools all nine; the corner (0, 0) pools itself and 3 neighbours.
    const std::vector<float> own = {1e-3f, 2e-3f, 1e-3f, port::emcv_history_no_variance(), 4e-3f, 1e-3f,
                                    1e-3f, 1e-3f, 3e-3f};
    const std::vector<float> frames = {1.0f, 9.0f, 1.0f, 0.0f, 4.0f, 9.0f, 9.0f, 1.0f, 2.0f};
    std::vector<float> pooled(9), pooled_frames(9);
    emcv::sampling_pool(own.data(), 9, 3, nullptr, pooled.data(), frames.data(), pooled_frames.data());
    double inverse = 0;
    for (std::size_t i = 0; i < 9; ++i)
        if (own[i] >= 0) inverse += 1.0 / frames[i];
    CHECK(pooled_frames[4] == Catch::Approx(8.0 * 8.0 / inverse).epsilon(1e-6));  // 8 with a variance
    CHECK(pooled_frames[0] == Catch::Approx(3.0 * 3.0 / (1.0 + 1.0 / 9.0 + 1.0 / 4.0)).epsilon(1e-6));
    // the pixel without a variance keeps its code; its frames are its neighbours' (not used: it takes the mean)
    CHECK(pooled[3] == port::emcv_history_no_variance());
    // only one of the two frame arrays: refused, naming the function
    CHECK_THROWS_WITH(emcv::sampling_pool(own.data(), 9, 3, nullptr, pooled.data(), frames.data(), nullptr),
                      Catch::Matchers::ContainsSubstring("emcv::sampling_pool"));
}

TEST_CASE("shrinkage: a fresh history is allocated the frame mean, an old one nearly its own variance") {
    const float mean = 2e-3f, between = 1e-6f, relative = 2.795f;
    // no variance yet: the mean
    CHECK(port::emcv_history_shrink_sigma2(port::emcv_history_no_variance(), 0.0f, mean, between, relative) == mean);
    // no samples stays; without a prior (the first frames) the value is kept as it is
    CHECK(port::emcv_history_shrink_sigma2(port::emcv_history_no_samples(), 9.0f, mean, between, relative) ==
          port::emcv_history_no_samples());
    CHECK(port::emcv_history_shrink_sigma2(5e-3f, 9.0f, 0.0f, between, relative) == 5e-3f);
    CHECK(port::emcv_history_shrink_sigma2(port::emcv_history_no_variance(), 0.0f, 0.0f, 0.0f, relative) ==
          port::emcv_history_no_variance());
    // a spread that is all noise (tau^2 = 0): every pixel the mean, the even split
    CHECK(port::emcv_history_shrink_sigma2(5e-3f, 81.0f, mean, 0.0f, relative) == mean);
    // the weight from its definition, young (a pool of 9 two-frame histories) to saturated (9 pixels x 9 frames)
    for (const float frames : {9.0f, 20.0f, 81.0f, 1000.0f}) {
        for (const float s2 : {1e-4f, 5e-3f}) {
            INFO("frames " << frames << ", s2 " << s2);
            const double expected = posterior(s2, frames, mean, between, relative);
            CHECK(port::emcv_history_shrink_sigma2(s2, frames, mean, between, relative) ==
                  Catch::Approx(expected).epsilon(1e-5));
            // more frames: closer to its own value
            CHECK(std::abs(port::emcv_history_shrink_sigma2(s2, 2 * frames, mean, between, relative) - s2) <
                  std::abs(float(expected) - s2));
        }
    }
}

TEST_CASE("the frame's prior recovers the true mean and spread of sigma^2 under the estimates' sampling noise") {
    emcv_policy_test::gaussian_source rng(77);
    const emcv::sampling_params p = budget_params(8.0f);
    const double relative = emcv::budget_relative_variance(p);
    REQUIRE(relative == Catch::Approx(2.0 + (9.36 - 3.0) / 8.0));
    constexpr std::size_t pixels = 40000;
    for (const double log_spread : {0.8, 0.0}) {
        INFO("log-normal spread of the true sigma^2: " << log_spread);
        emcv::budget_histogram h = emcv::make_budget_histogram();
        double true_sum = 0, true_squares = 0;
        for (std::size_t i = 0; i < pixels; ++i) {
            const double sigma2 = 1e-3 * std::exp(log_spread * rng.normal());
            const double frames = i % 2 == 0 ? 9.0 : 81.0;  // young and saturated pools
            // a mean-1 log-normal noise of relative variance r / K
            const double v = std::log(1 + relative / frames);
            const double s2 = sigma2 * std::exp(std::sqrt(v) * rng.normal() - v / 2);
            emcv::budget_add_raw(h, float(s2), float(frames));
            true_sum += sigma2;
            true_squares += sigma2 * sigma2;
        }
        const double mean = true_sum / pixels, between = true_squares / pixels - mean * mean;
        const emcv::budget_prior prior = emcv::budget_frame_prior(p, h);
        CHECK(prior.mean_sigma2 == Catch::Approx(mean).epsilon(0.02));
        if (log_spread > 0) {
            CHECK(prior.between_variance == Catch::Approx(between).epsilon(0.1));
        } else {
            CHECK(prior.between_variance < 0.02 * mean * mean);  // all noise: no spread left
        }
    }
    // an empty histogram: no prior
    const emcv::budget_prior none = emcv::budget_frame_prior(p, emcv::make_budget_histogram());
    CHECK(none.mean_sigma2 == 0.0f);
    CHECK(none.between_variance == 0.0f);
}

TEST_CASE("plan_frame under a budget shrinks by the prior it is given and hands on the frame's statistics") {
    const emcv::sampling_params p = budget_params(8.0f);
    const float eta = emcv::sampling_eta(p);
    constexpr std::size_t width = 8, pixels = 64;  // one tile
    std::vector<float> sigma2(pixels);
    std::vector<int> counts(pixels);

    // Every history fresh: each pixel is allocated the prior's mean, the even split.
    std::vector<port::EmcvMovingStats> states(pixels, port::emcv_moving_stats_init());
    emcv::budget_prior prior{1e-3f, 4e-7f};
    emcv::plan_frame(p, states.data(), pixels, width, nullptr, nullptr, 3u, 1u, sigma2.data(), counts.data(), prior);
    for (std::size_t i = 0; i < pixels; ++i) CHECK(sigma2[i] == 1e-3f);
    for (std::size_t i = 0; i < pixels; ++i) CHECK((counts[i] == 8 || counts[i] == 9));
    CHECK(prior.mean_sigma2 == 0.0f);  // no pixel had a variance: no statistics for the next frame

    // Saturated histories, variance 1e-3 on the left half and 4e-3 on the right: each pools its own half except
    // along the seam; the shrunk value is the posterior mean at the pool's frames.
    for (std::size_t i = 0; i < pixels; ++i) {
        states[i].count = 500u;
        states[i].variance = (i % width < 4 ? 1e-3f : 4e-3f) / port::emcv_history_unbias(eta);
    }
    std::vector<float> pooled(pixels), frames(pixels);
    emcv::sampling_sigma2(p, states.data(), pixels, nullptr, pooled.data());
    emcv::sampling_frames(p, states.data(), pixels, frames.data());
    emcv::sampling_pool(pooled.data(), pixels, width, nullptr, pooled.data(), frames.data(), frames.data());
    prior = emcv::budget_prior{2e-3f, 1e-6f};
    emcv::plan_frame(p, states.data(), pixels, width, nullptr, nullptr, 3u, 1u, sigma2.data(), counts.data(), prior);
    for (const std::size_t i : {std::size_t(9), std::size_t(14), std::size_t(36)}) {  // inside each half
        INFO("pixel " << i);
        const double k = 9.0 * (2.0 - eta) / eta;  // nine saturated histories
        CHECK(frames[i] == Catch::Approx(k).epsilon(1e-5));
        CHECK(sigma2[i] == Catch::Approx(posterior(pooled[i], k, 2e-3, 1e-6, emcv::budget_relative_variance(p)))
                               .epsilon(1e-5));
    }
    // the statistics handed on: the pooled variances' mean (at their bins' centres: sigma within 1/16 of its
    // octave, sigma^2 within 13%)
    double mean = 0;
    for (const float s : pooled) mean += s;
    mean /= pixels;
    CHECK(prior.mean_sigma2 == Catch::Approx(mean).epsilon(0.13));
    CHECK(prior.between_variance > 0.0f);
}

}  // namespace budget_shrink_tests
