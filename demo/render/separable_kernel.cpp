// SPDX-License-Identifier: MIT
#include "separable_kernel.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <emcv/port/burley.h>

namespace emcv::demo {

double burley_marginal_tail(double t, double d) {
    // P(X > t) = int_0^1 [r(u) > t] acos(t / r(u)) / pi du: cos(theta) > t / r on an arc of 2 acos(t / r) out
    // of 2 pi. Midpoint rule in u, r(u) the exact inverse CDF (docs/frame.md, in double).
    constexpr int steps = 8192;
    constexpr double pi = EMCV_PI;
    double sum = 0.0;
    for (int i = 0; i < steps; ++i) {
        const double u = (i + 0.5) / steps;
        const double r = emcv::port::emcv_burley_sample_exact(u, d);
        if (r > t) sum += std::acos(t / r) / pi;
    }
    return sum / steps;
}

separable_kernel make_separable_kernel(const glm::vec3& shape_distance_mm, int taps) {
    if (taps < 3 || taps % 2 == 0) throw std::invalid_argument("separable kernel: taps must be odd and >= 3");
    const float d_max = std::max({shape_distance_mm.x, shape_distance_mm.y, shape_distance_mm.z});
    separable_kernel k;
    k.half_width_mm = emcv::port::emcv_burley_sample_exact(0.99f, d_max);
    std::vector<double> offsets(static_cast<std::size_t>(taps));
    for (int i = 0; i < taps; ++i) {
        const double o = -1.0 + 2.0 * i / (taps - 1);
        offsets[static_cast<std::size_t>(i)] = k.half_width_mm * (o < 0.0 ? -o * o : o * o);
    }
    // Mass of (a, b) under the marginal of channel d: tail(a) - tail(b), with the marginal symmetric.
    const auto mass = [](double a, double b, double d) {
        const auto cdf_above = [d](double t) {  // P(X > t) for any t
            return t >= 0.0 ? burley_marginal_tail(t, d) : 1.0 - burley_marginal_tail(-t, d);
        };
        const double upper = std::isinf(b) ? 0.0 : cdf_above(b);
        const double lower = std::isinf(a) ? 1.0 : cdf_above(a);
        return lower - upper;
    };
    const double inf = std::numeric_limits<double>::infinity();
    std::vector<glm::vec4> ordered;
    for (int i = 0; i < taps; ++i) {
        const auto at = [&](int j) { return offsets[static_cast<std::size_t>(j)]; };
        const double a = i == 0 ? -inf : 0.5 * (at(i - 1) + at(i));
        const double b = i == taps - 1 ? inf : 0.5 * (at(i) + at(i + 1));
        ordered.emplace_back(static_cast<float>(mass(a, b, shape_distance_mm.x)),
                             static_cast<float>(mass(a, b, shape_distance_mm.y)),
                             static_cast<float>(mass(a, b, shape_distance_mm.z)), static_cast<float>(at(i)));
    }
    // Normalise each channel to 1 (the strips already sum to 1 up to the quadrature) and put the centre first.
    glm::vec3 total(0.0f);
    for (const glm::vec4& t : ordered) total += glm::vec3(t);
    for (glm::vec4& t : ordered) t = glm::vec4(glm::vec3(t) / total, t.w);
    const std::size_t centre = static_cast<std::size_t>(taps / 2);
    k.taps.push_back(ordered[centre]);
    for (std::size_t i = 0; i < ordered.size(); ++i) {
        if (i != centre) k.taps.push_back(ordered[i]);
    }
    return k;
}

}  // namespace emcv::demo
