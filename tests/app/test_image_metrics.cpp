// SPDX-License-Identifier: MIT
// The image metrics of metrics.csv on images whose answers are computed by hand.
#include <catch2/catch_approx.hpp>
#include <catch2/catch_test_macros.hpp>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "image_metrics.hpp"

using emcv::demo::app::image_view;
using emcv::demo::app::pixel_mask;
namespace app = emcv::demo::app;

namespace {

/// A w x h RGBA image, every pixel (r, g, b, a).
std::vector<float> filled(int w, int h, float r, float g, float b, float a = 1.0f) {
    std::vector<float> px;
    for (int i = 0; i < w * h; ++i) px.insert(px.end(), {r, g, b, a});
    return px;
}

image_view view(const std::vector<float>& px, int w, int h) { return {w, h, 4, px.data()}; }

}  // namespace

TEST_CASE("PSNR of a uniform 0.1 offset is 20 dB", "[app][metrics]") {
    const auto a = filled(4, 2, 0.5f, 0.5f, 0.5f), b = filled(4, 2, 0.6f, 0.6f, 0.6f);
    // MSE = 0.1^2 = 0.01, PSNR = 10 log10(1 / 0.01) = 20 dB.
    CHECK(*app::mean_squared_error(view(a, 4, 2), view(b, 4, 2)) == Catch::Approx(0.01).epsilon(1e-6));
    CHECK(*app::psnr_db(view(a, 4, 2), view(b, 4, 2)) == Catch::Approx(20.0).epsilon(1e-6));
}

TEST_CASE("PSNR averages the squared error over the RGB channels and ignores alpha", "[app][metrics]") {
    // Only red differs, by 0.3: MSE = 0.09 / 3 = 0.03. Alpha differs by 1 and must not count.
    const auto a = filled(2, 2, 0.3f, 0.2f, 0.1f, 0.0f), b = filled(2, 2, 0.0f, 0.2f, 0.1f, 1.0f);
    CHECK(*app::mean_squared_error(view(a, 2, 2), view(b, 2, 2)) == Catch::Approx(0.03).epsilon(1e-6));
    CHECK(*app::psnr_db(view(a, 2, 2), view(b, 2, 2)) == Catch::Approx(10.0 * std::log10(1.0 / 0.03)).epsilon(1e-6));
}

TEST_CASE("PSNR over a mask measures the selected pixels only", "[app][metrics]") {
    // 2x1 image: pixel 0 off by 0.1, pixel 1 off by 0.5. Mask {1, 0}: 20 dB; mask {0, 1}: 10 log10(1/0.25).
    std::vector<float> a = {0.1f, 0.1f, 0.1f, 1.0f, 0.5f, 0.5f, 0.5f, 1.0f};
    std::vector<float> b = {0.2f, 0.2f, 0.2f, 1.0f, 0.0f, 0.0f, 0.0f, 1.0f};
    const pixel_mask first = {1, 0}, second = {0, 1}, none = {0, 0};
    CHECK(*app::psnr_db(view(a, 2, 1), view(b, 2, 1), &first) == Catch::Approx(20.0).epsilon(1e-5));
    CHECK(*app::psnr_db(view(a, 2, 1), view(b, 2, 1), &second) ==
          Catch::Approx(10.0 * std::log10(1.0 / 0.25)).epsilon(1e-5));
    // Whole frame: MSE = (0.01 + 0.25) / 2 = 0.13.
    CHECK(*app::mean_squared_error(view(a, 2, 1), view(b, 2, 1)) == Catch::Approx(0.13).epsilon(1e-5));
    CHECK_FALSE(app::psnr_db(view(a, 2, 1), view(b, 2, 1), &none).has_value());
}

TEST_CASE("PSNR of identical images is +inf; mismatched shapes throw", "[app][metrics]") {
    const auto a = filled(3, 3, 0.25f, 0.5f, 0.75f);
    const std::optional<double> same = app::psnr_db(view(a, 3, 3), view(a, 3, 3));
    REQUIRE(same.has_value());
    CHECK(std::isinf(*same));
    CHECK(*same > 0.0);
    const auto b = filled(9, 1, 0.25f, 0.5f, 0.75f);
    CHECK_THROWS_AS(app::psnr_db(view(a, 3, 3), view(b, 9, 1)), std::invalid_argument);
    const pixel_mask short_mask = {1, 1};
    CHECK_THROWS_AS(app::psnr_db(view(a, 3, 3), view(a, 3, 3), &short_mask), std::invalid_argument);
}

TEST_CASE("relative MSE divides each squared error by the reference's square plus epsilon", "[app][metrics]") {
    // x = 1.1, r = 1: 0.01 / (1 + 0.01). x = 0.1, r = 0: 0.01 / (0 + 0.01) = 1.
    const auto x = filled(2, 2, 1.1f, 1.1f, 1.1f), r = filled(2, 2, 1.0f, 1.0f, 1.0f);
    CHECK(app::relative_mse(view(x, 2, 2), view(r, 2, 2)) == Catch::Approx(0.01 / 1.01).epsilon(1e-5));
    const auto dark = filled(2, 2, 0.1f, 0.1f, 0.1f), black = filled(2, 2, 0.0f, 0.0f, 0.0f);
    CHECK(app::relative_mse(view(dark, 2, 2), view(black, 2, 2)) == Catch::Approx(1.0).epsilon(1e-5));
    // Asymmetric: the reference is the second argument.
    CHECK(app::relative_mse(view(r, 2, 2), view(x, 2, 2)) == Catch::Approx(0.01 / (1.21 + 0.01)).epsilon(1e-5));
}

TEST_CASE("temporal error counts change the reference does not have", "[app][metrics]") {
    const auto dark = filled(2, 2, 0.2f, 0.2f, 0.2f), bright = filled(2, 2, 0.7f, 0.7f, 0.7f);
    const image_view d = view(dark, 2, 2), b = view(bright, 2, 2);
    // The method follows the reference's change (a light switching on): no temporal error.
    CHECK(app::temporal_error(b, d, b, d) == Catch::Approx(0.0).margin(1e-9));
    // The reference changes by 0.5, the method stays: RMS 0.5.
    CHECK(app::temporal_error(d, d, b, d) == Catch::Approx(0.5).epsilon(1e-5));
    // The reference is static, the method flickers by 0.5: RMS 0.5 too.
    CHECK(app::temporal_error(b, d, d, d) == Catch::Approx(0.5).epsilon(1e-5));
    // One channel of one pixel out of 2x2x3 values changes by 0.6: RMS = sqrt(0.36 / 12).
    auto one = dark;
    one[4 + 1] += 0.6f;
    CHECK(app::temporal_error(view(one, 2, 2), d, d, d) == Catch::Approx(std::sqrt(0.36 / 12.0)).epsilon(1e-5));
}

TEST_CASE("the tracked value's squared error averages over the selected pixels only", "[app][metrics]") {
    const std::vector<float> values = {0.1f, 0.2f, 0.3f, 0.4f}, reference = {0.1f, 0.1f, 0.1f, 0.1f};
    // Pixels 0, 1 and 3: (0 + 0.1^2 + 0.3^2) / 3 = 0.1 / 3; pixel 2 (0.2 off) is not selected.
    CHECK(*app::mean_squared_difference(values, reference, pixel_mask{1, 1, 0, 1}) ==
          Catch::Approx(0.1 / 3.0).epsilon(1e-5));
    CHECK_FALSE(app::mean_squared_difference(values, reference, pixel_mask{0, 0, 0, 0}));  // no SSS pixel
    CHECK_THROWS_AS(app::mean_squared_difference(values, {0.1f}, pixel_mask{1, 1, 1, 1}), std::invalid_argument);
    CHECK_THROWS_AS(app::mean_squared_difference(values, reference, pixel_mask{1}), std::invalid_argument);
}
