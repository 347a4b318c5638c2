// SPDX-License-Identifier: MIT
// demo/gl foundation pieces that need a context: readback into floats and image output through OpenImageIO
// (EXR exact, PNG the same values quantised to 8 bits with no colour transfer, no half-written file on
// error), the pass timestamps (a fake source for the ring's bookkeeping, then GL's two clocks), RAII handles.
#include <catch2/catch_test_macros.hpp>
#include <catch2/matchers/catch_matchers_string.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <stdexcept>

#include "gl/debug.hpp"
#include "gl/handles.hpp"
#include "gl/image_io.hpp"
#include "gl/program.hpp"
#include "gl/timestamps.hpp"
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

namespace {

/// A timestamp source whose stamps the test writes: stamp i records the "GPU" clock `now`, and a query is
/// ready only once the test has let the GPU reach it (`completed`).
class fake_stamps final : public emcv::gl::timestamp_source {
public:
    struct state {
        std::uint64_t now = 0;
        std::size_t completed = 0;  // stamps in recording order that the GPU has reached
        std::size_t grows = 0;
        std::vector<std::uint64_t> value;  // per query
        std::vector<std::size_t> order;    // per query: its stamp's position in recording order
        std::size_t stamped = 0;
    };
    explicit fake_stamps(std::shared_ptr<state> s) : s_(std::move(s)) {}
    std::size_t size() const override { return s_->value.size(); }
    void grow(std::size_t count) override {
        ++s_->grows;
        s_->value.resize(s_->value.size() + count, 0);
        s_->order.resize(s_->order.size() + count, 0);
    }
    void stamp(std::size_t q) override {
        s_->value.at(q) = s_->now;
        s_->order.at(q) = s_->stamped++;
    }
    bool ready(std::size_t q) override { return s_->order.at(q) < s_->completed; }
    std::uint64_t nanoseconds(std::size_t q) override {
        s_->completed = std::max(s_->completed, s_->order.at(q) + 1);  // waiting lets the GPU reach it
        return s_->value.at(q);
    }

private:
    std::shared_ptr<state> s_;
};

}  // namespace

TEST_CASE("pass timestamps: frames come back in order, each once, with their tags; the ring grows and never drops", "[timestamps]") {
    auto st = std::make_shared<fake_stamps::state>();
    emcv::gl::pass_timestamps stamps(std::make_unique<fake_stamps>(st));
    // 40 frames of 3 passes before the GPU finishes any: 160 stamps in flight, more than the first 16 queries.
    for (int frame = 0; frame < 40; ++frame) {
        stamps.begin_frame(frame);
        for (std::size_t pass = 0; pass < 3; ++pass) {
            st->now += 1'000'000 * (pass + 1) + static_cast<std::uint64_t>(frame);  // pass p lasts (p + 1) ms + frame ns
            stamps.end_pass(10 + pass);
        }
        st->now += 5'000'000;  // between frames: not inside any pass
        stamps.end_frame();
    }
    CHECK(stamps.pending_frames() == 40);
    CHECK(stamps.query_count() >= 160);
    CHECK(st->grows > 1);
    CHECK(stamps.collect(false).empty());  // nothing reached yet: nothing comes back, nothing waits

    st->completed = 4 * 7 + 2;  // the GPU is inside frame 7: frames 0..6 are complete
    std::vector<emcv::gl::timed_frame> got = stamps.collect(false);
    REQUIRE(got.size() == 7);
    CHECK(stamps.collect(false).empty());  // each frame once
    const std::vector<emcv::gl::timed_frame> rest = stamps.collect(true);
    got.insert(got.end(), rest.begin(), rest.end());
    REQUIRE(got.size() == 40);
    CHECK(stamps.pending_frames() == 0);
    for (int frame = 0; frame < 40; ++frame) {
        const emcv::gl::timed_frame& t = got[static_cast<std::size_t>(frame)];
        CHECK(t.frame == frame);
        REQUIRE(t.tags == std::vector<std::size_t>{10, 11, 12});
        REQUIRE(t.ms.size() == 3);
        for (std::size_t pass = 0; pass < 3; ++pass)
            CHECK(t.ms[pass] == static_cast<double>(1'000'000 * (pass + 1) + static_cast<std::uint64_t>(frame)) * 1e-6);
    }

    // Queries are reused once read: a steady stream needs no more.
    const std::size_t queries = stamps.query_count();
    for (int frame = 40; frame < 200; ++frame) {
        stamps.begin_frame(frame);
        stamps.end_pass(0);
        stamps.end_frame();
        st->completed = st->stamped;
        CHECK(stamps.collect(false).size() == 1);
    }
    CHECK(stamps.query_count() == queries);

    // Misuse is an error, not a corrupt frame.
    CHECK_THROWS_AS(stamps.end_pass(0), std::logic_error);
    CHECK_THROWS_AS(stamps.end_frame(), std::logic_error);
    stamps.begin_frame(200);
    CHECK_THROWS_AS(stamps.begin_frame(201), std::logic_error);
    CHECK_THROWS_AS(emcv::gl::pass_timestamps(nullptr), std::invalid_argument);
}

TEST_CASE("GL timestamps and the wall clock both time every pass of every frame, in order", "[timestamps]") {
    auto ctx = emcv::test::context_or_skip();
    emcv::gl::debug_messenger debug;
    auto work = emcv::gl::buffer::create();  // each "pass" clears a 1 MiB buffer (no framebuffer needed)
    glNamedBufferData(work.id(), 1 << 20, nullptr, GL_DYNAMIC_DRAW);
    const float one = 1.0f;
    for (const bool gpu : {true, false}) {
        INFO((gpu ? "GL_TIMESTAMP" : "wall clock"));
        emcv::gl::pass_timestamps stamps(gpu ? emcv::gl::make_gpu_timestamps() : emcv::gl::make_wall_timestamps());
        for (int frame = 0; frame < 30; ++frame) {
            stamps.begin_frame(frame);
            for (std::size_t pass = 0; pass < 2; ++pass) {
                glClearNamedBufferData(work.id(), GL_R32F, GL_RED, GL_FLOAT, &one);
                stamps.end_pass(pass);
            }
            stamps.end_frame();
        }
        std::vector<emcv::gl::timed_frame> got = stamps.collect(false);
        if (!gpu) CHECK(got.size() == 30);  // the wall clock finished every pass: all measured at once
        const std::vector<emcv::gl::timed_frame> rest = stamps.collect(true);
        got.insert(got.end(), rest.begin(), rest.end());
        REQUIRE(got.size() == 30);
        for (int frame = 0; frame < 30; ++frame) {
            CHECK(got[static_cast<std::size_t>(frame)].frame == frame);
            REQUIRE(got[static_cast<std::size_t>(frame)].ms.size() == 2);
            for (double ms : got[static_cast<std::size_t>(frame)].ms) CHECK((ms >= 0.0 && ms < 60'000.0));
        }
    }
    INFO(debug.last_error());
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
