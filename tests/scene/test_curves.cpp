// SPDX-License-Identifier: MIT
// Light intensity curves (scene.hpp): each kind evaluates as specified, and is_constant() agrees with
// evaluating the curve over enough frames to see every change.
#include <catch2/catch_approx.hpp>
#include <catch2/catch_test_macros.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include "scene/scene.hpp"

using emcv::demo::curve;

namespace {

curve steps_curve(float value, std::vector<std::pair<int, float>> steps) {
    curve c;
    c.type = curve::kind::steps;
    c.value = value;
    c.steps = std::move(steps);
    return c;
}

curve flicker_curve(float value, float peak, std::vector<int> bursts, int length) {
    curve c;
    c.type = curve::kind::flicker;
    c.value = value;
    c.peak = peak;
    c.bursts = std::move(bursts);
    c.burst_length = length;
    return c;
}

curve sinusoid_curve(float value, float amplitude, float period, float phase) {
    curve c;
    c.type = curve::kind::sinusoid;
    c.value = value;
    c.amplitude = amplitude;
    c.period_frames = period;
    c.phase = phase;
    return c;
}

/// Constant over frames 0..last by evaluation (every curve below changes, if at all, before `last`).
bool constant_by_evaluation(const curve& c, int last) {
    for (int f = 1; f <= last; ++f)
        if (c.at(f) != c.at(0)) return false;
    return true;
}

}  // namespace

TEST_CASE("a constant curve is its value at every frame") {
    curve c;
    c.value = 2.5f;
    for (int f : {0, 1, 59, 100000}) CHECK(c.at(f) == 2.5f);
    CHECK(c.is_constant());
}

TEST_CASE("steps switch at their frames and hold until the next") {
    const curve off = steps_curve(3.0f, {{30, 0.0f}});  // the light-off teaser
    CHECK(off.at(0) == 3.0f);
    CHECK(off.at(29) == 3.0f);
    CHECK(off.at(30) == 0.0f);
    CHECK(off.at(59) == 0.0f);
    CHECK_FALSE(off.is_constant());

    const curve off_on = steps_curve(1.0f, {{10, 0.0f}, {20, 2.0f}});
    CHECK(off_on.at(9) == 1.0f);
    CHECK(off_on.at(10) == 0.0f);
    CHECK(off_on.at(19) == 0.0f);
    CHECK(off_on.at(20) == 2.0f);
    CHECK(off_on.at(1000) == 2.0f);

    SECTION("a step at frame 0 applies from the first frame") {
        const curve from_start = steps_curve(1.0f, {{0, 4.0f}});
        CHECK(from_start.at(0) == 4.0f);
        CHECK(from_start.is_constant());
    }
    SECTION("a step to the value it already has changes nothing") {
        CHECK(steps_curve(3.0f, {{10, 3.0f}}).is_constant());
        CHECK_FALSE(steps_curve(3.0f, {{10, 3.0f}, {20, 1.0f}}).is_constant());
    }
}

TEST_CASE("flicker is at its peak for burst_length frames from each burst start") {
    const curve gun = flicker_curve(0.5f, 4.0f, {8, 20}, 2);
    const std::vector<int> peak_frames{8, 9, 20, 21};
    for (int f = 0; f < 30; ++f) {
        const bool at_peak = std::find(peak_frames.begin(), peak_frames.end(), f) != peak_frames.end();
        INFO("frame " << f);
        CHECK(gun.at(f) == (at_peak ? 4.0f : 0.5f));
    }
    CHECK_FALSE(gun.is_constant());
    CHECK(flicker_curve(0.5f, 0.5f, {8}, 2).is_constant());   // peak equals value
    CHECK(flicker_curve(0.5f, 4.0f, {}, 2).is_constant());    // no bursts
    SECTION("overlapping bursts stay at the peak") {
        const curve overlap = flicker_curve(0.0f, 1.0f, {3, 4}, 3);
        for (int f = 3; f <= 6; ++f) CHECK(overlap.at(f) == 1.0f);
        CHECK(overlap.at(7) == 0.0f);
    }
}

TEST_CASE("a sinusoid is value + amplitude sin(2 pi frame / period + phase), floored at 0") {
    const curve club = sinusoid_curve(2.0f, 1.0f, 20.0f, 0.0f);
    CHECK(club.at(0) == Catch::Approx(2.0f).margin(1e-6));
    CHECK(club.at(5) == Catch::Approx(3.0f).margin(1e-6));   // quarter period: the crest
    CHECK(club.at(10) == Catch::Approx(2.0f).margin(1e-6));
    CHECK(club.at(15) == Catch::Approx(1.0f).margin(1e-6));  // the trough
    CHECK(club.at(25) == Catch::Approx(3.0f).margin(1e-6));  // periodic
    const curve shifted = sinusoid_curve(2.0f, 1.0f, 20.0f, 3.14159265f / 2.0f);
    CHECK(shifted.at(0) == Catch::Approx(3.0f).margin(1e-6));  // the phase is in radians
    const curve floored = sinusoid_curve(0.5f, 2.0f, 20.0f, 0.0f);
    CHECK(floored.at(15) == 0.0f);
    CHECK(floored.at(5) == Catch::Approx(2.5f).margin(1e-6));
    CHECK_FALSE(club.is_constant());
    CHECK(sinusoid_curve(2.0f, 0.0f, 20.0f, 0.3f).is_constant());
    CHECK(sinusoid_curve(2.0f, 1.0f, 1.0f, 0.3f).is_constant());  // one cycle per frame: one phase sampled
}

TEST_CASE("is_constant agrees with evaluating the curve frame by frame") {
    std::vector<curve> curves{
        curve{},
        steps_curve(1.0f, {{5, 0.0f}}), steps_curve(1.0f, {{0, 0.0f}}), steps_curve(1.0f, {{5, 1.0f}}),
        steps_curve(1.0f, {{0, 2.0f}, {7, 2.0f}}), steps_curve(1.0f, {{0, 2.0f}, {7, 1.0f}}),
        steps_curve(1.0f, {{-5, 3.0f}, {0, 2.0f}}),  // steps before frame 0 are history, not change
        flicker_curve(0.0f, 1.0f, {4}, 1), flicker_curve(1.0f, 1.0f, {4}, 3), flicker_curve(0.0f, 1.0f, {}, 1),
        sinusoid_curve(1.0f, 0.5f, 8.0f, 0.0f), sinusoid_curve(1.0f, 0.0f, 8.0f, 1.0f),
        sinusoid_curve(1.0f, 0.5f, 1.0f, 0.7f), sinusoid_curve(1.0f, 0.5f, 0.5f, 0.7f),
        sinusoid_curve(0.0f, 0.0f, 3.0f, 0.0f),
    };
    for (std::size_t i = 0; i < curves.size(); ++i) {
        INFO("curve " << i);
        // Integer-frequency sinusoids agree only up to sin's rounding at large arguments: compare their values
        // with a tolerance, everything else exactly.
        const curve& c = curves[i];
        if (c.type == curve::kind::sinusoid && c.is_constant()) {
            for (int f = 0; f <= 200; ++f) CHECK(c.at(f) == Catch::Approx(c.at(0)).margin(1e-5));
        } else {
            CHECK(c.is_constant() == constant_by_evaluation(c, 200));
        }
    }
}
