// SPDX-License-Identifier: MIT
/// \file
/// emcv/port/cv.h — control-variate coefficient and residual in the shared C++/GLSL dialect (fp32).
//
// ABOUT      Float twins of emcv::cv_coefficient and emcv::cv_residual (include/emcv/control_variate.hpp):
//                alpha* = Cov(F, G) / Var(G)                        Eq. 31
//                r      = f - alpha g                               Eq. 29
//            with the same guard: alpha = 0 when Var(G) is not above the floor (default: the smallest normal
//            float; covers 0, negatives, NaN, subnormals), when either input is not finite, or when the
//            quotient overflows. alpha = 0 means "no control variate", which can only over-state variance.
// USAGE      float a = emcv_cv_coefficient(s.cov.y, s.cov.z);  float res = emcv_cv_residual(f, a, G);
#ifndef EMCV_PORT_CV_H
#define EMCV_PORT_CV_H

#include "port.h"
#include "ema.h"

EMCV_PORT_BEGIN

/// alpha* = cov_fg / var_g, guarded (see above). var_floor >= smallest normal.
EMCV_FN float emcv_cv_coefficient_floor(float cov_fg, float var_g, float var_floor) {
    if (!(var_g > var_floor) || !emcv_is_finite(var_g) || !emcv_is_finite(cov_fg)) return 0.0f;
    float alpha = cov_fg / var_g;
    return emcv_is_finite(alpha) ? alpha : 0.0f;
}

/// alpha* = cov_fg / var_g (Eq. 31), 0 when var_g is below the smallest normal float or a value is not finite.
EMCV_FN float emcv_cv_coefficient(float cov_fg, float var_g) {
    return emcv_cv_coefficient_floor(cov_fg, var_g, emcv_float_min_normal());
}

/// The coefficient of an EMCM over (f, G): C_fG / C_GG.
EMCV_FN float emcv_cv_coefficient_emcm2(EMCV_IN(EmcvEmcm2) s) {
    return emcv_cv_coefficient(s.cov.y, s.cov.z);
}

/// r = f - alpha g, the residual whose variance drives the sample count.
EMCV_FN float emcv_cv_residual(float f, float alpha, float g) {
    EMCV_PRECISE float r = f - alpha * g;
    return r;
}

/// Var(f - alpha G) = C_ff - 2 alpha C_fG + alpha^2 C_GG (Eq. 29), clamped to >= 0 (a negative value is
/// rounding); NaN stays NaN. Twin of emcv::cv_residual_variance.
EMCV_FN float emcv_cv_residual_variance(float c_ff, float c_fg, float c_gg, float alpha) {
    EMCV_PRECISE float v = c_ff - 2.0f * alpha * c_fg + alpha * alpha * c_gg;
    return v > 0.0f ? v : (emcv_is_nan(v) ? v : 0.0f);
}

/// min over alpha of Var(f - alpha G) = C_ff - C_fG^2 / C_GG (Eq. 31), evaluated as C_ff - alpha* C_fG with
/// the guarded alpha* (C_ff where the guard gives 0), clamped to >= 0. Twin of
/// emcv::cv_optimal_residual_variance.
EMCV_FN float emcv_cv_optimal_residual_variance(float c_ff, float c_fg, float c_gg) {
    float alpha = emcv_cv_coefficient(c_fg, c_gg);
    EMCV_PRECISE float v = c_ff - alpha * c_fg;
    return v > 0.0f ? v : (emcv_is_nan(v) ? v : 0.0f);
}

/// The same from an EMCM over (f, G).
EMCV_FN float emcv_cv_optimal_residual_variance_emcm2(EMCV_IN(EmcvEmcm2) s) {
    return emcv_cv_optimal_residual_variance(s.cov.x, s.cov.y, s.cov.z);
}

EMCV_PORT_END

#endif  // #ifndef EMCV_PORT_CV_H
