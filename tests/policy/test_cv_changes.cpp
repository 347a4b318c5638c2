// SPDX-License-Identifier: MIT
// cv's robust update (port::emcv_history_push_cv, which sampling_update calls for cv) on an analytic stream:
// 32x32 pixels, N = 16 samples a frame of standard deviation s = 0.1 around f = alpha G, alpha = 2, G = 0.25
// (static), eta = sampling_eta (cv's default), 200 frames: every history is mature (count >= 1 / eta) and its
// sigma^2 estimates s^2. With G static, C_GG = C_fG = 0 and the residual variance is C_ff; the predicted alpha
// is mu_f / mu_G.
//   unexplained step  f jumps by 20 s / sqrt(N) with G unchanged: the residual move e = f - mu_f has
//            N e^2 ~ 400 s^2 > 25 sigma^2, so the frame enters with weight n' = 25 sigma^2 / e^2 and its
//            comoment term is eta n' e^2 = 25 eta sigma^2 with sigma^2 = unbias C (unbias = (2 - eta) /
//            (2 (1 - eta))): C' = (1 - eta)(C + 25 eta unbias C), so every pixel's sigma^2 rises by exactly
//            (1 - eta)(1 + 25 eta unbias) (~1 + 24 eta; 2.17 at eta 0.05), up to float rounding. The plain batch
//            push (port::emcv_emcm2_push_batch) adds eta N e^2 ~ 400 eta s^2 instead: a rise of
//            (1 - eta)(1 + 400 eta unbias s^2 / sigma^2), ~20x at eta 0.05. The means restart at (f, G), so the
//            next frame at the new level is read as noise: sigma^2 does not rise again.
//   explained step   f and G step by the same factor 2 (f = alpha G still): the move d = (f - mu_f, G - mu_G) is
//            along the control, and the rank-one update leaves C_ff - C_fG^2 / C_GG at (1 - eta) C exactly,
//            whatever its weight. That frame's noise went into the move the control explains, so the estimate
//            is one frame's noise short, a deficit that fades as new frames come in: over the following frames
//            the pixel mean stays between (1 - eta) and 1 times the estimate before the step, within 6 of its
//            relative standard deviations sqrt(eta / (2 - eta) 2 / P) (1.5% at eta 0.2), and never rises.
//   the level's bias  a step the control explains still moves f's level; where f moves beyond 5 sigma
//            (N (f - mu_f)^2 > 25 sigma^2) the variance the history holds was measured at the old level and is off
//            by delta = (f^2 - sigma^2 / N) / mu_f^2 - 1 relatively. The estimate's relative mean squared error is
//            then r / K + delta^2 (r = 2 + (kurtosis - 3) / N, one frame's, at the port's kurtosis 9.36; K the
//            effective frames (1 - a^m)(1 + a) / (eta (1 + a^m)), a = 1 - eta, m = count - 1), worth
//            K' = r / (r / K + delta^2) frames, and the count is lowered to the largest count >= 2 whose K is at most
//            K'. Each pixel's count is computed here in double with std::pow. A step by 1.3 moves f by 6 sigma /
//            sqrt(N): with its noise, z ~ N(6, 1) passes 5 on about 84% of the pixels (fewer with sigma^2's own
//            noise; more than half), and there delta ~ 0.69 and K' ~ 3.6 from K ~ 9: counts near 4, up to 10 where a
//            pixel's low sigma^2 lets a smaller move pass (one pixel's estimate varies by ~47%). A step by
//            1.05 moves f by 1 sigma / sqrt(N): z ~ N(1, 1) passes 5 with probability 3e-5, on a handful of pixels
//            at most. Every pixel under the test keeps the count its push gives (201).
//   the tile's noise test  the pixels form a 32x32 image of 16 8x8 tiles, one material. Each pixel's term before
//            its push is z = min(N e^2 / sigma^2, 25) (e = f - mu_f - (mu_f / mu_G)(G - mu_G): G is static); a tile's
//            mean zbar over its 64 pixels estimates the ratio rho of the noise now to the history's, with sampling
//            variance v = sum(r) / 64^2 (r as above: v = r / 64 ~ 0.037); where zbar < 1 and (zbar - 1)^2 > v each
//            pixel's comoments are scaled after its push by 1 - sqrt((zbar - 1)^2 - v), recomputed here in double
//            from the states before the frame. The noise falls to a quarter (s^2 / 16): the residual e then also holds
//            the moving mean's error from the old noise, N Var(mu_f) = eta / (2 - eta) s^2 (0.11 s^2), so the first
//            frame's zbar ~ 1 / 16 + 0.11 = 0.17 and its ratio ~ 1 - sqrt(0.83^2 - 0.037) = 0.19: sigma^2 falls to
//            about a fifth of what the push alone leaves, and the later frames only rescale further, down to the new
//            level at most (the ratio is shrunk towards 1 by v). So 3 frames after the fall sigma^2 is at most a
//            third of the push alone's (which holds (1 - eta)^3 s^2 ~ 8 s^2 / 16) and at least half the new s^2.
//            Under
//            no change the test fires where zbar < 1 - sqrt(v) (zbar's own noise, sd sqrt(r / 64) ~ 0.19), and
//            each firing scales by 1 - sqrt((zbar - 1)^2 - v): sigma^2's mean is pulled under s^2 by what the
//            run measures, which the bound below keeps within 10% (the quality target's own tolerance is 15%).
#include <catch2/catch_test_macros.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include <emcv/adaptive_sampling.hpp>

#include "policy_support.hpp"

namespace cv_changes_tests {  // one namespace per file: the unity build (the sanitize preset) joins files

namespace {

constexpr std::size_t width = 32, pixels = width * width;
constexpr int warm_up = 200, n_samples = 16;
constexpr double s = 0.1, alpha = 2.0, g_before = 0.25;

struct stream {
    emcv::sampling_params p;
    std::vector<emcv::port::EmcvEmcm2> states = std::vector<emcv::port::EmcvEmcm2>(pixels, emcv::port::emcv_emcm2_init());
    std::vector<float> f = std::vector<float>(pixels), g = std::vector<float>(pixels);
    std::vector<int> n = std::vector<int>(pixels, n_samples);
    emcv_policy_test::gaussian_source rng{41};

    stream() { p.estimator = emcv::sampling_estimator::cv; }

    /// One frame: f = alpha G + offset + the mean of N samples of standard deviation s * noise.
    void frame(double g_value, double offset, double noise = 1.0) {
        for (std::size_t i = 0; i < pixels; ++i) {
            g[i] = static_cast<float>(g_value);
            f[i] = static_cast<float>(alpha * g_value + offset + noise * s * rng.normal() / std::sqrt(double(n_samples)));
        }
        emcv::sampling_update(p, states.data(), pixels, width, nullptr, f.data(), g.data(), n.data());
    }

    std::vector<float> sigma2() const {
        std::vector<float> out(pixels);
        emcv::sampling_sigma2(p, states.data(), pixels, nullptr, out.data());
        return out;
    }
};

}  // namespace

using emcv_policy_test::mean_of;

TEST_CASE("cv's update: a jump the control does not explain raises sigma^2 by the 5-sigma weight only") {
    stream st;
    for (int t = 0; t < warm_up; ++t) st.frame(g_before, 0.0);
    const double eta = emcv::sampling_eta(st.p);
    const std::vector<float> before = st.sigma2();
    REQUIRE(st.states[0].count * eta >= 1.0);
    const double mean_before = mean_of(before);
    INFO("sigma^2 before the step " << mean_before << ", s^2 " << s * s);
    REQUIRE(std::fabs(mean_before / (s * s) - 1) < 0.05);

    // the same frame pushed plainly, for comparison
    std::vector<emcv::port::EmcvEmcm2> plain = st.states;
    const double step = 20 * s / std::sqrt(double(n_samples));
    st.frame(g_before, step);
    for (std::size_t i = 0; i < pixels; ++i)
        emcv::port::emcv_emcm2_push_batch(plain[i], glm::vec2(st.f[i], st.g[i]), float(eta), float(n_samples));
    const std::vector<float> after = st.sigma2();
    std::vector<float> after_plain(pixels);
    emcv::sampling_sigma2(st.p, plain.data(), pixels, nullptr, after_plain.data());

    std::size_t restarted = 0;
    for (std::size_t i = 0; i < pixels; ++i)
        if (st.states[i].mean.x == st.f[i] && st.states[i].mean.y == st.g[i]) ++restarted;
    emcv_policy_test::check_clipped_jump(before, after, after_plain, restarted, eta, s, [&] {
        st.frame(g_before, step);  // the next frame at the new level: noise around the restarted mean
        return st.sigma2();
    });
}

TEST_CASE("cv's update: a step of f and G by the same factor (f = alpha G) leaves the residual variance") {
    stream st;
    for (int t = 0; t < warm_up; ++t) st.frame(g_before, 0.0);
    const double eta = emcv::sampling_eta(st.p);
    const std::vector<float> before = st.sigma2();
    const double mean_before = mean_of(before);
    st.frame(2 * g_before, 0.0);  // the light doubles: f and G both double (the noise does not)
    const std::vector<float> after = st.sigma2();
    double worst = 0;
    for (std::size_t i = 0; i < pixels; ++i)
        worst = std::max(worst, std::fabs(double(after[i]) / before[i] / (1 - eta) - 1));
    INFO("the step frame: sigma^2 / ((1 - eta) sigma^2 before) within 1 +- " << worst);
    CHECK(worst <= 1e-4);
    double lowest = 1e30, highest = 0;
    for (int t = 0; t < 20; ++t) {
        st.frame(2 * g_before, 0.0);
        const double m = mean_of(st.sigma2()) / mean_before;
        lowest = std::min(lowest, m), highest = std::max(highest, m);
    }
    const double scatter = 6 * std::sqrt(eta / (2 - eta) * 2 / double(pixels));
    INFO("the 20 frames after: mean sigma^2 / before in [" << lowest << ", " << highest << "], scatter " << scatter);
    CHECK(lowest >= (1 - eta) * (1 - scatter));
    CHECK(highest <= 1 + scatter);
}

TEST_CASE("cv's update: a step the control explains lowers the count to the frames its level's bias leaves") {
    for (const double factor : {1.3, 1.05}) {
        stream st;
        for (int t = 0; t < warm_up; ++t) st.frame(g_before, 0.0);
        const double eta = emcv::sampling_eta(st.p), a = 1 - eta;
        const std::vector<emcv::port::EmcvEmcm2> before = st.states;
        const std::vector<float> sigma2 = st.sigma2();
        st.frame(factor * g_before, 0.0);  // f = alpha G with G scaled: the control explains the step
        const double r = 2 + (9.36 - 3) / n_samples;
        const auto frames = [eta, a](double count) {
            const double am = std::pow(a, count - 1);
            return (1 - am) * (1 + a) / (eta * (1 + am));
        };
        std::size_t lowered = 0, mismatched = 0, near_tie = 0;
        double lowest_count = 1e30, highest_lowered = 0;
        for (std::size_t i = 0; i < pixels; ++i) {
            const double mu = before[i].mean.x, f = st.f[i], v = sigma2[i];
            double expected = double(before[i].count) + 1;  // the push's own frame
            if (n_samples * (f - mu) * (f - mu) > 25 * v) {
                const double delta = std::max(f * f - v / n_samples, 0.0) / (mu * mu) - 1;
                const double trusted = r / (r / frames(expected) + delta * delta);
                double c = 2;
                while (c + 1 < expected && frames(c + 1) <= trusted) c += 1;
                const bool tie = std::fabs(frames(c + 1) / trusted - 1) < 1e-4 || std::fabs(frames(c) / trusted - 1) < 1e-4;
                if (tie) ++near_tie;
                expected = c;
                ++lowered;
                highest_lowered = std::max(highest_lowered, double(st.states[i].count));
            }
            if (double(st.states[i].count) != expected) ++mismatched;
            lowest_count = std::min(lowest_count, double(st.states[i].count));
        }
        INFO("step by " << factor << ": " << lowered << " of " << pixels << " pixels past 5 sigma, counts from "
                        << lowest_count << ", at most " << highest_lowered << " where lowered, " << mismatched
                        << " off the derivation (" << near_tie << " within float rounding of a tie)");
        CHECK(mismatched <= near_tie);
        CHECK(lowest_count >= 2);
        if (factor > 1.2) {
            CHECK(lowered > pixels / 2);
            CHECK(highest_lowered <= 10);  // K' ~ 3.6 (more where a low sigma^2 passes a smaller move): a handful
        } else {
            CHECK(lowered <= 4);
        }
    }
}

TEST_CASE("cv's update: the tile's noise test scales the comoments by its pool's ratio where the noise fell") {
    stream st;
    for (int t = 0; t < warm_up; ++t) st.frame(g_before, 0.0);
    const double eta = emcv::sampling_eta(st.p), unbias = (2 - eta) / (2 * (1 - eta));
    const double r = 2 + (9.36 - 3) / n_samples;
    // One frame at noise scale k through the library and, from the same states, through the push alone; the
    // ratio each pixel's comoments were scaled by, against the derivation in double.
    std::size_t fired = 0, off = 0;
    const auto step = [&](double k) {
        const std::vector<emcv::port::EmcvEmcm2> before = st.states;
        st.frame(g_before, 0.0, k);
        constexpr std::size_t tile = emcv::sampling_tile_size;
        for (std::size_t y0 = 0; y0 < width; y0 += tile)
            for (std::size_t x0 = 0; x0 < width; x0 += tile) {
                double zsum = 0, rsum = 0, m = 0;
                for (std::size_t y = y0; y < y0 + tile; ++y)
                    for (std::size_t x = x0; x < x0 + tile; ++x) {
                        const std::size_t i = y * width + x;
                        const double sigma2 = unbias * before[i].cov.x, mu = before[i].mean.x;
                        const double e = double(st.f[i]) - mu - (mu / before[i].mean.y) * (double(st.g[i]) - before[i].mean.y);
                        zsum += std::min(n_samples * e * e / sigma2, 25.0), rsum += r, m += 1;
                    }
                const double z = zsum / m, bias2 = (z - 1) * (z - 1) - rsum / (m * m);
                const double ratio = z < 1 && bias2 > 0 ? 1 - std::sqrt(bias2) : 1.0;
                if (ratio < 1) ++fired;
                for (std::size_t y = y0; y < y0 + tile; ++y)
                    for (std::size_t x = x0; x < x0 + tile; ++x) {
                        const std::size_t i = y * width + x;
                        emcv::port::EmcvEmcm2 push = before[i];
                        emcv::port::emcv_history_push_cv(push, st.f[i], st.g[i], float(eta), float(n_samples));
                        if (std::fabs(double(st.states[i].cov.x) / double(push.cov.x) - ratio) > 1e-5) ++off;
                        if (st.states[i].count != push.count) ++off;
                    }
            }
    };
    // No change: 100 frames at the same noise.
    double mean_sigma2 = 0;
    for (int t = 0; t < 100; ++t) {
        step(1.0);
        mean_sigma2 += mean_of(st.sigma2()) / 100;
    }
    const std::size_t fired_static = fired;
    INFO("no change: " << fired_static << " of 1600 tile-frames rescaled, mean sigma^2 / s^2 " << mean_sigma2 / (s * s));
    CHECK(std::fabs(mean_sigma2 / (s * s) - 1) <= 0.10);
    // The noise falls to a quarter, the level and G unchanged; the push alone for comparison.
    std::vector<emcv::port::EmcvEmcm2> plain = st.states;
    fired = 0;
    for (int t = 0; t < 3; ++t) {
        step(0.25);
        for (std::size_t i = 0; i < pixels; ++i)
            emcv::port::emcv_history_push_cv(plain[i], st.f[i], st.g[i], float(eta), float(n_samples));
    }
    std::vector<float> plain_sigma2(pixels);
    emcv::sampling_sigma2(st.p, plain.data(), pixels, nullptr, plain_sigma2.data());
    const double now = mean_of(st.sigma2()) / (s * s / 16), without = mean_of(plain_sigma2) / (s * s / 16);
    INFO("3 frames after the fall: " << fired << " of 48 tile-frames rescaled; mean sigma^2 / the new s^2 " << now
                                     << " (the push alone: " << without << "); " << off << " pixel-frames off the derivation");
    CHECK(off == 0);
    CHECK(fired >= 16);  // every tile on the first frame
    CHECK(now >= 0.5);
    CHECK(now <= without / 3);
    CHECK(without >= 4.0);  // (1 - eta)^3 * 16 ~ 8
}

TEST_CASE("a batch push whose (1 - r) n d_f overflows keeps the cross comoment finite (fuzz finding)") {
    // tests/fuzz (sampling) found it: mean (-1, 0) after one sample, then (f, G) = (FLT_MAX, 0) as a batch of 64
    // at eta 0.2: (1 - r) n d_f = 0.8 * 64 * FLT_MAX overflowed to Inf, and Inf * d_G = Inf * 0 stored C_fG = NaN.
    emcv::port::EmcvEmcm2 s = emcv::port::emcv_emcm2_init();
    REQUIRE(emcv::port::emcv_emcm2_push_batch(s, glm::vec2(-1.0f, 0.0f), 0.2f, 64.0f));
    const float top = std::numeric_limits<float>::max();
    REQUIRE(emcv::port::emcv_emcm2_push_batch(s, glm::vec2(top, 0.0f), 0.2f, 64.0f));
    CHECK(emcv::port::emcv_emcm2_valid(s));
    CHECK(s.cov.y == 0.0f);    // d_G = 0: no cross term
    CHECK(s.cov.x == top);     // the variance saturates
    CHECK(s.cov.z == 0.0f);
    // and the per-frame API keeps the pixel usable: a finite variance code, a count in range
    emcv::sampling_params p;
    p.estimator = emcv::sampling_estimator::cv;
    CHECK(emcv::sampling_eta(p) == 0.2f);
    float sigma2 = 0;
    int n = 0;
    emcv::plan_frame(p, &s, 1, 1, nullptr, nullptr, 0u, 0u, &sigma2, &n);
    CHECK(sigma2 >= 0.0f);
    CHECK(n == p.n_max);
}

}  // namespace cv_changes_tests
