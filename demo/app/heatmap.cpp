// SPDX-License-Identifier: MIT
#include "heatmap.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

namespace emcv::demo::app {
namespace {

/// The colour map's stops, evenly spaced over the scale: black, blue, green, yellow, red (docs/demo.md, Outputs).
constexpr std::array<std::array<float, 3>, heatmap_ticks> stops = {
    {{0.0f, 0.0f, 0.0f}, {0.1f, 0.2f, 1.0f}, {0.1f, 0.8f, 0.2f}, {1.0f, 0.9f, 0.1f}, {1.0f, 0.1f, 0.1f}}};
constexpr std::array<const char*, heatmap_ticks> stop_names = {"black", "blue", "green", "yellow", "red"};

/// The colour of `value`: its place between the stops, linear between neighbours; NaN and Inf are red.
std::array<float, 3> colour_of(float value, const heatmap_scale& scale) {
    const float range = scale.max - scale.min;
    const float u = std::isfinite(value) ? (range > 0.0f ? (value - scale.min) / range : 0.0f) : 1.0f;
    const float t = std::clamp(u, 0.0f, 1.0f) * float(stops.size() - 1);
    const std::size_t i = std::min(static_cast<std::size_t>(t), stops.size() - 2);
    const float f = t - static_cast<float>(i);
    std::array<float, 3> rgb{};
    for (std::size_t c = 0; c < 3; ++c) rgb[c] = stops[i][c] + f * (stops[i + 1][c] - stops[i][c]);
    return rgb;
}

/// A number as the legend writes it: 64, 0.5, 2.
std::string number(float v) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", static_cast<double>(v));
    return text;
}

void fill(image::float_image& image, int x, int y_from_top, const std::array<float, 3>& rgb) {
    const std::size_t y = static_cast<std::size_t>(image.height - 1 - y_from_top);  // rows are bottom first
    float* p = &image.pixels[(y * static_cast<std::size_t>(image.width) + static_cast<std::size_t>(x)) * 4];
    std::copy(rgb.begin(), rgb.end(), p);
    p[3] = 1.0f;
}

}  // namespace

image::float_image sample_heatmap(const image::float_image& values, const heatmap_scale& scale) {
    image::float_image out;
    out.width = values.width;
    out.height = values.height;
    out.channels = 4;
    const std::size_t n = static_cast<std::size_t>(values.width) * static_cast<std::size_t>(values.height);
    out.pixels.resize(n * 4);
    for (std::size_t p = 0; p < n; ++p) {
        const std::array<float, 3> rgb = colour_of(values.pixels[p * static_cast<std::size_t>(values.channels)], scale);
        std::copy(rgb.begin(), rgb.end(), &out.pixels[p * 4]);
        out.pixels[p * 4 + 3] = 1.0f;
    }
    return out;
}

float heatmap_tick(const heatmap_scale& scale, int tick) {
    return scale.min + (scale.max - scale.min) * static_cast<float>(tick) / float(heatmap_ticks - 1);
}

std::string heatmap_scale_text(const heatmap_scale& scale) {
    std::string text = std::string(scale.quantity) + " " + number(scale.min) + ".." + number(scale.max);
    if (*scale.unit != '\0') text += std::string(" (") + scale.unit + ")";
    return text;
}

std::string heatmap_description(const heatmap_scale& scale) {
    std::string text = "heatmap of " + heatmap_scale_text(scale) + "; colour bar along the bottom, min at the left:";
    for (int k = 0; k < heatmap_ticks; ++k)
        text += std::string(k == 0 ? " " : ", ") + number(heatmap_tick(scale, k)) + " " +
                stop_names[static_cast<std::size_t>(k)];
    return text;
}

heatmap_png heatmap_with_legend(const image::float_image& values, const heatmap_scale& scale, const char* font) {
    const image::float_image colours = sample_heatmap(values, scale);
    heatmap_png out;
    image::float_image& image = out.image;
    image.width = std::max(values.width, heatmap_legend_min_width);
    image.height = values.height + heatmap_legend_height;
    image.channels = 4;
    image.pixels.assign(static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height) * 4, 0.0f);
    for (std::size_t p = 3; p < image.pixels.size(); p += 4) image.pixels[p] = 1.0f;  // opaque black

    // The heatmap at the top left: its rows are the image's top rows (both are stored bottom row first).
    const std::size_t heatmap_row = static_cast<std::size_t>(values.width) * 4;
    const std::size_t image_row = static_cast<std::size_t>(image.width) * 4;
    for (std::size_t y = 0; y < static_cast<std::size_t>(values.height); ++y)
        std::copy_n(colours.pixels.begin() + static_cast<std::ptrdiff_t>(y * heatmap_row), heatmap_row,
                    image.pixels.begin() +
                        static_cast<std::ptrdiff_t>((y + static_cast<std::size_t>(heatmap_legend_height)) * image_row));

    // The colour bar: column x shows the value min + (max - min) x / (width - 1), so both ends are stops.
    const int bar_top = values.height + heatmap_gap_height;
    const float last_column = static_cast<float>(std::max(image.width - 1, 1));
    for (int x = 0; x < image.width; ++x) {
        const std::array<float, 3> rgb =
            colour_of(scale.min + (scale.max - scale.min) * static_cast<float>(x) / last_column, scale);
        for (int y = bar_top; y < bar_top + heatmap_bar_height; ++y) fill(image, x, y, rgb);
    }
    // The ticks under the bar at the stops: the column nearest to each tick value.
    const int tick_top = bar_top + heatmap_bar_height;
    for (int k = 0; k < heatmap_ticks; ++k) {
        const int x = static_cast<int>(std::lround(last_column * static_cast<float>(k) / float(heatmap_ticks - 1)));
        for (int y = tick_top; y < tick_top + heatmap_tick_height; ++y) fill(image, x, y, {1.0f, 1.0f, 1.0f});
    }
    // The scale text, its baseline where the font's descenders still fit the band.
    const int text_baseline = tick_top + heatmap_tick_height + heatmap_font_px;
    out.text_drawn = image::draw_text(image, 2, text_baseline, heatmap_scale_text(scale), heatmap_font_px,
                                      image.width - 4, font);
    out.description = heatmap_description(scale);
    return out;
}

}  // namespace emcv::demo::app
