// SPDX-License-Identifier: MIT
/// \file
/// emcv::weighted_covariance — the one streaming recurrence every estimator of emcv is built on.
//
// REFERENCES  Xie & Olano 2021, supplementary section 1: variable-weight covariance (Eq. 17, Finch 2009
//             generalised), weighted means (Eq. 1), covariance about the current mean (Eq. 24).
//
// With decay = (W_n - w_n) / W_{n-1} and w = w_n, the total weight is W_n = decay * W_{n-1} + w, and with
// r = w / W_n and d = x_n - mu_{n-1}:
//     mu_n  = mu_{n-1} + r d                                   (Eq. 1 as a recurrence)
//     Cov_n = (1 - r) (Cov_{n-1} + r d d^T)                    (supp. Eq. 17 divided by W_n)
// Eq. 17 writes S_n = W_n Cov_n with the asymmetric product (y_n - nu_n)(x_n - mu_{n-1}); since
// x_n - mu_n = (1 - r) d the two are equal, and the symmetric form keeps every variance >= 0 and every
// matrix exactly symmetric in floating point. It is evaluated as the increment
// Cov_n = Cov_{n-1} + r ((1 - r) d d^T - Cov_{n-1}) (detail::comoment_step; why: docs/numerics.md).
// The normalised covariance is stored (not S_n), so the state has the scale of the data for any stream
// length and can live in a half-float texture.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <utility>

#include "detail/common.hpp"

namespace emcv {

/// Which of the two comoment updates a step uses.
enum class comoment_form {
    current_mean,   ///< exact weighted covariance about the current mean (Eq. 17/21/24)
    previous_mean,  ///< first term of the expansion only, about the previous mean (EWMA, Eq. 22)
};

/// How mean and covariance are accumulated (docs/numerics.md): `plain` stores them in T; `compensated` also
/// stores the rounding error of every update in state_type::mean_compensation and
/// state_type::covariance_compensation (two-term sums, made exact per step with TwoSum), so a large offset
/// against a small spread, or a cumulative float stream past 2^24 samples, no longer costs digits.
enum class mean_accuracy { plain, compensated };

namespace detail {

/// Error-free sum (Knuth TwoSum): s + e == a + b exactly, s = fl(a + b).
template <class T>
EMCV_ALWAYS_INLINE void two_sum(T a, T b, T& s, T& e) noexcept {
    s = a + b;
    const T b_virtual = s - a;
    e = (a - (s - b_virtual)) + (b - b_virtual);
}

/// The coefficients of one step: r = w_n / W_n, and the weight of the outer product d d^T inside the
/// update, outer = 1 - r (current mean, Eq. 17/21) or 1 (previous mean, Eq. 22).
template <class T>
struct step_weights {
    T r, outer;
};

template <class T>
step_weights<T> make_step_weights(T r, comoment_form form) noexcept {
    return {r, form == comoment_form::current_mean ? T(1) - r : T(1)};
}

/// Calls f(std::integral_constant<std::size_t, I>) for I = 0 .. Count-1, unrolled at compile time (so that
/// a loop over pixels around comoment_step has no inner loop left and vectorises).
template <std::size_t... I, class F>
void for_each_index(std::index_sequence<I...>, F&& f) {
    (f(std::integral_constant<std::size_t, I>{}), ...);
}

/// Row (first) and column (second) of entry k of the packed upper triangle of an n x n matrix
/// (the inverse of packed_index).
constexpr std::pair<std::size_t, std::size_t> packed_row_column(std::size_t k, std::size_t n) noexcept {
    std::size_t i = 0;
    while (k >= n - i) {
        k -= n - i;
        ++i;
    }
    return {i, i + k};
}

/// The one recurrence of the library, on caller-owned storage: mean[N], packed covariance[N (N + 1) / 2],
/// their low parts mean_low[N] and covariance_low[N (N + 1) / 2] (compensated only; ignored and may be null
/// otherwise), sample x[N], weights from make_step_weights.
///   mu_n = mu_{n-1} + r d,  d = x - mu_{n-1}
///   current_mean:  Cov_n = Cov_{n-1} + r ((1 - r) d d^T - Cov_{n-1})    supp. Eq. 17 / 21
///                        = (1 - r)(Cov_{n-1} + r d d^T)
///   previous_mean: Cov_n = Cov_{n-1} + r (d d^T - Cov_{n-1})            Eq. 22 (EWMA)
///                        = (1 - r) Cov_{n-1} + r d d^T
/// Written as an increment, like the mean: when r is below the resolution of T (a float cumulative stream
/// past 2^24 samples) the decay is not lost, as it is when (1 - r) rounds to 1 in the product form. The
/// product ((outer d_i) d_j) is 0 for r = 1 (a first sample) even when d^2 overflows, and by
/// monotonic rounding Cov + r (e - Cov) >= 0 whenever Cov >= 0 and e >= 0: every variance stays >= 0.
/// With Accuracy == compensated the mean is the unevaluated sum mean + mean_low, d is taken against both
/// parts, and the covariance increment is added to covariance + covariance_low the same way
/// (docs/numerics.md section 1).
/// Range policy: a difference x - mu that overflows (opposite signs near the top of the range) is clamped
/// to +-max, so the mean still moves towards x and stays finite, and a covariance beyond the largest finite
/// T saturates at +-max: finite input never stores Inf or NaN.
/// Where the clamps are evaluated (Range): range_check::select computes every clamp as a select with constant
/// or already computed arms (quiet compares, no branch around arithmetic) so that a loop over pixels
/// vectorises. range_check::branch, for one stream, skips each clamp behind a branch that is taken only when
/// the value is out of range (|v| <= max fails): the clamp is the identity on every in-range value, so the
/// results are bit-identical, and the predicted branch takes the compare and select off the loop-carried
/// chain mu -> d -> mu (sub + fma) and Cov -> Cov (docs/results/accuracy-vs-time.md, "One stream").
enum class range_check { select, branch };

#if defined(__GNUC__) || defined(__clang__)
/// Branch hint: the condition x is expected to be false (the out-of-range case of range_check::branch).
#define EMCV_UNLIKELY(x) __builtin_expect(!!(x), 0)
#else
/// Branch hint: the condition x is expected to be false (no hint on this compiler).
#define EMCV_UNLIKELY(x) (x)
#endif

template <mean_accuracy Accuracy, std::size_t N, range_check Range = range_check::select, class T>
EMCV_ALWAYS_INLINE void comoment_step(T* mean, T* mean_low, T* covariance, T* covariance_low, const T* x,
                   const step_weights<T>& w) noexcept {
    constexpr T largest = std::numeric_limits<T>::max();
    constexpr std::size_t packed = N * (N + 1) / 2;
    // Work on local copies: the four pointers may alias as far as the compiler knows, and reloading after
    // every store would put store-to-load forwarding on the loop-carried chain.
    T d[N];
    for_each_index(std::make_index_sequence<N>{}, [&](auto index) {
        constexpr std::size_t i = decltype(index)::value;
        T mu = mean[i];
        T di = Accuracy == mean_accuracy::compensated ? (x[i] - mu) - mean_low[i] : x[i] - mu;
        if (Range == range_check::select || EMCV_UNLIKELY(!(std::fabs(di) <= largest)))
            di = std::isgreater(di, largest) ? largest : (std::isless(di, -largest) ? -largest : di);
        d[i] = di;
        if (Accuracy == mean_accuracy::compensated) {
            T sum, error;
            two_sum(mu, w.r * di, sum, error);  // sum + error == mu + r d exactly
            // TwoSum's own s - a overflows when mu and r d have opposite signs and r d is near max, although
            // the sum does not (found by tests/fuzz): its error is then NaN. It is dropped: the mean is at
            // the saturated scale there, where numerics.md 4.3 promises finiteness only.
            error = std::isfinite(error) ? error : T(0);
            const T low_new = mean_low[i] + error;
            const T renormalised = sum + low_new;  // renormalise (fast two-sum): |low| <= ulp(mu) / 2
            const T low_renormalised = low_new - (renormalised - sum);
            // mu + r d (or its renormalised sum) rounded past max (r near 1, x near max): saturate, drop the
            // low part
            const bool above = std::isgreater(renormalised, largest), below = std::isless(renormalised, -largest);
            mu = above ? largest : (below ? -largest : renormalised);
            mean_low[i] = above || below ? T(0) : low_renormalised;
        } else {
            mu += w.r * di;
            // with r near 1 and x near max, mu + r d can round past max although x is finite (found by
            // tests/fuzz): saturate so that the mean stays finite and between mu and x
            mu = std::isgreater(mu, largest) ? largest : (std::isless(mu, -largest) ? -largest : mu);
        }
        mean[i] = mu;
    });
    for_each_index(std::make_index_sequence<packed>{}, [&](auto index) {
        constexpr std::size_t k = decltype(index)::value;
        constexpr std::size_t i = packed_row_column(k, N).first, j = packed_row_column(k, N).second;
        const T c = covariance[k];
        if (Accuracy == mean_accuracy::compensated) {
            // Clamping the product and the difference (constant arms) keeps every value finite: with
            // |e|, |t| <= max the sum c + r t stays in range, and TwoSum below never meets an Inf.
            const T low = covariance_low[k];
            const T e_raw = (w.outer * d[i]) * d[j];
            const bool above = std::isgreater(e_raw, largest), below = std::isless(e_raw, -largest);
            const T e = above ? largest : (below ? -largest : e_raw);
            T t = (e - c) - low;
            if (Range == range_check::select || EMCV_UNLIKELY(!(std::fabs(t) <= largest)))
                t = std::isgreater(t, largest) ? largest : (std::isless(t, -largest) ? -largest : t);
            T sum, error;
            two_sum(c, w.r * t, sum, error);  // sum + error == c + r t exactly
            error = std::isfinite(error) ? error : T(0);  // TwoSum's s - a overflowed (see the mean above)
            const T low_new = low + error;
            const T v = sum + low_new;  // renormalise (fast two-sum)
            const T low_renormalised = low_new - (v - sum);
            // an outer product beyond the range saturates the entry, as in the plain form
            if (Range == range_check::select || EMCV_UNLIKELY(above || below)) {
                covariance_low[k] = above || below ? T(0) : low_renormalised;
                covariance[k] = above ? largest : (below ? -largest : v);
            } else {
                covariance_low[k] = low_renormalised;
                covariance[k] = v;
            }
        } else {
            T v = c + w.r * ((w.outer * d[i]) * d[j] - c);
            // saturate, never store Inf (a variance, i == j, is never negative: one compare suffices)
            if (Range == range_check::select || EMCV_UNLIKELY(!(std::fabs(v) <= largest))) {
                const T capped = std::isgreater(v, largest) ? largest : v;
                v = i == j ? capped : (std::isless(capped, -largest) ? -largest : capped);
            }
            covariance[k] = v;
        }
    });
}

template <mean_accuracy Accuracy, std::size_t N, range_check Range = range_check::select, class T>
EMCV_ALWAYS_INLINE void comoment_step(T* mean, T* mean_low, T* covariance, T* covariance_low, const T* x, T r,
                   comoment_form form) noexcept {
    comoment_step<Accuracy, N, Range>(mean, mean_low, covariance, covariance_low, x, make_step_weights(r, form));
}

}  // namespace detail

/// One N-dimensional sample as the argument of a push: a braced list of exactly N scalars (`push({f, g})`),
/// a `std::array<T, N>` or a C array `T[N]`. Any other count is a compile error naming the dimension: a
/// `std::array<T, N>` parameter would accept `push({f})` for N = 2 and push (f, 0).
template <class T, std::size_t N>
class sample_vector {
public:
    /// From exactly N arithmetic scalars (a braced list `{f, g}`), each converted to T.
    template <class... Scalars,
              class = std::enable_if_t<(std::is_arithmetic<Scalars>::value && ...) && sizeof...(Scalars) != 0>>
    sample_vector(Scalars... components) : values_{{static_cast<T>(components)...}} {  // NOLINT: implicit by design
        static_assert(sizeof...(Scalars) == N,
                      "emcv: a sample needs exactly N components (the estimator's dimension N)");
    }
    /// From a std::array of M == N components.
    template <std::size_t M>
    sample_vector(const std::array<T, M>& x) : values_{} {  // NOLINT: implicit by design
        static_assert(M == N, "emcv: a sample needs exactly N components (the estimator's dimension N)");
        for (std::size_t i = 0; i < N; ++i) values_[i] = x[i];
    }
    /// From a C array of M == N components.
    template <std::size_t M>
    sample_vector(const T (&x)[M]) : values_{} {  // NOLINT: implicit by design
        static_assert(M == N, "emcv: a sample needs exactly N components (the estimator's dimension N)");
        for (std::size_t i = 0; i < N; ++i) values_[i] = x[i];
    }
    /// The components.
    const std::array<T, N>& values() const noexcept { return values_; }

private:
    std::array<T, N> values_;
};

/// Streaming weighted mean and covariance matrix of N-dimensional samples.
///
/// Non-finite samples (any component NaN or +-Inf) and NaN or +Inf weights are rejected: the state is left
/// unchanged, `rejected()` counts them and push() returns false. This is the one NaN/Inf policy of the whole
/// library. Invalid arguments (a negative weight, decay outside [0, 1]) throw std::invalid_argument.
/// Range policy (docs/numerics.md): the mean never overflows (an overflowing difference x - mu is clamped
/// to +-max, so the mean still moves towards x) and a covariance beyond the largest finite T saturates at
/// +-max, so the state stays finite for every finite input.
template <class T, std::size_t N>
class weighted_covariance {
    static_assert(std::is_floating_point<T>::value, "emcv estimators need a floating-point scalar T");
    static_assert(N >= 1, "dimension must be at least 1");

public:
    using value_type = T;                                  ///< the scalar type
    using vector_type = std::array<T, N>;                  ///< one sample, or the mean
    using matrix_type = std::array<std::array<T, N>, N>;   ///< the full covariance matrix
    static constexpr std::size_t dimension = N;            ///< N, the number of variables
    static constexpr std::size_t packed_size = N * (N + 1) / 2;  ///< entries of the packed upper triangle

    /// The whole estimator state, in the units of the data (what a history texture stores).
    struct state_type {
        std::uint64_t count = 0;     ///< accepted samples
        std::uint64_t rejected = 0;  ///< non-finite samples that were refused
        T total_weight = T(0);       ///< W_n
        vector_type mean{};          ///< mu_n
        std::array<T, packed_size> covariance{};  ///< Cov_n, packed upper triangle, row-major
        vector_type mean_compensation{};  ///< low part of mu_n (mean_accuracy::compensated only; else 0)
        std::array<T, packed_size> covariance_compensation{};  ///< low part of Cov_n (compensated only; else 0)
    };

    weighted_covariance() = default;
    /// Restores a saved (for example, quantised) state.
    /// Throws std::invalid_argument when the state is not finite (a half-float texture that overflowed to
    /// Inf), has a negative total weight or a negative variance, or has count == 0 with anything non-zero
    /// (see valid_state): a poisoned or half-restored history is refused, never used.
    explicit weighted_covariance(const state_type& s) : weighted_covariance(s, "emcv::weighted_covariance") {}

    /// True when s is a state this class could have produced: finite, W >= 0, variances >= 0, and, when
    /// count == 0, empty (W, mean, covariance and their low parts all 0). A texture that stores only a mean
    /// and a covariance is restored with count >= 1 (and W = 1 for the exponential estimators): with
    /// count == 0 the next push would seed the mean and silently discard what was stored.
    static bool valid_state(const state_type& s) noexcept { return invalid_state_reason(s) == nullptr; }

    /// Why s is not a valid_state (the first rule it breaks, as the text of an error message), or nullptr
    /// when it is valid.
    static const char* invalid_state_reason(const state_type& s) noexcept {
        if (!std::isfinite(s.total_weight)) return "restored state must be finite: total_weight is not";
        if (s.total_weight < T(0)) return "restored state must have total_weight >= 0";
        if (s.count == 0 && !(s.total_weight == T(0) && detail::all_zero(s.mean) &&
                              detail::all_zero(s.mean_compensation) && detail::all_zero(s.covariance) &&
                              detail::all_zero(s.covariance_compensation)))
            return "restored state must be all zero when count == 0 (restore a stored history with count >= 1)";
        if (!detail::all_finite(s.mean) || !detail::all_finite(s.mean_compensation))
            return "restored state must be finite: the mean (or its low part) is not";
        if (!detail::all_finite(s.covariance) || !detail::all_finite(s.covariance_compensation))
            return "restored state must be finite: the covariance (or its low part) is not";
        for (std::size_t i = 0; i < N; ++i)
            if (s.covariance[detail::packed_index(i, i, N)] < T(0))
                return "restored state must have every variance >= 0";
        return nullptr;
    }

    /// Adds x with weight w after scaling every earlier weight by decay.
    /// @param [in] sample the sample x: a braced list of exactly N scalars, a std::array<T, N> or T[N]
    /// @param [in] weight w_{n,n} >= 0; a NaN or +Inf weight (an importance weight whose pdf reached 0) is
    ///                    treated like a non-finite sample: rejected and counted
    /// @param [in] decay  in [0, 1]: 1 keeps old samples at full weight, 0 forgets them
    /// @returns false (and leaves the state untouched, rejected() + 1) when x or the weight is not finite.
    /// push(x, 0, 0) forgets everything and gives x no weight: the estimator then holds nothing (W, mean and
    /// covariance 0; count() still counts the call), and the next push with a positive weight seeds it.
    bool push(const sample_vector<T, N>& sample, T weight = T(1), T decay = T(1)) {
        constexpr const char* where = "emcv::weighted_covariance::push";
        // NaN fails neither test here (it is rejected below); -Inf is negative
        detail::require_value(!(weight < T(0)), where, "weight", weight, "must be >= 0");
        detail::require_value(decay >= T(0) && decay <= T(1), where, "decay", decay, "must lie in [0, 1]");
        const vector_type& x = sample.values();
        if (!detail::all_finite(x) || !(weight <= std::numeric_limits<T>::max())) {
            ++s_.rejected;
            return false;
        }
        // two weights near max overflow their sum: W saturates at max like the covariance (numerics.md 4.3),
        // never Inf (found by tests/fuzz); r = w / W then stays in [0, 1]
        const T w_sum = decay * s_.total_weight + weight;
        const T w_total = std::isgreater(w_sum, std::numeric_limits<T>::max()) ? std::numeric_limits<T>::max() : w_sum;
        ++s_.count;
        if (!(w_total > T(0))) {  // every weight is zero: the estimator holds nothing
            s_.total_weight = T(0);
            s_.mean = vector_type{};
            s_.mean_compensation = vector_type{};
            s_.covariance_compensation = {};
            s_.covariance = {};
            return true;
        }
        s_.total_weight = w_total;
        // r = 0 (a zero weight, or one that underflows against W) leaves mean and covariance as they are;
        // skipped rather than stepped, because 0 * (an outer product that overflowed to Inf) is NaN
        // (found by tests/fuzz, docs/numerics.md "Fuzzing").
        const T r = weight / w_total;
        if (r > T(0)) step(x, r, comoment_form::current_mean);
        return true;
    }

    /// Same, for glm::vec<N, T> or any type with static length() == N and operator[].
    template <class V, class = std::enable_if_t<detail::is_vector_like<V, N>::value>>
    bool push(const V& x, T weight = T(1), T decay = T(1)) {
        return push(detail::to_array<T, N>(x), weight, decay);
    }

    /// Scalar convenience for N == 1.
    template <std::size_t M = N, class = std::enable_if_t<M == 1>>
    bool push(T x, T weight = T(1), T decay = T(1)) {
        return push(vector_type{x}, weight, decay);
    }

    std::uint64_t count() const noexcept { return s_.count; }         ///< accepted samples
    std::uint64_t rejected() const noexcept { return s_.rejected; }   ///< refused non-finite samples
    T total_weight() const noexcept { return s_.total_weight; }       ///< W_n
    const vector_type& mean() const noexcept { return s_.mean; }      ///< mu_n; 0 before any sample
    /// Component i < N of mu_n (EMCV_ASSERT in debug builds; not noexcept, so that a throwing EMCV_ASSERT works).
    T mean(std::size_t i) const {
        EMCV_ASSERT(i < N, "emcv: mean(i) needs i < N (the estimator's dimension)");
        return s_.mean[i];
    }

    /// Weighted covariance about the current mean (Eq. 24 divided by W_n); 0 before any sample.
    /// Needs i, j < N (EMCV_ASSERT in debug builds: a packed index past the row would read another entry).
    T covariance(std::size_t i, std::size_t j) const {
        EMCV_ASSERT(i < N && j < N, "emcv: covariance(i, j) needs i < N and j < N (the estimator's dimension)");
        return s_.covariance[detail::packed_index(i, j, N)];
    }
    /// covariance(i, i), i < N.
    T variance(std::size_t i) const {
        EMCV_ASSERT(i < N, "emcv: variance(i) needs i < N (the estimator's dimension)");
        return s_.covariance[detail::packed_index(i, i, N)];
    }
    /// The full symmetric matrix of covariance(i, j).
    matrix_type covariance_matrix() const noexcept {
        matrix_type m{};
        for (std::size_t i = 0; i < N; ++i)
            for (std::size_t j = 0; j < N; ++j) m[i][j] = s_.covariance[detail::packed_index(i, j, N)];
        return m;
    }

    const state_type& state() const noexcept { return s_; }  ///< the state to save
    void reset() noexcept { s_ = state_type{}; }             ///< forgets every sample

protected:
    /// Restores s, or throws "<where>: <the broken rule>" (where: the public type restoring it).
    weighted_covariance(const state_type& s, const char* where) : s_(s) {
        if (const char* reason = invalid_state_reason(s)) detail::throw_invalid_argument(where, reason);
    }

    /// The recurrence itself (detail::comoment_step), given r = w_n / W_n in [0, 1]; the caller keeps W_n.
    template <mean_accuracy Accuracy = mean_accuracy::plain>
    void step(const vector_type& x, T r, comoment_form form) noexcept {
        // one stream: the range clamps behind predicted branches, off the dependent chain (bit-identical)
        detail::comoment_step<Accuracy, N, detail::range_check::branch>(
            s_.mean.data(), s_.mean_compensation.data(), s_.covariance.data(),
                                           s_.covariance_compensation.data(), x.data(), r, form);
    }

    /// Pushes with a fixed ratio r = w / W and W kept at 1 (exponential moving estimators).
    template <mean_accuracy Accuracy = mean_accuracy::plain>
    bool push_normalised(const vector_type& x, T r, comoment_form form) {
        if (!detail::all_finite(x)) {
            ++s_.rejected;
            return false;
        }
        ++s_.count;
        s_.total_weight = T(1);
        step<Accuracy>(x, r, form);
        return true;
    }

    /// Pushes with weight 1 and decay 1 (cumulative estimators): r = 1 / n from the exact integer count, so
    /// the ratio never stalls where a float total weight would (W + 1 == W beyond 2^24 in float).
    template <mean_accuracy Accuracy = mean_accuracy::plain>
    bool push_counted(const vector_type& x) {
        if (!detail::all_finite(x)) {
            ++s_.rejected;
            return false;
        }
        ++s_.count;
        s_.total_weight = static_cast<T>(s_.count);
        step<Accuracy>(x, T(1) / s_.total_weight, comoment_form::current_mean);
        return true;
    }

    state_type s_{};  ///< the whole state; derived estimators step it through the functions above
};

}  // namespace emcv
