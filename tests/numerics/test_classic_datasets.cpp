// SPDX-License-Identifier: MIT
// The classic accuracy datasets of the statistics literature, built from their published description
// (NIST StRD univariate "lower/average/higher difficulty" NumAcc1-4: a large constant plus a small
// alternating part) and checked against mean and variance of the binary inputs computed exactly in
// integer (rational) arithmetic (docs/numerics.md section 3.2).
#include <catch2/catch_template_test_macros.hpp>
#include <catch2/catch_test_macros.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "numerics_support.hpp"

using namespace emcv_numerics;

namespace {

__extension__ typedef __int128 int128;

struct dataset {
    std::string name;
    std::vector<double> values;  // decimal description; rounded to T when used
};

/// NumAcc1: 10000001, 10000003, 10000002. NumAcc2..4: c, then (c - 0.1, c + 0.1) 500 times (n = 1001),
/// with c = 1.2, 1000000.2 and 10000000.2.
std::vector<dataset> classic_datasets() {
    std::vector<dataset> out;
    out.push_back({"NumAcc1", {10000001.0, 10000003.0, 10000002.0}});
    const double centres[] = {1.2, 1000000.2, 10000000.2};
    const char* names[] = {"NumAcc2", "NumAcc3", "NumAcc4"};
    for (int k = 0; k < 3; ++k) {
        dataset d{names[k], {centres[k]}};
        for (int i = 0; i < 500; ++i) {
            d.values.push_back(centres[k] - 0.1);
            d.values.push_back(centres[k] + 0.1);
        }
        out.push_back(d);
    }
    return out;
}

/// Exact population mean and variance of the binary values x_i: each is k_i 2^-p with integer k_i (p from
/// the smallest exponent), so n^2 var 2^{2p} = n S2 - S1^2 exactly in 128-bit integers. Converting the two
/// integers to long double costs one rounding each (relative 2^-64).
template <class T>
void exact_moments(const std::vector<T>& xs, ld& mean, ld& variance) {
    int min_exponent = 1 << 20;
    for (T x : xs) {
        if (x == T(0)) continue;
        int e = 0;
        std::frexp(x, &e);
        min_exponent = std::min(min_exponent, e - std::numeric_limits<T>::digits);
    }
    int128 s1 = 0, s2 = 0;
    for (T x : xs) {
        const long long k = static_cast<long long>(std::ldexp(static_cast<ld>(x), -min_exponent));  // exact
        s1 += k;
        s2 += static_cast<int128>(k) * k;
    }
    const int128 n = static_cast<int128>(xs.size());
    const int128 numerator = n * s2 - s1 * s1;
    mean = std::ldexp(static_cast<ld>(s1), min_exponent) / static_cast<ld>(xs.size());
    variance = std::ldexp(static_cast<ld>(numerator), 2 * min_exponent) / static_cast<ld>(xs.size() * xs.size());
}

/// Log relative error (number of correct significant digits), as the StRD reports it.
ld correct_digits(ld computed, ld exact) {
    if (computed == exact) return 99;
    return -std::log10(std::fabs(computed - exact) / std::fabs(exact));
}

}  // namespace

TEMPLATE_TEST_CASE("NIST StRD NumAcc1-4: running and compensated running covariance meet the derived bound", "",
                   float, double) {
    using T = TestType;
    for (const dataset& d : classic_datasets()) {
        std::vector<T> xs;
        for (double v : d.values) xs.push_back(static_cast<T>(v));
        ld exact_mean = 0, exact_variance = 0;
        exact_moments(xs, exact_mean, exact_variance);
        if (exact_variance == 0) {  // NumAcc4 in float: every value rounds to 10000000 (ulp 1): a constant
            emcv::running_covariance<T, 1> plain;
            emcv::compensated_running_covariance<T, 1> comp;
            for (T x : xs) {
                plain.push(x);
                comp.push(x);
            }
            CHECK(plain.variance(0) == T(0));
            CHECK(comp.variance(0) == T(0));
            continue;
        }

        schedule sch;  // cumulative, r = 1/n
        reference_with_bound<1> plain_bound(sch, model_of<T>(false, false, true), long_double_model());
        reference_with_bound<1> comp_bound(sch, model_of<T>(false, true, true), long_double_model());
        emcv::running_covariance<T, 1> plain;
        emcv::compensated_running_covariance<T, 1> comp;
        for (T x : xs) {
            plain.push(x);
            comp.push(x);
            plain_bound.push({static_cast<ld>(x)});
            comp_bound.push({static_cast<ld>(x)});
        }
        // the long-double recurrence agrees with the exact rational result to within its own bound
        const ld reference_slack = 4 * unit_roundoff<ld>() * exact_variance;
        CHECK(std::fabs(plain_bound.cov(0) - exact_variance) <= plain_bound.cov_bound(0) + reference_slack);

        INFO(d.name << " in " << (sizeof(T) == 4 ? "float" : "double") << ": plain digits "
                    << static_cast<double>(correct_digits(static_cast<ld>(plain.variance(0)), exact_variance))
                    << ", compensated digits "
                    << static_cast<double>(correct_digits(static_cast<ld>(comp.variance(0)), exact_variance)));
        CHECK(std::fabs(static_cast<ld>(plain.variance(0)) - exact_variance) <= plain_bound.cov_bound(0) + reference_slack);
        CHECK(std::fabs(static_cast<ld>(comp.variance(0)) - exact_variance) <= comp_bound.cov_bound(0) + reference_slack);
        CHECK(std::fabs(static_cast<ld>(plain.mean(0)) - exact_mean) <= plain_bound.mean_bound(0) + unit_roundoff<ld>() * exact_mean);
        CHECK(plain.variance(0) >= T(0));
        // the certified values describe the decimal data; in double the binary inputs are within 1e-9 of them
        if (sizeof(T) == sizeof(double)) {
            const double certified_sd = d.name == "NumAcc1" ? 1.0 : 0.1;
            const double n = static_cast<double>(xs.size());
            const double sample_sd = std::sqrt(static_cast<double>(exact_variance) * n / (n - 1));
            CHECK(std::fabs(sample_sd - certified_sd) < 1e-6 * certified_sd);
            // compensated double keeps at least 9 of the certified digits on every StRD dataset
            CHECK(correct_digits(static_cast<ld>(comp.variance(0)), exact_variance) >= 9);
        }
    }
}
