// SPDX-License-Identifier: MIT
// The heatmap PNGs explain themselves (docs/demo.md, Outputs): written and read back, the file is the heatmap
// with a 32-row legend below it, at least 192 pixels wide; the colour bar runs from black at the left edge to
// red at the right edge through the documented stop colours at the tick columns; white ticks sit under the bar
// at those columns only; the scale text is drawn (and left out, nothing else changed, when the font is
// missing); the file's ImageDescription names the quantity, the range and the tick colours. The expected
// numbers and colours are docs/demo.md's, typed here, not read from heatmap.hpp.
#include <catch2/catch_test_macros.hpp>

#include <array>
#include <cmath>
#include <filesystem>
#include <string>

#include "heatmap.hpp"
#include "image/image_file.hpp"

namespace fs = std::filesystem;
using emcv::image::float_image;

namespace {

using rgb = std::array<float, 3>;

/// docs/demo.md's colour stops (the ticks): black, blue, green, yellow, red.
constexpr std::array<rgb, 5> documented_stops = {
    {{0.0f, 0.0f, 0.0f}, {0.1f, 0.2f, 1.0f}, {0.1f, 0.8f, 0.2f}, {1.0f, 0.9f, 0.1f}, {1.0f, 0.1f, 0.1f}}};
constexpr int legend_rows = 32;  // 2 gap, 12 bar, 4 ticks, 14 text
constexpr int legend_min_width = 192;

fs::path scratch(const std::string& name) {
    const fs::path dir = fs::temp_directory_path() / "emcv-app-heatmap-png";
    fs::create_directories(dir);
    return dir / name;
}

/// A one-channel image: every pixel `value`.
float_image uniform(int width, int height, float value) {
    float_image v{width, height, 1, {}};
    v.pixels.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), value);
    return v;
}

/// RGB of the pixel at column x, row y counted from the top (read_image keeps GL's bottom-first rows).
rgb at(const float_image& image, int x, int y_from_top) {
    const std::size_t row = static_cast<std::size_t>(image.height - 1 - y_from_top);
    const std::size_t p = (row * static_cast<std::size_t>(image.width) + static_cast<std::size_t>(x)) *
                          static_cast<std::size_t>(image.channels);
    return {image.pixels[p], image.pixels[p + 1], image.pixels[p + 2]};
}

bool near(const rgb& a, const rgb& b, float tolerance) {
    for (std::size_t c = 0; c < 3; ++c)
        if (!(std::abs(a[c] - b[c]) <= tolerance)) return false;
    return true;
}

/// Writes the heatmap PNG of `values` the way emcv-demo does and reads it back.
float_image written(const emcv::demo::app::heatmap_png& png, const std::string& name) {
    const fs::path path = scratch(name);
    emcv::image::write_image(path, png.image, png.description);
    return emcv::image::read_image(path);
}

}  // namespace

TEST_CASE("a heatmap PNG is its heatmap above a 32-row legend, at least 192 pixels wide",
          "[app][heatmap][image-files]") {
    using namespace emcv::demo::app;
    // Top-left pixel at the top of the scale, the rest 0: the heatmap keeps its place and orientation.
    float_image values = uniform(64, 64, 0.0f);
    values.pixels[static_cast<std::size_t>(63 * 64)] = 64.0f;  // bottom-first rows: the last row is the top
    const float_image image = written(heatmap_with_legend(values, samples_heatmap_scale), "place.png");
    CHECK(image.width == legend_min_width);
    CHECK(image.height == 64 + legend_rows);
    CHECK(near(at(image, 0, 0), documented_stops[4], 1.0f / 255));
    CHECK(near(at(image, 1, 0), documented_stops[0], 0.0f));
    CHECK(near(at(image, 100, 0), documented_stops[0], 0.0f));  // beside a narrower heatmap: black

    // Wider than the legend's minimum: the width stays.
    const float_image wide = written(heatmap_with_legend(uniform(256, 40, 1.0f), alpha_heatmap_scale), "wide.png");
    CHECK(wide.width == 256);
    CHECK(wide.height == 40 + legend_rows);
}

TEST_CASE("the colour bar follows the colour map at its ticks, black at the left, red at the right",
          "[app][heatmap][image-files]") {
    using namespace emcv::demo::app;
    for (int width : {64, 300}) {
        INFO("heatmap width " << width);
        const auto png = heatmap_with_legend(uniform(width, 64, 0.0f), samples_heatmap_scale);
        const float_image image = written(png, "bar.png");
        const int w = image.width;
        const int bar_middle = 64 + 2 + 6, tick_row = 64 + 2 + 12 + 1;
        for (int k = 0; k < 5; ++k) {
            // Tick k at the column nearest k/4 of the way across: the bar there shows stop k, within the 8-bit
            // rounding and the bar's slope over the half column the tick may be off.
            const int x = static_cast<int>(std::lround((w - 1) * k / 4.0));
            INFO("tick " << k << " at column " << x);
            CHECK(near(at(image, x, bar_middle), documented_stops[static_cast<std::size_t>(k)], 0.03f));
            CHECK(near(at(image, x, tick_row), {1.0f, 1.0f, 1.0f}, 0.0f));
            // Between two ticks: no mark.
            if (k < 4) CHECK(near(at(image, (x + static_cast<int>(std::lround((w - 1) * (k + 1) / 4.0))) / 2, tick_row),
                                  {0.0f, 0.0f, 0.0f}, 0.0f));
        }
        // The bar's values grow left to right: its red channel never falls before the last stop's plateau.
        for (int x = 1; x < w; ++x) CHECK(at(image, x, bar_middle)[0] >= at(image, x - 1, bar_middle)[0]);
    }
}

TEST_CASE("the scale text is drawn below the ticks, and left out when the font is missing",
          "[app][heatmap][image-files]") {
    using namespace emcv::demo::app;
    const auto lit_in_text_band = [](const float_image& image) {
        int lit = 0;
        for (int y = image.height - 14; y < image.height; ++y)
            for (int x = 0; x < image.width; ++x) lit += at(image, x, y)[0] > 0.5f ? 1 : 0;
        return lit;
    };
    const auto with_font = heatmap_with_legend(uniform(64, 64, 32.0f), samples_heatmap_scale);
    REQUIRE(with_font.text_drawn);  // needs fonts-dejavu-core (scripts/install-deps.sh)
    CHECK(lit_in_text_band(written(with_font, "text.png")) > 50);

    const auto without = heatmap_with_legend(uniform(64, 64, 32.0f), samples_heatmap_scale, "emcv-no-such-font");
    CHECK_FALSE(without.text_drawn);
    const float_image image = written(without, "no-text.png");
    CHECK(lit_in_text_band(image) == 0);
    CHECK(near(at(image, image.width - 1, 64 + 2 + 6), documented_stops[4], 1.0f / 255));  // the bar is still there
    CHECK(without.description == with_font.description);
}

TEST_CASE("a heatmap PNG's ImageDescription names the quantity, its range and the tick colours",
          "[app][heatmap][image-files]") {
    using namespace emcv::demo::app;
    const fs::path samples = scratch("samples-description.png");
    const auto s = heatmap_with_legend(uniform(64, 64, 8.0f), samples_heatmap_scale);
    emcv::image::write_image(samples, s.image, s.description);
    const std::string read_back = emcv::image::read_image_description(samples);
    INFO(read_back);
    CHECK(read_back.find("N 0..64 (samples per pixel)") != std::string::npos);
    CHECK(read_back.find("0 black, 16 blue, 32 green, 48 yellow, 64 red") != std::string::npos);

    const fs::path alpha = scratch("alpha-description.png");
    const auto a = heatmap_with_legend(uniform(64, 64, 1.0f), alpha_heatmap_scale);
    emcv::image::write_image(alpha, a.image, a.description);
    const std::string alpha_back = emcv::image::read_image_description(alpha);
    INFO(alpha_back);
    CHECK(alpha_back.find("alpha 0..2;") != std::string::npos);
    CHECK(alpha_back.find("0 black, 0.5 blue, 1 green, 1.5 yellow, 2 red") != std::string::npos);

    // A frame written without a description has none.
    const fs::path plain = scratch("plain.png");
    emcv::image::write_image(plain, s.image);
    CHECK(emcv::image::read_image_description(plain).empty());
}
