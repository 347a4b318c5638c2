// The special functions behind emcv/testing against tabulated values (Abramowitz & Stegun 26.2, 26.4, 26.7;
// 6.4.2 for trigamma) and closed forms.
#include <emcv/testing/distributions.hpp>
#include <emcv/testing/result.hpp>

#include <catch2/catch_test_macros.hpp>

#include <cmath>
#include <stdexcept>

namespace et = emcv::testing;

namespace {
bool close(double a, double b, double rel) { return std::fabs(a - b) <= rel * std::fabs(b); }
constexpr double pi = 3.14159265358979323846;
}  // namespace

TEST_CASE("normal CDF and quantile") {
    CHECK(close(et::normal_cdf(1.959963984540054), 0.975, 1e-14));
    CHECK(close(et::normal_cdf(-3.090232306167813), 0.001, 1e-12));
    CHECK(close(et::normal_quantile(0.975), 1.959963984540054, 1e-14));
    CHECK(close(et::normal_quantile(0.005), -2.5758293035489004, 1e-14));
    CHECK_THROWS_AS(et::normal_quantile(0.0), std::invalid_argument);
}

TEST_CASE("chi-square survival matches the tables and the closed forms") {
    // upper 5 % and 1 % points (A&S Table 26.8)
    CHECK(close(et::chi2_survival(3.841458820694124, 1), 0.05, 1e-12));
    CHECK(close(et::chi2_survival(18.307038053275146, 10), 0.05, 1e-12));
    CHECK(close(et::chi2_survival(63.690739751564465, 40), 0.01, 1e-11));
    CHECK(close(et::chi2_survival(1118.9480663231916, 1000), 0.005, 1e-9));  // scipy.stats.chi2.isf
    // Q(1, x) = e^-x (series branch x < 2, continued fraction x >= 2); 2 dof: e^{-chi2/2}
    for (double x : {0.1, 1.0, 1.9, 2.5, 10.0, 50.0}) CHECK(close(et::regularized_gamma_q(1.0, x), std::exp(-x), 1e-13));
    // Q(1/2, x) = erfc(sqrt(x))
    for (double x : {0.01, 0.7, 3.0, 20.0}) CHECK(close(et::regularized_gamma_q(0.5, x), std::erfc(std::sqrt(x)), 1e-12));
    CHECK(et::regularized_gamma_q(3.0, 0.0) == 1.0);
    CHECK_THROWS_AS(et::regularized_gamma_q(0.0, 1.0), std::invalid_argument);
}

TEST_CASE("Student t two-sided p-values") {
    CHECK(close(et::student_t_two_sided_p(2.228138851986274, 10), 0.05, 1e-12));
    CHECK(close(et::student_t_two_sided_p(-2.228138851986274, 10), 0.05, 1e-12));
    CHECK(close(et::student_t_two_sided_p(2.576, 1e7), std::erfc(2.576 / std::sqrt(2.0)), 1e-5));
    // one dof is the Cauchy distribution: P(|T| >= t) = 1 - 2 atan(t) / pi
    for (double t : {0.3, 1.0, 7.0, 300.0})
        CHECK(close(et::student_t_two_sided_p(t, 1), 1.0 - 2.0 * std::atan(t) / pi, 1e-11));
    CHECK(et::student_t_two_sided_p(0.0, 5) == 1.0);
    // I_x(a, 1) = x^a
    CHECK(close(et::regularized_beta(2.5, 1.0, 0.3), std::pow(0.3, 2.5), 1e-13));
}

TEST_CASE("trigamma") {
    CHECK(close(et::trigamma(1.0), pi * pi / 6.0, 1e-13));
    CHECK(close(et::trigamma(0.5), pi * pi / 2.0, 1e-13));
    double tail = pi * pi / 6.0;  // psi_1(16) = psi_1(1) - sum_{k=1}^{15} 1/k^2 (recurrence, A&S 6.4.6)
    for (int k = 1; k <= 15; ++k) tail -= 1.0 / (k * k);
    CHECK(close(et::trigamma(16.0), tail, 1e-12));
    CHECK(close(et::sidak_alpha(0.01, 1), 0.01, 1e-15));
    CHECK(close(et::sidak_alpha(0.05, 10), 1.0 - std::pow(0.95, 0.1), 1e-13));
}
