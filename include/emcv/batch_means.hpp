// SPDX-License-Identifier: MIT
/// \file
/// emcv::batch_mean_covariance — covariance of batch means (Eq. 25-27).
#pragma once

#include <cstdint>

#include "detail/common.hpp"

namespace emcv {

/// Cov(mean X, mean Y) = Cov(X, Y) / n for n pairs correlated only at equal index (Eq. 27): a per-frame mean
/// of n samples carries 1/n of the per-sample covariance. Throws std::invalid_argument when n == 0.
template <class T>
T batch_mean_covariance(T cov, std::uint64_t n) {
    detail::require_value(n > 0, "emcv::batch_mean_covariance", "batch size n", n, "must be at least 1");
    return cov / static_cast<T>(n);
}

}  // namespace emcv
