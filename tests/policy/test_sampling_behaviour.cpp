// SPDX-License-Identifier: MIT
// The estimator decides N, not a floor: a synthetic 64x64 stream under a quality target (1e-4, N in [1, 64]),
// each pixel's control G_i in [0.4, 0.6] and its per-sample value G_i (1 + rho z), rho = 0.089, so the
// per-sample variance G_i^2 rho^2 asks for N = G_i^2 rho^2 / 1e-4 in [12.7, 28.5]. 100 frames; the light goes off
// at frame 50 (G -> 0, f -> 0). Frame t's plan reads the history before frame t's push, as the renderer's passes do.
//   static (frames 20-49)  G is constant, so the EMCM's C_GG = C_fG = 0, alpha = 0 and cv's residual variance
//            is C_ff: spvg and cv estimate the same per-sample variance (unbiased in steady state, supp. Eq.
//            25-27) and their mean counts agree. They differ only by the noise of their estimates through ceil
//            and the clamps, and by the lag term of the batch push (test_per_sample_variance.cpp: eta (E[N] E[1/N]
//            - 1) / 2, about 2% for spvg's N fluctuating by its estimate's ~47% relative noise): within 10%.
//            The window starts at frame 20: both histories (eta 0.2, the defaults) reach 1 - 0.8^19 = 98.6% of
//            their steady comoment by then.
//            Both means also lie within 5% of mean_i G_i^2 rho^2 / target (+1 for the ceil): the batch scaling
//            is what makes them estimate the per-sample variance at all.
//   switch   (frames 50-79) spvg sees the step of f as variance (N d^2 with d ~ 0.5: ~8000 times the target)
//            and samples at n_max; cv's pushes (f, G) = (0, 0) are collinear with its mean (mu_f, mu_G)
//            (both decay by (1 - eta) per frame), so C_ff - C_fG^2 / C_GG stays the pre-switch residual times
//            (1 - eta)^k: each pixel's count never rises after the switch, and cv takes at most half of spvg's
//            samples.
#include <catch2/catch_test_macros.hpp>

#include <cmath>
#include <cstdint>
#include <vector>

#include <emcv/adaptive_sampling.hpp>

#include "policy_support.hpp"

namespace sampling_behaviour_tests {  // one namespace per file: the unity build (the sanitize preset) joins files

namespace {

constexpr std::size_t side = 64, pixels = side * side;
constexpr int frames = 100, switch_frame = 50;
constexpr double rho = 0.089;

struct stream_result {
    std::vector<std::vector<int>> counts;  // [frame][pixel]
    double mean_in(int first, int last) const {
        double sum = 0;
        for (int t = first; t <= last; ++t)
            for (int n : counts[std::size_t(t)]) sum += n;
        return sum / (double(last - first + 1) * double(pixels));
    }
};

template <class State>
stream_result run(emcv::sampling_estimator estimator, State init, const std::vector<float>& g0) {
    emcv::sampling_params p;
    p.estimator = estimator;
    p.mode = emcv::sampling_mode::quality_target;
    p.target = 1e-4f;
    p.n_min = 1;
    p.n_max = 64;
    std::vector<State> states(pixels, init);
    std::vector<float> sigma2(pixels), f(pixels), g(pixels);
    std::vector<int> n(pixels);
    emcv_policy_test::gaussian_source rng(77);  // the same noise for both estimators where they take as many samples
    stream_result r;
    for (int t = 0; t < frames; ++t) {
        emcv::plan_frame(p, states.data(), pixels, side, nullptr, nullptr, std::uint32_t(t), 5u, sigma2.data(),
                         n.data());
        r.counts.push_back(n);
        for (std::size_t i = 0; i < pixels; ++i) {
            const double light = t < switch_frame ? 1.0 : 0.0;
            g[i] = static_cast<float>(light * g0[i]);
            // the mean of n[i] samples G (1 + rho z_k): exactly G (1 + rho z / sqrt(n))
            f[i] = static_cast<float>(g[i] * (1 + rho * rng.normal() / std::sqrt(double(n[i]))));
        }
        emcv::sampling_update(p, states.data(), pixels, side, nullptr, f.data(), g.data(), n.data());
    }
    return r;
}

}  // namespace

TEST_CASE("the history's variance, not a floor, sets N: cv and spvg agree on a static light, cv ignores a switch") {
    emcv_policy_test::gaussian_source rng(5);
    std::vector<float> g0(pixels);
    double asked = 0;  // mean_i G_i^2 rho^2 / target: the count the per-sample variance asks for
    for (std::size_t i = 0; i < pixels; ++i) {
        g0[i] = static_cast<float>(0.4 + 0.2 * rng.uniform());
        asked += double(g0[i]) * g0[i] * rho * rho / 1e-4 / double(pixels);
    }
    const stream_result spvg = run(emcv::sampling_estimator::spvg, emcv::port::emcv_moving_stats_init(), g0);
    const stream_result cv = run(emcv::sampling_estimator::cv, emcv::port::emcv_emcm2_init(), g0);

    const double spvg_static = spvg.mean_in(20, switch_frame - 1), cv_static = cv.mean_in(20, switch_frame - 1);
    const double spvg_after = spvg.mean_in(switch_frame, switch_frame + 29),
                 cv_after = cv.mean_in(switch_frame, switch_frame + 29);
    INFO("static: spvg " << spvg_static << ", cv " << cv_static << ", asked " << asked << "; after the switch: spvg "
                         << spvg_after << ", cv " << cv_after);
    CHECK(std::fabs(cv_static / spvg_static - 1) <= 0.10);
    for (const double m : {spvg_static, cv_static}) {
        CHECK(m >= 0.95 * asked);
        CHECK(m <= 1.05 * (asked + 1));
    }
    CHECK(cv_after <= 0.5 * spvg_after);
    // cv's residual only decays after the switch: no pixel's count rises
    int rises = 0;
    for (int t = switch_frame + 1; t < switch_frame + 30; ++t)
        for (std::size_t i = 0; i < pixels; ++i)
            if (cv.counts[std::size_t(t)][i] > cv.counts[std::size_t(t - 1)][i]) ++rises;
    CHECK(rises == 0);
}

}  // namespace sampling_behaviour_tests
