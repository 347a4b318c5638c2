// SPDX-License-Identifier: MIT
// The temporal resolve's clip (include/emcv/port/resolve.h, emcv_resolve_clip) on the CPU, towards a target in
// the box (the renderer's: the filtered current value; here the current value itself): a history inside the box
// is kept, one outside is moved along the line to the target until it reaches the box, so the clipped colour is
// a mix of the two (never the neighbourhood's mean, which would blur), and a flat channel's box is half an
// 8-bit step wide. Also the target filter's weights.
#include <catch2/catch_test_macros.hpp>

#include <algorithm>
#include <cmath>
#include <random>

#include <emcv/port/resolve.h>

namespace port = emcv::port;

namespace {

constexpr float half_step = 0.5f / 255.0f;

bool inside(const glm::vec3& v, const glm::vec3& lo, const glm::vec3& hi, float slack) {
    for (int c = 0; c < 3; ++c)
        if (v[c] < lo[c] - slack || v[c] > hi[c] + slack) return false;
    return true;
}

}  // namespace

TEST_CASE("resolve clip: a history inside the box is kept as it is") {
    const glm::vec3 lo(0.1f, -0.2f, -0.1f), hi(0.6f, 0.2f, 0.1f), current(0.3f, 0.0f, 0.05f);
    const glm::vec3 history(0.55f, -0.15f, 0.0f);
    CHECK(port::emcv_resolve_clip(history, current, lo, hi) == history);
}

TEST_CASE("resolve clip: a history outside the box moves towards the current value, not the box's centre") {
    // Box [0, 1]^3, current near a corner, history beyond one face. Towards the current value: t = 0.1 / 1.1
    // along history - current. Towards the centre (0.5, 0.5, 0.5) the result would be (1, 0.5, 0.5): a colour
    // pulled to the neighbourhood's mean in the second channel, which neither the history nor the pixel holds.
    const glm::vec3 lo(0.0f), hi(1.0f), current(0.9f, 0.9f, 0.5f), history(2.0f, 0.5f, 0.5f);
    const glm::vec3 clipped = port::emcv_resolve_clip(history, current, lo, hi);
    const float t = 0.1f / 1.1f;
    CHECK(std::fabs(clipped.x - 1.0f) < 1e-6f);
    CHECK(std::fabs(clipped.y - (0.9f - 0.4f * t)) < 1e-6f);
    CHECK(clipped.z == 0.5f);
}

TEST_CASE("resolve clip: over random boxes the result is on the segment from the current value to the history, "
          "in the box, and as far along it as the box allows") {
    std::mt19937 rng(20261202u);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    int moved = 0;
    for (int i = 0; i < 2000; ++i) {
        const glm::vec3 a(unit(rng), unit(rng), unit(rng)), b(unit(rng), unit(rng), unit(rng));
        const glm::vec3 lo = glm::min(a, b), hi = glm::max(a, b);
        // The current value in the box (the box grown to hold it, as emcv_resolve_clip_box makes it).
        const glm::vec3 w(0.5f * (unit(rng) + 1.0f), 0.5f * (unit(rng) + 1.0f), 0.5f * (unit(rng) + 1.0f));
        const glm::vec3 current = lo + w * (hi - lo);
        const glm::vec3 history(2.0f * unit(rng), 2.0f * unit(rng), 2.0f * unit(rng));
        const glm::vec3 clipped = port::emcv_resolve_clip(history, current, lo, hi);
        INFO("case " << i);
        // The box the clip works in: [lo, hi] widened to half an 8-bit step around its centre where narrower.
        const glm::vec3 centre = 0.5f * (lo + hi);
        const glm::vec3 extent = glm::max(0.5f * (hi - lo), glm::vec3(half_step));
        REQUIRE(inside(clipped, centre - extent, centre + extent, 1e-5f));
        const glm::vec3 along = history - current, taken = clipped - current;
        const float length2 = glm::dot(along, along);
        if (length2 == 0.0f) continue;
        const float t = glm::dot(taken, along) / length2;
        CHECK(t >= -1e-6f);
        CHECK(t <= 1.0f + 1e-6f);
        CHECK(glm::length(taken - t * along) <= 1e-5f * (1.0f + std::sqrt(length2)));  // on the segment
        if (t < 1.0f - 1e-5f) {
            ++moved;
            // Stopped at the box: one channel sits on its face.
            bool on_face = false;
            for (int c = 0; c < 3; ++c)
                on_face = on_face || std::fabs(clipped[c] - (centre[c] - extent[c])) < 1e-5f ||
                          std::fabs(clipped[c] - (centre[c] + extent[c])) < 1e-5f;
            CHECK(on_face);
        } else {
            CHECK(inside(history, centre - extent, centre + extent, 1e-5f));
        }
    }
    CHECK(moved > 1000);  // most random histories start outside: the clipping branch is what was tested
}

TEST_CASE("resolve clip: a flat channel keeps half an 8-bit step either side of its value") {
    const glm::vec3 current(0.5f, 0.0f, 0.0f);
    const glm::vec3 near(0.5f + 0.4f / 255.0f, 0.0f, 0.0f), far(0.5f + 2.0f / 255.0f, 0.0f, 0.0f);
    CHECK(port::emcv_resolve_clip(near, current, current, current) == near);
    const glm::vec3 clipped = port::emcv_resolve_clip(far, current, current, current);
    CHECK(std::fabs(clipped.x - (0.5f + half_step)) < 1e-6f);
    CHECK(clipped.y == 0.0f);
    CHECK(clipped.z == 0.0f);
}

TEST_CASE("resolve clip target filter: the 3x3 weights sum to 1, are symmetric and peak at the pixel") {
    float sum = 0.0f;
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            const float w = port::emcv_resolve_filter_weight(dx, dy);
            sum += w;
            CHECK(w > 0.0f);
            CHECK(w == port::emcv_resolve_filter_weight(-dx, dy));
            CHECK(w == port::emcv_resolve_filter_weight(dy, dx));
            if (dx != 0 || dy != 0) CHECK(w < port::emcv_resolve_filter_weight(0, 0));
        }
    CHECK(sum == 1.0f);
    // Separable: w(dx, dy) w(0, 0) = w(dx, 0) w(0, dy).
    CHECK(port::emcv_resolve_filter_weight(1, 1) * port::emcv_resolve_filter_weight(0, 0) ==
          port::emcv_resolve_filter_weight(1, 0) * port::emcv_resolve_filter_weight(0, 1));
}

TEST_CASE("resolve clip target: the filtered value with the fraction of the raw deviation that the history's spread explains") {
    const glm::vec3 current(0.6f, 0.1f, -0.05f), filtered(0.4f, 0.02f, 0.01f);
    const glm::vec3 spread(0.004f, 0.001f, 0.001f);  // the current 3x3 neighbourhood's variance, total 0.006
    // The history shows no spread (flat under noise, or no neighbour on its surface): the filtered value.
    CHECK(port::emcv_resolve_target(current, filtered, spread, glm::vec3(0.0f)) == filtered);
    // As much spread as this frame, or more (a light that went down): the raw value.
    // (filtered + 1 (current - filtered): equal to the raw value up to the rounding of that sum)
    const auto close = [](const glm::vec3& a, const glm::vec3& b) { return glm::all(glm::lessThan(glm::abs(a - b), glm::vec3(1e-6f))); };
    CHECK(close(port::emcv_resolve_target(current, filtered, spread, spread), current));
    CHECK(close(port::emcv_resolve_target(current, filtered, spread, 3.0f * spread), current));
    // A quarter of the total spread, whichever channel holds it: a quarter of the way, the same in every channel
    // (one fraction for the colour, so the target stays on the line between the two values).
    for (const glm::vec3& history : {glm::vec3(0.0015f, 0.0f, 0.0f), glm::vec3(0.0f, 0.0f, 0.0015f), 0.25f * spread}) {
        const glm::vec3 target = port::emcv_resolve_target(current, filtered, spread, history);
        for (int c = 0; c < 3; ++c) CHECK(std::fabs(target[c] - (filtered[c] + 0.25f * (current[c] - filtered[c]))) < 1e-6f);
    }
    // A flat neighbourhood (no spread at all): the raw value, which is then the filtered one too.
    CHECK(port::emcv_resolve_target(current, current, glm::vec3(0.0f), glm::vec3(0.0f)) == current);
}

TEST_CASE("resolve clip target: the fraction D / S is the gain that minimises the expected squared error") {
    // A local Wiener filter: the raw value is signal s plus noise e, the filtered value the local mean m, with
    // Var(s - m) = D and Var(e) = S - D, s - m and e independent. Then m + g (x - m) errs by (g - 1)(s - m) + g e,
    // of expected square (1 - g)^2 D + g^2 (S - D), least at g = D / S. Checked on a fixed-seed draw: the error at
    // the function's target is below the error at the fraction 0.1 either side of it.
    std::mt19937 rng(7);
    std::normal_distribution<float> unit(0.0f, 1.0f);
    const float detail = 0.003f, noise = 0.005f;  // D and S - D, per channel
    double at[3] = {0.0, 0.0, 0.0};
    const float offsets[3] = {-0.1f, 0.0f, 0.1f};
    const glm::vec3 spread(detail + noise), history(detail);
    for (int i = 0; i < 20000; ++i) {
        const glm::vec3 mean(0.5f, 0.0f, 0.0f);
        const glm::vec3 signal = mean + std::sqrt(detail) * glm::vec3(unit(rng), unit(rng), unit(rng));
        const glm::vec3 raw = signal + std::sqrt(noise) * glm::vec3(unit(rng), unit(rng), unit(rng));
        const glm::vec3 target = port::emcv_resolve_target(raw, mean, spread, history);
        for (int k = 0; k < 3; ++k) {
            const glm::vec3 shifted = target + offsets[k] * (raw - mean);
            const glm::vec3 e = shifted - signal;
            at[k] += double(glm::dot(e, e));
        }
    }
    CHECK(at[1] < at[0]);
    CHECK(at[1] < at[2]);
}

TEST_CASE("resolve noise box: the YCoCg extent holds the deviation under every sign of its channels, and is tight") {
    // One estimate's channels move together or apart; the box must hold d with any signs (s_r d_r, s_g d_g,
    // s_b d_b) in YCoCg, and no narrower box does: some sign pattern reaches each half-width.
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> deviation(-0.2f, 0.2f);
    for (int trial = 0; trial < 200; ++trial) {
        const glm::vec3 d(deviation(rng), deviation(rng), deviation(rng));
        const glm::vec3 extent = port::emcv_resolve_ycocg_extent(d);
        glm::vec3 reached(0.0f);
        for (int signs = 0; signs < 8; ++signs) {
            const glm::vec3 s((signs & 1) ? -1.0f : 1.0f, (signs & 2) ? -1.0f : 1.0f, (signs & 4) ? -1.0f : 1.0f);
            const glm::vec3 y = glm::abs(port::emcv_rgb_to_ycocg(s * d));
            for (int c = 0; c < 3; ++c) {
                CHECK(y[c] <= extent[c] + 1e-7f);
                reached[c] = std::max(reached[c], y[c]);
            }
        }
        for (int c = 0; c < 3; ++c) CHECK(std::abs(reached[c] - extent[c]) <= 1e-6f);
    }
}

TEST_CASE("resolve noise box: narrowing keeps the current value and stays inside both boxes") {
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> value(-0.5f, 0.5f), width(0.0f, 0.2f);
    for (int trial = 0; trial < 200; ++trial) {
        const glm::vec3 current(value(rng), value(rng), value(rng));
        glm::vec3 lo = current - glm::vec3(width(rng), width(rng), width(rng));
        glm::vec3 hi = current + glm::vec3(width(rng), width(rng), width(rng));
        const glm::vec3 lo0 = lo, hi0 = hi;
        const glm::vec3 extent(width(rng), width(rng), width(rng));
        port::emcv_resolve_narrow_to_noise(current, extent, lo, hi);
        for (int c = 0; c < 3; ++c) {
            CHECK(lo[c] <= current[c]);
            CHECK(hi[c] >= current[c]);
            CHECK(lo[c] == std::max(lo0[c], current[c] - extent[c]));
            CHECK(hi[c] == std::min(hi0[c], current[c] + extent[c]));
        }
    }
    // Without noise the box closes on the current value; the clip still keeps half an 8-bit step around it.
    glm::vec3 lo(0.0f), hi(1.0f);
    const glm::vec3 current(0.4f, 0.1f, -0.1f);
    port::emcv_resolve_narrow_to_noise(current, glm::vec3(0.0f), lo, hi);
    const glm::vec3 kept = port::emcv_resolve_clip(glm::vec3(0.9f, 0.3f, 0.2f), current, lo, hi);
    for (int c = 0; c < 3; ++c) CHECK(std::abs(kept[c] - current[c]) <= half_step + 1e-7f);
}

TEST_CASE("resolve noise box: the pixel's variance is the larger of its own and its neighbourhood's mean, over its samples") {
    CHECK(std::abs(port::emcv_resolve_pooled_noise(0.1f, 0.9f, 3.0f, 4u) - 0.075f) <= 1e-8f);  // the neighbourhood's mean
    CHECK(std::abs(port::emcv_resolve_pooled_noise(0.6f, 0.9f, 3.0f, 4u) - 0.15f) <= 1e-8f);   // the pixel's own
    CHECK(port::emcv_resolve_pooled_noise(0.1f, 0.9f, 3.0f, 0u) == 0.0f);         // no samples: the value is exact
    CHECK(port::emcv_resolve_pooled_noise(-1.0f, 0.9f, 3.0f, 1u) < 0.0f);         // its own unknown: no noise box
}

TEST_CASE("resolve noise box: a history beyond it is taken up at the weight that minimises the blend's error") {
    // What the clip keeps of a history beyond the noise box lies up to k standard deviations sigma from the current
    // value (k = EMCV_RESOLVE_NOISE_SIGMA); the current value is unbiased with variance sigma^2. Mixed at weight w
    // the error's expected square is (1 - w)^2 k^2 sigma^2 + w^2 sigma^2: the function's weight must be where a
    // search over w finds that least (to the search's step), and a history inside the box keeps the blend's.
    const float k = float(EMCV_RESOLVE_NOISE_SIGMA);
    double best_w = 0.0, best = 1e30;
    for (int i = 0; i <= 10000; ++i) {
        const double w = i / 10000.0;
        const double e = (1.0 - w) * (1.0 - w) * double(k) * double(k) + w * w;
        if (e < best) best = e, best_w = w;
    }
    const glm::vec3 current(0.375f, 0.0625f, -0.03125f), extent(0.03125f, 0.0078125f, 0.015625f);  // exact in binary
    for (int c = 0; c < 3; ++c) {  // beyond in one channel, either side
        for (float side : {-1.0f, 1.0f}) {
            glm::vec3 history = current;
            history[c] += side * 1.5f * extent[c];
            const float w = port::emcv_resolve_current_weight(history, current, extent);
            INFO("channel " << c << ", side " << side << ": weight " << w << ", least error at " << best_w);
            CHECK(std::abs(double(w) - best_w) <= 1e-4);
        }
    }
    // Inside the box (on its edge, or within it in every channel): the blend's weight, a converged history kept
    // (the values are exact in binary, so the edge is exactly the extent away).
    CHECK(port::emcv_resolve_current_weight(current + extent, current, extent) == float(EMCV_RESOLVE_BLEND));
    CHECK(port::emcv_resolve_current_weight(current - 0.5f * extent, current, extent) == float(EMCV_RESOLVE_BLEND));
    // No noise at all (extent 0): any difference is beyond it.
    CHECK(port::emcv_resolve_current_weight(current + glm::vec3(1e-3f, 0.0f, 0.0f), current, glm::vec3(0.0f)) > 0.5f);
}

TEST_CASE("resolve noise box: the extent through the display encoding holds the deviation either way") {
    // A linear value x and a deviation d per channel: every x + s d (s in {-1, 0, 1} per channel, and halfway)
    // encoded for display (ACES or Reinhard, then sRGB) lies within the extent of the encoded x in YCoCg. The
    // encoding is concave over most of its range (sRGB), where a step down is the larger, and convex in ACES's toe,
    // where a step up is: a box sized one way alone misses the other (seen failing for the upward step alone).
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> log_value(-6.0f, 2.0f), fraction(0.0f, 1.0f);
    for (int tonemap = 0; tonemap < 2; ++tonemap) {
        for (int trial = 0; trial < 500; ++trial) {
            const glm::vec3 x(std::exp(log_value(rng)), std::exp(log_value(rng)), std::exp(log_value(rng)));
            const glm::vec3 d = x * glm::vec3(fraction(rng), fraction(rng), fraction(rng));
            const glm::vec3 shown = port::emcv_display_encode(x, tonemap);
            const glm::vec3 extent = port::emcv_resolve_noise_extent(x, shown, d, tonemap);
            const glm::vec3 centre = port::emcv_rgb_to_ycocg(shown);
            for (int signs = 0; signs < 27; ++signs) {
                const glm::vec3 s(float(signs % 3 - 1), float(signs / 3 % 3 - 1), float(signs / 9 - 1));
                for (float scale : {0.5f, 1.0f}) {
                    const glm::vec3 y = port::emcv_rgb_to_ycocg(port::emcv_display_encode(x + scale * s * d, tonemap));
                    for (int c = 0; c < 3; ++c) CHECK(std::abs(y[c] - centre[c]) <= extent[c] + 1e-6f);
                }
            }
        }
    }
}

TEST_CASE("resolve shift: a neighbourhood moved off this frame beyond the noise of its mean is taken up at the best weight") {
    // The mean of n current values less the history's mean, in units of the mean's noise sigma / sqrt(n): z. Over
    // k (EMCV_RESOLVE_NOISE_SIGMA) the shift b is estimated by b^2 = (z^2 - 1) sigma^2 / n, and the weight must be
    // where a search over w finds (1 - w)^2 b^2 + w^2 sigma^2 least; at or under k it is 0 (this frame's noise).
    const float k = float(EMCV_RESOLVE_NOISE_SIGMA), sigma = 0.01f;
    const glm::vec3 extent(k * sigma);  // the noise box: k sigma per channel
    for (float n : {1.0f, 4.0f, 9.0f}) {
        for (float z : {1.5f * k, 2.0f * k, 5.0f * k}) {
            const float mean_noise = sigma / std::sqrt(n);
            for (int c = 0; c < 3; ++c) {
                glm::vec3 difference(0.3f * mean_noise);  // the other channels well inside the noise
                difference[c] = -z * mean_noise;
                const float w = port::emcv_resolve_shift_weight(difference, extent, n);
                const double b2 = (double(z) * z - 1.0) / n;  // in units of sigma^2
                double best_w = 0.0, best = 1e30;
                for (int i = 0; i <= 10000; ++i) {
                    const double v = i / 10000.0, e = (1.0 - v) * (1.0 - v) * b2 + v * v;
                    if (e < best) best = e, best_w = v;
                }
                INFO("n " << n << ", z " << z << ", channel " << c << ": weight " << w << ", least error at " << best_w);
                CHECK(std::abs(double(w) - best_w) <= 2e-4);
            }
        }
        // At k mean deviations or under: no shift this frame's noise could not make.
        CHECK(port::emcv_resolve_shift_weight(glm::vec3(0.99f * k * sigma / std::sqrt(n)), extent, n) == 0.0f);
        CHECK(port::emcv_resolve_shift_weight(glm::vec3(0.0f), extent, n) == 0.0f);
    }
    // The same difference is a larger z for a mean of more values: more weight at n = 9 than at n = 1.
    const glm::vec3 d(2.0f * k * sigma);
    CHECK(port::emcv_resolve_shift_weight(d, extent, 9.0f) > port::emcv_resolve_shift_weight(d, extent, 1.0f));
}

TEST_CASE("resolve shift: z^2 - 1 estimates the shift, z^2 of a mean of n noisy values averaging 1 + n b^2 / sigma^2") {
    // The model the weight inverts, on draws: n values of noise sigma shifted by b; their mean's difference, in the
    // units emcv_resolve_shift_weight uses, squared, averages 1 + n b^2 / sigma^2. Over M = 20000 draws z^2 (a
    // noncentral chi-square with 1 degree of freedom, variance 2 + 4 n b^2 / sigma^2) has a mean within 5 of its
    // standard errors. The weight is read back to z^2: w = (z^2 - 1) / (z^2 - 1 + n) gives z^2 = 1 + n w / (1 - w),
    // so the draws use a shift large enough that z is over k on every draw (b = 3 sigma, n = 9: z about 9, and
    // under k = 3 only 6 of its standard deviations low, probability about 1e-9 a draw).
    std::mt19937 rng(13);
    std::normal_distribution<float> unit(0.0f, 1.0f);
    const float k = float(EMCV_RESOLVE_NOISE_SIGMA), sigma = 0.02f, b = 3.0f * sigma, n = 9.0f;
    const glm::vec3 extent(k * sigma);
    const int draws = 20000;
    double sum = 0.0;
    int over = 0;
    for (int i = 0; i < draws; ++i) {
        float mean = 0.0f;
        for (int j = 0; j < 9; ++j) mean += b + sigma * unit(rng);
        mean /= n;
        const float w = port::emcv_resolve_shift_weight(glm::vec3(mean, 0.0f, 0.0f), extent, n);
        if (w > 0.0f) {
            sum += 1.0 + double(n) * w / (1.0 - w);
            ++over;
        }
    }
    REQUIRE(over == draws);
    const double expected = 1.0 + n * double(b) * b / (double(sigma) * sigma);
    const double standard_error = std::sqrt((2.0 + 4.0 * n * double(b) * b / (double(sigma) * sigma)) / over);
    INFO("mean z^2 " << sum / over << ", expected " << expected << ", standard error " << standard_error);
    CHECK(std::abs(sum / over - expected) <= 5.0 * standard_error);
}
