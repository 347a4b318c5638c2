// SPDX-License-Identifier: MIT
/// \file
/// emcv control variates: the coefficient alpha (Eq. 29-31) and the residual policies of the toy experiment
/// (supplementary section 3), shared by emcv-toy and the renderer.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>

#include "emcm.hpp"
#include "moving_stats.hpp"

namespace emcv {

/// alpha* = Cov(F, G) / Var(G), Eq. 31.
///
/// Guard: returns 0 when var_g is not above var_floor (this covers 0, negative, NaN and, with the default
/// floor of the smallest normal number, subnormal variances; a NaN floor refuses every variance), when cov_fg
/// is not finite, or when the quotient overflows. alpha = 0 means "no control variate": the residual is then f itself, whose variance can only
/// over-state what the adaptive sampler needs, never under-state it. A meaningless coefficient divided out of
/// a vanishing variance would do the opposite. Callers whose G has a known scale pass a relative floor,
/// for example (1e-6 * |E[G]|)^2, see variance_floor().
template <class T>
T cv_coefficient(T cov_fg, T var_g, T var_floor = std::numeric_limits<T>::min()) noexcept {
    if (!(var_g > var_floor) || !std::isfinite(var_g) || !std::isfinite(cov_fg)) return T(0);
    const T alpha = cov_fg / var_g;
    return std::isfinite(alpha) ? alpha : T(0);
}

/// A variance floor relative to the control's scale: (relative * |mean_g|)^2, at least the smallest normal.
template <class T>
T variance_floor(T mean_g, T relative) noexcept {
    const T s = relative * std::fabs(mean_g);
    const T f = s * s;
    return f > std::numeric_limits<T>::min() ? f : std::numeric_limits<T>::min();
}

/// Control-variate residual r = f - alpha * g' = <F - alpha G>, the quantity whose variance drives sampling.
template <class T>
T cv_residual(T f, T alpha, T g) noexcept {
    return f - alpha * g;
}

/// Variance of the residual f - alpha G from the covariance of (f, G), Eq. 29:
///     Var(f - alpha G) = C_ff - 2 alpha C_fG + alpha^2 C_GG.
/// It is a variance of a linear combination, so it is >= 0 for any positive semi-definite covariance; a
/// negative value can only come from rounding (or an inconsistent state) and is clamped to 0. A non-finite
/// input gives a non-finite result (sample_count turns a NaN into n_max: a broken history samples).
template <class T>
T cv_residual_variance(T c_ff, T c_fg, T c_gg, T alpha) noexcept {
    const T v = c_ff - T(2) * alpha * c_fg + alpha * alpha * c_gg;
    return v > T(0) ? v : (v == v ? T(0) : v);
}

/// The residual variance at the optimal coefficient, min over alpha of Var(f - alpha G) (Eq. 31):
///     alpha* = C_fG / C_GG,   Var(f - alpha* G) = C_ff - C_fG^2 / C_GG.
/// The adaptive sample count is proportional to this variance (N = Var / target), and the alpha that minimises
/// N is the alpha that minimises the variance: one EMCM gives both (joint optimisation, Xie & Olano 2021, section 5).
/// Evaluated as C_ff - alpha* C_fG with alpha* = cv_coefficient(C_fG, C_GG, var_floor), so where alpha's guard
/// gives 0 (C_GG not above the floor, non-finite C_fG) the result is C_ff: no control variate, the variance
/// of f itself, which can only over-state what the sampler needs. Clamped to >= 0 like cv_residual_variance.
template <class T>
T cv_optimal_residual_variance(T c_ff, T c_fg, T c_gg, T var_floor = std::numeric_limits<T>::min()) noexcept {
    const T alpha = cv_coefficient(c_fg, c_gg, var_floor);
    const T v = c_ff - alpha * c_fg;
    return v > T(0) ? v : (v == v ? T(0) : v);
}

/// cv_optimal_residual_variance of an EMCM over (f, G): Var(f - alpha G) = C_ff - C_fG^2 / C_GG.
template <class T>
T cv_optimal_residual_variance(const emcm<T, 2>& fg, T var_floor = std::numeric_limits<T>::min()) noexcept {
    return cv_optimal_residual_variance(fg.variance(0), fg.covariance(0, 1), fg.variance(1), var_floor);
}

/// The residuals compared in the paper's toy experiment (Xie & Olano 2021, section 3, Table 1). In every policy the
/// coefficient applied to frame t comes from frames up to t - 1.
enum class residual_policy {
    none,              ///< Res_f = fbar: no control variate, alpha = 0
    single_frame,      ///< Res_SF = fbar - alpha_SF gbar, alpha_SF from the previous frame's samples alone
    single_frame_ema,  ///< Res_SF+EMA: as single_frame with alpha_SF smoothed by an exponential moving average
    emcm_sampled,      ///< Res_EMCM = fbar - alpha_EMCM gbar, alpha from an EMCM over (fbar, gbar) per frame
    emcm_constant,     ///< ResHat_EMCM = fbar - alpha_EMCM G: same EMCM, in-frame constant control G = E[g]
};

/// What one frame contributes, per pixel.
template <class T>
struct cv_frame {
    T f = T(0);           ///< frame mean of f (fbar)
    T g = T(0);           ///< frame mean of the sampled control (gbar); G itself where g is not sampled
    T g_expected = T(0);  ///< the control's known mean G(t), the in-frame constant (Eq. 38)
    T cov_fg = T(0);      ///< in-frame covariance of the per-sample (f, g) pairs (single-frame policies)
    T var_g = T(0);       ///< in-frame variance of the per-sample g (single-frame policies)
};

/// One pixel's control variate under a residual policy.
///   r_t = residual(frame_t)   uses alpha_{t-1}
///   update(frame_t)           advances alpha to alpha_t
template <class T>
class control_variate {
public:
    /// @param policy    how the residual and its coefficient are formed (residual_policy)
    /// @param eta_cov   EMCM weight over frames in (0, 1] (emcm_* policies), the paper uses 0.05
    /// @param eta_alpha EMA weight in (0, 1] that smooths alpha_SF (single_frame_ema); the paper leaves it open
    /// @param var_floor every alpha is cv_coefficient(C_fG, C_GG, var_floor): C_fG / C_GG where C_GG is above
    ///                  the floor, 0 (no control variate) where it is not. The default, the smallest normal
    ///                  number, only refuses zero and subnormal variances; a control with a known scale
    ///                  should pass variance_floor(E[G], 1e-6) (docs/estimators.md, "The coefficient guard").
    /// Throws std::invalid_argument (naming emcv::control_variate and the parameter) when a parameter the
    /// policy uses is invalid: eta_cov for the emcm_* policies, eta_alpha for single_frame_ema, var_floor (>= 0,
    /// not NaN) for every policy but none. A parameter the policy never reads is not checked.
    explicit control_variate(residual_policy policy, T eta_cov = T(0.05), T eta_alpha = T(0.05),
                             T var_floor = std::numeric_limits<T>::min())
        : policy_(policy),
          var_floor_(checked_floor(policy, var_floor)),
          cov_(uses_frame_emcm(policy) ? detail::checked_eta(eta_cov, "emcv::control_variate", "eta_cov") : T(1)),
          alpha_ema_(policy == residual_policy::single_frame_ema
                         ? detail::checked_eta(eta_alpha, "emcv::control_variate", "eta_alpha")
                         : T(1)) {}

    /// The residual policy given at construction.
    residual_policy policy() const noexcept { return policy_; }
    /// Coefficient that the next residual() applies; 0 until a frame has been seen.
    T alpha() const noexcept { return alpha_; }
    /// The variance floor every alpha is computed with (the constructor's var_floor).
    T var_floor() const noexcept { return var_floor_; }
    /// The EMCM over (f, g) frame means (the emcm_* policies; under the others it stays empty, with eta 1).
    const emcm<T, 2>& frame_covariance() const noexcept { return cov_; }

    /// r_t = f - alpha_{t-1} g (Eq. 29), with g = the known G(t) under emcm_constant, f itself under none.
    T residual(const cv_frame<T>& fr) const noexcept {
        switch (policy_) {
            case residual_policy::none: return fr.f;
            case residual_policy::emcm_constant: return cv_residual(fr.f, alpha_, fr.g_expected);
            default: return cv_residual(fr.f, alpha_, fr.g);
        }
    }

    /// Advances alpha to alpha_t from frame t, as the policy prescribes (Eq. 31 on the frame or on the EMCM).
    void update(const cv_frame<T>& fr) {
        switch (policy_) {
            case residual_policy::none: break;
            case residual_policy::single_frame: alpha_ = cv_coefficient(fr.cov_fg, fr.var_g, var_floor_); break;
            case residual_policy::single_frame_ema:
                alpha_ema_.push(cv_coefficient(fr.cov_fg, fr.var_g, var_floor_));
                alpha_ = alpha_ema_.mean();
                break;
            case residual_policy::emcm_sampled:
            case residual_policy::emcm_constant:
                cov_.push({fr.f, fr.g});
                alpha_ = cv_coefficient(cov_.covariance(0, 1), cov_.variance(1), var_floor_);
                break;
        }
    }

    /// residual() then update(): the residual of frame t with alpha_{t-1}.
    T push(const cv_frame<T>& fr) {
        const T r = residual(fr);
        update(fr);
        return r;
    }

    /// Forgets every frame: alpha = 0, empty EMCM and alpha EMA (a failed reprojection).
    void reset() noexcept {
        alpha_ = T(0);
        cov_.reset();
        alpha_ema_.reset();
    }

private:
    static bool uses_frame_emcm(residual_policy policy) noexcept {
        return policy == residual_policy::emcm_sampled || policy == residual_policy::emcm_constant;
    }
    static T checked_floor(residual_policy policy, T var_floor) {
        if (policy != residual_policy::none)
            detail::require_value(var_floor >= T(0), "emcv::control_variate", "var_floor", var_floor,
                                  "must be >= 0 (and not NaN)");
        return var_floor;
    }

    residual_policy policy_;
    T var_floor_;
    T alpha_ = T(0);
    emcm<T, 2> cov_;
    moving_stats<T> alpha_ema_;
};

}  // namespace emcv
