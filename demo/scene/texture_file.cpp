// SPDX-License-Identifier: MIT
#include "texture_file.hpp"

#include <algorithm>
#include <cmath>

#include "image/image_file.hpp"

namespace emcv::demo {

float srgb_to_linear(float encoded) noexcept {
    const float c = std::clamp(encoded, 0.0f, 1.0f);
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

texture read_texture_file(const std::filesystem::path& path) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) throw texture_file_error("texture file not found: " + path.string());
    image::float_image file;
    try {
        file = image::read_image(path);
    } catch (const std::exception& e) {
        throw texture_file_error(std::string("cannot read texture: ") + e.what());
    }
    if (file.width <= 0 || file.height <= 0 || file.channels < 1 || file.channels > 4)
        throw texture_file_error("unsupported texture layout (" + std::to_string(file.channels) +
                                 " channels): " + path.string());
    texture t;
    t.path = path;
    t.width = file.width;
    t.height = file.height;
    const auto texels = static_cast<std::size_t>(file.width) * static_cast<std::size_t>(file.height);
    const auto channels = static_cast<std::size_t>(file.channels);
    t.rgba.resize(texels * 4u);
    for (std::size_t i = 0; i < texels; ++i) {
        const float* in = file.pixels.data() + i * channels;
        float* out = t.rgba.data() + i * 4u;
        const bool grey = channels < 3;
        for (std::size_t c = 0; c < 3; ++c) out[c] = srgb_to_linear(in[grey ? 0 : c]);
        const bool has_alpha = channels == 2 || channels == 4;
        out[3] = has_alpha ? std::clamp(in[channels - 1], 0.0f, 1.0f) : 1.0f;
    }
    if (!std::all_of(t.rgba.begin(), t.rgba.end(), [](float x) { return std::isfinite(x); }))
        throw texture_file_error("non-finite texels in " + path.string());
    return t;
}

}  // namespace emcv::demo
