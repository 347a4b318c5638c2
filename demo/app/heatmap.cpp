// SPDX-License-Identifier: MIT
#include "heatmap.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace emcv::demo::app {

image::float_image sample_heatmap(const image::float_image& counts, float max_count) {
    // Stops evenly spaced over [0, max_count]: black, blue, green, yellow, red.
    static constexpr std::array<std::array<float, 3>, 5> stops = {
        {{0.0f, 0.0f, 0.0f}, {0.1f, 0.2f, 1.0f}, {0.1f, 0.8f, 0.2f}, {1.0f, 0.9f, 0.1f}, {1.0f, 0.1f, 0.1f}}};
    image::float_image out;
    out.width = counts.width;
    out.height = counts.height;
    out.channels = 4;
    const std::size_t n = static_cast<std::size_t>(counts.width) * static_cast<std::size_t>(counts.height);
    out.pixels.resize(n * 4);
    const float scale = max_count > 0.0f ? 1.0f / max_count : 0.0f;
    for (std::size_t p = 0; p < n; ++p) {
        const float v = counts.pixels[p * static_cast<std::size_t>(counts.channels)];
        const float t = std::clamp(std::isfinite(v) ? v * scale : 1.0f, 0.0f, 1.0f) * float(stops.size() - 1);
        const std::size_t i = std::min(static_cast<std::size_t>(t), stops.size() - 2);
        const float f = t - static_cast<float>(i);
        for (std::size_t c = 0; c < 3; ++c) out.pixels[p * 4 + c] = stops[i][c] + f * (stops[i + 1][c] - stops[i][c]);
        out.pixels[p * 4 + 3] = 1.0f;
    }
    return out;
}

}  // namespace emcv::demo::app
