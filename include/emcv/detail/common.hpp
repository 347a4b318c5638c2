// SPDX-License-Identifier: MIT
// Internal helpers shared by every estimator: argument checks, finiteness, vector-like adapters.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <type_traits>

/// Forces inlining of the per-sample recurrence (GCC and Clang): a pixel loop around it can only vectorise
/// when it is inlined, and inside a large translation unit GCC's heuristics sometimes decline.
#if defined(__GNUC__) || defined(__clang__)
#define EMCV_ALWAYS_INLINE inline __attribute__((always_inline))
#else
#define EMCV_ALWAYS_INLINE inline
#endif

namespace emcv {
namespace detail {

/// Throws std::invalid_argument naming the function and the broken requirement. Kept out of line and cold
/// so that a check in a per-sample push costs one predictable branch, not the string building.
#if defined(__GNUC__) || defined(__clang__)
[[noreturn]] __attribute__((noinline, cold))
#else
[[noreturn]]
#endif
inline void throw_invalid_argument(const char* where, const char* what) {
    throw std::invalid_argument(std::string("emcv::") + where + ": " + what);
}

inline void require(bool ok, const char* where, const char* what) {
    if (!ok) throw_invalid_argument(where, what);
}

template <class T>
void require_floating_point() {
    static_assert(std::is_floating_point<T>::value, "emcv estimators need a floating-point scalar T");
}

/// True when every component is finite (no NaN, no +-Inf).
template <class T, std::size_t N>
bool all_finite(const std::array<T, N>& x) noexcept {
    for (std::size_t i = 0; i < N; ++i)
        if (!std::isfinite(x[i])) return false;
    return true;
}

/// True when every component is exactly zero (+0 or -0).
template <class T, std::size_t N>
bool all_zero(const std::array<T, N>& x) noexcept {
    for (std::size_t i = 0; i < N; ++i)
        if (!(x[i] == T(0))) return false;
    return true;
}

/// A vector-like type of N components: glm::vec<N, T> and anything else with a static length() == N
/// and operator[]. Detected structurally so that the library never includes GLM itself.
template <class V, std::size_t N, class = void>
struct is_vector_like : std::false_type {};

template <class V, std::size_t N>
struct is_vector_like<V, N, std::void_t<decltype(V::length()), decltype(std::declval<const V&>()[0])>>
    : std::bool_constant<static_cast<std::size_t>(V::length()) == N> {};

template <class T, std::size_t N, class V>
std::array<T, N> to_array(const V& v) {
    std::array<T, N> a{};
    for (std::size_t i = 0; i < N; ++i) a[i] = static_cast<T>(v[static_cast<decltype(V::length())>(i)]);
    return a;
}

/// Index of (i, j) in packed upper-triangular storage of an N x N symmetric matrix (row-major, i <= j).
constexpr std::size_t packed_index(std::size_t i, std::size_t j, std::size_t n) noexcept {
    return i <= j ? i * n - i * (i + 1) / 2 + j : j * n - j * (j + 1) / 2 + i;
}

}  // namespace detail
}  // namespace emcv
