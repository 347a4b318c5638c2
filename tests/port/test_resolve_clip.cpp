// SPDX-License-Identifier: MIT
// The temporal resolve's clip (include/emcv/port/resolve.h, emcv_resolve_clip) on the CPU, towards a target in
// the box (the renderer's: the filtered current value; here the current value itself): a history inside the box
// is kept, one outside is moved along the line to the target until it reaches the box, so the clipped colour is
// a mix of the two (never the neighbourhood's mean, which would blur), and a flat channel's box is half an
// 8-bit step wide. Also the target filter's weights.
#include <catch2/catch_test_macros.hpp>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

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

TEST_CASE("resolve noise box: the box grows to the current value -+ EMCV_RESOLVE_NOISE_SIGMAS temporal deviations "
          "(luma's for Y, chroma's for Co and Cg), never shrinks, and a zero variance leaves it as it was") {
    const glm::vec3 current(0.5f, 0.1f, -0.05f);
    const glm::vec3 box_lo(0.45f, 0.0f, -0.2f), box_hi(0.52f, 0.3f, 0.3f);
    glm::vec3 lo = box_lo, hi = box_hi;
    port::emcv_resolve_noise_box(current, glm::vec4(0.0f, 0.0f, 0.7f, -0.3f), lo, hi);  // offsets: not widths
    CHECK(lo == box_lo);
    CHECK(hi == box_hi);
    // Luma deviation 0.02, chroma 0.1, at 3 deviations: Y grows on both sides (0.44 < 0.45, 0.56 > 0.52), Co too
    // (-0.2 < 0, 0.4 > 0.3), Cg at the bottom only (-0.35 < -0.2; 0.25 < 0.3 keeps the top).
    REQUIRE(EMCV_RESOLVE_NOISE_SIGMAS == 3.0f);
    port::emcv_resolve_noise_box(current, glm::vec4(0.02f * 0.02f, 0.1f * 0.1f, 0.0f, 0.0f), lo, hi);
    CHECK(std::fabs(lo.x - 0.44f) < 1e-6f);
    CHECK(std::fabs(hi.x - 0.56f) < 1e-6f);
    CHECK(std::fabs(lo.y - (-0.2f)) < 1e-6f);
    CHECK(std::fabs(hi.y - 0.4f) < 1e-6f);
    CHECK(std::fabs(lo.z - (-0.35f)) < 1e-6f);
    CHECK(hi.z == box_hi.z);
}

TEST_CASE("resolve change test: the filtered move against its learnt offset, and the mean of the pixel's moves, "
          "each beyond 3 of its deviations") {
    // Luma variance 1e-4 (deviation 0.01), weight 0.1. The filtered move's deviation: the filtered value's
    // variance is sum w^2 = (6/16)^2 = 9/64 of a pixel's and the history's 0.1 / 1.9 of it, so
    // 0.01 sqrt(9/64 + 1/19) = 0.004396, and the bound is 3 times that around the learnt offset 0.02. The moves'
    // mean: an exponential average at 0.1 keeps 1/19 of the variance, bound 3 x 0.01 / sqrt(19) = 0.006882.
    REQUIRE(EMCV_RESOLVE_NOISE_SIGMAS == 3.0f);
    const glm::vec4 state(1e-4f, 4e-4f, 0.02f, 0.0f);
    const float filtered_bound = 3.0f * 0.01f * std::sqrt(9.0f / 64.0f + 1.0f / 19.0f);
    for (const float side : {1.0f, -1.0f}) {
        CHECK_FALSE(port::emcv_resolve_history_changed(glm::vec2(0.02f + side * 0.98f * filtered_bound, 0.0f), state, 0.1f));
        CHECK(port::emcv_resolve_history_changed(glm::vec2(0.02f + side * 1.02f * filtered_bound, 0.0f), state, 0.1f));
    }
    // The mean with this frame's move taken in: 0.9 x 0.005 + 0.1 m against 0.006882.
    const float mean_bound = 3.0f * 0.01f / std::sqrt(19.0f);
    const glm::vec4 drifting(1e-4f, 4e-4f, 0.02f, 0.005f);
    const float at_bound = (mean_bound - 0.9f * 0.005f) / 0.1f;
    CHECK_FALSE(port::emcv_resolve_history_changed(glm::vec2(0.02f, 0.98f * at_bound), drifting, 0.1f));
    CHECK(port::emcv_resolve_history_changed(glm::vec2(0.02f, 1.02f * at_bound), drifting, 0.1f));
    // Nothing measured yet: never a change (the neighbourhood's box decides alone).
    CHECK_FALSE(port::emcv_resolve_history_changed(glm::vec2(1.0f, 1.0f), glm::vec4(0.0f, 0.0f, 0.0f, 0.5f), 0.1f));
}

TEST_CASE("resolve noise update: exponential averages of the squared moves, the filtered offset and the moves; "
          "the first frame taken as it is; kept where the clip moved the history; restarted where it changed, "
          "the moves' mean carried on") {
    const glm::vec4 state(1e-4f, 4e-4f, 0.01f, 0.002f);
    const glm::vec3 current(0.5f, 0.2f, 0.1f), kept(0.49f, 0.23f, 0.14f);
    const float w = 0.1f;
    const glm::vec2 moves(0.03f, 0.012f);
    const glm::vec3 d = current - kept;
    const float chroma = 0.5f * (d.y * d.y + d.z * d.z);
    const glm::vec4 next = port::emcv_resolve_noise_update(state, current, kept, 1.0f, moves, false, w);
    CHECK(std::fabs(next.x - (0.9f * 1e-4f + 0.1f * d.x * d.x)) < 1e-9f);
    CHECK(std::fabs(next.y - (0.9f * 4e-4f + 0.1f * chroma)) < 1e-9f);
    CHECK(std::fabs(next.z - (0.9f * 0.01f + 0.1f * 0.03f)) < 1e-8f);
    CHECK(std::fabs(next.w - (0.9f * 0.002f + 0.1f * 0.012f)) < 1e-8f);
    const glm::vec4 first = port::emcv_resolve_noise_update(glm::vec4(0.0f, 0.0f, 0.0f, 0.002f), current, kept, 1.0f,
                                                            moves, false, w);
    CHECK(std::fabs(first.x - d.x * d.x) < 1e-9f);
    CHECK(std::fabs(first.y - chroma) < 1e-9f);
    CHECK(first.z == moves.x);
    CHECK(std::fabs(first.w - (0.9f * 0.002f + 0.1f * 0.012f)) < 1e-8f);
    CHECK(port::emcv_resolve_noise_update(state, current, kept, 0.999f, moves, false, w) == state);
    CHECK(port::emcv_resolve_noise_update(state, current, kept, 0.0f, moves, false, w) == state);
    const glm::vec4 restarted = port::emcv_resolve_noise_update(state, current, kept, 1.0f, moves, true, w);
    CHECK(glm::vec3(restarted) == glm::vec3(0.0f));
    CHECK(std::fabs(restarted.w - (0.9f * 0.002f + 0.1f * 0.012f)) < 1e-8f);
}

namespace {

struct ridge_run {
    std::vector<double> error;     ///< per frame: the resolved value's squared error against the truth (channel mean)
    std::vector<bool> restarted;   ///< per frame: the noise state restarted (a change found, or a clip)
};

/// One pixel and its 3x3 neighbourhood resolved over `frames` frames with the port's functions in the order the
/// resolve pass calls them (clip box, change test, noise box, target, clip, blend, noise update). The pixel sits
/// on a ridge: its true value is `peak` on every channel, its eight neighbours' 0.06 lower; every value is its
/// truth plus Gaussian noise of deviation sigma, drawn anew each frame. From frame `change` on every truth drops
/// by `step` (a light change), and by `ramp` more every frame after it (a fade). Without the noise box (`noise_box` false) the change test and the box are skipped:
/// the resolve as it was.
ridge_run resolve_ridge(bool noise_box, int frames, int change, float step, std::uint32_t seed, float ramp = 0.0f) {
    const float peak = 0.6f, sigma = 0.02f, weight = EMCV_RESOLVE_BLEND;
    std::mt19937 rng(seed);
    std::normal_distribution<float> gauss(0.0f, sigma);
    glm::vec3 history(peak);
    glm::vec4 noise(0.0f);
    ridge_run run;
    for (int f = 0; f < frames; ++f) {
        const float drop = f >= change ? step + ramp * static_cast<float>(f - change) : 0.0f;
        glm::vec3 sum(0.0f), sum_squares(0.0f), filtered(0.0f), current(0.0f);
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                const float truth = (dx == 0 && dy == 0 ? peak : peak - 0.06f) - drop;
                const glm::vec3 v = glm::vec3(truth) + glm::vec3(gauss(rng), gauss(rng), gauss(rng));
                if (dx == 0 && dy == 0) current = v;
                sum += v;
                sum_squares += v * v;
                filtered += port::emcv_resolve_filter_weight(dx, dy) * v;
            }
        glm::vec3 lo, hi;
        port::emcv_resolve_clip_box(sum, sum_squares, 9.0f, current, lo, hi);
        const glm::vec2 moves = port::emcv_resolve_moves(filtered, current, history);
        const bool changed = noise_box && port::emcv_resolve_history_changed(moves, noise, weight);
        if (noise_box && !changed) port::emcv_resolve_noise_box(current, noise, lo, hi);
        const glm::vec3 target = port::emcv_resolve_clip(filtered, current, lo, hi);
        const float t = port::emcv_resolve_clip_fraction(history, target, lo, hi);
        const glm::vec3 kept = target + t * (history - target);
        history = port::emcv_resolve_blend(kept, current, weight);
        noise = port::emcv_resolve_noise_update(noise, current, kept, t, moves, changed, weight);
        const glm::vec3 e = history - glm::vec3(peak - drop);
        run.error.push_back(static_cast<double>(glm::dot(e, e)) / 3.0);
        run.restarted.push_back(glm::vec3(noise) == glm::vec3(0.0f));
    }
    return run;
}

double mean_of(const std::vector<double>& v, std::size_t from, std::size_t to) {
    double sum = 0.0;
    for (std::size_t i = from; i < to; ++i) sum += v[i];
    return sum / static_cast<double>(to - from);
}

}  // namespace

TEST_CASE("resolve noise box: a pixel above its neighbours keeps its converged history, and a light change, even "
          "one below the pixel's own noise, restarts it") {
    const float sigma = 0.02f;
    // Still lighting. An exponential average of weight w keeps w / (2 - w) of the noise variance (0.0526 sigma^2
    // at w = 0.1) when nothing clips it. The ridge's neighbourhood box ends under the pixel's true value (its
    // mean is 0.053 lower, its spread about 0.03), so without the noise box the converged history is clipped
    // towards the current value on every frame whose noise falls inwards: a bias the blend keeps, measured at
    // about 30 times that variance. With it, what is left is the frames after a false change (3-deviation tests on
    // a variance estimated from about 19 frames), each restarting the state at the neighbourhood's box for a
    // frame or more: 1.9-2.3 times the blend's variance over seeds 1-5 and this one. Bounds: under 4 times with
    // the noise box, over 10 times without.
    const double blend_variance = EMCV_RESOLVE_BLEND / (2.0 - EMCV_RESOLVE_BLEND) * sigma * sigma;
    const ridge_run with = resolve_ridge(true, 4000, 4000, 0.0f, 20261202u);
    const ridge_run without = resolve_ridge(false, 4000, 4000, 0.0f, 20261202u);
    const double with_mse = mean_of(with.error, 100, 4000), without_mse = mean_of(without.error, 100, 4000);
    INFO("mse / blend variance: with the noise box " << with_mse / blend_variance << ", without "
                                                     << without_mse / blend_variance);
    CHECK(with_mse < 4.0 * blend_variance);
    CHECK(without_mse > 10.0 * blend_variance);

    // A drop of 10 sigma at frame 200 leaves every box: the state restarts on that frame, and over the 30
    // frames from it the error is within the blend's variance of the resolve without the noise box.
    const ridge_run big = resolve_ridge(true, 260, 200, 10.0f * sigma, 7u);
    const ridge_run big_without = resolve_ridge(false, 260, 200, 10.0f * sigma, 7u);
    CHECK(big.restarted[200]);
    CHECK(mean_of(big.error, 200, 230) <= mean_of(big_without.error, 200, 230) + blend_variance);

    // A drop of 2 sigma, inside the pixel's own 3-deviation box but 4.5 deviations of the filtered move (sigma
    // sqrt(9/64 + 1/19) = 0.44 sigma): found on its first frame in most runs, within 3 frames in every one
    // of 20 seeds (a miss per frame needs the filtered noise 1.5 deviations against the drop: under 7%).
    int found_at_once = 0;
    for (std::uint32_t seed = 1; seed <= 20; ++seed) {
        const ridge_run small = resolve_ridge(true, 210, 200, 2.0f * sigma, seed);
        INFO("seed " << seed);
        CHECK((small.restarted[200] || small.restarted[201] || small.restarted[202]));
        found_at_once += small.restarted[200] ? 1 : 0;
    }
    CHECK(found_at_once >= 15);

    // A fade: from frame 200 every truth falls by 0.1 sigma a frame for 60 frames (6 sigma in all), under any
    // one frame's noise. The history lags a ramp by (1 - w) / w frames' worth of it (0.9 sigma here), which the
    // mean of the moves shows: the state restarts and the error over the fade is that of the resolve without
    // the noise box, within the blend's variance.
    for (std::uint32_t seed = 1; seed <= 5; ++seed) {
        const ridge_run fade = resolve_ridge(true, 260, 200, 0.0f, seed, 0.1f * sigma);
        const ridge_run fade_without = resolve_ridge(false, 260, 200, 0.0f, seed, 0.1f * sigma);
        INFO("seed " << seed << ": mse / blend variance over the fade " << mean_of(fade.error, 200, 260) / blend_variance
                     << ", without the noise box " << mean_of(fade_without.error, 200, 260) / blend_variance);
        CHECK(mean_of(fade.error, 200, 260) <= mean_of(fade_without.error, 200, 260) + blend_variance);
    }
}
