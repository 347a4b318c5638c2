// SPDX-License-Identifier: MIT
// Brute-force two-pass references in long double, straight from the definitions (supp. Eq. 1, 18, 24).
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

namespace emcv_test {

using real = long double;

/// The accuracy asked of the double estimators against these references: relative error at most 1e-12.
inline constexpr double kTolerance = 1e-12;

template <std::size_t N>
struct reference_moments {
    real total_weight = 0;
    std::array<real, N> mean{};
    std::array<std::array<real, N>, N> covariance{};
};

/// Weighted mean (Eq. 1) and weighted covariance about that mean (Eq. 24 / W), computed in two passes.
template <std::size_t N, class Sample>
reference_moments<N> two_pass(const std::vector<Sample>& x, const std::vector<real>& w, std::size_t n) {
    reference_moments<N> m;
    for (std::size_t i = 0; i < n; ++i) m.total_weight += w[i];
    for (std::size_t k = 0; k < N; ++k) {
        real s = 0;
        for (std::size_t i = 0; i < n; ++i) s += w[i] * static_cast<real>(x[i][k]);
        m.mean[k] = s / m.total_weight;
    }
    for (std::size_t a = 0; a < N; ++a)
        for (std::size_t b = 0; b < N; ++b) {
            real s = 0;
            for (std::size_t i = 0; i < n; ++i)
                s += w[i] * (static_cast<real>(x[i][a]) - m.mean[a]) * (static_cast<real>(x[i][b]) - m.mean[b]);
            m.covariance[a][b] = s / m.total_weight;
        }
    return m;
}

/// Effective weights w_{n,i} = w_i * prod_{k=i+1..n} decay_k of the first n samples (the recurrence's
/// rescaling of old weights, supp. section 1).
inline std::vector<real> effective_weights(const std::vector<real>& weight, const std::vector<real>& decay,
                                           std::size_t n) {
    std::vector<real> w(n);
    real scale = 1;
    for (std::size_t i = n; i-- > 0;) {
        w[i] = weight[i] * scale;
        scale *= decay[i];
    }
    return w;
}

/// Geometric weights of the exponential moving estimators after n + 1 samples x_0..x_n (Eq. 18):
/// w_{n,0} = (1 - eta)^n (the seed), w_{n,i} = eta (1 - eta)^{n-i} for i >= 1; they sum to 1.
inline std::vector<real> geometric_weights(real eta, std::size_t count) {
    std::vector<real> w(count);
    if (count == 0) return w;
    const std::size_t n = count - 1;
    for (std::size_t i = 1; i <= n; ++i) w[i] = eta * std::pow(1 - eta, static_cast<real>(n - i));
    w[0] = std::pow(1 - eta, static_cast<real>(n));
    return w;
}

/// |a - b| / scale, the error measure used against the references: the scale of a mean is |mean| + sd,
/// the scale of a covariance entry (i, j) is sqrt(var_i var_j) (an off-diagonal near 0 has no relative error).
inline real scaled_error(real a, real b, real scale) {
    return scale > 0 ? std::fabs(a - b) / scale : std::fabs(a - b);
}

}  // namespace emcv_test
