// SPDX-License-Identifier: MIT
// Image comparison with the semantics of OpenImageIO's `idiff`, on OIIO::ImageBufAlgo::compare: a channel
// value "fails" when |A - B| > fail and "warns" when |A - B| > warn; the comparison fails when more than
// fail_percent % of the pixels fail or any value differs by more than hard_fail, and warns likewise. RMSE,
// PSNR and the largest difference are reported alongside. Used by the golden-image test and by emcv-golden.
#pragma once

#include <cstddef>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <string>

#include <OpenImageIO/imagebuf.h>

namespace emcv::image {

/// The thresholds of `idiff -fail F -failpercent P -hardfail H -warn W -warnpercent Q`.
struct tolerance {
    float fail = 1e-6f;         ///< per channel value: |A - B| above this counts the pixel as failing
    double fail_percent = 0.0;  ///< share of failing pixels (%) still accepted
    float hard_fail = std::numeric_limits<float>::infinity();  ///< any single difference above this fails
    float warn = 1e-6f;
    double warn_percent = 0.0;
    float hard_warn = std::numeric_limits<float>::infinity();

    /// Bit-identical: any difference at all fails.
    static tolerance exact();
};

enum class verdict { pass, warn, fail };
const char* verdict_name(verdict v) noexcept;

struct comparison {
    std::size_t pixels = 0;
    std::size_t failing = 0;  ///< pixels with some channel over tolerance::fail (OIIO's nfail)
    std::size_t warning = 0;  ///< pixels with some channel over tolerance::warn (OIIO's nwarn)
    double max_error = 0.0;
    int max_x = 0, max_y = 0, max_channel = 0;  ///< where max_error was found (image coordinates, top row 0)
    double rmse = 0.0;
    double psnr_db = 0.0;  ///< OIIO's PSNR (infinite for identical images)
    verdict result = verdict::pass;

    double failing_percent() const;
    /// "2 of 9216 pixels over 0.0118 (0.022%), max 0.0431 at (40, 12) channel 1, RMSE 0.00093, PSNR 60.6 dB"
    std::string summary(const tolerance& t) const;
};

/// Bad input to a comparison (unreadable file, different sizes or channel counts); what() names the file(s).
class compare_error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

OIIO::ImageBuf read(const std::filesystem::path& file);

comparison compare(const OIIO::ImageBuf& actual, const OIIO::ImageBuf& expected, const tolerance& t);
comparison compare_files(const std::filesystem::path& actual, const std::filesystem::path& expected,
                         const tolerance& t);

/// What a failed comparison leaves next to the test output: copies of both images and the difference
/// |actual - expected| scaled so that a difference of tolerance::fail (or the largest one, when fail is 0)
/// is white, alpha 1.
struct failure_images {
    std::filesystem::path actual, expected, diff;
};
failure_images write_failure_images(const OIIO::ImageBuf& actual, const OIIO::ImageBuf& expected,
                                    const tolerance& t, const std::filesystem::path& dir, const std::string& stem);

/// Writes a buffer through a temporary sibling and a rename (no half-written file on failure), in `format`
/// (unknown: the format the buffer was read from or created with).
void write(const OIIO::ImageBuf& image, const std::filesystem::path& file, OIIO::TypeDesc format = OIIO::TypeUnknown);

}  // namespace emcv::image
