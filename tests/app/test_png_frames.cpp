// SPDX-License-Identifier: MIT
// emcv-demo's frame files hold the renderer's display image as it is: the composite pass has already
// tonemapped and sRGB-encoded it, so the PNG must store those values (within one 8-bit step), not encode them
// a second time; the EXR keeps the linear radiance exactly.
#include <catch2/catch_test_macros.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <string>

#include "../gpu/gl_test_support.hpp"
#include "../support/run_command.hpp"
#include "gl/image_io.hpp"
#include "render/renderer.hpp"
#include "scene/load.hpp"

namespace fs = std::filesystem;

namespace {

const std::string data_dir = EMCV_APP_TEST_DATA;
constexpr int width = 40, height = 32;
constexpr std::uint32_t seed = 7;

fs::path scratch_dir(const std::string& name) {
    const fs::path dir = fs::temp_directory_path() / ("emcv-app-png-" + name);
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

/// Frame 0 of tests/app/data/tiny.json with `method_name`, as emcv-demo renders it (same size and seed).
emcv::gl::float_image render_display(const std::string& method_name, emcv::gl::float_image* linear = nullptr) {
    const emcv::demo::scene s = emcv::demo::load_scene_argument(data_dir + "/tiny.json");
    emcv::demo::render_options o;
    o.width = width;
    o.height = height;
    o.seed = seed;
    emcv::demo::renderer r(s, *emcv::demo::parse_method(method_name), o);
    r.render(0);
    if (linear) *linear = r.linear();
    return r.display();
}

/// Largest |file - display| over the colour channels, in 8-bit steps; and how many colour values of the
/// display image are mid-tones, where a second sRGB encoding moves a value by many steps (so the comparison
/// can tell the two apart at all).
struct difference {
    float max_steps = 0.0f;
    std::size_t mid_tones = 0;
};

difference compare_colour(const emcv::gl::float_image& file, const emcv::gl::float_image& display) {
    REQUIRE(file.width == display.width);
    REQUIRE(file.height == display.height);
    REQUIRE(file.channels >= 3);
    const auto fc = static_cast<std::size_t>(file.channels), dc = static_cast<std::size_t>(display.channels);
    const std::size_t pixels = static_cast<std::size_t>(file.width) * static_cast<std::size_t>(file.height);
    difference d;
    for (std::size_t p = 0; p < pixels; ++p)
        for (std::size_t c = 0; c < 3; ++c) {
            const float want = display.pixels[p * dc + c];
            d.max_steps = std::max(d.max_steps, std::fabs(file.pixels[p * fc + c] - want) * 255.0f);
            d.mid_tones += want > 0.1f && want < 0.8f ? 1u : 0u;
        }
    return d;
}

}  // namespace

TEST_CASE("a frame written as PNG reads back as the display image, and as EXR as the linear image", "[app][gl]") {
    auto ctx = emcv::test::context_or_skip();
    emcv::gl::float_image linear;
    const emcv::gl::float_image display = render_display("burley-4", &linear);
    const fs::path dir = scratch_dir("in-process");

    emcv::gl::write_image(dir / "frame.png", display);
    const difference d = compare_colour(emcv::gl::read_image(dir / "frame.png"), display);
    INFO("largest difference " << d.max_steps << " steps, " << d.mid_tones << " mid-tone values");
    CHECK(d.mid_tones > 100);
    CHECK(d.max_steps <= 1.0f + 1e-3f);

    emcv::gl::write_image(dir / "frame.exr", linear);
    const emcv::gl::float_image exr = emcv::gl::read_image(dir / "frame.exr");
    CHECK(exr.pixels == linear.pixels);
    fs::remove_all(dir);
}

TEST_CASE("emcv-demo --out writes frame PNGs that hold the display image unchanged", "[app][gl]") {
    auto ctx = emcv::test::context_or_skip();
    const emcv::gl::float_image display = render_display("diffuse");
    const fs::path out = scratch_dir("demo") / "out";
    const emcv_test::command_result r = emcv_test::run_command(
        "'" + std::string(EMCV_DEMO_EXE) + "' --scene '" + data_dir + "/tiny.json' --method diffuse --frames 1 --size " +
        std::to_string(width) + "x" + std::to_string(height) + " --seed " + std::to_string(seed) + " --out '" +
        out.string() + "'");
    if (emcv_test::no_display(r)) emcv::test::skip_without_gl("emcv-demo: " + r.err);
    INFO(r.err << r.out);
    REQUIRE(r.exit_code == 0);
    const difference d = compare_colour(emcv::gl::read_image(out / "diffuse" / "frame-0000.png"), display);
    INFO("largest difference " << d.max_steps << " steps, " << d.mid_tones << " mid-tone values");
    CHECK(d.mid_tones > 100);
    CHECK(d.max_steps <= 1.0f + 1e-3f);
    fs::remove_all(out.parent_path());
}
