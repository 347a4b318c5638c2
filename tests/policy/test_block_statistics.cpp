// SPDX-License-Identifier: MIT
// The statistics' grain (include/emcv/port/history.h, EMCV_HISTORY_BLOCK): a block's history is the mean output
// of its m scattering pixels, each the mean of n samples, pushed as a batch of n m (emcv_history_block_batch).
// On an analytic stream of independent Gaussian pixel outputs of known per-sample variances sigma_i^2, the
// block's per-sample variance (emcv_history_sigma2_moving) estimates the mean of its pixels' sigma_i^2 (supp.
// Eq. 25-27: Var((1/m) sum f_i) = (1/m^2) sum sigma_i^2 / n).
#include <catch2/catch_test_macros.hpp>

#include <cmath>
#include <cstdint>
#include <vector>

#include <emcv/port/history.h>

#include "policy_support.hpp"

namespace emcv_block_statistics_test {

TEST_CASE("a block's history, pushed as a batch of n m, estimates the mean of its pixels' per-sample variances") {
    // 2048 independent 2x2 blocks (m = 4), n = 5 samples a pixel; the pixels' per-sample standard deviations in
    // a block are s (1, 1.5, 2, 3), s drawn per block from [0.01, 0.1], so that the mean of sigma_i^2 (4.0625 s^2)
    // and the square of the mean sigma (3.516 s^2) differ by 13.5%. 80 frames at eta 0.2 (a memory of 5 frames:
    // the estimate is at its steady state, where the unbias factor (2 - eta) / (2 (1 - eta)) is exact).
    //
    // Bound: at steady state a block's estimate is a weighted sum of squared Gaussian deviations whose effective
    // number of frames is (2 - eta) / eta = 9 (emcv_history_effective_frames at saturation), so its relative
    // variance is 2 / 9 (a chi-square's 2 / dof); the mean of estimate / truth over 2048 independent blocks has a
    // relative standard deviation of sqrt(2 / 9 / 2048) = 0.0104. 5 of those: 0.052. The scale errors the bound
    // must catch: a batch of n instead of n m (the estimate m = 4 times too large), n m^2 (4 times too small), and
    // the square of the mean sigma instead of the mean of sigma^2 (0.865).
    constexpr int blocks = 2048, m = 4, frames = 80;
    constexpr std::uint32_t n = 5;
    constexpr float eta = 0.2f;
    const double shape[m] = {1.0, 1.5, 2.0, 3.0};
    emcv_policy_test::gaussian_source rng(20261207u);
    double ratio_sum = 0.0;
    for (int b = 0; b < blocks; ++b) {
        const double scale = 0.01 + 0.09 * rng.uniform();
        double mean_sigma2 = 0.0;
        for (double k : shape) mean_sigma2 += (scale * k) * (scale * k) / m;
        const double level[m] = {0.3, 0.5, 0.2, 0.4};  // each pixel's own signal: cancels in the temporal variance
        emcv::port::EmcvMovingStats s = emcv::port::emcv_moving_stats_init();
        for (int frame = 0; frame < frames; ++frame) {
            float sum = 0.0f;
            for (int i = 0; i < m; ++i)
                sum += float(level[i] + scale * shape[i] / std::sqrt(double(n)) * rng.normal());  // a pixel's mean of n
            REQUIRE(emcv::port::emcv_moving_stats_push_batch(s, sum / float(m), eta,
                                                             emcv::port::emcv_history_block_batch(n, std::uint32_t(m))));
        }
        ratio_sum += double(emcv::port::emcv_history_sigma2_moving(s, eta)) / mean_sigma2;
    }
    const double ratio = ratio_sum / blocks;
    INFO("mean over blocks of the block's sigma^2 / the mean of its pixels' sigma_i^2: " << ratio);
    CHECK(std::fabs(ratio - 1.0) <= 0.052);
}

TEST_CASE("a block's batch is its pixels times each pixel's samples") {
    CHECK(emcv::port::emcv_history_block_batch(7u, 1u) == 7.0f);   // K = 1: the pixel's own n
    CHECK(emcv::port::emcv_history_block_batch(7u, 3u) == 21.0f);  // a block with one pixel that does not scatter
    CHECK(emcv::port::emcv_history_block_batch(0u, 4u) == 0.0f);   // no samples: nothing to push
}

}  // namespace emcv_block_statistics_test
