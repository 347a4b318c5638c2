// SPDX-License-Identifier: MIT
// The temporal resolve's guide (include/emcv/port/resolve.h, emcv_resolve_guide_slope, emcv_resolve_guide_weight and
// emcv_resolve_guided_history) on the CPU: the slope is the local linear model's least-squares slope, not biased
// by noise in the values and clamped to [0, 1]; and a history of a signal that follows the guide is moved back
// onto this frame's value by the guide's change, whatever its resampling did; the weight that change asks of the blend
// is the least-error weight for the moved history's uncertainty.
#include <catch2/catch_test_macros.hpp>

#include <array>
#include <cmath>
#include <random>

#include <emcv/port/resolve.h>

namespace port = emcv::port;

namespace {

/// The centred sums of a 3x3 neighbourhood (guide g, values v) that emcv_resolve_guide_slope takes.
struct centred_sums {
    glm::vec3 guide_variance{0.0f}, covariance{0.0f};
};

centred_sums sums_of(const std::array<glm::vec3, 9>& g, const std::array<glm::vec3, 9>& v) {
    glm::vec3 gm(0.0f), vm(0.0f);
    for (std::size_t i = 0; i < 9; ++i) {
        gm += g[i] / 9.0f;
        vm += v[i] / 9.0f;
    }
    centred_sums s;
    for (std::size_t i = 0; i < 9; ++i) {
        s.guide_variance += (g[i] - gm) * (g[i] - gm);
        s.covariance += (g[i] - gm) * (v[i] - vm);
    }
    return s;
}

/// A 3x3 guide with display-scale detail: a ramp and a step, each channel its own.
std::array<glm::vec3, 9> detailed_guide() {
    std::array<glm::vec3, 9> g{};
    for (std::size_t i = 0; i < 9; ++i) {
        const float x = float(i % 3), y = float(i / 3);
        g[i] = glm::vec3(0.3f + 0.05f * x + 0.02f * y, (x > 0.5f ? 0.1f : -0.05f), 0.01f * x * y - 0.02f);
    }
    return g;
}

/// The slope emcv_resolve_guide_slope fits in channel c on one neighbourhood of values 0.2 + b g with a normal
/// noise added in that channel (its nine draws in `e`).
double noisy_slope(const std::array<glm::vec3, 9>& g, float b, int c, std::normal_distribution<double>& noise,
                   std::mt19937& rng, std::array<double, 9>& e) {
    std::array<glm::vec3, 9> v{};
    for (std::size_t i = 0; i < 9; ++i) {
        e[i] = noise(rng);
        v[i] = 0.2f + b * g[i];
        v[i][c] += float(e[i]);
    }
    const centred_sums s = sums_of(g, v);
    return port::emcv_resolve_guide_slope(s.guide_variance, s.covariance, 9.0f)[c];
}

}  // namespace

TEST_CASE("resolve guide slope: values that are an affine function of the guide give its slope, clamped to [0, 1]") {
    const std::array<glm::vec3, 9> g = detailed_guide();
    const glm::vec3 slope(0.35f, 0.8f, 1.0f), offset(0.1f, -0.02f, 0.03f);
    std::array<glm::vec3, 9> v{}, steep{}, inverted{};
    for (std::size_t i = 0; i < 9; ++i) {
        v[i] = offset + slope * g[i];
        steep[i] = offset + 1.7f * g[i];
        inverted[i] = offset - 0.4f * g[i];
    }
    const centred_sums s = sums_of(g, v);
    const glm::vec3 b = port::emcv_resolve_guide_slope(s.guide_variance, s.covariance, 9.0f);
    for (int c = 0; c < 3; ++c) CHECK(std::fabs(b[c] - slope[c]) < 1e-4f);
    const centred_sums s_steep = sums_of(g, steep), s_inverted = sums_of(g, inverted);
    CHECK(port::emcv_resolve_guide_slope(s_steep.guide_variance, s_steep.covariance, 9.0f) == glm::vec3(1.0f));
    CHECK(port::emcv_resolve_guide_slope(s_inverted.guide_variance, s_inverted.covariance, 9.0f) == glm::vec3(0.0f));
}

TEST_CASE("resolve guide slope: a guide flatter than half an 8-bit step has no detail to regress on: slope 0") {
    // Each channel's 3x3 standard deviation a quarter of a step (under the half-step floor), the values following
    // it exactly: a slope the data would give as 1, which the floor refuses. At twice that spread (above the
    // floor) the slope is the data's.
    std::array<glm::vec3, 9> g{}, v{}, g2{}, v2{};
    const float quarter_step = 0.25f / 255.0f;
    for (std::size_t i = 0; i < 9; ++i) {
        const float sign = (i % 2 == 0) ? 1.0f : -1.0f;
        g[i] = glm::vec3(0.5f + sign * quarter_step);
        v[i] = g[i];
        g2[i] = glm::vec3(0.5f + 3.0f * sign * quarter_step);
        v2[i] = g2[i];
    }
    const centred_sums flat = sums_of(g, v), detailed = sums_of(g2, v2);
    CHECK(port::emcv_resolve_guide_slope(flat.guide_variance, flat.covariance, 9.0f) == glm::vec3(0.0f));
    const glm::vec3 b = port::emcv_resolve_guide_slope(detailed.guide_variance, detailed.covariance, 9.0f);
    for (int c = 0; c < 3; ++c) CHECK(std::fabs(b[c] - 1.0f) < 1e-3f);
}

TEST_CASE("resolve guide slope: this frame's noise in the values does not bias it, and spreads it as least squares does") {
    // v = a + b g + e, e independent normal noise of standard deviation sigma: the least-squares slope is
    // b + sum (g - mean g) e / S (S = sum (g - mean g)^2), normal with mean b and variance sigma^2 / S. With
    // sigma^2 / S = 0.05^2 and b = 0.5 the clamp at 0 and 1 lies 10 standard deviations away (never reached
    // here). Over N = 4000 neighbourhoods (fixed seed) the mean slope is within 5 standard errors
    // (5 * 0.05 / sqrt(N)) of b, and the sample variance within 5 of its standard errors (sqrt(2 / (N - 1)),
    // relative) of sigma^2 / S.
    const std::array<glm::vec3, 9> g = detailed_guide();
    const centred_sums clean = sums_of(g, g);
    const float b = 0.5f;
    const int n = 4000;
    std::mt19937 rng(20261206u);
    for (int c = 0; c < 3; ++c) {
        INFO("channel " << c);
        const double spread = 0.05, sigma = spread * std::sqrt(double(clean.guide_variance[c]));
        std::normal_distribution<double> noise(0.0, sigma);
        double sum = 0.0, sum_squares = 0.0;
        std::array<double, 9> e{};
        for (int k = 0; k < n; ++k) {
            const double slope = noisy_slope(g, b, c, noise, rng, e);
            sum += slope;
            sum_squares += slope * slope;
        }
        const double mean = sum / n, variance = (sum_squares - n * mean * mean) / (n - 1);
        INFO("mean " << mean << ", variance " << variance);
        CHECK(std::fabs(mean - b) < 5.0 * spread / std::sqrt(double(n)));
        CHECK(std::fabs(variance / (spread * spread) - 1.0) < 5.0 * std::sqrt(2.0 / (n - 1)));
    }
}

TEST_CASE("resolve guided history: a signal that follows the guide is moved back onto this frame's value, whatever "
          "the resampling did") {
    // One row of last frame's texels of a guide with sharp detail (a step and a spike) and of a signal s = a + b g
    // (b per channel in [0, 1]); the camera moved, and this frame's pixel lies at fraction t between texels 0 and 1.
    // The history is the signal resampled there (Catmull-Rom, emcv_resolve_catmull_rom): off this frame's value,
    // which is a + b g(x) for the guide's true value g(x) there (here a value that no interpolation of the texels
    // gives, as at a shadow edge). The guide resampled with the same weights carries the same error times 1 / b, so
    // the guided history is this frame's value; with the guide unchanged (a still camera) the history is kept.
    const std::array<glm::vec3, 4> texels_g = {glm::vec3(0.2f, 0.0f, 0.05f), glm::vec3(0.2f, 0.0f, 0.05f),
                                               glm::vec3(0.7f, 0.1f, -0.05f), glm::vec3(0.3f, 0.02f, 0.0f)};
    const glm::vec3 a(0.05f, 0.01f, 0.0f), b(0.6f, 1.0f, 0.25f);
    for (float t : {0.1f, 0.37f, 0.5f, 0.81f}) {
        INFO("t " << t);
        const glm::vec4 w = port::emcv_resolve_catmull_rom(t);
        glm::vec3 history(0.0f), guide_history(0.0f);
        for (int i = 0; i < 4; ++i) {
            history += w[i] * (a + b * texels_g[std::size_t(i)]);
            guide_history += w[i] * texels_g[std::size_t(i)];
        }
        const glm::vec3 guide_now(0.45f, 0.06f, -0.01f);  // the guide's true value at the pixel this frame
        const glm::vec3 value_now = a + b * guide_now;
        const glm::vec3 guided = port::emcv_resolve_guided_history(history, b, guide_now, guide_history);
        for (int c = 0; c < 3; ++c) {
            CHECK(std::fabs(history[c] - value_now[c]) > 1e-3f);  // resampling alone is off
            CHECK(std::fabs(guided[c] - value_now[c]) < 1e-6f);
        }
        CHECK(port::emcv_resolve_guided_history(history, b, guide_history, guide_history) == history);
    }
}

TEST_CASE("resolve guide weight: the moved history is off by as much as the slope's noise times the guide's change, "
          "and the weight is the one that mixes it with this frame at the least error") {
    // v = a + b g + e as above (b = 0.5, e normal, standard deviation sigma, in one channel c), the slope b_hat
    // fitted on it, and the history moved by b_hat d for a guide change d: if the history was right before the
    // change it is off by (b_hat - b) d, normal with mean 0 and variance sigma^2 d^2 / S. Over N = 4000
    // neighbourhoods (fixed seed) its mean square is within 5 standard errors (sqrt(2 / N), relative) of that.
    // Mixed with this frame's centre value (truth + e_4, independent of b_hat in channels 0 and 2, where the
    // centre's guide is the neighbourhood's mean) at weight w, the expected squared error is
    // (1 - w)^2 sigma^2 x + w^2 sigma^2 with x = d^2 / S: least at w = x / (x + 1), which the weight must be, and
    // the empirical error there is below its value 0.15 either side (the difference, (x + 1) sigma^2 0.15^2, is
    // at least 2% of sigma^2 for the x here; both errors come from the same draws).
    const std::array<glm::vec3, 9> g = detailed_guide();
    const centred_sums clean = sums_of(g, g);
    const float b = 0.5f;
    const int n = 4000;
    std::mt19937 rng(20261207u);
    for (int c = 0; c < 3; ++c) {
        for (double x : {0.25, 1.0, 4.0}) {
            INFO("channel " << c << ", x " << x);
            const double S = clean.guide_variance[c];
            const double sigma = 0.05 * std::sqrt(S);
            glm::vec3 change(0.0f);
            change[c] = float(std::sqrt(x * S));
            const float weight = port::emcv_resolve_guide_weight(change, clean.guide_variance, 9.0f);
            CHECK(std::fabs(double(weight) - x / (x + 1.0)) < 1e-5);
            std::normal_distribution<double> noise(0.0, sigma);
            double history_squares = 0.0, mixed[3] = {0.0, 0.0, 0.0};
            const double weights[3] = {double(weight) - 0.15, double(weight), double(weight) + 0.15};
            for (int k = 0; k < n; ++k) {
                std::array<double, 9> e{};
                const double slope = noisy_slope(g, b, c, noise, rng, e);
                const double history_error = (slope - b) * double(change[c]);
                history_squares += history_error * history_error;
                for (int j = 0; j < 3; ++j) {
                    const double error = (1.0 - weights[j]) * history_error + weights[j] * e[4];
                    mixed[j] += error * error;
                }
            }
            const double expected = sigma * sigma * x;
            CHECK(std::fabs(history_squares / n / expected - 1.0) < 5.0 * std::sqrt(2.0 / n));
            if (c != 1) {  // channel 1's centre is off its neighbourhood's mean: e_4 enters b_hat there
                CHECK(mixed[1] < mixed[0]);
                CHECK(mixed[1] < mixed[2]);
            }
        }
    }
}

TEST_CASE("resolve guide weight: 0 for a still guide and where the guide shows no detail; the largest channel's") {
    const std::array<glm::vec3, 9> g = detailed_guide();
    const centred_sums clean = sums_of(g, g);
    // A still camera under still lights: no change, the blend's weight stays.
    CHECK(port::emcv_resolve_guide_weight(glm::vec3(0.0f), clean.guide_variance, 9.0f) == 0.0f);
    // A flat guide (each channel's spread under the half-step floor) changed by a whole step: nothing was fitted,
    // so nothing is uncertain (the history was not moved).
    const glm::vec3 flat_sums(9.0f * (0.25f / 255.0f) * (0.25f / 255.0f));
    CHECK(port::emcv_resolve_guide_weight(glm::vec3(1.0f / 255.0f), flat_sums, 9.0f) == 0.0f);
    // The channels' weights d^2 / (d^2 + S): the largest is returned, whichever channel holds it.
    const glm::vec3 sums(0.01f, 0.04f, 0.09f);
    CHECK(std::fabs(port::emcv_resolve_guide_weight(glm::vec3(0.1f, 0.1f, 0.1f), sums, 9.0f) - 0.5f) < 1e-6f);
    CHECK(std::fabs(port::emcv_resolve_guide_weight(glm::vec3(0.0f, 0.0f, 0.3f), sums, 9.0f) - 0.5f) < 1e-6f);
    CHECK(std::fabs(port::emcv_resolve_guide_weight(glm::vec3(0.0f, 0.2f, 0.0f), sums, 9.0f) - 0.5f) < 1e-6f);
}
