// SPDX-License-Identifier: MIT
// Fuzz target: the estimator API on arbitrary streams. The input picks a scalar type (float, double), a
// dimension (1 to 3), an estimator (emcm, ewma_covariance, compensated_emcm, running_covariance,
// compensated_running_covariance, weighted_covariance) and its eta, then a sequence of operations: push a
// sample (NaN, Inf, huge, subnormal or any bits), push with a weight and decay, reset, restore the state
// (intact or with one field overwritten), and the free functions cv_coefficient and sample_count.
// Invariants checked (docs/estimators.md "Bad input", docs/numerics.md section 4):
//   - constructors and push throw std::invalid_argument exactly for the documented bad parameters
//     (eta outside (0, 1]; weight negative or not finite; decay outside [0, 1]), and a refused call changes
//     nothing; no other exception escapes;
//   - push returns false exactly when a component is not finite; rejected() then counts it and the rest of
//     the state is bit-for-bit unchanged; otherwise count() grows by one and rejected() does not;
//   - after any sequence of accepted (finite) samples the state is finite and every variance is >= 0;
//   - the covariance matrix is PSD to rounding: C + tol I has PSD 2x2 principal minors,
//     c_ij^2 <= (c_ii + tol)(c_jj + tol), tol = 32 (k + 1) (u max|c| + smallest subnormal) after k accepted
//     samples, max|c| over every state since the last reset (k rounded updates, each off by a few u of the
//     largest entry it met or by an underflow: with eta = 1 the EWMA's increment c + (d d^T - c) loses a
//     new d_j^2 of 6e-5 against an old c_jj of 3969 in float, an absolute error u c_old; the shift by tol I
//     is numerics.md B5's lambda_min >= -||B||), unless an entry has reached the saturated range (within a
//     factor 4 of max) since the last reset: numerics.md 4.3 clamps entries one by one and promises no more;
//   - restoring state() gives back the same estimator; a restored state is refused exactly when it is not
//     finite, has a negative total weight or a negative variance;
//   - cv_coefficient is finite for any input and 0 when var_g is not above the floor; sample_count lies in
//     [n_min, n_max] and throws only for a bad budget.
#include <emcv/emcv.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>

#include "fuzz_input.hpp"

namespace {

using emcv_fuzz::input;

template <class T, std::size_t N>
using state_of = typename emcv::weighted_covariance<T, N>::state_type;

template <class A>
bool same_bits(const A& a, const A& b) {
    return std::memcmp(&a, &b, sizeof(A)) == 0;  // std::array and scalars: no padding inside
}

/// Field by field (state_type itself may contain padding).
template <class T, std::size_t N>
bool same_state_except_rejected(const state_of<T, N>& a, const state_of<T, N>& b) {
    return a.count == b.count && same_bits(a.total_weight, b.total_weight) && same_bits(a.mean, b.mean) &&
           same_bits(a.covariance, b.covariance) && same_bits(a.mean_compensation, b.mean_compensation) &&
           same_bits(a.covariance_compensation, b.covariance_compensation);
}

template <class T, std::size_t N>
bool same_state(const state_of<T, N>& a, const state_of<T, N>& b) {
    return a.rejected == b.rejected && same_state_except_rejected<T, N>(a, b);
}

template <class T, std::size_t N>
void check_state(const state_of<T, N>& s, std::uint64_t accepted, long double& largest_seen) {
    using lim = std::numeric_limits<T>;
    EMCV_FUZZ_ASSERT(std::isfinite(s.total_weight) && s.total_weight >= T(0));
    for (std::size_t i = 0; i < N; ++i) EMCV_FUZZ_ASSERT(std::isfinite(s.mean[i]));
    for (T c : s.covariance) EMCV_FUZZ_ASSERT(std::isfinite(c));
    for (T c : s.mean_compensation) EMCV_FUZZ_ASSERT(std::isfinite(c));
    for (T c : s.covariance_compensation) EMCV_FUZZ_ASSERT(std::isfinite(c));
    long double largest = 0;
    for (T c : s.covariance) largest = std::max(largest, std::fabs(static_cast<long double>(c)));
    largest_seen = std::max(largest_seen, largest);
    for (std::size_t i = 0; i < N; ++i)
        EMCV_FUZZ_ASSERT(s.covariance[emcv::detail::packed_index(i, i, N)] >= T(0));
    // saturated (now or since the last reset): numerics.md 4.3 clamps entries one by one, which breaks the
    // PSD structure for as long as the clamped history decays; nothing is promised there but finiteness
    if (largest_seen >= static_cast<long double>(lim::max()) / 4) return;
    const long double u = lim::epsilon() / 2;
    const long double tol = 32 * u * static_cast<long double>(accepted + 1) * largest_seen +
                            static_cast<long double>(accepted + 1) * 32 * lim::denorm_min();
    for (std::size_t i = 0; i < N; ++i)
        for (std::size_t j = i + 1; j < N; ++j) {
            const long double cij = s.covariance[emcv::detail::packed_index(i, j, N)];
            const long double cii = s.covariance[emcv::detail::packed_index(i, i, N)];
            const long double cjj = s.covariance[emcv::detail::packed_index(j, j, N)];
            EMCV_FUZZ_ASSERT(std::fabs(cij) <= std::sqrt((cii + tol) * (cjj + tol)));
        }
}

template <class T, std::size_t N>
typename emcv::weighted_covariance<T, N>::vector_type sample(input& in) {
    typename emcv::weighted_covariance<T, N>::vector_type x{};
    for (auto& v : x) v = in.scalar<T>();
    return x;
}

template <class T, std::size_t N>
bool all_finite(const std::array<T, N>& x) {
    return std::all_of(x.begin(), x.end(), [](T v) { return std::isfinite(v); });
}

/// A restored state with one field overwritten: refused exactly when it is not valid (estimators.md).
template <class Estimator, class T, std::size_t N, class Make>
void check_restore(const Estimator& e, input& in, Make make) {
    state_of<T, N> s = e.state();
    const std::uint8_t which = in.byte();
    const T v = in.scalar<T>();
    if (which % 4 == 1) s.total_weight = v;
    if (which % 4 == 2) s.mean[which / 4 % N] = v;
    if (which % 4 == 3) s.covariance[which / 4 % s.covariance.size()] = v;
    const bool valid = emcv::weighted_covariance<T, N>::valid_state(s);
    bool threw = false;
    try {
        const Estimator restored = make(s);
        EMCV_FUZZ_ASSERT(same_state<T, N>(restored.state(), s));
    } catch (const std::invalid_argument&) {
        threw = true;
    }
    EMCV_FUZZ_ASSERT(threw == !valid);
    if (which % 4 == 0) EMCV_FUZZ_ASSERT(!threw);  // an estimator's own state is always accepted
}

template <class T>
void check_free_functions(input& in) {
    const T cov = in.scalar<T>(), var = in.scalar<T>();
    const T alpha = emcv::cv_coefficient(cov, var);
    EMCV_FUZZ_ASSERT(std::isfinite(alpha));
    if (!(var > std::numeric_limits<T>::min())) EMCV_FUZZ_ASSERT(alpha == T(0));
    const T target = in.scalar<T>();
    const int n_min = static_cast<std::int8_t>(in.byte()), n_max = static_cast<std::int8_t>(in.byte());
    const bool bad = !(std::isfinite(target) && target > T(0)) || n_min < 0 || n_min > n_max;
    try {
        const int n = emcv::sample_count(var, target, n_min, n_max);
        EMCV_FUZZ_ASSERT(!bad && n >= n_min && n <= n_max);
    } catch (const std::invalid_argument&) {
        EMCV_FUZZ_ASSERT(bad);
    }
}

enum class kind { emcm, ewma, compensated_emcm, running, compensated_running, weighted };

template <class Estimator, class T, std::size_t N, class Make>
void run_ops(Estimator& e, input& in, Make make) {
    long double largest_seen = 0;  // max |c| since the last reset: the scale of the rounding errors still in C
    for (int op_count = 0; !in.empty() && op_count < 4096; ++op_count) {
        const std::uint8_t op = in.byte() % 16;
        const state_of<T, N> before = e.state();
        if (op < 12) {  // push a sample
            const auto x = sample<T, N>(in);
            bool finite = all_finite<T, N>(x);
            bool accepted = false;
            if constexpr (std::is_same_v<Estimator, emcv::weighted_covariance<T, N>>) {
                const T weight = op < 6 ? T(1) : in.scalar<T>();
                const T decay = op < 6 ? T(1) : in.scalar<T>();
                // docs/estimators.md "Bad input": a negative weight or a decay outside [0, 1] throws; a NaN or
                // +Inf weight is rejected and counted like a non-finite sample
                const bool bad = weight < T(0) || !(decay >= T(0) && decay <= T(1));
                finite = finite && weight <= std::numeric_limits<T>::max();
                try {
                    accepted = e.push(x, weight, decay);
                    EMCV_FUZZ_ASSERT(!bad);
                } catch (const std::invalid_argument&) {
                    EMCV_FUZZ_ASSERT(bad);
                    EMCV_FUZZ_ASSERT(same_state<T, N>(e.state(), before));  // a refused call changes nothing
                    continue;
                }
            } else {
                accepted = e.push(x);
            }
            EMCV_FUZZ_ASSERT(accepted == finite);
            if (!finite) {
                EMCV_FUZZ_ASSERT(e.state().rejected == before.rejected + 1);
                EMCV_FUZZ_ASSERT(same_state_except_rejected<T, N>(e.state(), before));
            } else {
                EMCV_FUZZ_ASSERT(e.state().count == before.count + 1 && e.state().rejected == before.rejected);
            }
        } else if (op == 12) {
            e.reset();
            EMCV_FUZZ_ASSERT(e.count() == 0 && e.rejected() == 0);
            largest_seen = 0;
        } else if (op == 13 || op == 14) {
            check_restore<Estimator, T, N>(e, in, make);
        } else {
            check_free_functions<T>(in);
        }
        check_state<T, N>(e.state(), e.count(), largest_seen);
    }
}

template <class T, std::size_t N>
void run(kind k, input& in) {
    const T eta = in.scalar<T>();
    const bool bad_eta = !(eta > T(0) && eta <= T(1));
    auto exponential = [&](auto tag) {
        using E = decltype(tag);
        try {
            E e(eta);
            EMCV_FUZZ_ASSERT(!bad_eta);
            run_ops<E, T, N>(e, in, [&](const state_of<T, N>& s) { return E(eta, s); });
        } catch (const std::invalid_argument&) {
            EMCV_FUZZ_ASSERT(bad_eta);
        }
    };
    switch (k) {
        case kind::emcm: exponential(emcv::emcm<T, N>(T(0.5))); break;
        case kind::ewma: exponential(emcv::ewma_covariance<T, N>(T(0.5))); break;
        case kind::compensated_emcm: exponential(emcv::compensated_emcm<T, N>(T(0.5))); break;
        case kind::running: {
            emcv::running_covariance<T, N> e;
            run_ops<decltype(e), T, N>(e, in, [](const state_of<T, N>& s) { return emcv::running_covariance<T, N>(s); });
        } break;
        case kind::compensated_running: {
            emcv::compensated_running_covariance<T, N> e;
            run_ops<decltype(e), T, N>(
                e, in, [](const state_of<T, N>& s) { return emcv::compensated_running_covariance<T, N>(s); });
        } break;
        case kind::weighted: {
            emcv::weighted_covariance<T, N> e;
            run_ops<decltype(e), T, N>(e, in, [](const state_of<T, N>& s) { return emcv::weighted_covariance<T, N>(s); });
        } break;
    }
}

template <class T>
void run_dimension(std::uint8_t selector, kind k, input& in) {
    switch (selector / 2 % 3) {
        case 0: run<T, 1>(k, in); break;
        case 1: run<T, 2>(k, in); break;
        default: run<T, 3>(k, in); break;
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    input in(data, size);
    const std::uint8_t selector = in.byte();
    const auto k = static_cast<kind>(selector / 6 % 6);
    if (selector % 2 == 0) run_dimension<float>(selector, k, in);
    else run_dimension<double>(selector, k, in);
    return 0;
}
