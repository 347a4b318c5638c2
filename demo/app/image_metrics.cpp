// SPDX-License-Identifier: MIT
#include "image_metrics.hpp"

#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>

namespace emcv::demo::app {
namespace {

std::size_t pixel_count(const image_view& v) {
    return static_cast<std::size_t>(v.width) * static_cast<std::size_t>(v.height);
}

void require_same_shape(const image_view& a, const image_view& b, const char* what) {
    if (a.width != b.width || a.height != b.height)
        throw std::invalid_argument(std::string(what) + ": images differ in size (" + std::to_string(a.width) + "x" +
                                    std::to_string(a.height) + " vs " + std::to_string(b.width) + "x" +
                                    std::to_string(b.height) + ")");
    if (a.channels < 3 || b.channels < 3 || !a.pixels || !b.pixels)
        throw std::invalid_argument(std::string(what) + ": images need at least 3 channels");
}

/// The value of channel c of pixel p.
float at(const image_view& v, std::size_t p, std::size_t c) {
    return v.pixels[p * static_cast<std::size_t>(v.channels) + c];
}

}  // namespace

std::optional<double> mean_squared_error(const image_view& image, const image_view& reference,
                                         const pixel_mask* mask) {
    require_same_shape(image, reference, "mean_squared_error");
    const std::size_t n = pixel_count(image);
    if (mask && mask->size() != n) throw std::invalid_argument("mean_squared_error: mask size differs from image");
    double sum = 0.0;
    std::size_t selected = 0;
    for (std::size_t p = 0; p < n; ++p) {
        if (mask && (*mask)[p] == 0) continue;
        ++selected;
        for (std::size_t c = 0; c < 3; ++c) {
            const double d = static_cast<double>(at(image, p, c)) - static_cast<double>(at(reference, p, c));
            sum += d * d;
        }
    }
    if (selected == 0) return std::nullopt;
    return sum / static_cast<double>(3 * selected);
}

std::optional<double> mean_squared_difference(const std::vector<float>& values, const std::vector<float>& reference,
                                              const pixel_mask& mask) {
    if (values.size() != reference.size() || mask.size() != values.size())
        throw std::invalid_argument("mean_squared_difference: sizes differ (" + std::to_string(values.size()) + ", " +
                                    std::to_string(reference.size()) + " and mask " + std::to_string(mask.size()) +
                                    ")");
    double sum = 0.0;
    std::size_t selected = 0;
    for (std::size_t p = 0; p < values.size(); ++p) {
        if (mask[p] == 0) continue;
        ++selected;
        const double d = static_cast<double>(values[p]) - static_cast<double>(reference[p]);
        sum += d * d;
    }
    if (selected == 0) return std::nullopt;
    return sum / static_cast<double>(selected);
}

std::optional<double> psnr_db(const image_view& display, const image_view& reference_display,
                              const pixel_mask* mask) {
    const std::optional<double> mse = mean_squared_error(display, reference_display, mask);
    if (!mse) return std::nullopt;
    if (*mse == 0.0) return std::numeric_limits<double>::infinity();
    return 10.0 * std::log10(1.0 / *mse);  // peak value 1 (display values in [0, 1])
}

double relative_mse(const image_view& linear, const image_view& reference_linear) {
    require_same_shape(linear, reference_linear, "relative_mse");
    const std::size_t n = pixel_count(linear);
    if (n == 0) return 0.0;
    double sum = 0.0;
    for (std::size_t p = 0; p < n; ++p)
        for (std::size_t c = 0; c < 3; ++c) {
            const double r = at(reference_linear, p, c);
            const double d = static_cast<double>(at(linear, p, c)) - r;
            sum += d * d / (r * r + relative_mse_epsilon);
        }
    return sum / static_cast<double>(3 * n);
}

double temporal_error(const image_view& display, const image_view& previous_display,
                      const image_view& reference_display, const image_view& previous_reference_display) {
    require_same_shape(display, previous_display, "temporal_error");
    require_same_shape(display, reference_display, "temporal_error");
    require_same_shape(display, previous_reference_display, "temporal_error");
    const std::size_t n = pixel_count(display);
    if (n == 0) return 0.0;
    double sum = 0.0;
    for (std::size_t p = 0; p < n; ++p)
        for (std::size_t c = 0; c < 3; ++c) {
            const double method_change =
                static_cast<double>(at(display, p, c)) - static_cast<double>(at(previous_display, p, c));
            const double reference_change = static_cast<double>(at(reference_display, p, c)) -
                                            static_cast<double>(at(previous_reference_display, p, c));
            const double d = method_change - reference_change;
            sum += d * d;
        }
    return std::sqrt(sum / static_cast<double>(3 * n));
}

}  // namespace emcv::demo::app
