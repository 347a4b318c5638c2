// SPDX-License-Identifier: MIT
// The policy API's contract: parameters are checked and the message names the problem; the state type must be
// the estimator's; the variance codes (no variance yet, sub-pixel) give the counts the renderer gives them; the
// solve is deterministic and the budget's lambda grows with the budget.
#include <catch2/catch_test_macros.hpp>

#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <emcv/adaptive_sampling.hpp>

namespace sampling_api_tests {  // one namespace per file: the unity build (the sanitize preset) joins files

namespace {

std::string message_of(const emcv::sampling_params& p) {
    try {
        emcv::check_sampling_params(p);
    } catch (const std::invalid_argument& e) {
        return e.what();
    }
    return "";
}

bool mentions(const std::string& s, const std::string& what) { return s.find(what) != std::string::npos; }

}  // namespace

TEST_CASE("sampling_params: each invalid value throws std::invalid_argument naming it") {
    emcv::sampling_params ok;
    CHECK(message_of(ok).empty());
    CHECK(emcv::sampling_eta(ok) == EMCV_HISTORY_ETA_MOVING);
    ok.estimator = emcv::sampling_estimator::cv;
    CHECK(emcv::sampling_eta(ok) == EMCV_HISTORY_ETA_EMCM);
    ok.eta = 0.5f;  // the edge is allowed
    CHECK(message_of(ok).empty());

    emcv::sampling_params p;
    p.n_min = 0;
    CHECK(mentions(message_of(p), "emcv::sampling_params: n_min = 0 must be >= 1"));
    p = {};
    p.n_min = 9, p.n_max = 8;
    CHECK(mentions(message_of(p), "emcv::sampling_params: n_min = 9 must not exceed n_max = 8"));
    p = {};
    p.n_max = 1025;  // past the budget solve's range (a fuzz finding: 50332419 planned 50332420 samples)
    CHECK(mentions(message_of(p), "emcv::sampling_params: n_max = 1025 must not exceed 1024"));
    p.n_max = 1024;
    CHECK_NOTHROW(emcv::check_sampling_params(p));
    for (const float eta : {0.0f, -0.1f, 0.51f, std::numeric_limits<float>::quiet_NaN()}) {
        p = {};
        p.eta = eta;
        CHECK(mentions(message_of(p), "emcv::sampling_params: eta = " + emcv::detail::number_text(eta) +
                                          " must lie in (0, 0.5]"));
    }
    for (const float target : {0.0f, -1e-4f, std::numeric_limits<float>::infinity(),
                               std::numeric_limits<float>::quiet_NaN()}) {
        p = {};
        p.target = target;
        CHECK(mentions(message_of(p), "emcv::sampling_params: target = " + emcv::detail::number_text(target) +
                                          " must be finite and > 0"));
    }
    for (const float budget : {0.0f, -1.0f, 65.0f, std::numeric_limits<float>::quiet_NaN()}) {
        p = {};
        p.mode = emcv::sampling_mode::budget;
        p.budget = budget;
        CHECK(mentions(message_of(p), "emcv::sampling_params: budget = " + emcv::detail::number_text(budget) +
                                          " must be finite, > 0 and <= n_max"));
        p.mode = emcv::sampling_mode::quality_target;  // not read under a quality target
        CHECK(message_of(p).empty());
    }
}

TEST_CASE("the functions refuse the other estimator's state type and null arrays") {
    emcv::sampling_params p;  // spvg: moving stats
    std::vector<emcv::port::EmcvEmcm2> emcm(4, emcv::port::emcv_emcm2_init());
    std::vector<emcv::port::EmcvMovingStats> moving(4, emcv::port::emcv_moving_stats_init());
    std::vector<float> f(4, 0.5f), sigma2(4);
    std::vector<int> n(4, 1);
    CHECK_THROWS_AS(emcv::sampling_update(p, emcm.data(), 4, 2, nullptr, f.data(), f.data(), n.data()), std::invalid_argument);
    CHECK_NOTHROW(emcv::sampling_update(p, moving.data(), 4, 2, nullptr, f.data(), nullptr, n.data()));  // spvg needs no G
    p.estimator = emcv::sampling_estimator::cv;
    CHECK_THROWS_AS(emcv::sampling_sigma2(p, moving.data(), 4, nullptr, sigma2.data()), std::invalid_argument);
    CHECK_THROWS_AS(emcv::sampling_update(p, emcm.data(), 4, 2, nullptr, f.data(), nullptr, n.data()), std::invalid_argument);
    CHECK_THROWS_AS(emcv::sampling_counts(p, sigma2.data(), 4, 3, 0.0f, 0, 0, n.data()), std::invalid_argument);
}

TEST_CASE("variance codes: a young history takes n_max (quality) or B (budget), a sub-pixel kernel 0 under cv") {
    // Two pixels, one frame pushed each: no variance yet (count < 2). Pixel 1 is sub-pixel.
    const std::uint8_t sub[2] = {0, 1};
    std::vector<float> f = {0.5f, 0.5f}, g = {0.4f, 0.4f}, sigma2(2);
    std::vector<int> taken = {4, 4}, n(2);
    for (const auto e : {emcv::sampling_estimator::spvg, emcv::sampling_estimator::cv_notex}) {
        emcv::sampling_params p;
        p.estimator = e;
        std::vector<emcv::port::EmcvMovingStats> s(2, emcv::port::emcv_moving_stats_init());
        emcv::sampling_update(p, s.data(), 2, 2, nullptr, f.data(), g.data(), taken.data());
        emcv::plan_frame(p, s.data(), 2, 2, nullptr, sub, 0, 0, sigma2.data(), n.data());
        CHECK(n[0] == p.n_max);
        CHECK(n[1] == (e == emcv::sampling_estimator::spvg ? p.n_max : 0));  // spvg has no control: never skips
        p.mode = emcv::sampling_mode::budget;
        p.budget = 6;
        const emcv::frame_plan plan = emcv::plan_frame(p, s.data(), 2, 2, nullptr, sub, 0, 0, sigma2.data(), n.data());
        CHECK(n[0] == 6);
        CHECK(plan.samples == (e == emcv::sampling_estimator::spvg ? 12u : 6u));
    }
    // A pixel that took no samples is not pushed.
    emcv::sampling_params p;
    p.estimator = emcv::sampling_estimator::cv;
    std::vector<emcv::port::EmcvEmcm2> s(2, emcv::port::emcv_emcm2_init());
    taken = {0, 3};
    emcv::sampling_update(p, s.data(), 2, 2, nullptr, f.data(), g.data(), taken.data());
    CHECK(s[0].count == 0u);
    CHECK(s[1].count == 1u);
}

TEST_CASE("budget_solve: lambda grows with the budget and is the same on every call") {
    emcv::budget_histogram h = emcv::make_budget_histogram();
    for (int i = 1; i <= 1000; ++i) emcv::budget_add(h, 1e-4f * float(i));
    emcv::sampling_params p;
    p.mode = emcv::sampling_mode::budget;
    float previous = 0;
    for (const float b : {2.0f, 4.0f, 8.0f, 16.0f}) {
        p.budget = b;
        const float lambda = emcv::budget_solve(p, h);
        CHECK(lambda > previous);
        CHECK(emcv::budget_solve(p, h) == lambda);
        previous = lambda;
    }
}

}  // namespace sampling_api_tests
