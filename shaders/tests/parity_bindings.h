// SPDX-License-Identifier: MIT
// shaders/tests/parity_bindings.h — binding slots of the CPU<->GPU parity test, read by
// tests/gpu/test_port_parity.cpp and shaders/tests/port_parity.comp.glsl (the test's own, not installed).
#ifndef EMCV_SHADERS_TESTS_PARITY_BINDINGS_H
#define EMCV_SHADERS_TESTS_PARITY_BINDINGS_H

#define EMCV_BINDING_PARITY_PARAMS 0  // uniform block: stream parameters
#define EMCV_BINDING_PARITY_OUTPUT 1  // storage buffer: per-pixel results (EMCV_PARITY_OUTPUT_VEC4S vec4s)
#define EMCV_PARITY_OUTPUT_VEC4S 6    // vec4s per pixel in that buffer

#endif  // #ifndef EMCV_SHADERS_TESTS_PARITY_BINDINGS_H
