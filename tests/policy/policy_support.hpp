// SPDX-License-Identifier: MIT
// Shared by the policy tests: a seeded Gaussian source whose bits do not depend on the standard library
// (std::normal_distribution's algorithm is implementation-defined; std::mt19937_64's output is not), and what
// the change tests of cv and cv-notex read off a frame's sigma^2.
#pragma once

#include <catch2/catch_test_macros.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <random>
#include <vector>

namespace emcv_policy_test {

class gaussian_source {
public:
    explicit gaussian_source(std::uint64_t seed) : g_(seed) {}
    /// Uniform in (0, 1): 53 random bits, never 0.
    double uniform() { return (static_cast<double>(g_() >> 11) + 0.5) * 0x1.0p-53; }
    /// Standard normal (Box-Muller, both values used).
    double normal() {
        if (has_spare_) {
            has_spare_ = false;
            return spare_;
        }
        const double r = std::sqrt(-2.0 * std::log(uniform())), a = 6.283185307179586 * uniform();
        spare_ = r * std::sin(a);
        has_spare_ = true;
        return r * std::cos(a);
    }
    /// Uniform integer in [lo, hi] (the tiny modulo bias of 2^64 mod (hi - lo + 1) is irrelevant here).
    int integer(int lo, int hi) {
        return lo + static_cast<int>(g_() % static_cast<std::uint64_t>(hi - lo + 1));
    }

private:
    std::mt19937_64 g_;
    double spare_ = 0.0;
    bool has_spare_ = false;
};

/// The mean of a frame's per-pixel values.
inline double mean_of(const std::vector<float>& v) {
    double sum = 0;
    for (const float x : v) sum += x;
    return sum / double(v.size());
}

/// How one frame's push moved each pixel's sigma^2: the lowest and highest ratio after / before, and the mean ratio
/// the same frame pushed plainly (no change test) gives.
struct sigma2_rise {
    double lowest = 1e30, highest = 0, plain_mean = 0;
};

inline sigma2_rise rise_of(const std::vector<float>& before, const std::vector<float>& after,
                           const std::vector<float>& after_plain) {
    sigma2_rise r;
    for (std::size_t i = 0; i < before.size(); ++i) {
        const double ratio = double(after[i]) / before[i];
        r.lowest = std::min(r.lowest, ratio), r.highest = std::max(r.highest, ratio);
        r.plain_mean += double(after_plain[i]) / before[i] / double(before.size());
    }
    return r;
}

/// The checks of a jump that the change test clips (cv's and cv-notex's update; each test file derives them):
/// after the frame `after` of a stream at eta (`unbias` = (2 - eta) / (2 (1 - eta))) with sigma^2 `before`
/// (mean `mean_before`) and a step of 20 s / sqrt(N), every pixel's sigma^2 rose by exactly the 5-sigma
/// weight's factor (1 - eta)(1 + 25 eta unbias), all `restarted` means restarted, the same frame pushed plainly
/// rose by at least 0.9 (1 - eta)(1 + 400 eta unbias s^2 / sigma^2) (Jensen: E[1 / sigma^2] >= 1 / E[sigma^2]),
/// and the next frame at the new level (`next_frame()`, returning its sigma^2) does not raise sigma^2 again.
template <class NextFrame>
void check_clipped_jump(const std::vector<float>& before, const std::vector<float>& after,
                        const std::vector<float>& after_plain, std::size_t restarted, double eta, double s,
                        NextFrame next_frame) {
    const double unbias = (2 - eta) / (2 * (1 - eta)), mean_before = mean_of(before);
    const double clipped = (1 - eta) * (1 + 25 * eta * unbias);
    const sigma2_rise r = rise_of(before, after, after_plain);
    INFO("rise of sigma^2 per pixel in [" << r.lowest << ", " << r.highest << "], the 5-sigma weight's " << clipped
                                          << "; plain batch push: mean rise " << r.plain_mean);
    CHECK(r.highest <= clipped * (1 + 1e-5));
    CHECK(r.lowest >= clipped * (1 - 1e-5));  // 400 s^2 is beyond 25 sigma^2 on every pixel
    CHECK(restarted == before.size());
    CHECK(r.plain_mean >= 0.9 * (1 - eta) * (1 + 400 * eta * unbias * s * s / mean_before));
    const double mean_step = mean_of(after), mean_next = mean_of(next_frame());
    INFO("mean sigma^2 at the step " << mean_step << ", a frame later " << mean_next);
    CHECK(mean_next <= mean_step);
}

}  // namespace emcv_policy_test
