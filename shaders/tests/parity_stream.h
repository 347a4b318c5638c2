// SPDX-License-Identifier: MIT
// shaders/tests/parity_stream.h — the deterministic per-pixel streams of the CPU<->GPU parity test, written once
// in the port dialect and included by both tests/gpu/test_port_parity.cpp and port_parity.comp.glsl.
//
// Pixel class = pixel % 8 (the hard cases of the numerics issue that lie in the float range):
//   0 unit scale            1 large offset 1e4 (cancellation in x - mu)   2 tiny scale 1e-15
//   3 huge scale 1e18       4 constant control G (Var G = 0: alpha guard)  5 step change at mid-stream (x10)
//   6 NaN in f every 1000th update, +Inf in G every 1000th (rejections)    7 anti-correlated f and G
// All arithmetic on floats is EMCV_PRECISE so both sides compute the inputs bit-identically.
#ifndef EMCV_SHADERS_TESTS_PARITY_STREAM_H
#define EMCV_SHADERS_TESTS_PARITY_STREAM_H

#include "emcv/port/hash.h"

EMCV_PORT_BEGIN

EMCV_FN uint emcv_parity_class(uint pixel) { return pixel % 8u; }

/// Sample k of pixel `pixel`'s stream: (f, G).
EMCV_FN vec2 emcv_parity_sample(uint pixel, uint k, uint updates, uint seed) {
    uint h = emcv_pcg(emcv_pcg(pixel ^ seed) + k);
    float u1 = emcv_uint_to_unit_float(h) - 0.5f;
    float u2 = emcv_uint_to_unit_float(emcv_pcg(h)) - 0.5f;
    uint c = emcv_parity_class(pixel);
    float scale = 1.0f;
    float offset = 0.0f;
    float g_scale = 1.0f;
    if (c == 1u) offset = 1.0e4f;
    if (c == 2u) scale = 1.0e-15f;
    if (c == 3u) scale = 1.0e18f;
    if (c == 4u) g_scale = 0.0f;
    if (c == 5u && k >= updates / 2u) scale = 10.0f;
    if (c == 7u) g_scale = -1.0f;
    EMCV_PRECISE float f = offset + scale * u1;
    EMCV_PRECISE float mix_g = 0.5f * u1 + 0.5f * u2;
    EMCV_PRECISE float g = 2.0f * offset + scale * g_scale * mix_g + 0.25f * scale;
    if (c == 6u && k % 1000u == 999u) f = uintBitsToFloat(0x7fc00000u);  // NaN
    if (c == 6u && k % 1000u == 500u) g = uintBitsToFloat(0x7f800000u);  // +Inf
    return vec2(f, g);
}

EMCV_PORT_END

#endif  // #ifndef EMCV_SHADERS_TESTS_PARITY_STREAM_H
