// SPDX-License-Identifier: MIT
/// \file
/// emcv::running_covariance — cumulative (Welford) mean and covariance: weighted_covariance with w = 1, decay = 1.
#pragma once

#include "weighted_covariance.hpp"

namespace emcv {
namespace detail {

/// Shared body of the cumulative estimators: the recurrence of weighted_covariance with weight 1 and
/// decay 1, so r = 1/n (taken from the exact integer count).
template <class T, std::size_t N, mean_accuracy Accuracy>
class cumulative_covariance : private weighted_covariance<T, N> {
    using base = weighted_covariance<T, N>;

public:
    using typename base::matrix_type;
    using typename base::state_type;
    using typename base::value_type;
    using typename base::vector_type;
    static constexpr std::size_t dimension = N;

    cumulative_covariance() = default;
    /// Restores a saved state; throws std::invalid_argument naming the broken rule (weighted_covariance::valid_state).
    explicit cumulative_covariance(const state_type& s)
        : base(s, Accuracy == mean_accuracy::compensated ? "emcv::compensated_running_covariance"
                                                         : "emcv::running_covariance") {}

    /// Adds one sample; returns false (state unchanged, rejected() + 1) when it is not finite. x: a braced
    /// list of exactly N scalars, a std::array<T, N> or T[N] (any other count does not compile).
    bool push(const sample_vector<T, N>& x) { return base::template push_counted<Accuracy>(x.values()); }
    template <class V, class = std::enable_if_t<detail::is_vector_like<V, N>::value>>
    bool push(const V& x) { return push(detail::to_array<T, N>(x)); }
    template <std::size_t M = N, class = std::enable_if_t<M == 1>>
    bool push(T x) { return push(vector_type{x}); }

    using base::count;
    using base::covariance_matrix;
    using base::mean;
    using base::rejected;
    using base::reset;
    using base::state;
    using base::total_weight;

    /// Population (biased) covariance: sum (x - mean)(y - mean) / n.
    T covariance(std::size_t i, std::size_t j) const { return base::covariance(i, j); }
    /// Population (biased) variance of component i < N.
    T variance(std::size_t i) const { return base::variance(i); }

    /// Unbiased sample covariance: sum (x - mean)(y - mean) / (n - 1); 0 while n < 2.
    T sample_covariance(std::size_t i, std::size_t j) const {
        EMCV_ASSERT(i < N && j < N, "emcv: sample_covariance(i, j) needs i < N and j < N (the estimator's dimension)");
        const auto n = base::count();
        return n < 2 ? T(0) : base::covariance(i, j) * (static_cast<T>(n) / static_cast<T>(n - 1));
    }
    T sample_variance(std::size_t i) const { return sample_covariance(i, i); }
};

}  // namespace detail

/// Cumulative mean and covariance of every sample so far (Welford 1962): the recurrence of
/// weighted_covariance with weight 1 and decay 1, so r = 1/n.
template <class T, std::size_t N>
class running_covariance : public detail::cumulative_covariance<T, N, mean_accuracy::plain> {
    using base = detail::cumulative_covariance<T, N, mean_accuracy::plain>;

public:
    using base::base;
};

/// running_covariance with a compensated (two-term) mean: same recurrence, the mean's rounding error is
/// carried in state_type::mean_compensation (docs/numerics.md, docs/results/accuracy-vs-time.md).
template <class T, std::size_t N>
class compensated_running_covariance : public detail::cumulative_covariance<T, N, mean_accuracy::compensated> {
    using base = detail::cumulative_covariance<T, N, mean_accuracy::compensated>;

public:
    using base::base;
};

}  // namespace emcv
