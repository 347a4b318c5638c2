// SPDX-License-Identifier: MIT
// Internal helpers shared by every estimator: argument checks, finiteness, vector-like adapters.
#pragma once

#include <array>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
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

#if defined(__GNUC__) || defined(__clang__)
/// Marks a function that only runs on the error path: kept out of line, so that the check calling it costs
/// one predictable branch and not the message building.
#define EMCV_COLD __attribute__((noinline, cold))
#else
/// Marks a function that only runs on the error path (no attribute on this compiler).
#define EMCV_COLD
#endif

namespace emcv {
namespace detail {

/// What the default EMCV_ASSERT does when its condition fails: prints the condition, the message and the
/// place to stderr and aborts.
[[noreturn]] EMCV_COLD inline void assert_failed(const char* condition, const char* message, const char* file,
                                                 int line) {
    std::fprintf(stderr, "%s:%d: emcv assertion failed: %s (%s)\n", file, line, message, condition);
    std::abort();
}

}  // namespace detail
}  // namespace emcv

/// \def EMCV_ASSERT(cond, msg)
/// Checks a precondition that costs too much to check in release builds: an index out of range
/// (`mean(7)` of a 2-D estimator, `covariance(0, 2)`). Without NDEBUG a failed check prints `msg` and the
/// condition and aborts; with NDEBUG it compiles to nothing (the condition is not evaluated). Define it before
/// including any emcv header to route the check elsewhere: to an engine's assert handler, or to a throw in a
/// test (docs/api.md, "Debug assertions").
#ifndef EMCV_ASSERT
#ifdef NDEBUG
#define EMCV_ASSERT(cond, msg) static_cast<void>(0)
#else
#define EMCV_ASSERT(cond, msg) \
    ((cond) ? static_cast<void>(0) : ::emcv::detail::assert_failed(#cond, msg, __FILE__, __LINE__))
#endif
#endif

namespace emcv {
namespace detail {

/// Throws std::invalid_argument "<where>: <what>", where `where` names the public type or function
/// (emcv::emcm, emcv::sample_count).
[[noreturn]] EMCV_COLD inline void throw_invalid_argument(const char* where, const char* what) {
    throw std::invalid_argument(std::string(where) + ": " + what);
}

/// Throws when !ok (see throw_invalid_argument).
inline void require(bool ok, const char* where, const char* what) {
    if (!ok) throw_invalid_argument(where, what);
}

/// The shortest decimal text that reads back as `value` ("2", "1.0001", "nan", "-inf").
template <class T>
std::string number_text(T value) {
    if constexpr (std::is_floating_point<T>::value) {
        if (std::isnan(value)) return "nan";
        if (std::isinf(value)) return value > T(0) ? "inf" : "-inf";
    }
    char text[64];
    const auto end = std::to_chars(text, text + sizeof text, value).ptr;
    return std::string(text, end);
}

/// Throws std::invalid_argument "<where>: <name> = <value> <requirement>", e.g.
/// "emcv::emcm: eta = 2 must lie in (0, 1]": the public type, the parameter, its value, the condition.
template <class T>
[[noreturn]] EMCV_COLD void throw_invalid_value(const char* where, const char* name, T value,
                                                const char* requirement) {
    throw std::invalid_argument(std::string(where) + ": " + name + " = " + number_text(value) + " " + requirement);
}

/// Throws (throw_invalid_value) when !ok.
template <class T>
void require_value(bool ok, const char* where, const char* name, T value, const char* requirement) {
    if (!ok) throw_invalid_value(where, name, value, requirement);
}

/// Returns eta when it lies in (0, 1] (the weight of a new sample in the exponential estimators); throws
/// "<where>: <name> = <eta> must lie in (0, 1]" otherwise, NaN included.
template <class T>
T checked_eta(T eta, const char* where, const char* name = "eta") {
    require_value(eta > T(0) && eta <= T(1), where, name, eta, "must lie in (0, 1]");
    return eta;
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
