// SPDX-License-Identifier: MIT
// Image files as float buffers, through OpenImageIO. Values are stored as they are, with no colour transfer:
// an EXR keeps the floats (linear data stays linear), a PNG holds the same values clamped to [0, 1] and
// quantised to 8 bits, so what goes into a PNG must already be display-encoded (the renderer's display image
// is; a linear image is not and belongs in an EXR).
#pragma once

#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <vector>

namespace emcv::image {

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

/// One value as a PNG stores it: clamped to [0, 1], then round(v * 255). NaN stores 0.
std::uint8_t quantise_unorm8(float value) noexcept;

/// Writes the image, the format following the extension: ".exr" the floats unchanged, ".png" every channel
/// (alpha included) through quantise_unorm8, no transfer function. Writes to a temporary sibling and renames
/// it, so a failure leaves no half-written file. Throws image_error.
void write_image(const std::filesystem::path& path, const float_image& image);

/// Reads any image OpenImageIO reads, as floats (bottom row first, like write_image expects), values as stored:
/// 8-bit channels become n / 255, no transfer function. Throws image_error.
float_image read_image(const std::filesystem::path& path);

}  // namespace emcv::image
