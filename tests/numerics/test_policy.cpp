// SPDX-License-Identifier: MIT
// The library-wide policies of docs/numerics.md section 4: non-finite samples, binary16 overflow of a
// restored state, the range policy near the top of T, eta edge cases, and the guards of cv_coefficient
// and sample_count.
#include <catch2/catch_template_test_macros.hpp>
#include <catch2/catch_test_macros.hpp>

#include <cmath>
#include <cstring>
#include <vector>
#include <limits>
#include <stdexcept>

#include "hard_case_streams.hpp"
#include "raw_moments.hpp"

using namespace emcv_numerics;

namespace {

template <class State>
bool same_bits(const State& a, const State& b) {
    return a.count == b.count && std::memcmp(&a.mean, &b.mean, sizeof a.mean) == 0 &&
           std::memcmp(&a.covariance, &b.covariance, sizeof a.covariance) == 0 &&
           std::memcmp(&a.mean_compensation, &b.mean_compensation, sizeof a.mean_compensation) == 0 &&
           std::memcmp(&a.total_weight, &b.total_weight, sizeof a.total_weight) == 0;
}

}  // namespace

TEMPLATE_TEST_CASE("non-finite samples are rejected, counted, and leave every estimator's state bit-identical", "",
                   float, double) {
    using T = TestType;
    const auto s = offset_stream<T>(1e4, 0.1, 500, 5);
    const T poison[] = {std::numeric_limits<T>::quiet_NaN(), std::numeric_limits<T>::infinity(),
                        -std::numeric_limits<T>::infinity()};
    emcv::weighted_covariance<T, 2> w_clean, w_dirty;
    emcv::running_covariance<T, 2> r_clean, r_dirty;
    emcv::compensated_running_covariance<T, 2> c_clean, c_dirty;
    emcv::emcm<T, 2> e_clean(T(0.05)), e_dirty(T(0.05));
    emcv::ewma_covariance<T, 2> v_clean(T(0.2)), v_dirty(T(0.2));
    emcv::moving_stats<T> m_clean(T(0.2)), m_dirty(T(0.2));
    std::uint64_t injected = 0;
    for (std::size_t n = 0; n < s.x.size(); ++n) {
        if (n % 7 == 3) {  // one bad component in x, in y, or both
            const T bad = poison[n % 3];
            const std::array<T, 2> xs[] = {{bad, s.x[n][1]}, {s.x[n][0], bad}, {bad, bad}};
            const auto& x = xs[(n / 7) % 3];
            CHECK_FALSE(w_dirty.push(x, s.weight[n], T(0.9)));
            CHECK_FALSE(r_dirty.push(x));
            CHECK_FALSE(c_dirty.push(x));
            CHECK_FALSE(e_dirty.push(x));
            CHECK_FALSE(v_dirty.push(x));
            CHECK_FALSE(m_dirty.push(x[0] == x[0] && std::isfinite(x[0]) ? bad : x[0]));
            ++injected;
        }
        CHECK(w_clean.push(s.x[n], s.weight[n], T(0.9)) == w_dirty.push(s.x[n], s.weight[n], T(0.9)));
        r_clean.push(s.x[n]);
        r_dirty.push(s.x[n]);
        c_clean.push(s.x[n]);
        c_dirty.push(s.x[n]);
        e_clean.push(s.x[n]);
        e_dirty.push(s.x[n]);
        v_clean.push(s.x[n]);
        v_dirty.push(s.x[n]);
        m_clean.push(s.x[n][0]);
        m_dirty.push(s.x[n][0]);
    }
    CHECK(same_bits(w_clean.state(), w_dirty.state()));
    CHECK(same_bits(r_clean.state(), r_dirty.state()));
    CHECK(same_bits(c_clean.state(), c_dirty.state()));
    CHECK(same_bits(e_clean.state(), e_dirty.state()));
    CHECK(same_bits(v_clean.state(), v_dirty.state()));
    CHECK(same_bits(m_clean.state(), m_dirty.state()));
    CHECK(w_dirty.rejected() == injected);
    CHECK(r_dirty.rejected() == injected);
    CHECK(c_dirty.rejected() == injected);
    CHECK(e_dirty.rejected() == injected);
    CHECK(v_dirty.rejected() == injected);
    CHECK(m_dirty.rejected() == injected);
    CHECK(w_clean.rejected() == 0);
}

TEST_CASE("binary16 rounding: ties to even, subnormals, and overflow beyond 65504") {
    CHECK(round_to_half(1.0) == 1.0);
    CHECK(round_to_half(1.0 + 1.0 / 2048.0) == 1.0);                // tie -> even (1.0)
    CHECK(round_to_half(1.0 + 3.0 / 2048.0) == 1.0 + 2.0 / 1024.0);  // tie -> even (up)
    CHECK(round_to_half(0.1) == 0x1.998p-4);
    CHECK(round_to_half(half_subnormal_spacing * 0.75) == half_subnormal_spacing);
    CHECK(round_to_half(half_subnormal_spacing * 0.5) == 0.0);  // tie -> even (0)
    CHECK(round_to_half(65504.0) == 65504.0);
    CHECK(round_to_half(65519.0) == 65504.0);  // below the midpoint to 65536: rounds to the largest finite
    CHECK(std::isinf(round_to_half(65520.0)));
    CHECK(round_to_half(-1e6, half_overflow::saturate) == -65504.0);
}

TEMPLATE_TEST_CASE("a binary16 history that overflowed to Inf is refused on restore, never silently used", "",
                   float, double) {
    using T = TestType;
    // a 1e3 light switching off at eta 0.2: Cov = 0.8 * 0.2 * 1e6 = 1.6e5 > 65504
    emcv::emcm<T, 1> e(T(0.2));
    e.push(T(1000));
    e.push(T(0));
    const auto overflowed = round_state_to_half(e.state(), half_overflow::to_infinity);
    REQUIRE(std::isinf(overflowed.covariance[0]));
    CHECK_THROWS_AS((emcv::emcm<T, 1>(T(0.2), overflowed)), std::invalid_argument);
    CHECK_THROWS_AS((emcv::moving_stats<T>(T(0.2), overflowed)), std::invalid_argument);
    CHECK_THROWS_AS((emcv::running_covariance<T, 1>(overflowed)), std::invalid_argument);
    CHECK_THROWS_AS((emcv::weighted_covariance<T, 1>(overflowed)), std::invalid_argument);
    // a clamping store (min(v, 65504) in the shader) keeps a usable, finite, non-negative history
    const auto clamped = round_state_to_half(e.state(), half_overflow::saturate);
    emcv::emcm<T, 1> restored(T(0.2), clamped);
    CHECK(restored.variance(0) == T(65504));
    restored.push(T(0));
    CHECK(std::isfinite(restored.variance(0)));
    CHECK(restored.variance(0) >= T(0));
    // negative variance or negative total weight in a restored state are refused as well
    auto negative = e.state();
    negative.covariance[0] = T(-1);
    CHECK_THROWS_AS((emcv::emcm<T, 1>(T(0.2), negative)), std::invalid_argument);
    auto bad_weight = e.state();
    bad_weight.total_weight = T(-1);
    CHECK_THROWS_AS((emcv::weighted_covariance<T, 1>(bad_weight)), std::invalid_argument);
    auto nan_mean = e.state();
    nan_mean.mean[0] = std::numeric_limits<T>::quiet_NaN();
    CHECK_THROWS_AS((emcv::emcm<T, 1>(T(0.2), nan_mean)), std::invalid_argument);
}

TEMPLATE_TEST_CASE("a first sample whose square overflows seeds a zero covariance, not NaN", "", float, double) {
    using T = TestType;
    const T big = std::sqrt(std::numeric_limits<T>::max()) * T(4);  // big^2 overflows
    emcv::emcm<T, 2> e(T(0.05));
    e.push({big, -big});
    CHECK(e.covariance(0, 0) == T(0));
    CHECK(e.covariance(0, 1) == T(0));
    emcv::running_covariance<T, 1> r;
    r.push(big);
    CHECK(r.variance(0) == T(0));
    r.push(-big);  // the exact variance big^2 is beyond the range: saturates at max
    CHECK(r.variance(0) == std::numeric_limits<T>::max());
    CHECK(r.mean(0) == T(0));
}

TEMPLATE_TEST_CASE("a zero weight after a saturated covariance changes nothing (fuzz finding)", "", float, double) {
    // tests/fuzz found it: weights 1 for 0, 0, -max (covariance saturates at max), then a sample of weight 0
    // at 0.125. r = 0 / W = 0 met an outer product d^2 that overflowed to Inf: 0 * Inf = NaN was stored.
    const TestType big = std::numeric_limits<TestType>::max();
    emcv::weighted_covariance<TestType, 2> e;
    e.push({TestType(0), TestType(0)});
    e.push({TestType(0), TestType(0)});
    e.push({-big, big});
    const auto before = e.state();
    CHECK(e.push({TestType(0.125), TestType(-0.125)}, TestType(0), TestType(1)));
    CHECK(e.count() == before.count + 1);
    for (std::size_t k = 0; k < 3; ++k) CHECK(std::isfinite(e.state().covariance[k]));
    CHECK(same_bits(e.state(), [&] { auto s = before; s.count += 1; return s; }()));
    // a weight that underflows against W (r rounds to 0) is the same case
    CHECK(e.push({TestType(0.5), TestType(0.5)}, std::numeric_limits<TestType>::denorm_min(), TestType(1)));
    for (std::size_t k = 0; k < 3; ++k) CHECK(std::isfinite(e.state().covariance[k]));
}

TEMPLATE_TEST_CASE("weights near max saturate the total weight instead of overflowing it (fuzz finding)", "", float,
                   double) {
    const TestType big = std::numeric_limits<TestType>::max();
    emcv::weighted_covariance<TestType, 1> e;
    CHECK(e.push(TestType(1), big));
    CHECK(e.push(TestType(3), big));  // W = 2 max would be Inf
    CHECK(e.total_weight() == big);
    // r = max / max = 1: the newest sample takes over, everything finite
    CHECK(e.mean(0) == TestType(3));
    CHECK(std::isfinite(e.variance(0)));
    CHECK(emcv::weighted_covariance<TestType, 1>::valid_state(e.state()));
}

TEMPLATE_TEST_CASE("opposite signs near the top of the range: the mean stays finite and inside the data", "",
                   float, double) {
    using T = TestType;
    const T top = std::numeric_limits<T>::max();
    for (T eta : {T(1e-6), T(0.05), T(0.2), T(1)}) {
        emcv::emcm<T, 1> e(eta);
        emcv::ewma_covariance<T, 1> v(eta);
        for (int n = 0; n < 100; ++n) {
            const T x = n % 2 == 0 ? top : -top;
            e.push(x);
            v.push(x);
            CHECK(std::isfinite(e.mean(0)));
            CHECK(std::isfinite(v.mean(0)));
            CHECK(std::isfinite(e.variance(0)));
            CHECK(std::isfinite(v.variance(0)));
            CHECK(e.variance(0) >= T(0));
        }
    }
}

TEMPLATE_TEST_CASE("a mean update that rounds past max saturates instead of storing Inf (fuzz finding)", "", float,
                   double) {
    // eta = 1 from mu = 1e37 (float) / 1e307 (double) to x = max: mu + (x - mu) rounds above max
    using T = TestType;
    const T top = std::numeric_limits<T>::max();
    const T start = top / T(34);
    emcv::emcm<T, 1> plain(T(1));
    emcv::compensated_emcm<T, 1> compensated(T(1));
    emcv::running_covariance<T, 1> running;
    for (T x : {start, top}) {
        plain.push(x);
        compensated.push(x);
    }
    CHECK(plain.mean(0) == top);
    CHECK(compensated.mean(0) == top);
    CHECK(std::isfinite(compensated.state().mean_compensation[0]));
    for (T x : {-top, -top, -top}) running.push(x);
    CHECK(running.mean(0) == -top);
}

TEMPLATE_TEST_CASE("a compensated mean whose TwoSum overflows stays finite (fuzz finding)", "", float, double) {
    // eta = 1 from mu just above max / 4 to x = -max: x - mu clamps to -max and mu + r d is finite, but
    // TwoSum's own s - mu rounds past -max: its error, then the low part and the mean, were NaN
    using T = TestType;
    const T top = std::numeric_limits<T>::max();
    emcv::compensated_emcm<T, 1> e(T(1));
    for (T x : {top / T(4096) * T(1025), -top, T(0), T(1)}) {
        e.push(x);
        CHECK(std::isfinite(e.mean(0)));
        CHECK(std::isfinite(e.state().mean_compensation[0]));
        CHECK(e.variance(0) >= T(0));
    }
    CHECK(std::fabs(e.mean(0) - T(1)) <= top * std::numeric_limits<T>::epsilon());  // back near the samples
}

TEMPLATE_TEST_CASE("invalid eta, weight and decay are refused with std::invalid_argument", "", float, double) {
    using T = TestType;
    for (T eta : {T(0), T(-0.1), T(1.5), std::numeric_limits<T>::quiet_NaN()}) {
        CHECK_THROWS_AS((emcv::emcm<T, 1>(eta)), std::invalid_argument);
        CHECK_THROWS_AS((emcv::compensated_emcm<T, 1>(eta)), std::invalid_argument);
        CHECK_THROWS_AS((emcv::ewma_covariance<T, 1>(eta)), std::invalid_argument);
        CHECK_THROWS_AS((emcv::moving_stats<T>(eta)), std::invalid_argument);
    }
    emcv::weighted_covariance<T, 1> w;
    CHECK_THROWS_AS((w.push(T(1), T(-1))), std::invalid_argument);
    CHECK_THROWS_AS((w.push(T(1), -std::numeric_limits<T>::infinity())), std::invalid_argument);
    CHECK_FALSE(w.push(T(1), std::numeric_limits<T>::infinity()));  // rejected and counted, not thrown
    CHECK(w.rejected() == 1);
    CHECK_THROWS_AS((w.push(T(1), T(1), T(1.5))), std::invalid_argument);
    CHECK(w.count() == 0);
}

TEMPLATE_TEST_CASE("eta = 1 keeps only the newest sample: emcm variance exactly 0, ewma the squared step", "",
                   float, double) {
    using T = TestType;
    emcv::emcm<T, 1> e(T(1));
    emcv::ewma_covariance<T, 1> v(T(1));
    const T xs[] = {T(3), T(-1), T(1e4), T(0.5)};
    T previous = xs[0];
    e.push(xs[0]);
    v.push(xs[0]);
    for (std::size_t i = 1; i < 4; ++i) {
        e.push(xs[i]);
        v.push(xs[i]);
        CHECK(e.mean(0) == xs[i]);
        CHECK(e.variance(0) == T(0));
        CHECK(v.variance(0) == (xs[i] - previous) * (xs[i] - previous));
        previous = xs[i];
    }
}

TEMPLATE_TEST_CASE("cv_coefficient with var_g exactly 0, about 1e-30, subnormal or non-finite", "", float, double) {
    using T = TestType;
    CHECK(emcv::cv_coefficient(T(1), T(0)) == T(0));
    CHECK(emcv::cv_coefficient(T(0), T(0)) == T(0));
    CHECK(emcv::cv_coefficient(T(1), -T(0)) == T(0));
    CHECK(emcv::cv_coefficient(T(1), std::numeric_limits<T>::denorm_min()) == T(0));
    CHECK(emcv::cv_coefficient(T(1), std::numeric_limits<T>::quiet_NaN()) == T(0));
    CHECK(emcv::cv_coefficient(std::numeric_limits<T>::infinity(), T(1)) == T(0));
    // 1e-30 is a normal number in both precisions: the quotient is used when it is finite...
    const T tiny = T(1e-30);
    const T alpha = emcv::cv_coefficient(T(0.5) * tiny, tiny);
    CHECK(alpha == T(0.5));
    // ...and refused (0) when it overflows
    CHECK(emcv::cv_coefficient(std::numeric_limits<T>::max(), tiny) == T(0));
    // a relative floor turns a variance that is negligible next to the control's scale into "no CV"
    CHECK(emcv::cv_coefficient(T(1e-31), tiny, emcv::variance_floor(T(1), T(1e-6))) == T(0));
}

TEMPLATE_TEST_CASE("sample_count on hard variances stays inside [n_min, n_max]", "", float, double) {
    using T = TestType;
    const T values[] = {T(0), std::numeric_limits<T>::denorm_min(), T(1e-30), T(1), std::numeric_limits<T>::max(),
                        std::numeric_limits<T>::infinity(), std::numeric_limits<T>::quiet_NaN()};
    for (T v : values) {
        const int n = emcv::sample_count(v, T(1e-3), 1, 64);
        CHECK(n >= 1);
        CHECK(n <= 64);
    }
    CHECK(emcv::sample_count(std::numeric_limits<T>::quiet_NaN(), T(1), 0, 16) == 16);
    CHECK(emcv::sample_count(std::numeric_limits<T>::infinity(), T(1), 0, 16) == 16);
    CHECK(emcv::sample_count(T(0), T(1), 0, 16) == 0);
}

TEMPLATE_TEST_CASE("raw moments E[x^2] - E[x]^2 break on a large offset where the recurrence meets its bound", "",
                   float, double) {
    using T = TestType;
    const double offset = sizeof(T) == sizeof(float) ? 1e4 : 1e9;
    const auto s = offset_stream<T>(offset, 0.1, 3000, 77);
    const T eta = T(0.05);
    emcv::emcm<T, 2> ours(eta);
    raw_moments<T> raw;
    schedule sch;
    sch.kind = schedule_kind::exponential;
    sch.eta = static_cast<ld>(eta);
    reference_with_bound<2> ref(sch, model_of<T>(false, false, false), long_double_model());
    bool raw_negative = false;
    ld raw_worst = 0, ours_worst_ratio = 0;
    for (std::size_t n = 0; n < s.x.size(); ++n) {
        ours.push(s.x[n]);
        raw.push(s.x[n][0], s.x[n][1], n == 0 ? T(1) : eta);
        ref.push({static_cast<ld>(s.x[n][0]), static_cast<ld>(s.x[n][1])});
        if (n < 100) continue;  // past the transient
        raw_negative = raw_negative || raw.variance_x() < T(0);
        const ld exact = ref.cov(0);
        raw_worst = std::max(raw_worst, std::fabs(static_cast<ld>(raw.variance_x()) - exact) / exact);
        ours_worst_ratio = std::max(ours_worst_ratio, std::fabs(static_cast<ld>(ours.variance(0)) - exact) / ref.cov_bound(0));
    }
    CHECK(ours_worst_ratio <= 1);
    // the raw form loses every digit: relative error above 100% and negative variances
    CHECK(raw_worst > 1);
    CHECK(raw_negative);
}

TEMPLATE_TEST_CASE("moving_stats_update on a structure-of-arrays history is moving_stats, bit for bit", "", float,
                   double) {
    using T = TestType;
    const T eta = T(0.05);
    const std::size_t pixels = 37;  // not a multiple of any vector width
    const auto s = offset_stream<T>(1e3, 1.0, 60, 9);
    std::vector<T> mean(pixels), variance(pixels, T(0)), mean_low(pixels, T(0)), variance_low(pixels, T(0));
    std::vector<T> c_mean(pixels), c_variance(pixels, T(0));
    std::vector<emcv::moving_stats<T>> reference(pixels, emcv::moving_stats<T>(eta));
    std::vector<emcv::compensated_emcm<T, 1>> compensated(pixels, emcv::compensated_emcm<T, 1>(eta));
    std::vector<T> frame(pixels);
    std::uint64_t expected_rejections = 0;
    for (std::size_t t = 0; t < s.x.size(); ++t) {
        for (std::size_t p = 0; p < pixels; ++p) {
            frame[p] = s.x[(t + p) % s.x.size()][p % 2] + static_cast<T>(p);
            if (t > 0 && (t * 31 + p) % 11 == 0) frame[p] = std::numeric_limits<T>::quiet_NaN();
        }
        if (t == 0) {  // the caller seeds the first sample: mean = x, variance = 0
            for (std::size_t p = 0; p < pixels; ++p) {
                mean[p] = c_mean[p] = frame[p];
                reference[p].push(frame[p]);
                compensated[p].push(frame[p]);
            }
            continue;
        }
        std::uint64_t rejected_now = 0;
        for (std::size_t p = 0; p < pixels; ++p) {
            rejected_now += reference[p].push(frame[p]) ? 0u : 1u;
            compensated[p].push(frame[p]);
        }
        expected_rejections += rejected_now;
        CHECK(emcv::moving_stats_update(mean.data(), static_cast<T*>(nullptr), variance.data(), static_cast<T*>(nullptr),
                                        frame.data(), pixels, eta)
                  .rejected == rejected_now);
        CHECK(emcv::moving_stats_update(c_mean.data(), mean_low.data(), c_variance.data(), variance_low.data(),
                                        frame.data(), pixels, eta)
                  .rejected == rejected_now);
        for (std::size_t p = 0; p < pixels; ++p) {
            T m = reference[p].mean(), v = reference[p].variance();
            CHECK(std::memcmp(&m, &mean[p], sizeof m) == 0);
            CHECK(std::memcmp(&v, &variance[p], sizeof v) == 0);
            const auto& cs = compensated[p].state();
            CHECK(cs.mean[0] == c_mean[p]);
            CHECK(cs.mean_compensation[0] == mean_low[p]);
            CHECK(cs.covariance[0] == c_variance[p]);
            CHECK(cs.covariance_compensation[0] == variance_low[p]);
        }
    }
    CHECK(expected_rejections > 0);
    // scalar forms agree with the array form
    T m = T(1), v = T(0), ml = T(0), vl = T(0);
    CHECK_FALSE(emcv::moving_stats_update(m, v, std::numeric_limits<T>::infinity(), eta));
    CHECK(emcv::moving_stats_update(m, v, T(3), eta));
    CHECK(emcv::moving_stats_update(m, ml, v, vl, T(3), eta));
    CHECK_THROWS_AS((emcv::moving_stats_update(m, v, T(3), T(0))), std::invalid_argument);
    CHECK_THROWS_AS((emcv::moving_stats_update(mean.data(), mean_low.data(), variance.data(), static_cast<T*>(nullptr),
                                               frame.data(), pixels, eta)),
                    std::invalid_argument);
}

TEMPLATE_TEST_CASE("scalar moving_stats_update forms equal emcm<T, 1> and compensated_emcm<T, 1> after every call",
                   "", float, double) {
    // The scalar forms share no code path with the classes' push (push_normalised); compare every stored part bit
    // for bit, including the low parts, so that a different comoment form or a dropped low part is caught.
    using T = TestType;
    const T eta = T(0.05);
    const auto s = offset_stream<T>(sizeof(T) == sizeof(float) ? 1e4 : 1e9, 0.1, 300, 21);
    emcv::emcm<T, 1> plain(eta);
    emcv::compensated_emcm<T, 1> compensated(eta);
    T m = s.x[0][0], v = T(0), cm = s.x[0][0], cml = T(0), cv = T(0), cvl = T(0);  // the caller seeds
    plain.push(s.x[0][0]);
    compensated.push(s.x[0][0]);
    bool low_parts_used = false;
    for (std::size_t n = 1; n < s.x.size(); ++n) {
        const T x = n % 13 == 5 ? std::numeric_limits<T>::quiet_NaN() : s.x[n][0];
        const bool accepted = plain.push(x);
        CHECK(compensated.push(x) == accepted);
        CHECK(emcv::moving_stats_update(m, v, x, eta) == accepted);
        CHECK(emcv::moving_stats_update(cm, cml, cv, cvl, x, eta) == accepted);
        const auto& p = plain.state();
        const auto& c = compensated.state();
        INFO("step " << n);
        CHECK(std::memcmp(&p.mean[0], &m, sizeof m) == 0);
        CHECK(std::memcmp(&p.covariance[0], &v, sizeof v) == 0);
        CHECK(std::memcmp(&c.mean[0], &cm, sizeof cm) == 0);
        CHECK(std::memcmp(&c.mean_compensation[0], &cml, sizeof cml) == 0);
        CHECK(std::memcmp(&c.covariance[0], &cv, sizeof cv) == 0);
        CHECK(std::memcmp(&c.covariance_compensation[0], &cvl, sizeof cvl) == 0);
        low_parts_used = low_parts_used || (cml != T(0) && cvl != T(0));
    }
    CHECK(low_parts_used);  // the offset stream exercises both low parts
    CHECK(plain.rejected() > 0);
}

TEMPLATE_TEST_CASE("a restored state with a non-finite low part is refused", "", float, double) {
    using T = TestType;
    emcv::compensated_emcm<T, 1> e(T(0.2));
    for (T x : {T(1e4), T(1e4 + 0.25), T(1e4 - 0.5)}) e.push(x);
    REQUIRE_NOTHROW((emcv::compensated_emcm<T, 1>(T(0.2), e.state())));
    for (T bad : {std::numeric_limits<T>::quiet_NaN(), std::numeric_limits<T>::infinity()}) {
        auto low_cov = e.state();
        low_cov.covariance_compensation[0] = bad;
        CHECK_THROWS_AS((emcv::compensated_emcm<T, 1>(T(0.2), low_cov)), std::invalid_argument);
        CHECK_FALSE(emcv::weighted_covariance<T, 1>::valid_state(low_cov));
        auto low_mean = e.state();
        low_mean.mean_compensation[0] = bad;
        CHECK_THROWS_AS((emcv::compensated_emcm<T, 1>(T(0.2), low_mean)), std::invalid_argument);
    }
}

TEMPLATE_TEST_CASE("moving_stats_update reseeds and counts an invalid stored pixel, keeps it without a finite value",
                   "", float, double) {
    // A half-float history whose variance overflowed to Inf, a NaN that got into the state, a negative variance
    // (a lossy store): each would stay poisoned for ever (Inf becomes NaN at the next step, and sample_count
    // maps NaN to n_max). A finite frame value reseeds such a pixel as a first sample and counts it.
    using T = TestType;
    const T inf = std::numeric_limits<T>::infinity(), nan = std::numeric_limits<T>::quiet_NaN();
    const T eta = T(0.25);
    for (const bool compensated : {false, true}) {
        //                pixel:  0 valid  1 Inf var   2 NaN mean  3 neg. var  4 Inf mean, NaN frame  5 valid, NaN frame
        std::vector<T> mean{T(1), T(2), nan, T(4), inf, T(6)};
        std::vector<T> variance{T(0.5), inf, T(1), T(-1), T(1), T(0.5)};
        std::vector<T> mean_low(6, T(0)), variance_low(6, T(0));
        const std::vector<T> frame{T(3), T(10), T(20), T(30), nan, nan};
        T* ml = compensated ? mean_low.data() : nullptr;
        T* vl = compensated ? variance_low.data() : nullptr;
        INFO("compensated " << compensated);
        const auto counts = emcv::moving_stats_update(mean.data(), ml, variance.data(), vl, frame.data(), 6, eta);
        CHECK(counts.rejected == 2);
        CHECK(counts.reseeded == 3);
        // pixel 0: the ordinary step, mean 1 + 0.25 * 2 = 1.5, variance 0.75 (0.5 + 0.25 * 4) = 1.125
        CHECK(mean[0] == T(1.5));
        CHECK(variance[0] == T(1.125));
        for (std::size_t p = 1; p <= 3; ++p) {  // reseeded: mean = x, variance 0
            CHECK(mean[p] == frame[p]);
            CHECK(variance[p] == T(0));
        }
        CHECK(std::isinf(mean[4]));  // invalid and no finite value: its stored bits stay, counted as rejected
        CHECK(variance[4] == T(1));
        CHECK(mean[5] == T(6));  // valid and rejected: untouched
        CHECK(variance[5] == T(0.5));
        // the next finite value reseeds pixel 4 as well
        const std::vector<T> next{T(3), T(10), T(20), T(30), T(40), T(6)};
        const auto again = emcv::moving_stats_update(mean.data(), ml, variance.data(), vl, next.data(), 6, eta);
        CHECK(again.rejected == 0);
        CHECK(again.reseeded == 1);
        CHECK(mean[4] == T(40));
        CHECK(variance[4] == T(0));
    }
    // a non-finite low part makes the compensated pixel invalid too
    T m = T(1), ml = nan, v = T(1), vl = T(0);
    CHECK(emcv::moving_stats_update(m, ml, v, vl, T(5), eta));
    CHECK(m == T(5));
    CHECK(ml == T(0));
    CHECK(v == T(0));
    // the scalar plain form follows the same rule
    T pm = T(2), pv = inf;
    CHECK(emcv::moving_stats_update(pm, pv, T(7), eta));
    CHECK(pm == T(7));
    CHECK(pv == T(0));
}

TEMPLATE_TEST_CASE("one-stream range clamps (behind branches) equal the vectorisable selects bit for bit at the "
                   "top of the range", "", float, double) {
    // emcm's push evaluates the overflow clamps of x - mu and of the covariance behind predicted branches
    // (detail::range_check::branch); the per-pixel batch evaluates them as selects. Both must store the same
    // bits, above all where the clamps act: opposite signs near max (x - mu overflows) and squares beyond max.
    using T = TestType;
    const T top = std::numeric_limits<T>::max();
    const T eta = T(0.25);
    std::vector<std::array<T, 2>> xs;
    std::uint64_t z = 12345;
    for (int n = 0; n < 400; ++n) {
        z = z * 6364136223846793005ull + 1442695040888963407ull;
        const T u = static_cast<T>(static_cast<double>(z >> 11) * 0x1p-53);  // [0, 1)
        const T big = n % 3 == 0 ? top * (T(0.5) + u / 2) : std::sqrt(top) * T(8) * u;
        xs.push_back({n % 2 == 0 ? big : -big, n % 5 == 0 ? -big : T(1) + u});
    }
    for (const bool compensated : {false, true}) {
        INFO("compensated " << compensated);
        emcv::emcm<T, 2> plain(eta);
        emcv::compensated_emcm<T, 2> comp(eta);
        std::array<T, 2> mean = xs[0], mean_low{};
        std::array<T, 3> cov{}, cov_low{};
        compensated ? (void)comp.push(xs[0]) : (void)plain.push(xs[0]);
        bool clamped = false;
        for (std::size_t n = 1; n < xs.size(); ++n) {
            if (compensated) {
                comp.push(xs[n]);
                emcv::detail::comoment_step<emcv::mean_accuracy::compensated, 2, emcv::detail::range_check::select>(
                    mean.data(), mean_low.data(), cov.data(), cov_low.data(), xs[n].data(), eta,
                    emcv::comoment_form::current_mean);
            } else {
                plain.push(xs[n]);
                emcv::detail::comoment_step<emcv::mean_accuracy::plain, 2, emcv::detail::range_check::select>(
                    mean.data(), static_cast<T*>(nullptr), cov.data(), static_cast<T*>(nullptr), xs[n].data(), eta,
                    emcv::comoment_form::current_mean);
            }
            const auto& s = compensated ? comp.state() : plain.state();
            INFO("step " << n);
            REQUIRE(std::memcmp(s.mean.data(), mean.data(), sizeof mean) == 0);
            REQUIRE(std::memcmp(s.covariance.data(), cov.data(), sizeof cov) == 0);
            if (compensated) {
                REQUIRE(std::memcmp(s.mean_compensation.data(), mean_low.data(), sizeof mean_low) == 0);
                REQUIRE(std::memcmp(s.covariance_compensation.data(), cov_low.data(), sizeof cov_low) == 0);
            }
            clamped = clamped || cov[0] == top || cov[1] == -top || cov[1] == top;
        }
        CHECK(clamped);  // the stream does reach the saturation
    }
}
