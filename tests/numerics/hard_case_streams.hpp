// SPDX-License-Identifier: MIT
// The hard-case stream families of docs/numerics.md section 3, per precision T.
#pragma once

#include <array>
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "numerics_support.hpp"

namespace emcv_numerics {

template <class T>
struct stream {
    std::string name;
    std::vector<std::array<T, 2>> x;  // (x, y) pairs; 1-D estimators read the first component
    std::vector<T> weight;            // per-sample weights for weighted_covariance
    bool constant = false;            // variance and covariance must be exactly 0
    bool check_bound = true;          // false where the exact covariance leaves the range of T (saturation)
};

template <class T>
T as_t(double v) {
    return static_cast<T>(v);
}

template <class T>
void fill_weights(stream<T>& s, std::uint64_t seed) {
    uniform_source u(seed);
    s.weight.resize(s.x.size());
    for (auto& w : s.weight) w = as_t<T>(1.25 + 0.75 * u.next());  // in [0.5, 2)
}

/// Large offset m against spread s (x), and a correlated y with offset m / 2 and the same spread.
template <class T>
stream<T> offset_stream(double m, double s, std::size_t n, std::uint64_t seed) {
    stream<T> out;
    out.name = "offset " + std::to_string(m) + " spread " + std::to_string(s);
    uniform_source u(seed);
    for (std::size_t i = 0; i < n; ++i) {
        const double z1 = u.next(), z2 = u.next();
        out.x.push_back({as_t<T>(m + s * z1), as_t<T>(0.5 * m + s * (0.6 * z1 + 0.8 * z2))});
    }
    fill_weights(out, seed + 1);
    return out;
}

template <class T>
stream<T> constant_stream(double a, double b, std::size_t n) {
    stream<T> out;
    out.name = "constant " + std::to_string(a);
    out.x.assign(n, {as_t<T>(a), as_t<T>(b)});
    out.constant = true;
    fill_weights(out, 7);
    return out;
}

template <class T>
stream<T> alternating_stream(double a, double b, std::size_t n) {
    stream<T> out;
    out.name = "alternating " + std::to_string(a) + " " + std::to_string(b);
    for (std::size_t i = 0; i < n; ++i)
        out.x.push_back(i % 2 == 0 ? std::array<T, 2>{as_t<T>(a), as_t<T>(b)}
                                   : std::array<T, 2>{as_t<T>(b), as_t<T>(a)});
    fill_weights(out, 11);
    return out;
}

/// A light switching off and on: level -> 0 -> level, thirds of the stream, with 1% noise while on.
template <class T>
stream<T> step_stream(double level, std::size_t n) {
    stream<T> out;
    out.name = "step " + std::to_string(level) + " -> 0 -> " + std::to_string(level);
    uniform_source u(13);
    for (std::size_t i = 0; i < n; ++i) {
        const bool on = i < n / 3 || i >= 2 * n / 3;
        const double z = u.next();
        out.x.push_back({as_t<T>(on ? level * (1 + 0.01 * z) : 0.0), as_t<T>(on ? 0.5 * level : 0.0)});
    }
    fill_weights(out, 17);
    return out;
}

/// A gunshot: base (1 +- 10%) with one frame at base * 1e4 in the middle of the stream.
template <class T>
stream<T> impulse_stream(double base, std::size_t n) {
    stream<T> out;
    out.name = "impulse x1e4 on " + std::to_string(base);
    uniform_source u(19);
    for (std::size_t i = 0; i < n; ++i) {
        const double z = u.next();
        const double v = i == n / 2 ? base * 1e4 : base * (1 + 0.1 * z);
        out.x.push_back({as_t<T>(v), as_t<T>(base * (1 - 0.1 * z))});
    }
    fill_weights(out, 23);
    return out;
}

/// Integer multiples of the smallest subnormal of T (1..1000): every sample, mean and variance is subnormal
/// or underflows.
template <class T>
stream<T> subnormal_stream(std::size_t n) {
    stream<T> out;
    out.name = "subnormal";
    uniform_source u(29);
    const T tiny = std::numeric_limits<T>::denorm_min();
    for (std::size_t i = 0; i < n; ++i) {
        const double k1 = std::floor(500.5 + 499.5 * u.next()), k2 = std::floor(500.5 + 499.5 * u.next());
        out.x.push_back({static_cast<T>(tiny * as_t<T>(k1)), static_cast<T>(tiny * as_t<T>(k2))});
    }
    fill_weights(out, 31);
    return out;
}

/// Values near the top of the range: x within [max/2, max) and y alternating in sign at 0.9 max, so x - mu
/// overflows for y and every variance leaves the range (it must saturate, never become Inf or NaN).
template <class T>
stream<T> near_top_stream(std::size_t n) {
    stream<T> out;
    out.name = "near the top of the range";
    uniform_source u(37);
    const T top = std::numeric_limits<T>::max();
    for (std::size_t i = 0; i < n; ++i) {
        const double z = u.next();
        out.x.push_back({static_cast<T>(top * as_t<T>(0.75 + 0.25 * z * 0.999)),
                         static_cast<T>(top * as_t<T>(i % 2 == 0 ? 0.9 : -0.9))});
    }
    fill_weights(out, 41);
    out.check_bound = false;
    return out;
}

/// Every family at the scale of T's own state (float or double history).
template <class T>
std::vector<stream<T>> native_families(std::size_t n) {
    std::vector<stream<T>> f;
    const bool is_float = sizeof(T) == sizeof(float);
    const std::vector<double> offsets = is_float ? std::vector<double>{1e4, 1e6} : std::vector<double>{1e4, 1e6, 1e9};
    std::uint64_t seed = 100;
    for (double m : offsets)
        for (double s : {0.1, 1.0})
            for (double sign : {1.0, -1.0}) f.push_back(offset_stream<T>(sign * m, s, n, ++seed));
    f.push_back(constant_stream<T>(0.7, -3.0, n));
    f.push_back(constant_stream<T>(-2.5e4, 1e3, n));
    f.push_back(alternating_stream<T>(1.0, 3.0, n));
    f.push_back(alternating_stream<T>(1e3, 1e-3, n));
    f.push_back(step_stream<T>(1e3, n));
    f.push_back(impulse_stream<T>(1.0, n));
    f.push_back(subnormal_stream<T>(n));
    f.push_back(near_top_stream<T>(n));
    return f;
}

/// The families scaled so that an RGBA16F history can hold the state (|values|, variances <= 65504):
/// offsets 1e2..1e3, a 1e2 light, a 1e-2 base with a x1e4 impulse, values in the half subnormal range.
template <class T>
std::vector<stream<T>> half_families(std::size_t n) {
    std::vector<stream<T>> f;
    std::uint64_t seed = 200;
    for (double m : {1e2, 1e3})
        for (double s : {0.1, 1.0})
            for (double sign : {1.0, -1.0}) f.push_back(offset_stream<T>(sign * m, s, n, ++seed));
    f.push_back(constant_stream<T>(0.75, -3.0, n)  /* representable in binary16 */);
    f.push_back(alternating_stream<T>(1.0, 3.0, n));
    f.push_back(step_stream<T>(1e2, n));
    f.push_back(impulse_stream<T>(1e-2, n));
    stream<T> sub = offset_stream<T>(2e-6, 1e-6, n, 300);  // half subnormals lie below 2^-14 = 6.1e-5
    sub.name = "half subnormal range";
    f.push_back(sub);
    return f;
}

}  // namespace emcv_numerics
