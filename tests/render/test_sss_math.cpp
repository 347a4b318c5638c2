// SPDX-License-Identifier: MIT
// The renderer's per-pixel SSS maths (include/emcv/port/sss.h) and the separable kernel, on the CPU.
#include <catch2/catch_test_macros.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include <emcv/port/hash.h>
#include <emcv/port/sss.h>

#include "render/separable_kernel.hpp"

using namespace emcv::port;

TEST_CASE("pixelsPerMm maps a world offset to the pixels the projection moves it by") {
    // A horizontal offset of delta world units at view depth z moves 0.5 P00 W delta / z pixels
    // (docs/frame.md); checked against glm's projection of both points.
    const int width = 320;
    const int height = 200;
    const float mm_per_unit = 25.0f;
    const glm::mat4 proj = glm::perspective(glm::radians(40.0f), float(width) / float(height), 0.1f, 100.0f);
    for (float z : {0.5f, 2.0f, 9.0f}) {
        const float delta = 0.01f * z;
        const glm::vec4 a = proj * glm::vec4(0.1f, 0.05f, -z, 1.0f);
        const glm::vec4 b = proj * glm::vec4(0.1f + delta, 0.05f, -z, 1.0f);
        const float pixels = (b.x / b.w - a.x / a.w) * 0.5f * float(width);
        const float predicted = emcv_sss_pixels_per_mm(proj[0][0], float(width), z, mm_per_unit) * delta * mm_per_unit;
        INFO("z " << z << ": projected " << pixels << " px, predicted " << predicted);
        CHECK(std::abs(pixels - predicted) <= 1e-4f * pixels);
    }
}

TEST_CASE("the search-light scaling fit and the shape distance") {
    CHECK(emcv_sss_scaling(0.33f) == 3.5f);
    CHECK(std::abs(emcv_sss_scaling(0.83f) - 9.75f) < 1e-5f);  // 3.5 + 100 * 0.5^4
    const vec3 d = emcv_sss_shape_distance(vec3(3.0f, 1.0f, 0.5f), vec3(0.83f, 0.33f, 0.33f));
    CHECK(std::abs(d.x - 3.0f / 9.75f) < 1e-6f);
    CHECK(d.y == 1.0f / 3.5f);
    CHECK(emcv_sss_widest(d) == d.x);
}

TEST_CASE("the sampled channel's weight is 1 / (2 pi) at every radius without a depth step") {
    // w = r R(r) / p(r) = [(e^{-r/d} + e^{-r/3d}) / (8 pi d)] / [(e^{-r/d} + e^{-r/3d}) / (4 d)] = 1 / (2 pi):
    // importance sampling the widest channel makes its own weight constant; the other channels are not.
    const vec3 d(0.4f, 1.2f, 0.3f);
    const float dmax = emcv_sss_widest(d);
    for (float u : {0.01f, 0.3f, 0.9f, 0.999f}) {
        const float r = emcv_sss_sample_radius(u, dmax, false);
        const vec3 w = emcv_sss_weight(r, emcv_sss_depth_aware_radius(r, 0.0f), d, dmax);
        CHECK(std::abs(w.y * 2.0f * 3.14159265f - 1.0f) < 1e-5f);
        CHECK(w.x != w.y);
        // A depth step only lowers the weight (the profile decreases with r_e >= r).
        const vec3 stepped = emcv_sss_weight(r, emcv_sss_depth_aware_radius(r, 2.0f), d, dmax);
        CHECK(stepped.x < w.x);
        CHECK(stepped.y < w.y);
    }
}

TEST_CASE("sample offsets have length r pixelsPerMm and angle 2 pi u_theta and rotated R2 points stay in the unit square") {
    const vec2 o = emcv_sss_offset_pixels(2.0f, 0.25f, 3.0f);
    CHECK(std::abs(o.x) < 1e-5f);
    CHECK(std::abs(o.y - 6.0f) < 1e-5f);
    for (std::uint32_t pixel = 0; pixel < 200; ++pixel) {
        const vec2 rotation = emcv_sss_rotation(pixel, 7u, 3u, 11u);
        for (std::uint32_t i = 0; i < 64; ++i) {
            const vec2 u = emcv_sss_sample_uv(i, rotation);
            REQUIRE(u.x >= 0.0f);
            REQUIRE(u.x < 1.0f);
            REQUIRE(u.y >= 0.0f);
            REQUIRE(u.y < 1.0f);
        }
    }
}

TEST_CASE("the Burley marginal's tail matches Monte Carlo") {
    // X = r cos(theta), r from the exact inverse CDF, theta uniform: P(X > t) estimated from n samples has
    // standard deviation sqrt(p (1 - p) / n); the quadrature must lie within 4 of them (+ 1e-4 quadrature error).
    const double d = 0.8;
    const int n = 400000;
    for (double t : {0.0, 0.3, 1.0, 4.0}) {
        int above = 0;
        for (int i = 0; i < n; ++i) {
            const float u = emcv_uint_to_unit_float(emcv_pcg(std::uint32_t(2 * i) ^ 0x9e3779b9u));
            const float v = emcv_uint_to_unit_float(emcv_pcg(std::uint32_t(2 * i + 1) ^ 0x85ebca6bu));
            const double r = emcv_burley_sample_exact(u, float(d));
            above += r * std::cos(2.0 * 3.14159265358979 * v) > t ? 1 : 0;
        }
        const double p_mc = double(above) / n;
        const double p = emcv::demo::burley_marginal_tail(t, d);
        INFO("t " << t << ": quadrature " << p << ", Monte Carlo " << p_mc);
        CHECK(std::abs(p - p_mc) < 4.0 * std::sqrt(p * (1.0 - p) / n) + 1e-4);
    }
    CHECK(std::abs(emcv::demo::burley_marginal_tail(0.0, d) - 0.5) < 1e-6);
}

namespace {

/// The sums the burley pass keeps over its samples (w, L per channel), and emcv_sss_noise's inputs from them.
struct noise_sums {
    vec3 w{0.0f}, wl{0.0f}, w2{0.0f}, w2l{0.0f}, w2l2{0.0f};
    void add(vec3 weight, vec3 value) {
        w += weight;
        wl += weight * value;
        w2 += weight * weight;
        w2l += weight * weight * value;
        w2l2 += weight * weight * value * value;
    }
    vec3 estimate() const { return wl / w; }
};

}  // namespace

TEST_CASE("this frame's noise: the ratio estimate's per-sample variance from the pass's sums") {
    // The delta method's variance of R = sum(w L) / sum(w) written directly from the residuals, two passes over
    // the samples: n^2 / (n - 1) sum w_i^2 (L_i - R)^2 / (sum w)^2. The pass expands the square into three sums
    // (one pass, no stored samples); the two must agree to float rounding.
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> weight(0.0f, 3.0f), value(0.0f, 2.0f);
    for (unsigned n : {2u, 5u, 16u}) {
        std::vector<vec3> w(n), l(n);
        noise_sums sums;
        for (unsigned i = 0; i < n; ++i) {
            w[i] = vec3(weight(rng), weight(rng), weight(rng));
            l[i] = vec3(value(rng), value(rng), value(rng));
            sums.add(w[i], l[i]);
        }
        const vec3 r = sums.estimate();
        const vec3 v = emcv_sss_sample_variance(sums.w, sums.w2, sums.w2l, sums.w2l2, r, n);
        float largest = 0.0f;
        for (int c = 0; c < 3; ++c) {
            double squares = 0.0;
            for (unsigned i = 0; i < n; ++i) squares += double(w[i][c] * w[i][c]) * std::pow(double(l[i][c] - r[c]), 2.0);
            const double direct = double(n) * double(n) / double(n - 1) * squares / std::pow(double(sums.w[c]), 2.0);
            INFO("n " << n << " channel " << c << ": pass " << v[c] << ", direct " << direct);
            CHECK(std::abs(double(v[c]) - direct) <= 1e-4 * direct + 1e-6);
            largest = std::max(largest, v[c]);
        }
        // the largest channel, where every channel has two effective samples or more (Kish: (sum w)^2 / sum w^2)
        bool effective = true;
        for (int c = 0; c < 3; ++c) effective = effective && sums.w[c] * sums.w[c] >= 2.0f * sums.w2[c];
        CHECK(emcv_sss_noise(sums.w, sums.w2, sums.w2l, sums.w2l2, r, n) == (effective ? largest : emcv_sss_noise_unknown()));
    }
}

TEST_CASE("this frame's noise: with equal weights it is the unbiased sample variance, whose mean is the variance") {
    // With w = 1 the estimate is the sample mean and the per-sample variance is s^2 = sum (L - mean)^2 / (n - 1),
    // unbiased: E[s^2] = sigma^2. L uniform on [0, 1): sigma^2 = 1 / 12, mu4 = 1 / 80, and
    // Var(s^2) = (mu4 - sigma^4 (n - 3) / (n - 1)) / n, so the mean of M independent s^2 has standard deviation
    // sqrt(Var(s^2) / M); it must lie within 5 of them of 1 / 12. Without the n / (n - 1) it would sit at
    // (n - 1) / n of it (0.073 for n = 8, 44 standard deviations off).
    const unsigned n = 8;
    const int trials = 20000;
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> value(0.0f, 1.0f);
    double mean = 0.0;
    for (int t = 0; t < trials; ++t) {
        noise_sums sums;
        for (unsigned i = 0; i < n; ++i) sums.add(vec3(1.0f), vec3(value(rng)));
        mean += double(emcv_sss_noise(sums.w, sums.w2, sums.w2l, sums.w2l2, sums.estimate(), n)) / trials;
    }
    const double sigma2 = 1.0 / 12.0, mu4 = 1.0 / 80.0;
    const double sd = std::sqrt((mu4 - sigma2 * sigma2 * (n - 3.0) / (n - 1.0)) / n / trials);
    INFO("mean of s^2 " << mean << ", sigma^2 " << sigma2 << ", standard deviation of the mean " << sd);
    CHECK(std::abs(mean - sigma2) <= 5.0 * sd);
}

TEST_CASE("this frame's noise: exact without samples, unknown from one sample, a channel that accepted none or one dominant weight") {
    noise_sums none;
    CHECK(emcv_sss_noise(none.w, none.w2, none.w2l, none.w2l2, vec3(0.3f), 0u) == emcv_sss_noise_exact());
    noise_sums one;
    one.add(vec3(1.0f), vec3(0.5f));
    CHECK(emcv_sss_noise(one.w, one.w2, one.w2l, one.w2l2, one.estimate(), 1u) == emcv_sss_noise_unknown());
    noise_sums blue_rejected;  // every sample's blue weight 0: the blue channel keeps the pixel's own irradiance
    blue_rejected.add(vec3(1.0f, 1.0f, 0.0f), vec3(0.2f));
    blue_rejected.add(vec3(1.0f, 2.0f, 0.0f), vec3(0.6f));
    CHECK(emcv_sss_noise(blue_rejected.w, blue_rejected.w2, blue_rejected.w2l, blue_rejected.w2l2, vec3(0.4f), 2u) ==
          emcv_sss_noise_unknown());
    noise_sums dominated;  // three samples, one weighing 10 times the others: (sum w)^2 / sum w^2 = 144 / 102 < 2
    dominated.add(vec3(1.0f), vec3(0.1f));
    dominated.add(vec3(1.0f), vec3(0.1f));
    dominated.add(vec3(10.0f), vec3(5.0f));
    CHECK(emcv_sss_noise(dominated.w, dominated.w2, dominated.w2l, dominated.w2l2, dominated.estimate(), 3u) ==
          emcv_sss_noise_unknown());
    noise_sums balanced;  // the same values under weights 1, 1, 2: (sum w)^2 / sum w^2 = 16 / 6 >= 2, known
    balanced.add(vec3(1.0f), vec3(0.1f));
    balanced.add(vec3(1.0f), vec3(0.1f));
    balanced.add(vec3(2.0f), vec3(5.0f));
    CHECK(emcv_sss_noise(balanced.w, balanced.w2, balanced.w2l, balanced.w2l2, balanced.estimate(), 3u) > 0.0f);
    CHECK(emcv_sss_noise_exact() < 0.0f);  // both codes are below every variance, which the resolve pools
    CHECK(emcv_sss_noise_unknown() < 0.0f);
    CHECK(emcv_sss_noise_exact() != emcv_sss_noise_unknown());
}

TEST_CASE("separable kernels put the centre first with symmetric offsets and unit channel sums and spread wider channels more") {
    for (int taps : {11, 17, 25}) {
        const emcv::demo::separable_kernel k = emcv::demo::make_separable_kernel(glm::vec3(0.9f, 0.3f, 0.2f), taps);
        REQUIRE(k.taps.size() == std::size_t(taps));
        CHECK(k.taps[0].w == 0.0f);
        glm::vec3 sum(0.0f);
        float offset_sum = 0.0f;
        float max_offset = 0.0f;
        for (const glm::vec4& t : k.taps) {
            sum += glm::vec3(t);
            offset_sum += t.w;
            max_offset = std::max(max_offset, std::abs(t.w));
        }
        CHECK(std::abs(sum.x - 1.0f) < 1e-5f);
        CHECK(std::abs(sum.y - 1.0f) < 1e-5f);
        CHECK(std::abs(sum.z - 1.0f) < 1e-5f);
        CHECK(std::abs(offset_sum) < 1e-4f * max_offset);
        CHECK(max_offset == k.half_width_mm);
        // The widest channel (red) keeps the least weight at the centre.
        CHECK(k.taps[0].x < k.taps[0].y);
        CHECK(k.taps[0].y < k.taps[0].z);
    }
}
