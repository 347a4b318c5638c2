// SPDX-License-Identifier: MIT
// emcv::moving_stats — exponential moving mean and variance of one scalar (SPVG's per-pixel history).
#pragma once

#include "emcm.hpp"

namespace emcv {

/// Exponential moving mean and variance of a scalar: emcm<T, 1> with a scalar interface.
///     mu' = (1 - eta) mu + eta x,   var' = (1 - eta) (var + eta (x - mu)^2)
/// This is the update of SPVG / Unreal's quality history (eta = 0.2); reset() on failed reprojection.
template <class T>
class moving_stats {
public:
    using value_type = T;
    using state_type = typename emcm<T, 1>::state_type;

    explicit moving_stats(T eta) : e_(eta) {}
    moving_stats(T eta, const state_type& s) : e_(eta, s) {}

    /// Returns false (state unchanged, rejected() + 1) when x is not finite.
    bool push(T x) { return e_.push(x); }
    T mean() const noexcept { return e_.mean(0); }
    T variance() const noexcept { return e_.variance(0); }
    T eta() const noexcept { return e_.eta(); }
    std::uint64_t count() const noexcept { return e_.count(); }
    std::uint64_t rejected() const noexcept { return e_.rejected(); }
    const state_type& state() const noexcept { return e_.state(); }
    void reset() noexcept { e_.reset(); }

private:
    emcm<T, 1> e_;
};

}  // namespace emcv
