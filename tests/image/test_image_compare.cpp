// SPDX-License-Identifier: MIT
// The comparison harness on images made here: idiff's verdict rules, the reported RMSE against its closed
// form, the failure images, and the errors for bad input. No GL.
#include <catch2/catch_approx.hpp>
#include <catch2/catch_test_macros.hpp>

#include <OpenImageIO/imagebufalgo.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "image_compare.hpp"

namespace fs = std::filesystem;
using emcv::image::compare;
using emcv::image::tolerance;
using emcv::image::verdict;

namespace {

constexpr int width = 32, height = 24, channels = 3;

// A smooth gradient, so no two neighbouring values are equal by accident.
OIIO::ImageBuf gradient() {
    OIIO::ImageBuf buf(OIIO::ImageSpec(width, height, channels, OIIO::TypeDesc::FLOAT));
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const float rgb[channels] = {static_cast<float>(x) / width, static_cast<float>(y) / height, 0.5f};
            buf.setpixel(x, y, rgb);
        }
    return buf;
}

// Adds `delta` to channel 1 of the first `count` pixels (row-major from the top left).
OIIO::ImageBuf perturbed(int count, float delta) {
    OIIO::ImageBuf buf = gradient();
    for (int i = 0; i < count; ++i) {
        float rgb[channels];
        buf.getpixel(i % width, i / width, rgb);
        rgb[1] += delta;
        buf.setpixel(i % width, i / width, rgb);
    }
    return buf;
}

fs::path scratch_dir(const std::string& name) {
    const fs::path dir = fs::temp_directory_path() / ("emcv-test-image-" + std::to_string(::getpid())) / name;
    fs::create_directories(dir);
    return dir;
}

}  // namespace

TEST_CASE("identical images pass, even bit-exactly, with zero error") {
    const auto c = compare(gradient(), gradient(), tolerance::exact());
    CHECK(c.result == verdict::pass);
    CHECK(c.failing == 0);
    CHECK(c.rmse == 0.0);
    CHECK(c.max_error == 0.0);
    CHECK(c.pixels == std::size_t{width * height});
}

TEST_CASE("failing pixels, RMSE and the largest difference are counted like idiff") {
    const int count = 7;
    const float delta = 0.125f;  // exact in binary, so the closed form below is exact too
    tolerance t;
    t.fail = 0.1f;
    t.warn = 0.01f;
    const auto c = compare(perturbed(count, delta), gradient(), t);
    CHECK(c.failing == std::size_t{count});
    CHECK(c.warning == std::size_t{count});
    CHECK(c.max_error == Catch::Approx(delta));
    CHECK(c.max_channel == 1);
    // RMSE over every value of the image: sqrt(count * delta^2 / (pixels * channels)).
    CHECK(c.rmse == Catch::Approx(std::sqrt(count * delta * delta / (width * height * channels))).epsilon(1e-6));
    // A difference below the fail threshold is not a failing pixel, only a warning.
    const auto small = compare(perturbed(count, 0.05f), gradient(), t);
    CHECK(small.failing == 0);
    CHECK(small.warning == std::size_t{count});
}

TEST_CASE("the verdict: fail_percent is the share of failing pixels still accepted") {
    const int count = 6;
    const double allowed_exactly = 100.0 * count / (width * height);
    tolerance t;
    t.fail = 0.1f;
    t.warn = 0.1f;
    t.fail_percent = allowed_exactly;  // idiff fails only when nfail > failpercent * npels
    t.warn_percent = 100.0;
    CHECK(compare(perturbed(count, 0.25f), gradient(), t).result == verdict::pass);
    CHECK(compare(perturbed(count + 1, 0.25f), gradient(), t).result == verdict::fail);
    SECTION("hard_fail fails on one value even when the share is accepted") {
        t.hard_fail = 0.2f;
        CHECK(compare(perturbed(1, 0.25f), gradient(), t).result == verdict::fail);
        CHECK(compare(perturbed(1, 0.15f), gradient(), t).result == verdict::pass);
    }
    SECTION("warnings: too many pixels over warn, none over fail") {
        t.warn = 0.01f;
        t.warn_percent = 0.0;
        CHECK(compare(perturbed(1, 0.05f), gradient(), t).result == verdict::warn);
    }
}

TEST_CASE("bit-exact tolerance catches the smallest representable change") {
    const float one_ulp = std::nextafter(0.5f, 1.0f) - 0.5f;
    OIIO::ImageBuf b = gradient();
    float rgb[channels];
    b.getpixel(3, 4, rgb);
    rgb[2] = std::nextafter(rgb[2], 1.0f);
    b.setpixel(3, 4, rgb);
    const auto c = compare(b, gradient(), tolerance::exact());
    CHECK(c.result == verdict::fail);
    CHECK(c.failing == 1);
    CHECK(c.max_x == 3);
    CHECK(c.max_y == 4);
    CHECK(c.max_error == Catch::Approx(one_ulp));
}

TEST_CASE("images of different shapes are an error naming both shapes, not a verdict") {
    OIIO::ImageBuf smaller(OIIO::ImageSpec(width - 1, height, channels, OIIO::TypeDesc::FLOAT));
    CHECK_THROWS_AS(compare(smaller, gradient(), tolerance{}), emcv::image::compare_error);
    OIIO::ImageBuf grey(OIIO::ImageSpec(width, height, 1, OIIO::TypeDesc::FLOAT));
    try {
        compare(grey, gradient(), tolerance{});
        FAIL("no error for a channel-count mismatch");
    } catch (const emcv::image::compare_error& e) {
        CHECK(std::string(e.what()).find("1 channels") != std::string::npos);
    }
}

TEST_CASE("a missing file is an error naming it") {
    const fs::path missing = scratch_dir("missing") / "nope.png";
    try {
        emcv::image::compare_files(missing, missing, tolerance{});
        FAIL("no error for a missing file");
    } catch (const emcv::image::compare_error& e) {
        CHECK(std::string(e.what()).find(missing.string()) != std::string::npos);
    }
}

TEST_CASE("failure images: actual and expected as given, the difference white where it reaches fail") {
    const fs::path dir = scratch_dir("failure");
    // 8-bit values, so the PNG copies hold them exactly.
    OIIO::ImageBuf expected8;
    expected8.copy(gradient(), OIIO::TypeDesc::UINT8);
    OIIO::ImageBuf actual8;
    actual8.copy(expected8);
    const float changed[channels] = {0.0f, 1.0f, 0.0f};
    actual8.setpixel(5, 2, changed);
    float half_fail[channels];  // channel 0 raised by 13/255, about half of fail: a mid grey in the diff
    actual8.getpixel(10, 3, half_fail);
    half_fail[0] += 13.0f / 255.0f;
    actual8.setpixel(10, 3, half_fail);
    tolerance t;
    t.fail = 0.1f;
    const auto files = emcv::image::write_failure_images(actual8, expected8, t, dir, "case");
    CHECK(files.actual == dir / "case.actual.png");
    CHECK(files.expected == dir / "case.expected.png");
    CHECK(files.diff == dir / "case.diff.png");
    CHECK(compare(emcv::image::read(files.actual), actual8, tolerance::exact()).result == verdict::pass);
    CHECK(compare(emcv::image::read(files.expected), expected8, tolerance::exact()).result == verdict::pass);
    const OIIO::ImageBuf diff = emcv::image::read(files.diff);
    float at_change[channels], elsewhere[channels];
    diff.getpixel(5, 2, at_change);
    diff.getpixel(20, 20, elsewhere);
    CHECK(at_change[1] == 1.0f);  // |1 - g| >= 0.1 = fail: saturated
    float at_half[channels];
    diff.getpixel(10, 3, at_half);
    CHECK(at_half[0] == Catch::Approx(13.0f / 255.0f / t.fail).margin(1.0 / 255.0));
    CHECK(elsewhere[0] == 0.0f);
    CHECK(elsewhere[1] == 0.0f);
    // No temporary sibling is left behind.
    for (const auto& entry : fs::directory_iterator(dir))
        CHECK(entry.path().string().find(".tmp") == std::string::npos);
    fs::remove_all(dir);
}
