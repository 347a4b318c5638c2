// SPDX-License-Identifier: MIT
// emcv/testing/distributions.hpp — the special functions the statistical checks need, standard library only:
// normal CDF and quantile, regularised incomplete gamma Q(a, x) (chi-square tail), regularised incomplete beta
// (Student t tail) and the trigamma function (variance of log chi-square).
// Series and continued fractions as in Numerical Recipes 3rd ed. 6.2 and 6.4 (Lentz's method), to ~1e-14.
#pragma once

#include <cmath>
#include <limits>
#include <stdexcept>

namespace emcv::testing {

/// Phi(x), the standard normal CDF.
inline double normal_cdf(double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); }

/// Phi^-1(p) for p in (0, 1), by bisection on erfc (exact to double rounding; speed is not a concern here).
inline double normal_quantile(double p) {
    if (!(p > 0.0 && p < 1.0)) throw std::invalid_argument("emcv::testing::normal_quantile: p must lie in (0, 1)");
    double lo = -40.0, hi = 40.0;
    for (int i = 0; i < 200 && hi - lo > 0.0; ++i) {
        const double mid = 0.5 * (lo + hi);
        if (mid == lo || mid == hi) break;
        (normal_cdf(mid) < p ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

/// Q(a, x) = Gamma(a, x) / Gamma(a), the upper regularised incomplete gamma function, a > 0, x >= 0.
/// The chi-square survival function with k degrees of freedom is Q(k / 2, chi2 / 2).
inline double regularized_gamma_q(double a, double x) {
    if (!(a > 0.0) || !(x >= 0.0)) throw std::invalid_argument("emcv::testing::regularized_gamma_q: needs a > 0, x >= 0");
    if (x == 0.0) return 1.0;
    if (std::isinf(x)) return 0.0;
    const double log_prefactor = -x + a * std::log(x) - std::lgamma(a);
    constexpr double eps = 1e-15;
    if (x < a + 1.0) {  // series for P(a, x) (NR 6.2.5)
        double ap = a, term = 1.0 / a, sum = term;
        for (int n = 0; n < 10000; ++n) {
            ap += 1.0;
            term *= x / ap;
            sum += term;
            if (std::fabs(term) < std::fabs(sum) * eps) break;
        }
        return 1.0 - sum * std::exp(log_prefactor);
    }
    // continued fraction for Q(a, x) (NR 6.2.7), modified Lentz
    constexpr double tiny = 1e-300;
    double b = x + 1.0 - a, c = 1.0 / tiny, d = 1.0 / b, h = d;
    for (int i = 1; i < 10000; ++i) {
        const double an = -i * (i - a);
        b += 2.0;
        d = an * d + b;
        if (std::fabs(d) < tiny) d = tiny;
        c = b + an / c;
        if (std::fabs(c) < tiny) c = tiny;
        d = 1.0 / d;
        const double delta = d * c;
        h *= delta;
        if (std::fabs(delta - 1.0) < eps) break;
    }
    return std::exp(log_prefactor) * h;
}

/// Survival function of the chi-square distribution with `dof` degrees of freedom.
inline double chi2_survival(double chi2, double dof) { return regularized_gamma_q(0.5 * dof, 0.5 * chi2); }

namespace detail {
/// Continued fraction of the incomplete beta function (NR 6.4.5), modified Lentz.
inline double beta_continued_fraction(double a, double b, double x) {
    constexpr double tiny = 1e-300, eps = 1e-15;
    const double qab = a + b, qap = a + 1.0, qam = a - 1.0;
    double c = 1.0, d = 1.0 - qab * x / qap;
    if (std::fabs(d) < tiny) d = tiny;
    d = 1.0 / d;
    double h = d;
    for (int m = 1; m < 10000; ++m) {
        const double m2 = 2.0 * m;
        double aa = m * (b - m) * x / ((qam + m2) * (a + m2));
        d = 1.0 + aa * d;
        if (std::fabs(d) < tiny) d = tiny;
        c = 1.0 + aa / c;
        if (std::fabs(c) < tiny) c = tiny;
        d = 1.0 / d;
        h *= d * c;
        aa = -(a + m) * (qab + m) * x / ((a + m2) * (qap + m2));
        d = 1.0 + aa * d;
        if (std::fabs(d) < tiny) d = tiny;
        c = 1.0 + aa / c;
        if (std::fabs(c) < tiny) c = tiny;
        d = 1.0 / d;
        const double delta = d * c;
        h *= delta;
        if (std::fabs(delta - 1.0) < eps) break;
    }
    return h;
}
}  // namespace detail

/// I_x(a, b), the regularised incomplete beta function, a, b > 0, x in [0, 1].
inline double regularized_beta(double a, double b, double x) {
    if (!(a > 0.0 && b > 0.0) || !(x >= 0.0 && x <= 1.0))
        throw std::invalid_argument("emcv::testing::regularized_beta: needs a, b > 0 and x in [0, 1]");
    if (x == 0.0 || x == 1.0) return x;
    const double log_front = std::lgamma(a + b) - std::lgamma(a) - std::lgamma(b) + a * std::log(x) + b * std::log1p(-x);
    if (x < (a + 1.0) / (a + b + 2.0)) return std::exp(log_front) * detail::beta_continued_fraction(a, b, x) / a;
    return 1.0 - std::exp(log_front) * detail::beta_continued_fraction(b, a, 1.0 - x) / b;
}

/// P(|T| >= |t|) for Student's t with `dof` > 0 degrees of freedom: I_{dof / (dof + t^2)}(dof / 2, 1 / 2).
inline double student_t_two_sided_p(double t, double dof) {
    if (std::isinf(t)) return 0.0;
    return regularized_beta(0.5 * dof, 0.5, dof / (dof + t * t));
}

/// psi_1(x) = d^2/dx^2 ln Gamma(x), x > 0: recurrence up to x >= 12, then the asymptotic series (A&S 6.4.12).
/// Var[ln X] = psi_1(k / 2) for X ~ chi-square(k).
inline double trigamma(double x) {
    if (!(x > 0.0)) throw std::invalid_argument("emcv::testing::trigamma: x must be positive");
    double sum = 0.0;
    while (x < 12.0) {
        sum += 1.0 / (x * x);
        x += 1.0;
    }
    const double r = 1.0 / x, r2 = r * r;
    return sum + r + 0.5 * r2 +
           r * r2 * (1.0 / 6.0 - r2 * (1.0 / 30.0 - r2 * (1.0 / 42.0 - r2 * (1.0 / 30.0 - r2 * 5.0 / 66.0))));
}

}  // namespace emcv::testing
