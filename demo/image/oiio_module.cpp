// SPDX-License-Identifier: MIT
// The OpenImageIO module (oiio_module.hpp): image files through OpenImageIO, loaded by image_file.cpp on the first
// image file operation. Every operation throws image_error inside the module; its entry point turns that (and
// anything else thrown) into the message it returns.
#include "oiio_module.hpp"

#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cctype>
#include <exception>
#include <vector>

namespace emcv::image {
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


void oiio_write_image(const std::filesystem::path& path, const float_image& image, const std::string& description) {
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

float_image oiio_read_image(const std::filesystem::path& path) {
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

std::string oiio_read_image_description(const std::filesystem::path& path) {
    auto in = OIIO::ImageInput::open(path.string());
    if (!in) throw image_error("read_image_description " + path.string() + ": " + OIIO::geterror());
    return in->spec().get_string_attribute("ImageDescription");
}

bool oiio_draw_text(float_image& image, int x, int baseline_from_top, const std::string& text, int font_px, int max_width,
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

/// Runs `operation`, returning "" or what it threw.
template <class Operation>
std::string guarded(Operation&& operation) noexcept {
    try {
        operation();
        return {};
    } catch (const std::exception& e) {
        return e.what();
    } catch (...) {
        return "unknown error in the OpenImageIO module";
    }
}

const oiio_functions functions{
    [](const std::filesystem::path& path, const float_image& image, const std::string& description) {
        return guarded([&] { oiio_write_image(path, image, description); });
    },
    [](const std::filesystem::path& path, float_image& image) {
        return guarded([&] { image = oiio_read_image(path); });
    },
    [](const std::filesystem::path& path, std::string& description) {
        return guarded([&] { description = oiio_read_image_description(path); });
    },
    [](float_image& image, int x, int baseline_from_top, const std::string& text, int font_px, int max_width,
       const std::string& font, bool& drawn) {
        return guarded([&] { drawn = oiio_draw_text(image, x, baseline_from_top, text, font_px, max_width, font); });
    },
};

}  // namespace
}  // namespace emcv::image

extern "C" const emcv::image::oiio_functions* emcv_image_oiio_functions() { return &emcv::image::functions; }
