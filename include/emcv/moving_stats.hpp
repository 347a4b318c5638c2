// SPDX-License-Identifier: MIT
/// \file
/// emcv::moving_stats — exponential moving mean and variance of one scalar (SPVG's per-pixel history).
#pragma once

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
    explicit moving_stats(T eta) : e_(eta) {}
    /// Restores a saved state; a state that is not finite or has a negative variance throws.
    moving_stats(T eta, const state_type& s) : e_(eta, s) {}

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
    emcm<T, 1> e_;
};

/// One moving_stats update on caller-owned storage, for a per-pixel structure-of-arrays history (an array
/// of means and one of variances, as two texture channels): the recurrence of moving_stats::push after its
/// first sample (detail::comoment_step, supp. Eq. 21). The caller seeds mean = x, variance = 0 on a pixel's
/// first sample. Returns false, leaving the state untouched, when x is not finite (the library's policy; the
/// caller counts rejections). Throws std::invalid_argument when eta is outside (0, 1].
template <class T>
bool moving_stats_update(T& mean, T& variance, T x, T eta) {
    detail::checked_eta(eta, "moving_stats_update");
    if (!std::isfinite(x)) return false;
    detail::comoment_step<mean_accuracy::plain, 1>(&mean, static_cast<T*>(nullptr), &variance,
                                                   static_cast<T*>(nullptr), &x, eta, comoment_form::current_mean);
    return true;
}

namespace detail {

/// Body of the array form of moving_stats_update, one loop per accuracy so that neither has a branch.
template <mean_accuracy Accuracy, class T>
std::size_t moving_stats_batch(T* mean, T* mean_low, T* variance, T* variance_low, const T* frame,
                               std::size_t pixels, T eta) {
    const step_weights<T> take = make_step_weights(eta, comoment_form::current_mean);
    const step_weights<T> hold{T(0), T(1)};
    constexpr bool compensated = Accuracy == mean_accuracy::compensated;
    std::size_t rejected = 0;
    for (std::size_t i = 0; i < pixels; ++i) {
        // A rejected (non-finite) frame value becomes the step x = mu with r = 0, which leaves the pixel's
        // mean and variance at their values (mu + 0 d, Cov + 0 (e - Cov)): no branch, no conditional store.
        const bool accept = std::isfinite(frame[i]);
        const T x = accept ? frame[i] : mean[i];
        const step_weights<T> w{accept ? take.r : hold.r, accept ? take.outer : hold.outer};
        comoment_step<Accuracy, 1>(&mean[i], compensated ? &mean_low[i] : nullptr, &variance[i],
                                   compensated ? &variance_low[i] : nullptr, &x, w);
        rejected += accept ? 0u : 1u;
    }
    return rejected;
}

}  // namespace detail

/// The same update over a whole structure-of-arrays history: pixel i takes frame[i] into mean[i] and
/// variance[i]. With mean_low and variance_low both non-null the update is compensated (docs/numerics.md):
/// the pixel's mean is mean + mean_low and its variance variance + variance_low (seed both low parts with 0).
/// A non-finite frame[i] leaves pixel i untouched. Written without branches so that it vectorises; returns
/// how many frame values were rejected. Throws std::invalid_argument when eta is outside (0, 1] or when only
/// one of the two low-part arrays is given.
template <class T>
std::size_t moving_stats_update(T* mean, T* mean_low, T* variance, T* variance_low, const T* frame,
                                std::size_t pixels, T eta) {
    detail::checked_eta(eta, "moving_stats_update");
    detail::require((mean_low == nullptr) == (variance_low == nullptr), "moving_stats_update",
                    "mean_low and variance_low must both be given (compensated) or both be null (plain)");
    return mean_low ? detail::moving_stats_batch<mean_accuracy::compensated>(mean, mean_low, variance, variance_low,
                                                                            frame, pixels, eta)
                    : detail::moving_stats_batch<mean_accuracy::plain>(mean, mean_low, variance, variance_low, frame,
                                                                      pixels, eta);
}

/// Scalar form of the compensated update: mean + mean_low and variance + variance_low (seed the lows with 0).
template <class T>
bool moving_stats_update(T& mean, T& mean_low, T& variance, T& variance_low, T x, T eta) {
    detail::checked_eta(eta, "moving_stats_update");
    if (!std::isfinite(x)) return false;
    detail::comoment_step<mean_accuracy::compensated, 1>(&mean, &mean_low, &variance, &variance_low, &x, eta,
                                                         comoment_form::current_mean);
    return true;
}

}  // namespace emcv
