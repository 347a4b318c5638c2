// SPDX-License-Identifier: MIT
// Shared by the policy tests: a seeded Gaussian source whose bits do not depend on the standard library
// (std::normal_distribution's algorithm is implementation-defined; std::mt19937_64's output is not).
#pragma once

#include <cmath>
#include <cstdint>
#include <random>

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

}  // namespace emcv_policy_test
