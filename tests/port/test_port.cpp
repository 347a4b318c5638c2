// SPDX-License-Identifier: MIT
// The shared port (include/emcv/port) against the templated C++ API on the CPU: where the C++ API has a float
// instance of the same formula the two must agree bit for bit (same operations in the same order, built with
// -ffp-contract=off). Burley sampling is checked against the CDF and a double evaluation of the formulas.
#include <catch2/catch_test_macros.hpp>

#include <array>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include <emcv/control_variate.hpp>
#include <emcv/emcm.hpp>
#include <emcv/moving_stats.hpp>
#include <emcv/sample_count.hpp>
#include <emcv/port/burley.h>
#include <emcv/port/cv.h>
#include <emcv/port/ema.h>
#include <emcv/port/hash.h>
#include <emcv/port/samples.h>
#include <emcv/port/sss.h>

namespace port = emcv::port;

namespace {

std::uint32_t bits(float x) {
    std::uint32_t b;
    std::memcpy(&b, &x, sizeof b);
    return b;
}

/// A stream with the hard cases: unit scale, offset 1e4, tiny and huge scales, overflowing differences,
/// NaN and Inf samples.
std::vector<glm::vec2> hard_stream(std::uint32_t seed, std::size_t n) {
    std::vector<glm::vec2> xs;
    const float scales[] = {1.0f, 1.0e-15f, 1.0e18f};
    for (std::uint32_t k = 0; k < n; ++k) {
        const std::uint32_t h = port::emcv_pcg(seed + k);
        const float u1 = port::emcv_uint_to_unit_float(h) - 0.5f;
        const float u2 = port::emcv_uint_to_unit_float(port::emcv_pcg(h)) - 0.5f;
        const float s = scales[(k / 1000u) % 3u];
        const float offset = (seed % 2u) ? 1.0e4f : 0.0f;
        glm::vec2 x(offset + s * u1, offset + s * (0.5f * u1 + 0.5f * u2));
        if (k >= 5000u && k < 5010u) x = glm::vec2(k % 2u ? 3.0e38f : -3.0e38f, 1.0f);  // x - mu overflows
        if (k % 997u == 996u) x.x = std::numeric_limits<float>::quiet_NaN();
        if (k % 991u == 990u) x.y = std::numeric_limits<float>::infinity();
        xs.push_back(x);
    }
    return xs;
}

}  // namespace

TEST_CASE("port EMCM 2x2 equals emcv::emcm<float, 2> bit for bit") {
    for (std::uint32_t seed : {1u, 2u}) {
        for (float eta : {0.05f, 0.2f, 1.0f}) {
            emcv::emcm<float, 2> ref(eta);
            port::EmcvEmcm2 s = port::emcv_emcm2_init();
            const auto xs = hard_stream(seed, 10000);
            for (std::size_t k = 0; k < xs.size(); ++k) {
                const bool accepted_ref = ref.push(std::array<float, 2>{xs[k].x, xs[k].y});
                const bool accepted = port::emcv_emcm2_push(s, xs[k], eta);
                INFO("seed " << seed << " eta " << eta << " update " << k);
                REQUIRE(accepted == accepted_ref);
                REQUIRE(bits(s.mean.x) == bits(ref.mean(0)));
                REQUIRE(bits(s.mean.y) == bits(ref.mean(1)));
                REQUIRE(bits(s.cov.x) == bits(ref.covariance(0, 0)));
                REQUIRE(bits(s.cov.y) == bits(ref.covariance(0, 1)));
                REQUIRE(bits(s.cov.z) == bits(ref.covariance(1, 1)));
            }
            CHECK(s.count == ref.count());
            CHECK(s.rejected == ref.rejected());
            CHECK(s.rejected > 0u);
        }
    }
}

TEST_CASE("port moving stats equal emcv::moving_stats<float> bit for bit") {
    emcv::moving_stats<float> ref(0.2f);
    port::EmcvMovingStats s = port::emcv_moving_stats_init();
    for (const auto& x : hard_stream(3u, 10000)) {
        REQUIRE(port::emcv_moving_stats_push(s, x.x, 0.2f) == ref.push(x.x));
        REQUIRE(bits(s.mean) == bits(ref.mean()));
        REQUIRE(bits(s.variance) == bits(ref.variance()));
    }
    CHECK(s.count == ref.count());
    CHECK(s.rejected == ref.rejected());
}

TEST_CASE("port moving stats equal the caller-owned emcv::moving_stats_update<float> bit for bit") {
    // The per-pixel structure-of-arrays form: the caller seeds mean = x, variance = 0 on the first sample.
    port::EmcvMovingStats s = port::emcv_moving_stats_init();
    float mean = 0.0f, variance = 0.0f;
    bool seeded = false;
    for (const auto& x : hard_stream(4u, 10000)) {
        const bool accepted = port::emcv_moving_stats_push(s, x.y, 0.05f);
        if (!seeded) {
            if (!std::isfinite(x.y)) continue;
            mean = x.y;
            variance = 0.0f;
            seeded = true;
        } else {
            REQUIRE(emcv::moving_stats_update(mean, variance, x.y, 0.05f) == accepted);
        }
        REQUIRE(bits(s.mean) == bits(mean));
        REQUIRE(bits(s.variance) == bits(variance));
    }
}

TEST_CASE("port cv coefficient and residual equal the C++ API, guard included") {
    const float inf = std::numeric_limits<float>::infinity();
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float tiny = std::numeric_limits<float>::min();
    const float denorm = std::numeric_limits<float>::denorm_min();
    const float values[] = {0.0f, -0.0f, 1.0f, -2.5f, 3.0e-20f, 1.0e30f, -1.0e-30f, tiny, denorm, 1.0e-38f,
                            std::numeric_limits<float>::max(), inf, -inf, nan};
    for (float cov : values) {
        for (float var : values) {
            INFO("cov " << cov << " var " << var);
            REQUIRE(bits(port::emcv_cv_coefficient(cov, var)) == bits(emcv::cv_coefficient(cov, var)));
            for (float fl : {tiny, 1.0e-6f, 1.0f})
                REQUIRE(bits(port::emcv_cv_coefficient_floor(cov, var, fl)) == bits(emcv::cv_coefficient(cov, var, fl)));
            REQUIRE(bits(port::emcv_cv_residual(cov, 0.5f, var)) == bits(emcv::cv_residual(cov, 0.5f, var)));
        }
    }
    // the guard: no control variate when Var(G) vanishes or the quotient overflows
    CHECK(port::emcv_cv_coefficient(1.0f, 0.0f) == 0.0f);
    CHECK(port::emcv_cv_coefficient(1.0f, denorm) == 0.0f);
    CHECK(port::emcv_cv_coefficient(1.0e30f, 1.0e-30f) == 0.0f);
    CHECK(port::emcv_cv_coefficient(nan, 1.0f) == 0.0f);
}

TEST_CASE("port sample count equals emcv::sample_count<float>") {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    std::vector<float> vars = {0.0f, -1.0f, nan, inf, -inf, 1.0e-4f, 8.0e-4f, 8.00001e-4f, 6.4e-3f, 1.0e30f};
    for (std::uint32_t k = 0; k < 20000; ++k) vars.push_back(1.0e-2f * port::emcv_uint_to_unit_float(port::emcv_pcg(k)));
    for (float v : vars) {
        for (int n_min : {0, 8}) {
            INFO("variance " << v << " n_min " << n_min);
            REQUIRE(port::emcv_sample_count(v, 1.0e-4f, n_min, 64) == emcv::sample_count(v, 1.0e-4f, n_min, 64));
        }
    }
    CHECK(port::emcv_sample_count(nan, 1.0e-4f, 8, 64) == 64);
}

namespace {
double cdf_d(double r, double d) { return 1.0 - 0.25 * std::exp(-r / d) - 0.75 * std::exp(-r / (3.0 * d)); }
double pdf_d(double r, double d) { return (std::exp(-r / d) + std::exp(-r / (3.0 * d))) / (4.0 * d); }
}  // namespace

TEST_CASE("Burley: exact inverse CDF inverts the CDF; pdf, CDF and profile match their double formulas") {
    // F(r_float(u)) - u = p(r) dr with p <= p(0) = 1/(2d), and dr = 3d * (absolute error of the log's argument
    // ratio). Each of the ~12 float operations before the log contributes at most 1 ulp relative to values of
    // order c = 1 + G^{1/3} + G^{-1/3} >= 4, so |dr| <= 3d * 16 eps and |F(r) - u| <= 1.5 * 16 eps = 24 eps.
    const double eps = std::numeric_limits<float>::epsilon();
    const double inverse_bound = 24.0 * eps;
    for (float d : {0.05f, 1.0f, 7.0f}) {
        double worst = 0.0;
        float previous = -1.0f;
        for (std::uint32_t i = 0; i < 4096; ++i) {
            const float u = (static_cast<float>(i) + 0.5f) / 4096.0f;
            const float r = port::emcv_burley_sample_exact(u, d);
            REQUIRE(std::isfinite(r));
            REQUIRE(r > previous);  // monotone
            previous = r;
            const double err = std::fabs(cdf_d(r, d) - static_cast<double>(u));
            worst = std::max(worst, err);
            // the float formulas against double (relative; exp/log of glibc are within 1 ulp, 4 ops each)
            const double p = pdf_d(r, d);
            REQUIRE(std::fabs(port::emcv_burley_pdf(r, d) - p) <= 8.0 * eps * p);
            REQUIRE(std::fabs(port::emcv_burley_cdf(r, d) - cdf_d(r, d)) <= 8.0 * eps);
            const double rr = p / (2.0 * 3.14159265358979323846);
            REQUIRE(std::fabs(port::emcv_burley_profile_r(r, d) - rr) <= 8.0 * eps * rr);
        }
        INFO("d " << d << " worst |F(r(u)) - u| " << worst << " bound " << inverse_bound);
        CHECK(worst <= inverse_bound);
    }
    CHECK(port::emcv_burley_sample_exact(0.0f, 1.0f) == 0.0f);
}

TEST_CASE("Burley: SPVG's approximation starts at 0, is monotone, and is exact in the mean to within its fit") {
    // r ~ d (2 + (c - 2) u)(-ln(1 - u)): r(0) = 0 and increasing. For u -> 1 the exact inverse grows like
    // 3 d (-ln(1 - u)) and the approximation like c d (-ln(1 - u)), so their ratio tends to c / 3 from above.
    float previous = -1.0f;
    for (std::uint32_t i = 0; i < 4096; ++i) {
        const float u = static_cast<float>(i) / 4096.0f;
        const float r = port::emcv_burley_sample_spvg(u, 1.0f);
        REQUIRE(r > previous);
        previous = r;
    }
    CHECK(port::emcv_burley_sample_spvg(0.0f, 1.0f) == 0.0f);
    const float u = 1.0f - 1.0e-6f;
    const double ratio = static_cast<double>(port::emcv_burley_sample_spvg(u, 1.0f)) /
                         static_cast<double>(port::emcv_burley_sample_exact(u, 1.0f));
    CHECK(ratio > 2.5715 / 3.0);
    CHECK(ratio < 1.0);
}

TEST_CASE("Sobol's first two dimensions are a (0, 2)-sequence, and the pixel's scrambling keeps it one") {
    // A (0, 2)-sequence in base 2: for every k, each block of 2^k points from a multiple of 2^k puts exactly one
    // point in each elementary interval [a 2^-j, (a + 1) 2^-j) x [b 2^-(k-j), (b + 1) 2^-(k-j)), j = 0..k.
    // XOR-ing every point's bits with one fixed word (a random digit scrambling) maps each elementary interval onto
    // another of the same shape, so the scrambled points keep the property.
    const glm::vec2 rotation(0.3141592f, 0.7182818f);
    for (const bool scrambled : {false, true}) {
        for (std::uint32_t k = 0; k <= 8; ++k) {
            const std::uint32_t count = 1u << k;
            for (std::uint32_t first : {0u, count, 5u * count}) {
                for (std::uint32_t j = 0; j <= k; ++j) {
                    std::vector<int> cells(count, 0);
                    for (std::uint32_t n = first; n < first + count; ++n) {
                        const glm::vec2 u = scrambled ? port::emcv_sss_sample_uv_sobol(n, rotation)
                                                      : glm::vec2(port::emcv_uint_to_unit_float(port::emcv_sobol2_bits(n).x),
                                                                  port::emcv_uint_to_unit_float(port::emcv_sobol2_bits(n).y));
                        REQUIRE(u.x >= 0.0f);
                        REQUIRE(u.x < 1.0f);
                        REQUIRE(u.y >= 0.0f);
                        REQUIRE(u.y < 1.0f);
                        const auto a = static_cast<std::uint32_t>(u.x * float(1u << j));
                        const auto b = static_cast<std::uint32_t>(u.y * float(1u << (k - j)));
                        ++cells[(a << (k - j)) | b];
                    }
                    INFO("scrambled " << scrambled << ", 2^" << k << " points from " << first << ", intervals 2^-" << j
                                      << " x 2^-" << (k - j));
                    CHECK(std::count(cells.begin(), cells.end(), 1) == static_cast<long>(count));
                }
            }
        }
    }
    // the first dimension is the radical inverse (van der Corput): 1, 2, 3 -> 1/2, 1/4, 3/4
    CHECK(port::emcv_sobol2_bits(1u).x == 0x80000000u);
    CHECK(port::emcv_sobol2_bits(2u).x == 0x40000000u);
    CHECK(port::emcv_sobol2_bits(3u).x == 0xc0000000u);
}

TEST_CASE("hash and low-discrepancy helpers") {
    // pcg against an independent uint32_t transcription of the JCGT 2020 listing
    for (std::uint32_t v : {0u, 1u, 12345u, 0xffffffffu}) {
        const std::uint32_t state = v * 747796405u + 2891336453u;
        const std::uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
        CHECK(port::emcv_pcg(v) == ((word >> 22u) ^ word));
    }
    // unit floats are in [0, 1) and reach both ends' neighbourhoods
    CHECK(port::emcv_uint_to_unit_float(0u) == 0.0f);
    CHECK(port::emcv_uint_to_unit_float(0xffffffffu) < 1.0f);
    // Hammersley's second coordinate is the base-2 radical inverse: i = 1, 2, 3 -> 1/2, 1/4, 3/4
    CHECK(port::emcv_hammersley(1u, 8u).y == 0.5f);
    CHECK(port::emcv_hammersley(2u, 8u).y == 0.25f);
    CHECK(port::emcv_hammersley(3u, 8u).y == 0.75f);
    CHECK(port::emcv_hammersley(3u, 8u).x == 0.375f);
    // R2: 1024 points fill a 32 x 32 grid with at most 2 points per cell (low discrepancy; i.i.d. points
    // would leave about 1024 / e ~ 377 cells empty)
    std::vector<int> cells(32 * 32, 0);
    for (std::uint32_t n = 0; n < 1024; ++n) {
        const glm::vec2 p = port::emcv_r2(n);
        REQUIRE(p.x >= 0.0f);
        REQUIRE(p.x < 1.0f);
        REQUIRE(p.y >= 0.0f);
        REQUIRE(p.y < 1.0f);
        ++cells[static_cast<std::size_t>(p.y * 32.0f) * 32u + static_cast<std::size_t>(p.x * 32.0f)];
    }
    int worst = 0;
    for (int c : cells) worst = std::max(worst, c);
    CHECK(worst <= 3);
}

TEST_CASE("port pushes reseed an invalid stored state as moving_stats_update does, and count it") {
    // A state read back from a texture whose variance overflowed to Inf, or that holds a NaN or a negative
    // variance: the port replaces it by the next finite sample (mean = x, variance 0), bit for bit as the C++
    // per-pixel form, and counts it; a non-finite sample leaves it (and the count) alone.
    const float inf = std::numeric_limits<float>::infinity();
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const std::array<std::array<float, 2>, 3> broken{{{2.0f, inf}, {nan, 1.0f}, {4.0f, -1.0f}}};
    for (const auto& stored : broken) {
        port::EmcvMovingStats s = port::emcv_moving_stats_init();
        s.mean = stored[0];
        s.variance = stored[1];
        s.count = 7u;
        REQUIRE_FALSE(port::emcv_moving_stats_push(s, nan, 0.05f));
        CHECK(s.reseeded == 0u);
        float mean = stored[0], variance = stored[1];
        REQUIRE(port::emcv_moving_stats_push(s, 3.5f, 0.05f));
        REQUIRE(emcv::moving_stats_update(mean, variance, 3.5f, 0.05f));
        CHECK(bits(s.mean) == bits(mean));
        CHECK(bits(s.variance) == bits(variance));
        CHECK(s.mean == 3.5f);
        CHECK(s.variance == 0.0f);
        CHECK(s.reseeded == 1u);
        CHECK(s.count == 1u);
        REQUIRE(port::emcv_moving_stats_push(s, 4.5f, 0.5f));  // and the history continues: mean 4, var 0.25
        CHECK(s.mean == 4.0f);
        CHECK(s.variance == 0.25f);
    }
    port::EmcvEmcm2 e = port::emcv_emcm2_init();
    e.mean = glm::vec2(1.0f, 2.0f);
    e.cov = glm::vec3(inf, 0.0f, 1.0f);  // C_ff overflowed
    e.count = 3u;
    REQUIRE(port::emcv_emcm2_push(e, glm::vec2(5.0f, 6.0f), 0.05f));
    CHECK(e.mean == glm::vec2(5.0f, 6.0f));
    CHECK(e.cov == glm::vec3(0.0f));
    CHECK(e.reseeded == 1u);
    e.cov = glm::vec3(0.5f, nan, 0.5f);  // a NaN cross term
    REQUIRE(port::emcv_emcm2_push(e, glm::vec2(7.0f, 8.0f), 0.05f));
    CHECK(e.mean == glm::vec2(7.0f, 8.0f));
    CHECK(e.reseeded == 2u);
}

TEST_CASE("the unchecked port (the default) validates no parameter: what docs/porting.md says it does") {
    // EMCV_PORT_CHECKS 0: an eta outside (0, 1] is applied as given (eta = 2: r = 2, outer weight 1 - r = -1, so
    // the variance of 0 then 1 is 0 + 2 ((-1 * 1) * 1 - 0) = -2), and a target of 0 gives n_max where
    // emcv::sample_count throws; tests/port/test_port_checks.cpp covers the checked variant.
    port::EmcvMovingStats m = port::emcv_moving_stats_init();
    REQUIRE(port::emcv_moving_stats_push(m, 0.0f, 2.0f));
    REQUIRE(port::emcv_moving_stats_push(m, 1.0f, 2.0f));
    CHECK(m.variance == -2.0f);
    CHECK(m.rejected == 0u);
    CHECK(port::emcv_sample_count(1e-3f, 0.0f, 8, 64) == 64);
}
