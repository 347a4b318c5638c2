// SPDX-License-Identifier: MIT
// The golden-image cases, read from tests/image/golden/cases.txt (one source for the test and emcv-golden),
// and the tolerances each kind of golden image is compared with.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "image_compare.hpp"

namespace emcv::image {

/// One line of cases.txt: `<scene> <method> <frames> <W>x<H>`. Frames 0..frames-1 are rendered with seed
/// golden_seed; the golden images are the last frame's display image and, for the adaptive methods, its
/// per-pixel sample counts.
struct golden_case {
    std::string scene;   ///< built-in scene name
    std::string method;  ///< --method name
    int frames = 1;
    int width = 96;
    int height = 96;

    int last_frame() const { return frames - 1; }
    /// "light-off.cv.f23": the file stem of the case's golden images.
    std::string stem() const;
    std::string display_file() const { return stem() + ".png"; }     ///< 8-bit sRGB RGB
    std::string samples_file() const { return stem() + ".spp.png"; }  ///< 16-bit grey: the count itself
};

inline constexpr unsigned golden_seed = 1;

/// A malformed cases file; what() is "<file>:<line>: <problem>".
class cases_error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// Reads the cases file ('#' starts a comment). Throws cases_error.
std::vector<golden_case> read_cases(const std::filesystem::path& file);

/// Display images (8-bit sRGB). The same build on the same Mesa is bit-identical (tested separately, exactly);
/// this tolerance lets through a one-step rounding difference of the 8-bit encoding on a few pixels (a
/// different compiler or Mesa point release), nothing a reader could see. docs/results.md, "Regression renders".
tolerance display_tolerance();
/// Sample-count images (16-bit, the count itself): any changed count fails the pixel; a few pixels may change
/// by a sample or two (a variance landing on the other side of a rounding boundary), none by more than 4.
tolerance samples_tolerance();

}  // namespace emcv::image
