// SPDX-License-Identifier: MIT
/// \file
/// emcv::ewma_covariance — the RiskMetrics-style EWMA covariance estimator (Eq. 22).
#pragma once

#include "emcm.hpp"

namespace emcv {

/// EWMA covariance, Eq. 22: Cov~_n = (1 - eta) Cov~_{n-1} + eta d d^T, d = x_n - mu_{n-1}.
/// It keeps only the first term of the four-term expansion (Eq. 11, 23); from the same seed it equals
/// emcm's covariance divided by (1 - eta) at every step, so it over-estimates by 1/(1 - eta) relative to
/// EMCM and by 2/(2 - eta) relative to the variance of i.i.d. samples.
template <class T, std::size_t N>
class ewma_covariance : public detail::exponential_moving<T, N, comoment_form::previous_mean> {
    using base = detail::exponential_moving<T, N, comoment_form::previous_mean>;

public:
    using base::base;
};

}  // namespace emcv
