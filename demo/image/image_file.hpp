// SPDX-License-Identifier: MIT
// Image files as float buffers, through OpenImageIO (loaded on the first file operation: oiio_module.hpp). Values are stored as they are, with no colour transfer:
// an EXR keeps the floats (linear data stays linear), a PNG holds the same values clamped to [0, 1] and
// quantised to 8 bits, so what goes into a PNG must already be display-encoded (the renderer's display image
// is; a linear image is not and belongs in an EXR).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
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
inline std::uint8_t quantise_unorm8(float value) noexcept {
    if (!(value > 0.0f)) return 0;  // also NaN, which std::clamp would pass through
    return static_cast<std::uint8_t>(std::lround(std::min(value, 1.0f) * 255.0f));
}

/// Makes sure image files can be read and written here: loads the OpenImageIO module now (oiio_module.hpp), so
/// that a run which will write images can refuse before it renders or creates anything. Throws image_error
/// naming the problem (the module missing or broken; a build without OpenImageIO).
void require_image_files();

/// Writes the image, the format following the extension: ".exr" the floats unchanged, ".png" every channel
/// (alpha included) through quantise_unorm8, no transfer function. Writes to a temporary sibling and renames
/// it, so a failure leaves no half-written file. A non-empty `description` is stored as the file's
/// "ImageDescription" (what the image shows; read_image_description returns it). Throws image_error.
void write_image(const std::filesystem::path& path, const float_image& image, const std::string& description = {});

/// Reads any image OpenImageIO reads, as floats (bottom row first, like write_image expects), values as stored:
/// 8-bit channels become n / 255, no transfer function. Throws image_error.
float_image read_image(const std::filesystem::path& path);

/// The "ImageDescription" a file stores, "" when it has none. Throws image_error.
std::string read_image_description(const std::filesystem::path& path);

/// Draws one line of `text` in opaque white onto `image` (RGBA, bottom row first), its baseline's left end at
/// column `x` and at row `baseline_from_top` counted from the image's top. The font is `font_px` pixels tall,
/// or smaller where the text would be wider than `max_width`. `font` is a font name OpenImageIO searches for
/// (its font directories and /usr/share/fonts) or a font file's path. Returns false, the image unchanged, when
/// the font cannot be found (or this build has no OpenImageIO).
bool draw_text(float_image& image, int x, int baseline_from_top, const std::string& text, int font_px, int max_width,
               const std::string& font);

}  // namespace emcv::image
