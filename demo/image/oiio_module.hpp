// SPDX-License-Identifier: MIT
// The OpenImageIO module: image_file.cpp's file operations, built as a shared module of their own
// (libemcv_image_oiio.so, demo/image/CMakeLists.txt) that image_file.cpp loads on the first image file operation.
// Debian's OpenImageIO needs about 260 shared libraries (codecs, OpenCV, OpenBLAS, DICOM, ...), whose loading and
// start-up cost every process that links it about 0.35 s on the 2-core machine (and 0.65 s under ASan), whether
// or not it touches an image: `emcv-eval --bogus` took 369 ms against 3 ms for emcv-glinfo. Loaded on demand, a
// process that reads or writes no image file (a usage error, --help, --print-passes, a metrics-only render)
// never loads them. Internal to the demo and the tests, like image_file.hpp.
#pragma once

#include <filesystem>
#include <string>

#include "image_file.hpp"

namespace emcv::image {

/// The module's operations, as image_file.hpp documents them. Each returns "" on success, else what failed (the
/// caller throws image_error with it): no exception crosses the module's boundary.
struct oiio_functions {
    std::string (*write_image)(const std::filesystem::path& path, const float_image& image, const std::string& description);
    std::string (*read_image)(const std::filesystem::path& path, float_image& image);
    std::string (*read_image_description)(const std::filesystem::path& path, std::string& description);
    /// `drawn`: false when the font cannot be found.
    std::string (*draw_text)(float_image& image, int x, int baseline_from_top, const std::string& text, int font_px,
                             int max_width, const std::string& font, bool& drawn);
};

}  // namespace emcv::image

/// The module's one exported symbol (looked up by this name with dlsym).
#define EMCV_IMAGE_OIIO_ENTRY "emcv_image_oiio_functions"
extern "C" const emcv::image::oiio_functions* emcv_image_oiio_functions();
