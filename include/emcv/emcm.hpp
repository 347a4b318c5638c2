// SPDX-License-Identifier: MIT
/// \file
/// emcv::emcm — exponential moving covariance matrix (supp. Eq. 21).
#pragma once

#include "weighted_covariance.hpp"

namespace emcv {
namespace detail {

/// The public name of the exponential estimator with this comoment form and accuracy (error messages).
constexpr const char* exponential_moving_name(comoment_form form, mean_accuracy accuracy) noexcept {
    return form == comoment_form::previous_mean
               ? "emcv::ewma_covariance"
               : (accuracy == mean_accuracy::compensated ? "emcv::compensated_emcm" : "emcv::emcm");
}

/// Shared body of the exponential moving estimators: the weighted recurrence with geometric weights
/// w_{n,i} = (1 - eta)^{n-i} eta (Eq. 18), W == 1, and the first sample seeding the mean with Cov_0 = 0.
template <class T, std::size_t N, comoment_form Form, mean_accuracy Accuracy = mean_accuracy::plain>
class exponential_moving : private weighted_covariance<T, N> {
    using base = weighted_covariance<T, N>;

public:
    using typename base::matrix_type;
    using typename base::state_type;
    using typename base::value_type;
    using typename base::vector_type;
    static constexpr std::size_t dimension = N;

    /// The estimator's public name, as error messages give it ("emcv::emcm").
    static constexpr const char* name = exponential_moving_name(Form, Accuracy);

    /// An empty estimator; throws std::invalid_argument unless 0 < eta <= 1.
    explicit exponential_moving(T eta) : eta_(checked_eta(eta, name)) {}
    /// Restores a saved state; throws std::invalid_argument naming the broken rule (weighted_covariance::valid_state).
    exponential_moving(T eta, const state_type& s) : base(s, name), eta_(checked_eta(eta, name)) {}

    /// First sample: mu = x, Cov = 0 (r = 1). Later: r = eta, i.e. weight eta and decay 1 - eta.
    /// Returns false (state unchanged, rejected() + 1) when x is not finite. x: a braced list of exactly N
    /// scalars, a std::array<T, N> or T[N] (any other count does not compile; sample_vector).
    bool push(const sample_vector<T, N>& x) {
        return base::count() == 0
                   ? base::template push_normalised<Accuracy>(x.values(), T(1), comoment_form::current_mean)
                   : base::template push_normalised<Accuracy>(x.values(), eta_, Form);
    }
    template <class V, class = std::enable_if_t<detail::is_vector_like<V, N>::value>>
    bool push(const V& x) { return push(detail::to_array<T, N>(x)); }
    template <std::size_t M = N, class = std::enable_if_t<M == 1>>
    bool push(T x) { return push(vector_type{x}); }

    T eta() const noexcept { return eta_; }
    using base::count;
    using base::covariance;
    using base::covariance_matrix;
    using base::mean;
    using base::rejected;
    using base::reset;
    using base::state;
    using base::total_weight;
    using base::variance;

private:
    T eta_;
};

}  // namespace detail

/// Exponential moving covariance matrix, supp. Eq. 21:
///     Cov_n = (1 - eta) (Cov_{n-1} + eta d d^T),  d = x_n - mu_{n-1},   mu_n = mu_{n-1} + eta d
/// It is exactly the covariance about the current mean under geometric weights (Eq. 24), so in steady state
/// on i.i.d. samples E[Cov] = 2 (1 - eta) / (2 - eta) Var (docs/estimators.md).
template <class T, std::size_t N>
class emcm : public detail::exponential_moving<T, N, comoment_form::current_mean> {
    using base = detail::exponential_moving<T, N, comoment_form::current_mean>;

public:
    using base::base;
};

/// emcm with a compensated (two-term) mean: the same recurrence (supp. Eq. 21), with the rounding error of
/// every mean update kept in state_type::mean_compensation (docs/numerics.md).
template <class T, std::size_t N>
class compensated_emcm
    : public detail::exponential_moving<T, N, comoment_form::current_mean, mean_accuracy::compensated> {
    using base = detail::exponential_moving<T, N, comoment_form::current_mean, mean_accuracy::compensated>;

public:
    using base::base;
};

}  // namespace emcv
