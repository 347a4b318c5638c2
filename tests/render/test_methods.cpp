// SPDX-License-Identifier: MIT
// Every method renders every scene (the built-in scenes, and scenes built in code) without a GL error, NaN or
// Inf, with display values in [0, 1], at 64x48 on llvmpipe.
#include <catch2/catch_test_macros.hpp>
#include <catch2/matchers/catch_matchers_string.hpp>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "../gpu/gl_test_support.hpp"
#include "../support/source_dirs.hpp"
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

/// A fresh copy of shaders/ in the temporary folder under `name`, for a test that edits it (the renderer reads
/// it through render_options::shader_dir).
std::filesystem::path fresh_shader_copy(const std::string& name) {
    const std::filesystem::path copy = std::filesystem::temp_directory_path() / name;
    std::filesystem::remove_all(copy);
    std::filesystem::copy(emcv_test::shader_dir(), copy, std::filesystem::copy_options::recursive);
    return copy;
}

}  // namespace

TEST_CASE("every method renders every scene without GL errors or non-finite values", "[image-files]") {
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
                    CHECK(stats.times.frame == frame);  // the wall clock (default) measures a frame as it renders
                    CHECK(stats.times.frame_ms >= stats.times.sss_ms);
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

TEST_CASE("the reference is reused while its inputs hold and re-rendered when they change") {
    // Frame 0 renders; frame 1 (same camera, same lights) shows it again without an SSS pass; a light switched
    // off (renderer::set_light_scale) changes the inputs, so frame 2 renders again; frame 3 reuses that.
    emcv::gl::context ctx = emcv::test::context_or_skip();
    emcv::gl::debug_messenger messenger;
    const scene s = emcv::test::sphere_on_floor();
    render_options options;
    options.width = 48;
    options.height = 32;
    renderer r(s, make_reference(256), options);
    const auto has_sss_pass = [](const frame_stats& st) {
        return std::any_of(st.times.passes.begin(), st.times.passes.end(), [](const pass_time& p) { return p.name == "sss-burley"; });
    };
    const frame_stats& f0 = r.render(0);
    CHECK_FALSE(f0.reference_reused);
    CHECK(has_sss_pass(f0));
    const emcv::gl::float_image image0 = r.linear();
    const frame_stats& f1 = r.render(1);
    CHECK(f1.reference_reused);
    CHECK_FALSE(has_sss_pass(f1));
    CHECK(f1.times.sss_ms == 0.0);
    CHECK(f1.mean_spp == 256.0);  // the samples that made the image shown
    CHECK(r.linear().pixels == image0.pixels);
    r.set_light_scale(1, 0.0f);
    const frame_stats& f2 = r.render(2);
    CHECK_FALSE(f2.reference_reused);
    CHECK(has_sss_pass(f2));
    CHECK(r.linear().pixels != image0.pixels);
    CHECK(r.render(3).reference_reused);
    CHECK(messenger.error_count() == 0);
}

TEST_CASE("SSS tiles dispatched in many rows render the same image as in one row") {
    // Large frames dispatch the SSS tiles in rows of EMCV_RENDER_TILE_ROW (1024) workgroups; the renderer may
    // only be run at small sizes here, so a copy of shaders/ whose render/bindings.h defines rows of 3 tiles
    // before its own #ifndef default (48 tiles: 16 rows at 64x48) must give the bit-identical image of the
    // default (one row).
    emcv::gl::context ctx = emcv::test::context_or_skip();
    emcv::gl::debug_messenger messenger;
    namespace fs = std::filesystem;
    const fs::path copy = fresh_shader_copy("emcv-test-render-tile-rows");
    const fs::path bindings = copy / "render" / "bindings.h";
    std::string text;
    {
        std::ifstream in(bindings);
        text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
    REQUIRE(!text.empty());
    std::ofstream(bindings) << "#define EMCV_RENDER_TILE_ROW 3\n" << text;

    const scene s = emcv::test::lit_sss_plane(1.0f);
    for (const method& m : {method{method::kind::burley, 8}, method{method::kind::separable, 11}}) {
        render_options options;
        options.width = 64;
        options.height = 48;
        renderer one_row(s, m, options);
        one_row.render(0);
        options.shader_dir = copy;
        renderer many_rows(s, m, options);
        const frame_stats& stats = many_rows.render(0);
        INFO(m.name());
        CHECK(stats.sss_pixels == 64u * 48u);
        CHECK(many_rows.linear().pixels == one_row.linear().pixels);
    }
    fs::remove_all(copy);
    CHECK(messenger.error_count() == 0);
}

TEST_CASE("a renderer compiles only the programs of the passes its scene and method can record") {
    // A copy of shaders/ whose separable, shadow and resolve programs do not compile: a renderer that never
    // records those passes is built and renders; one that can record them fails naming the file, at construction
    // or at the method switch that first needs it. Compiling a program no pass dispatches cost a renderer's
    // construction a third of its time.
    emcv::gl::context ctx = emcv::test::context_or_skip();
    emcv::gl::debug_messenger messenger;
    namespace fs = std::filesystem;
    const fs::path copy = fresh_shader_copy("emcv-test-render-unused-programs");
    const std::vector<std::string> broken{"render/sss_separable.comp.glsl", "render/shadow.frag.glsl",
                                         "render/resolve.comp.glsl"};
    for (const std::string& file : broken) std::ofstream(copy / file, std::ios::app) << "\nnot glsl at all\n";

    const scene plane = emcv::test::lit_sss_plane(1.0f);
    REQUIRE(shadow_casters(plane).empty());
    render_options options;
    options.width = 32;
    options.height = 24;
    options.shader_dir = copy;
    for (const method& m : {method{method::kind::diffuse, 0}, method{method::kind::burley, 4}, method{method::kind::cv, 0}}) {
        INFO(m.name());
        renderer r(plane, m, options);
        CHECK(r.render(0).times.passes.size() >= 3);
    }
    CHECK(messenger.error_count() == 0);  // from here on each failed compile also reports a GL error
    const auto fails_naming = [](const std::string& file) {
        return Catch::Matchers::ContainsSubstring(fs::path(file).filename().string());
    };
    CHECK_THROWS_WITH(renderer(plane, method{method::kind::separable, 11}, options), fails_naming(broken[0]));
    CHECK_THROWS_WITH(renderer(emcv::test::sphere_on_floor(), method{method::kind::burley, 4}, options),
                      fails_naming(broken[1]));
    render_options taa = options;
    taa.resolve = resolve_mode::taa;
    CHECK_THROWS_WITH(renderer(plane, method{method::kind::burley, 4}, taa), fails_naming(broken[2]));
    {  // a method switch builds what the new method records
        renderer r(plane, method{method::kind::burley, 4}, options);
        r.render(0);
        CHECK_THROWS_WITH(r.set_method(method{method::kind::separable, 11}), fails_naming(broken[0]));
        CHECK(r.current_method() == method{method::kind::burley, 4});  // kept: the switch failed before it
        const std::size_t errors = messenger.error_count();
        CHECK(r.render(1).times.passes.size() >= 3);
        CHECK(messenger.error_count() == errors);
    }
    fs::remove_all(copy);
}
