// SPDX-License-Identifier: MIT
// Every method renders every scene (the built-in scenes, and scenes built in code) without a GL error, NaN or
// Inf, with display values in [0, 1], at 64x48 on llvmpipe.
#include <catch2/catch_test_macros.hpp>

#include <algorithm>
#include <vector>

#include "../gpu/gl_test_support.hpp"
#include "gl/debug.hpp"
#include "render/renderer.hpp"
#include "render_test_support.hpp"
#include "scene/load.hpp"

using namespace emcv::demo;

namespace {

std::vector<scene> scenes_under_test() {
    std::vector<scene> scenes{emcv::test::sphere_on_floor(), emcv::test::lit_sss_plane(2.0f), emcv::test::no_sss(),
                              emcv::test::sss_outside_view()};
    for (const std::string& name : builtin_scene_names()) scenes.push_back(load_scene_argument(name));
    return scenes;
}

}  // namespace

TEST_CASE("every method renders every scene without GL errors, NaN or Inf") {
    emcv::gl::context ctx = emcv::test::context_or_skip();
    emcv::gl::debug_messenger messenger;
    std::vector<method> methods = all_methods();
    methods.push_back(*parse_method("burley-1"));
    methods.push_back(*parse_method("separable-11"));
    methods.push_back(*parse_method("separable-25"));
    for (const scene& s : scenes_under_test()) {
        for (const method& m : methods) {
            for (bool approximate : {false, true}) {
                if (approximate && m.type != method::kind::burley) continue;
                INFO("scene " << s.name << ", method " << m.name() << (approximate ? ", SPVG inverse CDF" : ""));
                render_options options;
                options.width = 64;
                options.height = 48;
                options.seed = 7;
                options.approximate_inverse_cdf = approximate;
                renderer r(s, m, options);
                for (int frame = 0; frame < 2; ++frame) {
                    const frame_stats& stats = r.render(frame);
                    CHECK(stats.frame_ms >= stats.sss_ms);
                    if (stats.sss_pixels > 0 && m.type == method::kind::burley) {
                        CHECK(stats.mean_spp == m.samples);
                        CHECK(stats.max_spp == m.samples);
                    }
                }
                const emcv::gl::float_image linear = r.linear();
                const emcv::gl::float_image display = r.display();
                CHECK(emcv::test::count_non_finite(linear) == 0);
                CHECK(emcv::test::count_non_finite(display) == 0);
                CHECK(std::all_of(display.pixels.begin(), display.pixels.end(),
                                  [](float v) { return v >= 0.0f && v <= 1.0f; }));
                CHECK(messenger.error_count() == 0);
            }
        }
    }
}
