// SPDX-License-Identifier: MIT
/// \file
/// emcv/port/port.h — the portability layer of the shared C++17 / GLSL 4.50 core (FidelityFX ffx_a.h pattern).
//
// ABOUT      Every header in include/emcv/port/ is written once in the common dialect of GLSL 4.50 and GLM
//            (docs/porting.md lists the rules). This file maps the few things that differ: function linkage,
//            parameter qualifiers, `precise`, the finiteness test and the namespace. fp32 throughout.
// USAGE C++  #include <emcv/port/ema.h> (or any port header); everything lives in namespace emcv::port and
//            needs GLM (glm::glm). Compile with -ffp-contract=off where bit-equality with the GPU matters.
// USAGE GLSL #include "emcv/port/ema.h" through demo/gl's shader preprocessor (include root: include/);
//            the preprocessor drops the C++-only `#include <...>` lines, GLSL never defines __cplusplus.
//            Without an include resolver: the installed share/emcv/emcv_port.glsl, every header in one file
//            (docs/integration.md, section 4).
// OPTIONS    EMCV_FN ........ function linkage          (C++ `inline`, GLSL empty)
//            EMCV_IN(T) ..... input parameter           (C++ `T const&`, GLSL `in T`)
//            EMCV_INOUT(T) .. in/out parameter          (C++ `T&`, GLSL `inout T`)
//            EMCV_OUT(T) .... output parameter          (C++ `T&`, GLSL `out T`)
//            EMCV_PRECISE ... no FMA contraction / reassociation of the value (C++ empty, GLSL `precise`)
//            EMCV_PORT_CHECKS  0 (default) or 1: parameter checks, for debug builds (below)
//            Each is defined only when the includer has not defined it already.
// CHECKS     The port validates no parameter by default: a shader cannot throw, and a check per pixel and
//            frame costs instructions and registers for values the host validated once (docs/porting.md,
//            "What the port does not check"). With EMCV_PORT_CHECKS 1 (a debug build), the pushes refuse an
//            eta outside (0, 1] or a batch size n < 1 like a non-finite sample (state unchanged, `rejected`
//            + 1, false), and emcv_sample_count returns -1 for a target that is not finite and > 0 or for
//            n_min < 0 or n_min > n_max; in C++ each refusal also reaches EMCV_ASSERT
//            (emcv/detail/common.hpp: aborts without NDEBUG, overridable). With 0 the checks are not
//            compiled at all: the code is the code without them.
#ifndef EMCV_PORT_PORT_H
#define EMCV_PORT_PORT_H

/// pi, written once for the whole project: a double in C++ (use float(EMCV_PI) for fp32), a float literal in
/// GLSL. Both round to the same fp32 value, 0x40490FDB.
#define EMCV_PI 3.14159265358979323846

#ifndef EMCV_PORT_CHECKS
/// 1: the port checks its parameters (debug builds; see CHECKS above); 0 (default): no check is compiled.
#define EMCV_PORT_CHECKS 0
#endif

#ifdef __cplusplus
// The C++ side is written in GLM's GLSL-like types: without GLM, stop here and say so (not "not a member" later).
#if defined(__has_include)
#if !__has_include(<glm/glm.hpp>)
#error "emcv: <emcv/port/*.h> and <emcv/adaptive_sampling.hpp> need GLM, and <glm/glm.hpp> is not on the include path: install GLM (Debian: libglm-dev) and link emcv::port (find_package(emcv COMPONENTS port))"
#endif
#endif
#include <cmath>
#include <glm/glm.hpp>
#if EMCV_PORT_CHECKS
#include <emcv/detail/common.hpp>
/// Under EMCV_PORT_CHECKS: the condition's value, after EMCV_ASSERT on it (C++); GLSL: the condition.
#define EMCV_PORT_CHECK(cond) ::emcv::port::emcv_port_check((cond), "emcv port: parameter check failed: " #cond)
#endif
#ifndef EMCV_FN
/// Function linkage: C++ `inline`, GLSL empty.
#define EMCV_FN inline
#endif
#ifndef EMCV_IN
/// Input parameter of type T: C++ `T const&`, GLSL `in T`.
#define EMCV_IN(T) T const&
#endif
#ifndef EMCV_INOUT
/// In/out parameter of type T: C++ `T&`, GLSL `inout T`.
#define EMCV_INOUT(T) T&
#endif
#ifndef EMCV_OUT
/// Output parameter of type T: C++ `T&`, GLSL `out T`.
#define EMCV_OUT(T) T&
#endif
#ifndef EMCV_PRECISE
/// No FMA contraction or reassociation of the value: C++ empty (compile with -ffp-contract=off), GLSL `precise`.
#define EMCV_PRECISE
#endif
/// Opens the port's scope: C++ `namespace emcv::port` with GLM's names, GLSL nothing.
#define EMCV_PORT_BEGIN namespace emcv { namespace port { using namespace glm;
/// Closes what EMCV_PORT_BEGIN opened.
#define EMCV_PORT_END } }
#else  // GLSL
#ifndef EMCV_FN
#define EMCV_FN
#endif
#ifndef EMCV_IN
#define EMCV_IN(T) in T
#endif
#ifndef EMCV_INOUT
#define EMCV_INOUT(T) inout T
#endif
#ifndef EMCV_OUT
#define EMCV_OUT(T) out T
#endif
#ifndef EMCV_PRECISE
#define EMCV_PRECISE precise
#endif
#define EMCV_PORT_BEGIN
#define EMCV_PORT_END
#endif  // #ifdef __cplusplus

#ifdef __cplusplus
/// \namespace emcv::port
/// The shared C++/GLSL per-pixel core (fp32), the C++ side of include/emcv/port/*.h; docs/porting.md.
namespace emcv { namespace port {
using namespace glm;
/// True when x is neither NaN nor +-Inf (std::isfinite; GLSL has no isfinite, see below).
inline bool emcv_is_finite(float x) { return std::isfinite(x); }
/// True when x is NaN.
inline bool emcv_is_nan(float x) { return std::isnan(x); }
#if EMCV_PORT_CHECKS
/// EMCV_PORT_CHECK's C++ side: reports a failed parameter check through EMCV_ASSERT and returns ok.
inline bool emcv_port_check(bool ok, const char* what) {
    EMCV_ASSERT(ok, what);
    return ok;
}
#endif
} }
#else
bool emcv_is_finite(float x) { return !(isnan(x) || isinf(x)); }
bool emcv_is_nan(float x) { return isnan(x); }
#if EMCV_PORT_CHECKS
#define EMCV_PORT_CHECK(cond) (cond)
#endif
#endif  // #ifdef __cplusplus

EMCV_PORT_BEGIN

/// Smallest positive normal fp32 number, 2^-126 (std::numeric_limits<float>::min()).
EMCV_FN float emcv_float_min_normal() { return 1.17549435e-38f; }

/// Largest finite fp32 value, (2 - 2^-23) 2^127 (std::numeric_limits<float>::max()).
EMCV_FN float emcv_float_max() { return 3.40282347e38f; }

EMCV_PORT_END

#endif  // #ifndef EMCV_PORT_PORT_H
