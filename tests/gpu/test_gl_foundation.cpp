// SPDX-License-Identifier: MIT
// demo/gl foundation pieces that need a context: readback into floats and image output through OpenImageIO
// (EXR exact, PNG the same values quantised to 8 bits with no colour transfer, no half-written file on
// error), the GPU timer ring, RAII handles.
#include <catch2/catch_test_macros.hpp>
#include <catch2/matchers/catch_matchers_string.hpp>

#include <cmath>
#include <filesystem>

#include "gl/debug.hpp"
#include "gl/handles.hpp"
#include "gl/image_io.hpp"
#include "gl/program.hpp"
#include "gl/timer.hpp"
#include "gl_test_support.hpp"

namespace fs = std::filesystem;
using Catch::Matchers::ContainsSubstring;

TEST_CASE("a texture reads back into floats and round-trips through EXR exactly and PNG quantised, no transfer", "[image-files]") {
    auto ctx = emcv::test::context_or_skip();
    emcv::gl::debug_messenger debug;
    constexpr int w = 8, h = 4;
    auto tex = emcv::gl::texture_2d::create();
    glTextureStorage2D(tex.id(), 1, GL_RGBA32F, w, h);
    std::vector<float> texels(w * h * 4);
    for (std::size_t i = 0; i < texels.size(); ++i) texels[i] = static_cast<float>(i) / static_cast<float>(texels.size());
    glTextureSubImage2D(tex.id(), 0, 0, 0, w, h, GL_RGBA, GL_FLOAT, texels.data());
    const auto img = emcv::gl::read_texture_rgba32f(tex.id(), w, h);
    REQUIRE(debug.error_count() == 0);
    REQUIRE(img.pixels == texels);

    const fs::path dir = fs::current_path() / "gl_foundation_out";
    fs::create_directories(dir);
    emcv::gl::write_image(dir / "roundtrip.exr", img);
    const auto exr = emcv::gl::read_image(dir / "roundtrip.exr");
    CHECK(exr.width == w);
    CHECK(exr.height == h);
    CHECK(exr.pixels == texels);  // float EXR: exact, rows in GL order

    emcv::gl::write_image(dir / "roundtrip.png", img);
    const auto png = emcv::gl::read_image(dir / "roundtrip.png");
    REQUIRE(png.pixels.size() == texels.size());
    for (std::size_t i = 0; i < texels.size(); ++i) {
        // Colour and alpha alike: the stored byte is the value itself, rounded (a transfer would move it).
        const float want = static_cast<float>(emcv::image::quantise_unorm8(texels[i])) / 255.0f;
        REQUIRE(std::fabs(png.pixels[i] - want) <= 1e-6f);
        REQUIRE(std::fabs(png.pixels[i] - texels[i]) <= 0.5f / 255.0f + 1e-6f);
    }
    for (const auto& e : fs::directory_iterator(dir)) CHECK(e.path().string().find(".tmp") == std::string::npos);
}

TEST_CASE("PNG quantisation clamps to [0, 1], rounds to the nearest step and stores NaN as 0") {
    using emcv::image::quantise_unorm8;
    CHECK(quantise_unorm8(0.0f) == 0);
    CHECK(quantise_unorm8(1.0f) == 255);
    CHECK(quantise_unorm8(-0.5f) == 0);
    CHECK(quantise_unorm8(7.0f) == 255);
    CHECK(quantise_unorm8(0.5f) == 128);  // 127.5 rounds away from zero
    CHECK(quantise_unorm8(0.5f / 255.0f - 1e-4f) == 0);
    CHECK(quantise_unorm8(100.0f / 255.0f) == 100);  // a display byte read back is stored as itself
    CHECK(quantise_unorm8(std::nanf("")) == 0);
}

TEST_CASE("image output errors are clear and leave no file", "[image-files]") {
    emcv::gl::float_image img{2, 2, 4, std::vector<float>(16, 0.5f)};
    const fs::path dir = fs::current_path() / "gl_foundation_out";
    fs::create_directories(dir);
    CHECK_THROWS_WITH(emcv::gl::write_image(dir / "bad.tiff_unknown", img), ContainsSubstring("unsupported extension"));
    CHECK_FALSE(fs::exists(dir / "bad.tiff_unknown"));
    img.pixels.pop_back();
    CHECK_THROWS_WITH(emcv::gl::write_image(dir / "short.exr", img), ContainsSubstring("pixel count"));
    CHECK_FALSE(fs::exists(dir / "short.exr"));
    img.pixels.push_back(0.5f);
    CHECK_THROWS_AS(emcv::gl::write_image(dir / "no_such_dir" / "x.exr", img), emcv::gl::image_error);
    CHECK_FALSE(fs::exists(dir / "no_such_dir"));
    CHECK_THROWS_AS(emcv::gl::read_image(dir / "missing.exr"), emcv::gl::image_error);
}

TEST_CASE("the GPU timer ring returns one measurement per begin/end and never blocks in pop") {
    auto ctx = emcv::test::context_or_skip();
    emcv::gl::debug_messenger debug;
    emcv::gl::gpu_timer timer(2);
    CHECK_FALSE(timer.pop_ms().has_value());
    for (int i = 0; i < 3; ++i) {  // the third begin finds the 2-slot ring full and is dropped, not stalled
        timer.begin();
        glFinish();
        timer.end();
    }
    const auto times = timer.drain_ms();
    CHECK(times.size() == 2);
    for (double t : times) CHECK(t >= 0.0);
    CHECK(debug.error_count() == 0);
}

TEST_CASE("RAII handles are move-only owners") {
    auto ctx = emcv::test::context_or_skip();
    emcv::gl::debug_messenger debug;
    auto a = emcv::gl::buffer::create();
    const GLuint id = a.id();
    REQUIRE(glIsBuffer(id));
    emcv::gl::buffer b = std::move(a);
    CHECK(a.id() == 0u);
    CHECK(b.id() == id);
    b.reset();
    CHECK_FALSE(glIsBuffer(id));
    CHECK(debug.error_count() == 0);
}
