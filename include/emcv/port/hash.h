// SPDX-License-Identifier: MIT
/// \file
/// emcv/port/hash.h — integer hashing and low-discrepancy points in the shared C++/GLSL dialect.
//
// ABOUT      All arithmetic is on 32-bit unsigned integers (wrap-around is defined in both languages), and
//            the conversion to float is exact (24 bits), so the CPU and the GPU produce identical bits.
//            emcv_pcg:      PCG-based hash (Jarzynski & Olano, "Hash Functions for GPU Rendering", JCGT 2020).
//            emcv_r2:       R2 sequence (Roberts 2018) in 0.32 fixed point: x_n = frac(1/2 + n (1/g, 1/g^2)),
//                           g the plastic number 1.3247179572...
//            emcv_hammersley: (i / n, radical inverse of i in base 2).
// USAGE      uint h = emcv_pcg(seed ^ emcv_pcg(index)); float u = emcv_uint_to_unit_float(h);
#ifndef EMCV_PORT_HASH_H
#define EMCV_PORT_HASH_H

#include "port.h"

EMCV_PORT_BEGIN

/// PCG hash: one LCG step and an output permutation (JCGT 2020, "pcg").
EMCV_FN uint emcv_pcg(uint v) {
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

/// The top 24 bits of x as a float in [0, 1): exact, identical on every IEEE-754 device.
EMCV_FN float emcv_uint_to_unit_float(uint x) {
    return float(x >> 8u) * (1.0f / 16777216.0f);
}

/// Point n of the first two dimensions of Sobol's sequence as 0.32 fixed point: the bits of n reversed (van der
/// Corput) and Sobol's second dimension (direction numbers v_k = v_(k-1) ^ (v_(k-1) >> 1), v_0 = 2^31). Together a
/// (0, 2)-sequence in base 2: every 2^k consecutive points from a multiple of 2^k put one point in each elementary
/// interval of area 2^-k. Bit operations only: the same bits in C++ and GLSL.
EMCV_FN uvec2 emcv_sobol2_bits(uint n) {
    uint x = 0u;
    uint y = 0u;
    uint v = 2147483648u;
    for (uint k = 0u; k < 32u; ++k) {
        if ((n & (1u << k)) != 0u) {
            x ^= 2147483648u >> k;
            y ^= v;
        }
        v ^= v >> 1u;
    }
    return uvec2(x, y);
}

/// Point n of the R2 sequence, in [0, 1)^2 (0.32 fixed point: 2^32/g = 3242174889, 2^32/g^2 = 2447445414).
EMCV_FN vec2 emcv_r2(uint n) {
    uint x = 2147483648u + n * 3242174889u;
    uint y = 2147483648u + n * 2447445414u;
    return vec2(emcv_uint_to_unit_float(x), emcv_uint_to_unit_float(y));
}

/// Point i of an n-point Hammersley set: (i / n, radical inverse of i), in [0, 1)^2.
EMCV_FN vec2 emcv_hammersley(uint i, uint n) {
    return vec2(float(i) / float(n), emcv_uint_to_unit_float(bitfieldReverse(i)));
}

EMCV_PORT_END

#endif  // #ifndef EMCV_PORT_HASH_H
