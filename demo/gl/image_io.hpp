// SPDX-License-Identifier: MIT
// Readback of GL textures into float buffers and image output through OpenImageIO: EXR keeps linear
// floats, PNG gets the sRGB display encoding, clamped to [0, 1] and quantised to 8 bits.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <vector>

#include "gl.hpp"

namespace emcv::gl {

struct float_image {
    int width = 0;
    int height = 0;
    int channels = 0;
    std::vector<float> pixels;  ///< row-major, bottom row first (GL order), channels interleaved
};

class image_error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// glGetTextureImage of level 0 as GL_RGBA / GL_FLOAT (4 channels).
float_image read_texture_rgba32f(GLuint texture, int width, int height);

/// Writes the image: ".exr" linear half/float, ".png" sRGB 8-bit; the format follows the extension.
/// Writes to a temporary sibling and renames it, so a failure leaves no half-written file. Throws image_error.
void write_image(const std::filesystem::path& path, const float_image& image);

/// Reads any image OpenImageIO reads, as floats (bottom row first, like write_image expects).
float_image read_image(const std::filesystem::path& path);

/// The sRGB transfer function (IEC 61966-2-1) of one linear value in [0, 1].
float linear_to_srgb(float linear) noexcept;

}  // namespace emcv::gl
