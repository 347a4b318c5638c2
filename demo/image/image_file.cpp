// SPDX-License-Identifier: MIT
#include "image_file.hpp"

#ifndef EMCV_IMAGE_NO_FILES
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>
#endif

#include <algorithm>
#include <cmath>
#include <string>

namespace emcv::image {
#ifndef EMCV_IMAGE_NO_FILES
namespace {

std::string lower_extension(const std::filesystem::path& p) {
    std::string e = p.extension().string();
    std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return e;
}

/// The rows in the other order: GL's bottom-up rows to an image file's top-down ones, and back.
std::vector<float> flip_rows(const std::vector<float>& pixels, std::size_t row, int height) {
    std::vector<float> out(pixels.size());
    for (int y = 0; y < height; ++y)
        std::copy_n(pixels.begin() + static_cast<std::ptrdiff_t>(static_cast<std::size_t>(height - 1 - y) * row), row,
                    out.begin() + static_cast<std::ptrdiff_t>(static_cast<std::size_t>(y) * row));
    return out;
}

}  // namespace
#endif  // #ifndef EMCV_IMAGE_NO_FILES

std::uint8_t quantise_unorm8(float value) noexcept {
    if (!(value > 0.0f)) return 0;  // also NaN, which std::clamp would pass through
    return static_cast<std::uint8_t>(std::lround(std::min(value, 1.0f) * 255.0f));
}

#ifdef EMCV_IMAGE_NO_FILES
// Built with -DEMCV_GL_IMAGE_FILES=OFF (a build for a machine without OpenImageIO, e.g. GPU timing runs that
// write metrics only): every image file operation fails with a line that says why.
void write_image(const std::filesystem::path& path, const float_image&, const std::string&) {
    throw image_error("write_image " + path.string() + ": built without OpenImageIO (EMCV_GL_IMAGE_FILES=OFF)");
}

float_image read_image(const std::filesystem::path& path) {
    throw image_error("read_image " + path.string() + ": built without OpenImageIO (EMCV_GL_IMAGE_FILES=OFF)");
}

std::string read_image_description(const std::filesystem::path& path) {
    throw image_error("read_image_description " + path.string() +
                      ": built without OpenImageIO (EMCV_GL_IMAGE_FILES=OFF)");
}

bool draw_text(float_image&, int, int, const std::string&, int, int, const std::string&) { return false; }
#else
void write_image(const std::filesystem::path& path, const float_image& image, const std::string& description) {
    const std::size_t expected =
        static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height) *
        static_cast<std::size_t>(image.channels);
    if (image.width <= 0 || image.height <= 0 || image.channels <= 0 || image.pixels.size() != expected)
        throw image_error("write_image " + path.string() + ": image size and pixel count disagree");
    const std::string ext = lower_extension(path);
    const bool png = ext == ".png";
    if (!png && ext != ".exr")
        throw image_error("write_image " + path.string() + ": unsupported extension (use .exr or .png)");
    const std::filesystem::path tmp = path.string() + ".tmp" + ext;
    auto out = OIIO::ImageOutput::create(tmp.string());
    if (!out) throw image_error("write_image " + path.string() + ": " + OIIO::geterror());
    OIIO::ImageSpec spec(image.width, image.height, image.channels, png ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::FLOAT);
    // Our pixels are straight (unassociated) alpha; without this OIIO would un-premultiply PNG data on write.
    spec.attribute("oiio:UnassociatedAlpha", 1);
    if (!description.empty()) spec.attribute("ImageDescription", description);
    if (!out->open(tmp.string(), spec))
        throw image_error("write_image " + path.string() + ": " + out->geterror());
    const std::size_t row = static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.channels);
    const std::vector<float> flipped = flip_rows(image.pixels, row, image.height);  // GL rows are bottom-up
    bool ok = false;
    if (png) {
        std::vector<std::uint8_t> bytes(expected);
        std::transform(flipped.begin(), flipped.end(), bytes.begin(), quantise_unorm8);
        ok = out->write_image(OIIO::TypeDesc::UINT8, bytes.data());
    } else {
        ok = out->write_image(OIIO::TypeDesc::FLOAT, flipped.data());
    }
    ok = out->close() && ok;
    if (!ok) {
        std::error_code ec;
        std::filesystem::remove(tmp, ec);
        throw image_error("write_image " + path.string() + ": " + out->geterror());
    }
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) {
        std::filesystem::remove(tmp, ec);
        throw image_error("write_image " + path.string() + ": cannot rename the temporary file: " + ec.message());
    }
}

float_image read_image(const std::filesystem::path& path) {
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);  // keep PNG alpha straight, as written
    auto in = OIIO::ImageInput::open(path.string(), &config);
    if (!in) throw image_error("read_image " + path.string() + ": " + OIIO::geterror());
    const OIIO::ImageSpec& spec = in->spec();
    float_image img;
    img.width = spec.width;
    img.height = spec.height;
    img.channels = spec.nchannels;
    const std::size_t row = static_cast<std::size_t>(img.width) * static_cast<std::size_t>(img.channels);
    std::vector<float> top_down(row * static_cast<std::size_t>(img.height));
    if (!in->read_image(0, 0, 0, img.channels, OIIO::TypeDesc::FLOAT, top_down.data()))
        throw image_error("read_image " + path.string() + ": " + in->geterror());
    img.pixels = flip_rows(top_down, row, img.height);
    return img;
}

std::string read_image_description(const std::filesystem::path& path) {
    auto in = OIIO::ImageInput::open(path.string());
    if (!in) throw image_error("read_image_description " + path.string() + ": " + OIIO::geterror());
    return in->spec().get_string_attribute("ImageDescription");
}

bool draw_text(float_image& image, int x, int baseline_from_top, const std::string& text, int font_px, int max_width,
               const std::string& font) {
    const std::size_t row = static_cast<std::size_t>(image.width) * 4u;
    if (image.channels != 4 || image.width <= 0 || image.height <= 0 ||
        image.pixels.size() != row * static_cast<std::size_t>(image.height))
        throw image_error("draw_text: the image must be RGBA with width x height x 4 pixels");
    int px = font_px;
    OIIO::ROI extent = OIIO::ImageBufAlgo::text_size(text, px, font);
    if (!extent.defined()) {
        (void)OIIO::geterror();  // "font not found": ours to report, not OIIO's to keep
        return false;
    }
    while (px > 1 && extent.width() > max_width) extent = OIIO::ImageBufAlgo::text_size(text, --px, font);
    std::vector<float> top_down = flip_rows(image.pixels, row, image.height);
    OIIO::ImageBuf buffer(OIIO::ImageSpec(image.width, image.height, 4, OIIO::TypeDesc::FLOAT));
    buffer.set_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, top_down.data());
    const float white[4] = {1.0f, 1.0f, 1.0f, 1.0f};
    if (!OIIO::ImageBufAlgo::render_text(buffer, x, baseline_from_top, text, px, font, white)) {
        (void)buffer.geterror();
        return false;
    }
    buffer.get_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, top_down.data());
    image.pixels = flip_rows(top_down, row, image.height);
    return true;
}
#endif  // #ifdef EMCV_IMAGE_NO_FILES

}  // namespace emcv::image
