// SPDX-License-Identifier: MIT
// emcv_adaptive_language.glsl — installed GPU module (share/emcv/module): the GLSL side of the few macros through
// which the modules are also HLSL. The modules are written in the subset of GLSL 4.50 that HLSL shares (no splat
// or struct constructors, no vector ==, no global initialised by a call: docs/porting.md, "HLSL modules"); what
// the two languages spell differently goes through these macros, which module/hlsl/emcv_adaptive_language.hlsl
// defines for HLSL. The modules include it; an application need not.
#ifndef EMCV_ADAPTIVE_LANGUAGE_H
#define EMCV_ADAPTIVE_LANGUAGE_H

// A global of the invocation's own: GLSL's plain global (HLSL needs `static`, else the global is a constant).
#define EMCV_STATIC
// Atomics as statements: HLSL's Interlocked* return the original value through an out parameter only.
#define EMCV_ATOMIC_ADD(dest, value) atomicAdd(dest, value)
#define EMCV_ATOMIC_EXCHANGE(dest, value, original) original = atomicExchange(dest, value)

#endif  // #ifndef EMCV_ADAPTIVE_LANGUAGE_H
