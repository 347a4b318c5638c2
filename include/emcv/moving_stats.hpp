// SPDX-License-Identifier: MIT
/// \file
/// emcv::moving_stats — exponential moving mean and variance of one scalar (SPVG's per-pixel history).
#pragma once

#include <cmath>
#include <cstddef>
#include <limits>

#include "emcm.hpp"

namespace emcv {

/// Exponential moving mean and variance of a scalar: emcm<T, 1> with a scalar interface.
///     mu' = (1 - eta) mu + eta x,   var' = (1 - eta) (var + eta (x - mu)^2)
/// This is the update of SPVG / Unreal's quality history (eta = 0.2); reset() on failed reprojection.
template <class T>
class moving_stats {
public:
    using value_type = T;                                 ///< the scalar type
    using state_type = typename emcm<T, 1>::state_type;  ///< what a history texture stores

    /// An empty history with weight eta in (0, 1] (SPVG: 0.2); other values throw std::invalid_argument.
    explicit moving_stats(T eta) : e_(detail::checked_eta(eta, "emcv::moving_stats")) {}
    /// Restores a saved state; a state that is not finite or has a negative variance throws (naming the rule).
    moving_stats(T eta, const state_type& s) : e_(detail::checked_eta(eta, "emcv::moving_stats"), checked_state(s)) {}

    /// Returns false (state unchanged, rejected() + 1) when x is not finite.
    bool push(T x) { return e_.push(x); }
    T mean() const noexcept { return e_.mean(0); }                    ///< mu; 0 before any sample
    T variance() const noexcept { return e_.variance(0); }            ///< var; 0 before two samples
    T eta() const noexcept { return e_.eta(); }                       ///< the weight of a new sample
    std::uint64_t count() const noexcept { return e_.count(); }       ///< accepted samples
    std::uint64_t rejected() const noexcept { return e_.rejected(); } ///< refused non-finite samples
    const state_type& state() const noexcept { return e_.state(); }  ///< the state to save
    void reset() noexcept { e_.reset(); }                             ///< forgets every sample

private:
    static const state_type& checked_state(const state_type& s) {
        if (const char* reason = weighted_covariance<T, 1>::invalid_state_reason(s))
            detail::throw_invalid_argument("emcv::moving_stats", reason);
        return s;
    }

    emcm<T, 1> e_;
};

/// What one call of the array form of moving_stats_update did, counted over its pixels.
struct moving_stats_counts {
    std::size_t rejected = 0;  ///< non-finite frame values: the pixel was left untouched
    std::size_t reseeded = 0;  ///< invalid stored pixels (see moving_stats_update) that the frame value reseeded
};

namespace detail {

/// Body of the array form of moving_stats_update, one loop per accuracy so that neither has a branch.
template <mean_accuracy Accuracy, class T>
moving_stats_counts moving_stats_batch(T* mean, T* mean_low, T* variance, T* variance_low, const T* frame,
                                       std::size_t pixels, T eta) {
    constexpr T largest = std::numeric_limits<T>::max();
    constexpr bool compensated = Accuracy == mean_accuracy::compensated;
    const step_weights<T> take = make_step_weights(eta, comoment_form::current_mean);
    moving_stats_counts counts;
    for (std::size_t i = 0; i < pixels; ++i) {
        const T m0 = mean[i], v0 = variance[i];
        const T ml0 = compensated ? mean_low[i] : T(0), vl0 = compensated ? variance_low[i] : T(0);
        // Compares that NaN fails: a stored pixel this update cannot have produced (NaN, an Inf from an
        // overflowed half-float texture, a negative variance) is invalid.
        // (non-short-circuit & : one straight-line mask per pixel, so that the loop vectorises)
        const bool valid = (std::fabs(m0) <= largest) & (v0 >= T(0)) & (v0 <= largest) &
                           (compensated ? (std::fabs(ml0) <= largest) & (std::fabs(vl0) <= largest) : true);
        const bool accept = std::fabs(frame[i]) <= largest;
        // An invalid pixel with a finite frame value is reseeded as a first sample: mean = x, variance 0
        // (the step with r = 1 and outer weight 0 on mean = x gives exactly that).
        const bool reseed = accept & (!valid);
        T m = reseed ? frame[i] : m0, v = reseed ? T(0) : v0;
        T ml = reseed ? T(0) : ml0, vl = reseed ? T(0) : vl0;
        // A rejected (non-finite) frame value becomes the step x = mu with r = 0, which leaves the pixel's
        // mean and variance at their values (mu + 0 d, Cov + 0 (e - Cov)): no branch, no conditional store.
        const T x = accept ? frame[i] : m;
        const step_weights<T> w{reseed ? T(1) : (accept ? take.r : T(0)),
                                reseed ? T(0) : (accept ? take.outer : T(1))};
        comoment_step<Accuracy, 1>(&m, &ml, &v, &vl, &x, w);
        // an invalid pixel without a usable frame value keeps its stored bits until a finite value reseeds it
        const bool keep = (!accept) & (!valid);
        mean[i] = keep ? m0 : m;
        variance[i] = keep ? v0 : v;
        if (compensated) {
            mean_low[i] = keep ? ml0 : ml;
            variance_low[i] = keep ? vl0 : vl;
        }
        counts.rejected += accept ? 0u : 1u;
        counts.reseeded += reseed ? 1u : 0u;
    }
    return counts;
}

}  // namespace detail

/// One moving_stats update over a whole structure-of-arrays history (a per-pixel array of means and one of
/// variances, as two texture channels): pixel i takes frame[i] into mean[i] and variance[i] by the
/// recurrence of moving_stats::push after its first sample (detail::comoment_step, supp. Eq. 21). The caller
/// seeds mean = x, variance = 0 on a pixel's first sample. With mean_low and variance_low both non-null the
/// update is compensated (docs/numerics.md): the pixel's mean is mean + mean_low and its variance
/// variance + variance_low (seed both low parts with 0).
/// Policies (docs/estimators.md, "Bad input"), each counted in the result:
/// - a non-finite frame[i] is rejected: pixel i is left untouched (`rejected`);
/// - a stored pixel that is not finite (NaN, or the Inf of an overflowed half-float store), has a negative
///   variance or a non-finite low part is invalid: a finite frame[i] reseeds it as a first sample, mean = x,
///   variance 0, low parts 0 (`reseeded`); without a finite frame value it keeps its stored bits.
/// Written without branches so that it vectorises. Throws std::invalid_argument when eta is outside (0, 1] or
/// when only one of the two low-part arrays is given.
template <class T>
moving_stats_counts moving_stats_update(T* mean, T* mean_low, T* variance, T* variance_low, const T* frame,
                                        std::size_t pixels, T eta) {
    detail::checked_eta(eta, "emcv::moving_stats_update");
    detail::require((mean_low == nullptr) == (variance_low == nullptr), "emcv::moving_stats_update",
                    "mean_low and variance_low must both be given (compensated) or both be null (plain)");
    return mean_low ? detail::moving_stats_batch<mean_accuracy::compensated>(mean, mean_low, variance, variance_low,
                                                                            frame, pixels, eta)
                    : detail::moving_stats_batch<mean_accuracy::plain>(mean, mean_low, variance, variance_low, frame,
                                                                      pixels, eta);
}

/// The same update for one pixel (the array form with one element, same policies). Returns false, leaving
/// the state untouched, when x is not finite; an invalid stored state with a finite x is reseeded (mean = x,
/// variance 0) and the call returns true. Throws std::invalid_argument when eta is outside (0, 1].
template <class T>
bool moving_stats_update(T& mean, T& variance, T x, T eta) {
    return moving_stats_update(&mean, static_cast<T*>(nullptr), &variance, static_cast<T*>(nullptr), &x,
                               std::size_t{1}, eta)
               .rejected == 0;
}

/// Scalar form of the compensated update: mean + mean_low and variance + variance_low (seed the lows with 0).
template <class T>
bool moving_stats_update(T& mean, T& mean_low, T& variance, T& variance_low, T x, T eta) {
    return moving_stats_update(&mean, &mean_low, &variance, &variance_low, &x, std::size_t{1}, eta).rejected == 0;
}

}  // namespace emcv
