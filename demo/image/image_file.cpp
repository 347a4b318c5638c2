// SPDX-License-Identifier: MIT
#include "image_file.hpp"

#ifndef EMCV_IMAGE_NO_FILES
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

}  // namespace
#endif  // #ifndef EMCV_IMAGE_NO_FILES

std::uint8_t quantise_unorm8(float value) noexcept {
    if (!(value > 0.0f)) return 0;  // also NaN, which std::clamp would pass through
    return static_cast<std::uint8_t>(std::lround(std::min(value, 1.0f) * 255.0f));
}

#ifdef EMCV_IMAGE_NO_FILES
// Built with -DEMCV_GL_IMAGE_FILES=OFF (a build for a machine without OpenImageIO, e.g. GPU timing runs that
// write metrics only): every image file operation fails with a line that says why.
void write_image(const std::filesystem::path& path, const float_image&) {
    throw image_error("write_image " + path.string() + ": built without OpenImageIO (EMCV_GL_IMAGE_FILES=OFF)");
}

float_image read_image(const std::filesystem::path& path) {
    throw image_error("read_image " + path.string() + ": built without OpenImageIO (EMCV_GL_IMAGE_FILES=OFF)");
}
#else
void write_image(const std::filesystem::path& path, const float_image& image) {
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
    if (!out->open(tmp.string(), spec))
        throw image_error("write_image " + path.string() + ": " + out->geterror());
    const std::size_t row = static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.channels);
    // GL rows are bottom-up; image files are top-down.
    std::vector<float> flipped(expected);
    for (int y = 0; y < image.height; ++y)
        std::copy_n(image.pixels.begin() + static_cast<std::ptrdiff_t>(static_cast<std::size_t>(image.height - 1 - y) * row),
                    row, flipped.begin() + static_cast<std::ptrdiff_t>(static_cast<std::size_t>(y) * row));
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
    img.pixels.resize(top_down.size());
    for (int y = 0; y < img.height; ++y)
        std::copy_n(top_down.begin() + static_cast<std::ptrdiff_t>(static_cast<std::size_t>(img.height - 1 - y) * row),
                    row, img.pixels.begin() + static_cast<std::ptrdiff_t>(static_cast<std::size_t>(y) * row));
    return img;
}
#endif  // #ifdef EMCV_IMAGE_NO_FILES

}  // namespace emcv::image
