// SPDX-License-Identifier: MIT
// The reference converges: its error against a render with 4x the samples falls like 1/sqrt(N).
#include <catch2/catch_test_macros.hpp>

#include <cmath>
#include <vector>

#include "../gpu/gl_test_support.hpp"
#include "gl/debug.hpp"
#include "render/renderer.hpp"
#include "render_test_support.hpp"

using namespace emcv::demo;

namespace {

struct rendered {
    emcv::gl::float_image linear;
    emcv::gl::float_image mask;
};

rendered render_reference(const scene& s, int samples, std::uint32_t seed) {
    render_options options;
    options.width = 64;
    options.height = 64;
    options.seed = seed;
    renderer r(s, make_reference(samples), options);
    r.render(0);
    return {r.linear(), r.sss_mask()};
}

/// RMS over SSS pixels and colour channels of a - b.
double rms_difference(const rendered& a, const rendered& b) {
    double sum = 0.0;
    std::size_t n = 0;
    for (std::size_t p = 0; p < a.mask.pixels.size(); ++p) {
        if (a.mask.pixels[p] == 0.0f) continue;
        for (std::size_t c = 0; c < 3; ++c) {
            const double d = double(a.linear.pixels[4 * p + c]) - double(b.linear.pixels[4 * p + c]);
            sum += d * d;
            ++n;
        }
    }
    return std::sqrt(sum / double(n));
}

}  // namespace

// e(N) = RMS over the SSS pixels of reference(N, seed 1) - reference(4N, seed 2). With independent Monte Carlo
// estimates of variance s^2 / N, E[e(N)^2] = s^2 / N + s^2 / (4N), so e(N) / e(4N) = 2 exactly. The samples
// are a per-pixel rotated R2 set (randomised quasi-Monte Carlo), whose error falls at least that fast, and
// no N-point rule beats 1/N on an integrand with discontinuities (the pixel grid, depth steps): ratio <= 4.
// Statistical slack: e^2 averages ~2000 squared errors (700 SSS pixels x 3 channels, correlated: count 700),
// so sd(e^2) / e^2 ~ sqrt(2 / 700) = 5.3%, sd(e) / e ~ 2.7%, sd of a ratio of two ~ 3.8%; 4 sd = 15%.
// Band: 2 x 0.85 = 1.7 <= e(N) / e(4N) <= 4 x 1.15 = 4.6. A biased reference (an error floor) drives the
// ratio towards 1; a sample count that does not reach the pass leaves e(N) flat.
TEST_CASE("the reference's error against a 4x-sample render falls like 1/sqrt(N)") {
    emcv::gl::context ctx = emcv::test::context_or_skip();
    emcv::gl::debug_messenger messenger;
    const scene s = emcv::test::sphere_on_floor();
    std::vector<double> errors;
    for (int n : {16, 64, 256, 1024}) {
        const double e = rms_difference(render_reference(s, n, 1u), render_reference(s, 4 * n, 2u));
        errors.push_back(e);
        UNSCOPED_INFO("N " << n << ": RMS difference to 4N " << e);
    }
    for (std::size_t i = 0; i + 1 < errors.size(); ++i) {
        const double ratio = errors[i] / errors[i + 1];
        INFO("e(N) / e(4N) = " << ratio);
        CHECK(ratio >= 1.7);
        CHECK(ratio <= 4.6);
    }
    CHECK(messenger.error_count() == 0);
}
