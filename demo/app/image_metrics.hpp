// SPDX-License-Identifier: MIT
// Image metrics of the demo's metrics.csv: PSNR (whole frame and SSS pixels only), relative MSE, temporal
// error and the tracked value's squared error. Pure functions over float images; definitions in docs/demo.md ("Outputs"). No GL.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

namespace emcv::demo::app {

/// A read-only view of an interleaved float image; the first three channels (RGB) are measured, the rest
/// (alpha) ignored. Row order does not matter as long as every image compared uses the same one.
struct image_view {
    int width = 0;
    int height = 0;
    int channels = 0;              ///< >= 3
    const float* pixels = nullptr;  ///< width * height * channels values
};

/// Per-pixel selection (non-zero: measured), width * height entries; nullptr measures every pixel.
using pixel_mask = std::vector<std::uint8_t>;

/// Mean squared error over the RGB channels of the selected pixels; empty when no pixel is selected.
/// Throws std::invalid_argument when the images (or the mask) differ in size or have fewer than 3 channels.
std::optional<double> mean_squared_error(const image_view& image, const image_view& reference,
                                         const pixel_mask* mask = nullptr);

/// Mean squared difference of two one-value-per-pixel images (the tracked values of a method and of the
/// reference) over the pixels `mask` selects; empty when it selects none. Throws std::invalid_argument when the
/// three differ in size.
std::optional<double> mean_squared_difference(const std::vector<float>& values, const std::vector<float>& reference,
                                              const pixel_mask& mask);

/// PSNR in dB of display images with values in [0, 1] (peak 1): 10 log10(1 / MSE); +inf when MSE == 0,
/// empty when no pixel is selected.
std::optional<double> psnr_db(const image_view& display, const image_view& reference_display,
                              const pixel_mask* mask = nullptr);

/// Relative MSE of linear HDR radiance: mean over pixels and RGB of (x - r)^2 / (r^2 + relative_mse_epsilon).
/// The epsilon keeps black reference pixels from dominating (the usual relMSE of rendering papers).
inline constexpr double relative_mse_epsilon = 1e-2;
double relative_mse(const image_view& linear, const image_view& reference_linear);

/// Temporal error of frame t: RMS over pixels and RGB of (D_t - D_{t-1}) - (R_t - R_{t-1}), D the method's
/// display image and R the reference's. 0 for a method that changes exactly as the reference does (a light
/// switching off is not counted as error); flicker and noise that the reference does not have are.
double temporal_error(const image_view& display, const image_view& previous_display,
                      const image_view& reference_display, const image_view& previous_reference_display);

}  // namespace emcv::demo::app
