// SPDX-License-Identifier: MIT
// emcv/port/tonemap.h — display transform of the renderer (linear HDR -> display values), shared C++/GLSL.
//
// ABOUT      ACES fitted (Narkowicz 2015): f(x) = x (2.51 x + 0.03) / (x (2.43 x + 0.59) + 0.14), clamped to [0, 1]
//            Reinhard:                     f(x) = x / (1 + x)
//            sRGB encoding (IEC 61966-2-1): 12.92 x for x <= 0.0031308, else 1.055 x^(1/2.4) - 0.055
//            Applied per channel after multiplying by the scene's fixed exposure. PSNR is taken on the result.
// USAGE      vec3 display = emcv_display_encode(linear_rgb * exposure, 0);   // 0 ACES, 1 Reinhard
#ifndef EMCV_PORT_TONEMAP_H
#define EMCV_PORT_TONEMAP_H

#include "port.h"

EMCV_PORT_BEGIN

/// Narkowicz's fit of the ACES reference tonemap, x >= 0 -> [0, 1].
EMCV_FN float emcv_tonemap_aces(float x) {
    float y = (x * (2.51f * x + 0.03f)) / (x * (2.43f * x + 0.59f) + 0.14f);
    return clamp(y, 0.0f, 1.0f);
}

/// Reinhard: x / (1 + x).
EMCV_FN float emcv_tonemap_reinhard(float x) {
    return x / (1.0f + x);
}

/// The sRGB transfer function of a value in [0, 1].
EMCV_FN float emcv_srgb_encode(float x) {
    if (x <= 0.0031308f) return 12.92f * x;
    return 1.055f * pow(x, 1.0f / 2.4f) - 0.055f;
}

/// One channel: exposure already applied; negative and NaN inputs give 0 (a broken pixel shows black).
EMCV_FN float emcv_display_channel(float x, int tonemap) {
    if (!(x > 0.0f)) return 0.0f;
    float t = tonemap == 0 ? emcv_tonemap_aces(x) : emcv_tonemap_reinhard(x);
    return emcv_srgb_encode(min(t, 1.0f));
}

/// Display encoding of a linear colour: emcv_display_channel per channel (tonemap 0: ACES fit, else Reinhard).
EMCV_FN vec3 emcv_display_encode(vec3 x, int tonemap) {
    return vec3(emcv_display_channel(x.x, tonemap), emcv_display_channel(x.y, tonemap),
                emcv_display_channel(x.z, tonemap));
}

/// The inverse of emcv_tonemap_aces on [0, 1]: the root x >= 0 of (2.43 y - 2.51) x^2 + (0.59 y - 0.03) x +
/// 0.14 y = 0 (the fit's rational function solved for x). Its leading coefficient is negative for every y <= 1
/// and its constant term non-negative, so exactly one root is non-negative: (-b - sqrt(b^2 - 4ac)) / (2a).
/// y = 1 gives 7.24, the smallest x the fit clamps to 1.
EMCV_FN float emcv_tonemap_aces_inverse(float y) {
    float a = 2.43f * y - 2.51f, b = 0.59f * y - 0.03f, c = 0.14f * y;
    return (-b - sqrt(max(b * b - 4.0f * a * c, 0.0f))) / (2.0f * a);
}

/// The inverse of emcv_srgb_encode on [0, 1].
EMCV_FN float emcv_srgb_decode(float y) {
    if (y <= 0.04045f) return y / 12.92f;
    return pow((y + 0.055f) / 1.055f, 2.4f);
}

/// The inverse of emcv_display_channel on [0, 1] (values outside are clamped to it): the exposed linear value
/// that displays as y. Reinhard's inverse is t / (1 - t), at most 2^20 where t rounds to 1 (it then displays
/// as 1 again).
EMCV_FN float emcv_display_decode_channel(float y, int tonemap) {
    float t = emcv_srgb_decode(clamp(y, 0.0f, 1.0f));
    return tonemap == 0 ? emcv_tonemap_aces_inverse(t) : t / max(1.0f - t, 1.0f / 1048576.0f);
}

/// The inverse of emcv_display_encode on display values in [0, 1]: what a display value's exposed linear colour
/// was. The temporal resolve filters the scattered light alone in display space and adds the specular light back
/// through it (include/emcv/port/resolve.h).
EMCV_FN vec3 emcv_display_decode(vec3 y, int tonemap) {
    return vec3(emcv_display_decode_channel(y.x, tonemap), emcv_display_decode_channel(y.y, tonemap),
                emcv_display_decode_channel(y.z, tonemap));
}

EMCV_PORT_END

#endif  // #ifndef EMCV_PORT_TONEMAP_H
