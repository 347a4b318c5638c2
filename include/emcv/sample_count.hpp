// SPDX-License-Identifier: MIT
/// \file
/// emcv adaptive sample counts: SPVG's N = clamp(var / target, n_min, n_max) and Unreal's
/// "true distribution" variant (docs/frame.md).
#pragma once

#include <cmath>
#include <string>

#include "detail/common.hpp"

namespace emcv {
namespace detail {

template <class T>
void check_budget(T target, int n_min, int n_max, const char* where) {
    require_value(std::isfinite(target) && target > T(0), where, "target variance", target, "must be finite and > 0");
    require_value(n_min >= 0, where, "n_min", n_min, "must be >= 0");
    if (n_min > n_max)
        throw_invalid_value(where, "n_min", n_min, ("must not exceed n_max = " + std::to_string(n_max)).c_str());
}

/// clamp(q, n_min, n_max) rounded up to whole samples; NaN -> n_max (when the history is broken, sample).
template <class T>
int clamp_count(T q, int n_min, int n_max) noexcept {
    if (std::isnan(q) || q >= static_cast<T>(n_max)) return n_max;
    if (!(q > static_cast<T>(n_min))) return n_min;
    return static_cast<int>(std::ceil(q));
}

}  // namespace detail

/// SPVG (2020): N = clamp(variance / target, n_min, n_max), rounded up. n_min may be 0: a pixel whose tracked
/// variance is 0 (sub-pixel kernel, static light) takes no scattering samples. A NaN variance gives n_max.
/// Throws std::invalid_argument when target <= 0, n_min < 0 or n_min > n_max.
template <class T>
int sample_count(T variance, T target, int n_min, int n_max) {
    detail::check_budget(target, n_min, n_max, "emcv::sample_count");
    return detail::clamp_count(variance / target, n_min, n_max);
}

/// Unreal's USE_TRUE_DISTRIBUTION_VAR variant (off by default there): with g the stored per-sample variance
/// history (sigma^2_old * N) and eta the history weight, n_est = g (2/eta - 1) and
/// N = clamp(variance * n_est / target - n_est, n_min, n_max), rounded up. A NaN or Inf history (or variance)
/// makes the count NaN, which gives n_max, as in sample_count.
template <class T>
int sample_count_true_distribution(T variance, T per_sample_history, T eta, T target, int n_min, int n_max) {
    detail::check_budget(target, n_min, n_max, "emcv::sample_count_true_distribution");
    detail::checked_eta(eta, "emcv::sample_count_true_distribution");
    const T n_est = per_sample_history * (T(2) / eta - T(1));
    return detail::clamp_count(variance * n_est / target - n_est, n_min, n_max);
}

}  // namespace emcv
