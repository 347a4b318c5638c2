// SPDX-License-Identifier: MIT
#include "image_compare.hpp"

#include <OpenImageIO/imagebufalgo.h>

#include <algorithm>
#include <cstdio>
#include <system_error>

namespace emcv::image {

tolerance tolerance::exact() {
    tolerance t;
    t.fail = 0.0f;
    t.warn = 0.0f;
    t.hard_fail = 0.0f;
    return t;
}

const char* verdict_name(verdict v) noexcept {
    switch (v) {
        case verdict::pass: return "PASS";
        case verdict::warn: return "WARNING";
        case verdict::fail: return "FAILURE";
    }
    return "?";
}

double comparison::failing_percent() const {
    return pixels == 0 ? 0.0 : 100.0 * static_cast<double>(failing) / static_cast<double>(pixels);
}

std::string comparison::summary(const tolerance& t) const {
    char line[320];
    std::snprintf(line, sizeof line,
                  "%s: %zu of %zu pixels over %.4g (%.3f%%, %.3g%% allowed), max %.4g at (%d, %d) channel %d, "
                  "RMSE %.3g, PSNR %.1f dB",
                  verdict_name(result), failing, pixels, static_cast<double>(t.fail), failing_percent(),
                  t.fail_percent, max_error, max_x, max_y, max_channel, rmse, psnr_db);
    return line;
}

OIIO::ImageBuf read(const std::filesystem::path& file) {
    if (!std::filesystem::is_regular_file(file)) throw compare_error(file.string() + ": no such image file");
    OIIO::ImageBuf buf(file.string());
    // Read as float now, so the comparison never depends on a lazily opened file that may change under it.
    if (!buf.read(0, 0, true, OIIO::TypeDesc::FLOAT))
        throw compare_error(file.string() + ": " + buf.geterror());
    return buf;
}

comparison compare(const OIIO::ImageBuf& actual, const OIIO::ImageBuf& expected, const tolerance& t) {
    const OIIO::ImageSpec& a = actual.spec();
    const OIIO::ImageSpec& e = expected.spec();
    if (a.width != e.width || a.height != e.height || a.nchannels != e.nchannels) {
        char what[200];
        std::snprintf(what, sizeof what, "images differ in shape: actual %dx%d with %d channels, expected %dx%d with %d",
                      a.width, a.height, a.nchannels, e.width, e.height, e.nchannels);
        throw compare_error(what);
    }
    const OIIO::ImageBufAlgo::CompareResults r = OIIO::ImageBufAlgo::compare(actual, expected, t.fail, t.warn);
    // CompareResults::error is not a failure report here: OIIO 2.4 sets it whenever some pixel fails. A real
    // failure leaves a message in the global error queue.
    if (const std::string why = OIIO::geterror(); !why.empty()) throw compare_error("OpenImageIO compare: " + why);
    comparison c;
    c.pixels = static_cast<std::size_t>(a.width) * static_cast<std::size_t>(a.height);
    c.failing = static_cast<std::size_t>(r.nfail);
    c.warning = static_cast<std::size_t>(r.nwarn);
    c.max_error = r.maxerror;
    c.max_x = r.maxx;
    c.max_y = r.maxy;
    c.max_channel = r.maxc;
    c.rmse = r.rms_error;
    c.psnr_db = r.PSNR;
    // idiff's verdict: too many failing pixels or one value beyond the hard limit.
    const double pixels = static_cast<double>(c.pixels);
    if (static_cast<double>(c.failing) > t.fail_percent / 100.0 * pixels || c.max_error > static_cast<double>(t.hard_fail))
        c.result = verdict::fail;
    else if (static_cast<double>(c.warning) > t.warn_percent / 100.0 * pixels ||
             c.max_error > static_cast<double>(t.hard_warn))
        c.result = verdict::warn;
    return c;
}

comparison compare_files(const std::filesystem::path& actual, const std::filesystem::path& expected,
                         const tolerance& t) {
    const OIIO::ImageBuf a = read(actual);
    const OIIO::ImageBuf e = read(expected);
    try {
        return compare(a, e, t);
    } catch (const compare_error& err) {
        throw compare_error(actual.string() + " vs " + expected.string() + ": " + err.what());
    }
}

void write(const OIIO::ImageBuf& image, const std::filesystem::path& file, OIIO::TypeDesc format) {
    if (format == OIIO::TypeUnknown) format = image.nativespec().format;
    std::error_code ec;
    if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path(), ec);
    const std::filesystem::path tmp = file.string() + ".tmp" + file.extension().string();
    if (!image.write(tmp.string(), format)) {
        std::filesystem::remove(tmp, ec);
        throw compare_error(file.string() + ": " + image.geterror());
    }
    std::filesystem::rename(tmp, file, ec);
    if (ec) {
        std::filesystem::remove(tmp, ec);
        throw compare_error(file.string() + ": cannot rename the temporary file: " + ec.message());
    }
}

failure_images write_failure_images(const OIIO::ImageBuf& actual, const OIIO::ImageBuf& expected,
                                    const tolerance& t, const std::filesystem::path& dir, const std::string& stem) {
    failure_images out{dir / (stem + ".actual.png"), dir / (stem + ".expected.png"), dir / (stem + ".diff.png")};
    write(actual, out.actual);
    write(expected, out.expected);
    OIIO::ImageBuf diff = OIIO::ImageBufAlgo::absdiff(actual, expected);
    float white = t.fail;
    if (!(white > 0.0f)) {
        const OIIO::ImageBufAlgo::PixelStats stats = OIIO::ImageBufAlgo::computePixelStats(diff);
        white = stats.max.empty() ? 1.0f : *std::max_element(stats.max.begin(), stats.max.end());
        if (!(white > 0.0f)) white = 1.0f;
    }
    diff = OIIO::ImageBufAlgo::clamp(OIIO::ImageBufAlgo::mul(diff, 1.0f / white), 0.0f, 1.0f);
    if (diff.nchannels() == 4) {  // an opaque alpha, so viewers show the colour difference
        const float opaque[] = {0.0f, 0.0f, 0.0f, 1.0f};
        OIIO::ImageBufAlgo::fill(diff, opaque, OIIO::ROI(0, diff.spec().width, 0, diff.spec().height, 0, 1, 3, 4));
    }
    write(diff, out.diff, OIIO::TypeDesc::UINT8);
    return out;
}

}  // namespace emcv::image
