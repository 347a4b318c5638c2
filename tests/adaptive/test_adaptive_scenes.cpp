// SPDX-License-Identifier: MIT
// The adaptive methods' behaviours in the renderer, on llvmpipe at CI sizes with fixed seeds (these are
// behaviours of the algorithm, not timings):
//   light switch  an SSS sphere whose key light switches off: over the 30 frames from the switch, cv takes at
//                 most 1/2.5 of spvg's samples (the paper's x2.5) at a PSNR within 1.5 dB of spvg's (issue 9;
//                 cv's settling floor, docs/renderer.md "Settling after a change"); cv-notex only the samples
//                 bound (alpha = 1 cannot tell a change from noise, so it has no settling floor)
//   static        the same scene with a constant light: cv's mean N within 10% of spvg's, PSNR within 0.5 dB
//   far           the built-in `far` scene (every kernel under a pixel): cv and cv-notex take 0 samples
// PSNR as emcv-demo reports it: display images (tonemapped, sRGB) against the reference's, per frame, averaged.
// The switch uses a sphere built in code rather than the built-in light-off, so that its bounds do not follow the
// demo's scene choices (light-off's key light now changes most of its SSS pixels too: docs/scenes.md).
#include <catch2/catch_test_macros.hpp>

#include <cmath>
#include <vector>

#include "../gpu/gl_test_support.hpp"
#include "../render/render_test_support.hpp"
#include "gl/debug.hpp"
#include "render/renderer.hpp"
#include "scene/load.hpp"

using namespace emcv::demo;

namespace {

constexpr int test_width = 64, test_height = 48;

struct run_result {
    std::vector<double> mean_spp;
    std::vector<std::size_t> sss_pixels;
    std::vector<emcv::gl::float_image> display;
};

run_result render_all(const scene& s, const char* method_name, int frames) {
    render_options o;
    o.width = test_width;
    o.height = test_height;
    o.seed = 7;
    renderer r(s, *parse_method(method_name), o);
    run_result out;
    for (int f = 0; f < frames; ++f) {
        const frame_stats& st = r.render(f);
        out.mean_spp.push_back(st.mean_spp);
        out.sss_pixels.push_back(st.sss_pixels);
        out.display.push_back(r.display());
    }
    return out;
}

double psnr(const emcv::gl::float_image& a, const emcv::gl::float_image& b) {
    double se = 0.0;
    std::size_t n = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) {
        if (i % 4 == 3) continue;  // alpha
        const double d = double(a.pixels[i]) - double(b.pixels[i]);
        se += d * d;
        ++n;
    }
    return se > 0.0 ? 10.0 * std::log10(double(n) / se) : 200.0;
}

double mean_over(const std::vector<double>& v, int first, int last) {
    double s = 0.0;
    for (int i = first; i < last; ++i) s += v[std::size_t(i)];
    return s / double(last - first);
}

double mean_psnr(const run_result& r, const run_result& ref, int first, int last) {
    double s = 0.0;
    for (int i = first; i < last; ++i) s += psnr(r.display[std::size_t(i)], ref.display[std::size_t(i)]);
    return s / double(last - first);
}

/// The render tests' SSS sphere on a floor, shadows off, the key light switching off at `switch_frame`
/// (steps 3 -> 0), the spot light on.
scene switching_sphere(int switch_frame) {
    scene s = emcv::test::sphere_on_floor();
    for (light& l : s.lights) l.casts_shadow = false;
    s.lights[0].intensity.type = curve::kind::steps;
    s.lights[0].intensity.value = 3.0f;
    if (switch_frame >= 0) s.lights[0].intensity.steps = {{switch_frame, 0.0f}};
    return s;
}

}  // namespace

namespace {

struct switch_measurement {
    double n_spvg, n_cv, n_notex, db_spvg, db_cv, db_notex;
};

/// spvg, cv and cv-notex over the 30 frames from the key light's switch (frame 20), against the reference.
const switch_measurement& measure_switch() {
    static const switch_measurement m = [] {
        constexpr int switch_frame = 20, frames = switch_frame + 30;
        const scene s = switching_sphere(switch_frame);
        const run_result spvg = render_all(s, "spvg", frames), cv = render_all(s, "cv", frames),
                         notex = render_all(s, "cv-notex", frames), ref = render_all(s, "reference", frames);
        return switch_measurement{mean_over(spvg.mean_spp, switch_frame, frames),
                                  mean_over(cv.mean_spp, switch_frame, frames),
                                  mean_over(notex.mean_spp, switch_frame, frames),
                                  mean_psnr(spvg, ref, switch_frame, frames),
                                  mean_psnr(cv, ref, switch_frame, frames),
                                  mean_psnr(notex, ref, switch_frame, frames)};
    }();
    return m;
}

}  // namespace

TEST_CASE("light switch: cv takes at most 1/2.5 of spvg's samples in the 30 frames after it, within 1.5 dB") {
    emcv::gl::context ctx = emcv::test::context_or_skip();
    emcv::gl::debug_messenger messenger;
    const switch_measurement& m = measure_switch();
    INFO("after the switch: spvg " << m.n_spvg << " spp, " << m.db_spvg << " dB; cv " << m.n_cv << " spp, "
                                   << m.db_cv << " dB; cv-notex " << m.n_notex << " spp, " << m.db_notex << " dB");
    CHECK(m.n_spvg > 16.0);  // SPVG reads the switch as noise: its count jumps
    CHECK(m.n_cv <= m.n_spvg / 2.5);
    CHECK(m.db_cv >= m.db_spvg - 1.5);
    CHECK(m.n_cv > 8.5);  // the settling floor acts: cv spends above the static floor after the change
    CHECK(m.n_notex <= m.n_spvg / 2.5);
    CHECK(messenger.error_count() == 0);
}

TEST_CASE("static light: cv's mean N is within 10% of spvg's and its PSNR within 0.5 dB") {
    emcv::gl::context ctx = emcv::test::context_or_skip();
    emcv::gl::debug_messenger messenger;
    constexpr int frames = 24, settled = 4;
    const scene s = switching_sphere(-1);
    const run_result spvg = render_all(s, "spvg", frames), cv = render_all(s, "cv", frames),
                     ref = render_all(s, "reference", frames);
    const double n_spvg = mean_over(spvg.mean_spp, settled, frames), n_cv = mean_over(cv.mean_spp, settled, frames);
    const double db_spvg = mean_psnr(spvg, ref, settled, frames), db_cv = mean_psnr(cv, ref, settled, frames);
    INFO("static: spvg " << n_spvg << " spp, " << db_spvg << " dB; cv " << n_cv << " spp, " << db_cv << " dB");
    CHECK(std::fabs(db_cv - db_spvg) <= 0.5);
    CHECK(std::fabs(n_cv - n_spvg) <= 0.10 * n_spvg);  // issue 9: no under- (nor over-) sampling
    CHECK(messenger.error_count() == 0);
}

TEST_CASE("far: every kernel is under a pixel, cv and cv-notex take 0 samples") {
    emcv::gl::context ctx = emcv::test::context_or_skip();
    emcv::gl::debug_messenger messenger;
    const scene s = load_scene_argument("far");
    for (const char* m : {"cv", "cv-notex"}) {
        INFO("method " << m);
        const run_result r = render_all(s, m, 4);
        for (std::size_t f = 0; f < r.mean_spp.size(); ++f) {
            CHECK(r.sss_pixels[f] > 0);  // the head is on screen: its pixels exist and take no samples
            CHECK(r.mean_spp[f] == 0.0);
        }
    }
    const run_result spvg = render_all(s, "spvg", 4);
    CHECK(spvg.mean_spp.back() >= 8.0);  // SPVG's floor: the pixels exist and SPVG samples them
    CHECK(messenger.error_count() == 0);
}
