// SPDX-License-Identifier: MIT
/// \file
/// emcv/port/burley.h — Burley normalized diffusion: profile, radial pdf, CDF and radius sampling, in the
/// shared C++/GLSL dialect (fp32).
//
// ABOUT      Per colour channel with shape distance d = l / s(A) > 0 (Xie & Olano 2021, section 4, docs/frame.md):
//                R(r)   = (e^{-r/d} + e^{-r/(3d)}) / (8 pi d r)          area profile, integral R 2 pi r dr = 1
//                p(r)   = (e^{-r/d} + e^{-r/(3d)}) / (4 d)               radial pdf, p = 2 pi r R
//                F(r)   = 1 - e^{-r/d} / 4 - 3 e^{-r/(3d)} / 4           CDF
//                F^-1(u): u' = 1 - u, G = 1 + 4 u' (2 u' + sqrt(1 + 4 u'^2)),
//                         r = 3 d ln((1 + G^{1/3} + G^{-1/3}) / (4 u'))  exact closed form (Golubev)
//                SPVG:    r ~ d (2 + (c - 2) u) (-ln(1 - u)), c = 2.5715 (SPVG 2020; Unreal ships c = 2.6)
//            The approximation is only a sampling strategy: evaluate the exact pdf at the radius it returns.
// USAGE      float r = emcv_burley_sample_exact(u, d); float w = emcv_burley_profile_r(r, d) / emcv_burley_pdf(r, d);
#ifndef EMCV_PORT_BURLEY_H
#define EMCV_PORT_BURLEY_H

#include "port.h"

EMCV_PORT_BEGIN

/// The constant of SPVG's inverse-CDF approximation (SPVG 2020).
EMCV_FN float emcv_burley_spvg_c() { return 2.5715f; }

/// pi in fp32.
EMCV_FN float emcv_burley_pi() { return float(EMCV_PI); }

/// r R(r) = (e^{-r/d} + e^{-r/(3d)}) / (8 pi d): the profile times r, finite at r = 0 (what shaders evaluate).
EMCV_FN float emcv_burley_profile_r(float r, float d) {
    return (exp(-r / d) + exp(-r / (3.0f * d))) / (8.0f * emcv_burley_pi() * d);
}

/// R(r) = (e^{-r/d} + e^{-r/(3d)}) / (8 pi d r), the area profile; infinite at r = 0.
EMCV_FN float emcv_burley_profile(float r, float d) {
    return emcv_burley_profile_r(r, d) / r;
}

/// p(r) = (e^{-r/d} + e^{-r/(3d)}) / (4 d), the radial pdf of the profile.
EMCV_FN float emcv_burley_pdf(float r, float d) {
    return (exp(-r / d) + exp(-r / (3.0f * d))) / (4.0f * d);
}

/// F(r) = 1 - e^{-r/d}/4 - 3 e^{-r/(3d)}/4.
EMCV_FN float emcv_burley_cdf(float r, float d) {
    return 1.0f - 0.25f * exp(-r / d) - 0.75f * exp(-r / (3.0f * d));
}

// The exact inverse CDF is written once for fp32 (C++ and GLSL) and, in C++ only, for double as well: the
// separable kernel's quadrature (demo/render/separable_kernel.cpp) integrates it in double. EMCV_BURLEY_REAL is
// the scalar: a template parameter in C++ (deduced from the arguments), float in GLSL.
#ifdef __cplusplus
/// The scalar of emcv_burley_sample_exact: its template parameter in C++ (undefined after the function).
#define EMCV_BURLEY_REAL Real
template <class Real>
#else
/// The scalar of emcv_burley_sample_exact: float in GLSL (undefined after the function).
#define EMCV_BURLEY_REAL float
#endif
/// Exact inverse of the CDF, u in [0, 1): closed form (Golubev; docs/frame.md).
EMCV_FN EMCV_BURLEY_REAL emcv_burley_sample_exact(EMCV_BURLEY_REAL u, EMCV_BURLEY_REAL d) {
    EMCV_BURLEY_REAL one = EMCV_BURLEY_REAL(1);
    EMCV_BURLEY_REAL v = one - u;
    EMCV_BURLEY_REAL g = one + EMCV_BURLEY_REAL(4) * v * (EMCV_BURLEY_REAL(2) * v + sqrt(one + EMCV_BURLEY_REAL(4) * v * v));
    EMCV_BURLEY_REAL g13 = pow(g, one / EMCV_BURLEY_REAL(3));
    EMCV_BURLEY_REAL x = log((one + g13 + one / g13) / (EMCV_BURLEY_REAL(4) * v));
    return EMCV_BURLEY_REAL(3) * d * x;
}
#undef EMCV_BURLEY_REAL

/// SPVG's approximation r ~ d (2 + (c - 2) u) (-ln(1 - u)), u in [0, 1).
EMCV_FN float emcv_burley_sample_spvg(float u, float d) {
    return d * (2.0f + (emcv_burley_spvg_c() - 2.0f) * u) * (-log(1.0f - u));
}

EMCV_PORT_END

#endif  // #ifndef EMCV_PORT_BURLEY_H
