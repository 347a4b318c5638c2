// SPDX-License-Identifier: MIT
// Decodes a fuzzer's byte string into the values the fuzz targets feed the library: every scalar is either one
// of the hard cases (0, -0, +-1, NaN, +-Inf, +-max, smallest normal, +-smallest subnormal, 1e10-scale offsets)
// or raw bits (any float at all, NaN payloads included), chosen by a tag byte so that mutations move between
// them. Past the end of the input every read returns 0: a target always terminates.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <cstdio>
#include <limits>
#include <type_traits>

namespace emcv_fuzz {

class input {
public:
    input(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}

    bool empty() const noexcept { return pos_ >= size_; }
    std::size_t remaining() const noexcept { return empty() ? 0 : size_ - pos_; }

    std::uint8_t byte() noexcept { return empty() ? 0 : data_[pos_++]; }

    /// An unsigned integer from the next sizeof(U) bytes, least significant first (as a memcpy on x86). Built
    /// by shifts rather than through a byte array, which g++ 12 misreads as an overflow once inlined.
    template <class U>
    U bits() noexcept {
        static_assert(std::is_unsigned<U>::value, "bits<U>() reads an unsigned integer");
        std::uint64_t u = 0;
        for (std::size_t k = 0; k < sizeof(U); ++k) u |= static_cast<std::uint64_t>(byte()) << (8u * k);
        return static_cast<U>(u);
    }

    /// One scalar of type T: a hard case or raw bits, by tag.
    template <class T>
    T scalar() noexcept {
        using lim = std::numeric_limits<T>;
        const std::uint8_t tag = byte();
        switch (tag % 20) {
            case 0: return T(0);
            case 1: return -T(0);
            case 2: return T(1);
            case 3: return T(-1);
            case 4: return lim::quiet_NaN();
            case 5: return lim::infinity();
            case 6: return -lim::infinity();
            case 7: return lim::max();
            case 8: return -lim::max();
            case 9: return lim::min();
            case 10: return lim::denorm_min();
            case 11: return -lim::denorm_min();
            case 12: return static_cast<T>(static_cast<std::int8_t>(byte()));  // small integers
            case 13: {  // mantissa * 2^exponent over the whole range, subnormals included
                const auto mantissa = static_cast<std::int16_t>(bits<std::uint16_t>());
                const int exponent = static_cast<std::int8_t>(byte()) * (lim::max_exponent / 96 + 1);
                return std::ldexp(static_cast<T>(mantissa), exponent);  // overflow gives +-Inf, defined
            }
            case 14: return static_cast<T>(1e10L + static_cast<std::int8_t>(byte()));  // offset + spread
            case 15: return static_cast<T>(static_cast<std::int8_t>(byte())) / T(128);  // in [-1, 1)
            default: {  // raw bits
                if constexpr (sizeof(T) == 4) {
                    const auto u = bits<std::uint32_t>();
                    T t;
                    std::memcpy(&t, &u, sizeof t);
                    return t;
                } else {
                    const auto u = bits<std::uint64_t>();
                    T t;
                    std::memcpy(&t, &u, sizeof t);
                    return t;
                }
            }
        }
    }

private:
    const std::uint8_t* data_;
    std::size_t size_;
    std::size_t pos_ = 0;
};

/// An invariant does not hold: print it and abort (libFuzzer and the corpus replay both report the abort).
[[noreturn]] inline void violated(const char* what, const char* file, int line) {
    std::fprintf(stderr, "emcv fuzz invariant violated: %s (%s:%d)\n", what, file, line);
    std::abort();
}

}  // namespace emcv_fuzz

#define EMCV_FUZZ_ASSERT(...) \
    ((__VA_ARGS__) ? void(0) : ::emcv_fuzz::violated(#__VA_ARGS__, __FILE__, __LINE__))
