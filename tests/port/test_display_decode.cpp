// SPDX-License-Identifier: MIT
// The display transform's inverse (include/emcv/port/tonemap.h, emcv_display_decode), which the temporal resolve
// uses to add the specular light back to the resolved scattered light in linear: it must undo
// emcv_display_encode over the range the encoding does not clamp, for both tonemaps, and be monotonic.
#include <catch2/catch_test_macros.hpp>

#include <cmath>

#include <emcv/port/tonemap.h>

namespace port = emcv::port;

TEST_CASE("display decode: undoes the display encoding of every linear value it does not clamp, both tonemaps") {
    // Exposed linear values from 1e-4 to 7 (the ACES fit clamps to 1 from 7.24 on; Reinhard never does, but
    // float display values within 2^-24 of 1 cannot tell large inputs apart, so test Reinhard up to 7 too).
    for (int tonemap = 0; tonemap <= 1; ++tonemap) {
        for (int k = 0; k <= 400; ++k) {
            const float x = 1e-4f * std::pow(7e4f, float(k) / 400.0f);
            const float y = port::emcv_display_channel(x, tonemap);
            const float back = port::emcv_display_decode_channel(y, tonemap);
            // A float display value rounds the encoding by 2^-24 relative; the inverse's slope at the top of the
            // range amplifies that to at most about 1e-3 relative (ACES at x = 7: dx/dy ~ 170 x).
            CHECK(std::fabs(back - x) <= 2e-3f * x + 1e-7f);
        }
    }
}

TEST_CASE("display decode: the encoding of the decoded value is the display value again, increasing in it") {
    for (int tonemap = 0; tonemap <= 1; ++tonemap) {
        float previous = -1.0f;
        for (int k = 0; k <= 255; ++k) {
            const float y = float(k) / 255.0f;
            const float x = port::emcv_display_decode_channel(y, tonemap);
            CHECK(x >= 0.0f);
            CHECK(std::fabs(port::emcv_display_channel(x, tonemap) - y) <= 1e-5f);
            CHECK(x > previous);
            previous = x;
        }
        // The vector form is the channel form per channel; values outside [0, 1] are clamped to it.
        const glm::vec3 v = port::emcv_display_decode(glm::vec3(0.25f, 0.5f, 1.5f), tonemap);
        CHECK(v.x == port::emcv_display_decode_channel(0.25f, tonemap));
        CHECK(v.y == port::emcv_display_decode_channel(0.5f, tonemap));
        CHECK(v.z == port::emcv_display_decode_channel(1.0f, tonemap));
    }
    // The ACES fit reaches 1 at x = 7.2417 (the positive root of -0.08 x^2 + 0.56 x + 0.14).
    CHECK(std::fabs(port::emcv_display_decode_channel(1.0f, 0) - 7.2417f) < 1e-3f);
}
