// SPDX-License-Identifier: MIT
// 3x3 covariance matrices stay positive semi-definite (docs/numerics.md, Eq. B5): the exact matrix C is PSD,
// and |C^_ij - C_ij| <= B_ij gives lambda_min(C^) >= -||B||_F, i.e. C^ + ||B||_F I has a Cholesky factor.
// Streams include a rank-deficient one (z = x - y), where the exact smallest eigenvalue is 0.
#include <catch2/catch_template_test_macros.hpp>
#include <catch2/catch_test_macros.hpp>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "numerics_support.hpp"

using namespace emcv_numerics;

namespace {

using matrix3 = std::array<std::array<ld, 3>, 3>;

/// True when the symmetric m has a Cholesky factor (every pivot > 0), i.e. m is positive definite.
bool cholesky_succeeds(matrix3 m) {
    for (std::size_t j = 0; j < 3; ++j) {
        ld pivot = m[j][j];
        for (std::size_t k = 0; k < j; ++k) pivot -= m[j][k] * m[j][k];
        if (!(pivot > 0)) return false;
        const ld l = std::sqrt(pivot);
        m[j][j] = l;
        for (std::size_t i = j + 1; i < 3; ++i) {
            ld s = m[i][j];
            for (std::size_t k = 0; k < j; ++k) s -= m[i][k] * m[j][k];
            m[i][j] = s / l;
        }
    }
    return true;
}

template <class T>
std::vector<std::array<T, 3>> stream3(double offset, double spread, bool rank_deficient, std::size_t n,
                                      std::uint64_t seed) {
    uniform_source u(seed);
    std::vector<std::array<T, 3>> out;
    for (std::size_t i = 0; i < n; ++i) {
        const double a = u.next(), b = u.next(), c = u.next();
        const T x = static_cast<T>(offset + spread * a);
        const T y = static_cast<T>(0.5 * offset + spread * (0.8 * a + 0.6 * b));
        const T z = rank_deficient ? static_cast<T>(x - y) : static_cast<T>(-offset + spread * (0.3 * a - 0.4 * b + c));
        out.push_back({x, y, z});
    }
    return out;
}

/// Pushes the stream through E and the reference; returns the first failure ("" when none).
template <class T, class E, class Push>
std::string check_psd(E e, Push push, schedule sch, bool compensated, const std::vector<std::array<T, 3>>& xs) {
    reference_with_bound<3> ref(sch, model_of<T>(false, compensated, sch.kind == schedule_kind::cumulative),
                                long_double_model());
    for (std::size_t n = 0; n < xs.size(); ++n) {
        push(e, xs[n]);
        ref.push({static_cast<ld>(xs[n][0]), static_cast<ld>(xs[n][1]), static_cast<ld>(xs[n][2])});
        matrix3 c{};
        ld frobenius = 0;
        std::size_t k = 0;
        for (std::size_t i = 0; i < 3; ++i) {
            for (std::size_t j = i; j < 3; ++j, ++k) {
                const ld v = static_cast<ld>(e.covariance(i, j));
                const ld read_out = compensated ? unit_roundoff<T>() * std::fabs(v) : 0;  // mean() / covariance() rounding
                const ld b = ref.cov_bound(k) + read_out;
                if (!std::isfinite(v)) return "step " + std::to_string(n) + ": covariance not finite";
                if (std::fabs(v - ref.cov(k)) > b) return "step " + std::to_string(n) + ": entry above its bound";
                c[i][j] = c[j][i] = v;
                frobenius += (i == j ? 1 : 2) * b * b;
            }
            if (c[i][i] < 0) return "step " + std::to_string(n) + ": negative variance";
        }
        frobenius = std::sqrt(frobenius);
        // B5: C^ + ||B||_F I must be positive definite (a tiny relative slack covers the long-double
        // Cholesky's own rounding, 2^-64 against entries of size |C|)
        ld scale = 0;
        for (const auto& row : c)
            for (ld v : row) scale = std::max(scale, std::fabs(v));
        for (std::size_t i = 0; i < 3; ++i) c[i][i] += frobenius + 64 * unit_roundoff<ld>() * scale;
        if (scale > 0 && !cholesky_succeeds(c)) {
            std::ostringstream os;
            os << "step " << n << ": not positive semi-definite within the bound (||B||_F = "
               << static_cast<double>(frobenius) << ")";
            return os.str();
        }
    }
    return "";
}

}  // namespace

TEMPLATE_TEST_CASE("3x3 covariance matrices stay positive semi-definite within the derived bound", "", float,
                   double) {
    using T = TestType;
    using vec = std::array<T, 3>;
    const bool is_float = sizeof(T) == sizeof(float);
    const std::size_t n = 2000;
    struct family {
        const char* name;
        double offset, spread;
        bool rank_deficient;
    };
    const family families[] = {{"correlated, offset 0", 0.0, 1.0, false},
                               {"correlated, large offset", is_float ? 1e4 : 1e9, 0.1, false},
                               {"rank deficient z = x - y", 0.0, 1.0, true},
                               {"rank deficient, offset", is_float ? 1e3 : 1e6, 1.0, true}};
    std::uint64_t seed = 500;
    for (const family& f : families) {
        const auto xs = stream3<T>(f.offset, f.spread, f.rank_deficient, n, ++seed);
        schedule cumulative;
        schedule weighted;
        weighted.kind = schedule_kind::weighted;
        weighted.decay = static_cast<ld>(T(0.9));
        for (T eta : {T(0.05), T(0.2)}) {
            schedule ex;
            ex.kind = schedule_kind::exponential;
            ex.eta = static_cast<ld>(eta);
            schedule ew = ex;
            ew.form = emcv::comoment_form::previous_mean;
            INFO(f.name << ", eta " << static_cast<double>(eta));
            CHECK(check_psd<T>(emcv::emcm<T, 3>(eta), [](auto& e, const vec& x) { e.push(x); }, ex, false, xs) == "");
            CHECK(check_psd<T>(emcv::compensated_emcm<T, 3>(eta), [](auto& e, const vec& x) { e.push(x); }, ex, true, xs) ==
                  "");
            CHECK(check_psd<T>(emcv::ewma_covariance<T, 3>(eta), [](auto& e, const vec& x) { e.push(x); }, ew, false, xs) ==
                  "");
        }
        INFO(f.name);
        CHECK(check_psd<T>(emcv::running_covariance<T, 3>(), [](auto& e, const vec& x) { e.push(x); }, cumulative, false,
                           xs) == "");
        CHECK(check_psd<T>(emcv::compensated_running_covariance<T, 3>(), [](auto& e, const vec& x) { e.push(x); },
                           cumulative, true, xs) == "");
        CHECK(check_psd<T>(emcv::weighted_covariance<T, 3>(), [](auto& e, const vec& x) { e.push(x, T(1), T(0.9)); },
                           weighted, false, xs) == "");
    }
}
