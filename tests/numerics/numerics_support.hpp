// SPDX-License-Identifier: MIT
// Shared machinery of the hard-case suite (docs/numerics.md): binary16 rounding of estimator state, the
// long-double reference recurrence, and the first-order running error bound every case is checked against.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <emcv/emcv.hpp>

namespace emcv_numerics {

using ld = long double;

// ---------------------------------------------------------------------------------------------------------
// binary16 (RGBA16F) rounding
// ---------------------------------------------------------------------------------------------------------

constexpr double half_max = 65504.0;
constexpr double half_unit_roundoff = 1.0 / 2048.0;              // 2^-11
constexpr double half_subnormal_spacing = 1.0 / 16777216.0;      // 2^-24, the smallest half subnormal

/// What a store beyond the half range does: IEEE round-to-nearest-even overflows to +-Inf (values at or
/// above 65520 in magnitude); a shader that clamps before storing (min(v, 65504)) saturates instead.
enum class half_overflow { to_infinity, saturate };

/// Rounds v to the nearest binary16 value, ties to even (IEEE 754 roundTiesToEven), including the half
/// subnormals (spacing 2^-24). NaN stays NaN.
inline double round_to_half(double v, half_overflow overflow = half_overflow::to_infinity) {
    if (std::isnan(v) || v == 0.0) return v;
    if (std::isinf(v)) return overflow == half_overflow::saturate ? std::copysign(half_max, v) : v;
    int exponent = 0;
    std::frexp(v, &exponent);  // |v| = m 2^exponent, m in [0.5, 1): the leading bit has weight 2^(exponent-1)
    const int leading = std::max(exponent - 1, -14);   // below 2^-14 the spacing stays at 2^-24 (subnormals)
    const double spacing = std::ldexp(1.0, leading - 10);  // 11 significant bits
    const double q = std::nearbyint(v / spacing) * spacing;  // scaling by a power of two is exact
    if (std::fabs(q) > half_max)
        return overflow == half_overflow::saturate ? std::copysign(half_max, v)
                                                   : std::copysign(std::numeric_limits<double>::infinity(), v);
    return q;
}

/// Rounds every floating-point field of an estimator state as an RGBA16F history texture would store it.
template <class State>
State round_state_to_half(State s, half_overflow overflow) {
    using T = decltype(s.total_weight);
    auto q = [overflow](T& v) { v = static_cast<T>(round_to_half(static_cast<double>(v), overflow)); };
    q(s.total_weight);
    for (auto& v : s.mean) q(v);
    for (auto& v : s.covariance) q(v);
    for (auto& v : s.mean_compensation) q(v);
    for (auto& v : s.covariance_compensation) q(v);
    return s;
}

// ---------------------------------------------------------------------------------------------------------
// Estimator schedules: which r_n = w_n / W_n a stream sees
// ---------------------------------------------------------------------------------------------------------

enum class schedule_kind { cumulative, weighted, exponential };

struct schedule {
    schedule_kind kind = schedule_kind::cumulative;
    emcv::comoment_form form = emcv::comoment_form::current_mean;
    ld eta = 0;     // exponential: the eta as stored in T
    ld decay = 1;   // weighted: decay of every step (weights come with the samples)
};

/// Unit roundoff of T under round to nearest.
template <class T>
constexpr ld unit_roundoff() {
    return static_cast<ld>(std::numeric_limits<T>::epsilon()) / 2;
}

/// Floating-point model of one precision for the bound: u of the arithmetic, u of the state store (0 unless
/// the state is re-rounded, for example to binary16), absolute underflow terms, and the mean form.
struct precision_model {
    ld u = 0;
    ld store_u = 0;
    ld tiny = 0;        // absolute error of one rounding in the subnormal range of the arithmetic
    ld store_tiny = 0;  // same for the store (half subnormal spacing / 2)
    bool compensated = false;
    bool count_ratio = false;  // r = 1 / T(n) computed in T (cumulative estimators)
};

/// Exact-arithmetic reference of the one recurrence, carried in long double, together with the first-order
/// running error bound of the T computation (docs/numerics.md, section 2). Both the T estimator and this
/// reference see the same samples, weights and (T-rounded) eta.
template <std::size_t N>
class reference_with_bound {
public:
    static constexpr std::size_t packed = N * (N + 1) / 2;

    reference_with_bound(schedule sch, precision_model model, precision_model reference_model)
        : sch_(sch), m_(model), mr_(reference_model) {}

    void push(const std::array<ld, N>& x, ld weight = 1) {
        ++n_;
        // ---- r_n, and the relative error bounds rho of the computed r (T side) and of the reference's ----
        ld r = 1, rho = 0, rho_ref = 0;
        if (sch_.kind == schedule_kind::cumulative) {
            r = 1 / static_cast<ld>(n_);
            rho = 2.02L * m_.u;  // T(n) rounded, then one division
            rho_ref = 1.01L * mr_.u;
        } else if (sch_.kind == schedule_kind::weighted) {
            const ld w_new = sch_.decay * w_ + weight;
            // relative error of the T total weight: old error carried with weight decay W / W', two roundings
            // (product, sum), and the store rounding when the state is re-rounded
            omega_ = (w_new > 0 ? sch_.decay * w_ * omega_ / w_new : 0) + 2.02L * m_.u + 1.01L * m_.store_u;
            omega_ref_ = (w_new > 0 ? sch_.decay * w_ * omega_ref_ / w_new : 0) + 2.02L * mr_.u;
            w_ = w_new;
            if (!(w_ > 0)) {
                mean_.fill(0);
                cov_.fill(0);
                bm_.fill(0);
                bc_.fill(0);
                return;
            }
            r = weight / w_;
            rho = omega_ + 1.01L * m_.u;
            rho_ref = omega_ref_ + 1.01L * mr_.u;
        } else {
            r = n_ == 1 ? 1 : sch_.eta;
        }
        const bool current = n_ == 1 || sch_.form == emcv::comoment_form::current_mean;
        const ld keep = 1 - r;

        std::array<ld, N> d{};
        for (std::size_t i = 0; i < N; ++i) d[i] = x[i] - mean_[i];
        std::array<ld, N> mean_new{};
        for (std::size_t i = 0; i < N; ++i) mean_new[i] = mean_[i] + r * d[i];

        step_bound(m_, rho, r, keep, current, d, mean_new, bm_, bc_);
        step_bound(mr_, rho_ref, r, keep, current, d, mean_new, bmr_, bcr_);

        mean_ = mean_new;
        std::size_t k = 0;
        for (std::size_t i = 0; i < N; ++i)
            for (std::size_t j = i; j < N; ++j, ++k) cov_[k] = cov_[k] + r * ((current ? keep : 1) * d[i] * d[j] - cov_[k]);
    }

    ld mean(std::size_t i) const { return mean_[i]; }
    ld cov(std::size_t k) const { return cov_[k]; }
    /// Bound on |computed - exact| for the mean: the T estimator's bound plus the reference's own.
    ld mean_bound(std::size_t i) const { return bm_[i] + bmr_[i]; }
    ld cov_bound(std::size_t k) const { return bc_[k] + bcr_[k]; }
    std::uint64_t count() const { return n_; }

private:
    // One step of the running bound (docs/numerics.md, Eq. B1-B3). bm, bc are bounds on the errors of the
    // stored mean and covariance; exact quantities come from the reference.
    void step_bound(const precision_model& m, ld rho, ld r, ld keep, bool current,
                    const std::array<ld, N>& d, const std::array<ld, N>& mean_new, std::array<ld, N>& bm,
                    std::array<ld, packed>& bc) const {
        const ld u = m.u;
        std::array<ld, N> delta{};  // bound on |d_computed - d|
        for (std::size_t i = 0; i < N; ++i) {
            const ld ad = std::fabs(d[i]);
            if (m.compensated)
                delta[i] = bm[i] + 2.02L * u * (ad + bm[i]) + 1.01L * u * u * std::fabs(mean_[i]) + 2 * m.tiny;
            else
                delta[i] = (1 + u) * bm[i] + u * ad + m.tiny;
        }
        std::array<ld, N> bm_new{};
        for (std::size_t i = 0; i < N; ++i) {
            const ld ad = std::fabs(d[i]);
            const ld am = std::fabs(mean_new[i]);
            ld b;
            if (m.compensated)  // (B1c)
                b = keep * bm[i] + r * (delta[i] - bm[i]) + r * (1.01L * u + rho) * (ad + delta[i]) +
                    2.2L * u * u * (am + bm[i]) + 3 * m.tiny;
            else  // (B1)
                b = keep * bm[i] + r * u * (ad + bm[i]) + r * (2.02L * u + rho) * (ad + delta[i]) +
                    1.01L * u * (am + bm[i] + r * (ad + delta[i])) + 3 * m.tiny;
            bm_new[i] = b + m.store_u * (am + b) + m.store_tiny;  // (B3) store rounding
        }
        // outer = 1 - r (current mean) or 1 (previous mean), and the absolute error of its computed value
        const ld outer = current ? keep : 1;
        const ld douter = current ? r * rho + 1.01L * u * (keep + r * rho) : 0;
        std::size_t k = 0;
        for (std::size_t i = 0; i < N; ++i) {
            for (std::size_t j = i; j < N; ++j, ++k) {
                const ld ai = std::fabs(d[i]), aj = std::fabs(d[j]);
                const ld ac = std::fabs(cov_[k]);
                const ld e = std::fabs(outer * d[i] * d[j]);
                const ld c_new = std::fabs(cov_[k] + r * (outer * d[i] * d[j] - cov_[k]));
                // (B2) computed Cov' = Cov + r ((outer d_i) d_j - Cov): error of the product e, then of the
                // difference, of the multiplication by r (and r's own error rho), of the final sum
                const ld de = douter * (ai + delta[i]) * (aj + delta[j]) +
                              outer * (ai * delta[j] + aj * delta[i] + delta[i] * delta[j]) +
                              2.02L * u * (outer + douter) * (ai + delta[i]) * (aj + delta[j]) + 2 * m.tiny;
                const ld t = e + de + ac + bc[k];
                // (B2c) compensated: the final sum is exact (TwoSum), the low part's sum costs u^2 |Cov'|
                const ld final_sum = m.compensated ? 2.2L * u * u * (c_new + bc[k] + r * de)
                                                   : 1.01L * u * (c_new + bc[k] + r * de);
                ld b = (keep + r * rho) * bc[k] + r * de + r * (2.02L * u + rho) * t + final_sum + 3 * m.tiny;
                bc[k] = b + m.store_u * (c_new + b) + m.store_tiny;
            }
        }
        bm = bm_new;
    }

    schedule sch_;
    precision_model m_, mr_;
    std::uint64_t n_ = 0;
    ld w_ = 0, omega_ = 0, omega_ref_ = 0;
    std::array<ld, N> mean_{}, bm_{}, bmr_{};
    std::array<ld, packed> cov_{}, bc_{}, bcr_{};
};

template <class T>
precision_model model_of(bool half_state, bool compensated, bool count_ratio) {
    precision_model m;
    m.u = unit_roundoff<T>();
    m.tiny = static_cast<ld>(std::numeric_limits<T>::denorm_min()) / 2;
    m.store_u = half_state ? static_cast<ld>(half_unit_roundoff) : 0;
    m.store_tiny = half_state ? static_cast<ld>(half_subnormal_spacing) / 2 : 0;
    m.compensated = compensated;
    m.count_ratio = count_ratio;
    return m;
}

inline precision_model long_double_model() { return model_of<ld>(false, false, false); }

// ---------------------------------------------------------------------------------------------------------
// Deterministic streams
// ---------------------------------------------------------------------------------------------------------

/// Uniform in [-1, 1) from a fixed-seed 64-bit Mersenne Twister, independent of the standard library's
/// distribution implementations.
class uniform_source {
public:
    explicit uniform_source(std::uint64_t seed) : g_(seed) {}
    double next() { return static_cast<double>(g_() >> 11) * 0x1.0p-52 - 1.0; }

private:
    std::mt19937_64 g_;
};

}  // namespace emcv_numerics
