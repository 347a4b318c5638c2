// Bad input: invalid parameters throw a clear std::invalid_argument; non-finite samples follow the one
// library-wide policy (rejected, counted, state unchanged, push returns false).
#include <emcv/emcv.hpp>

#include <catch2/catch_template_test_macros.hpp>
#include <catch2/catch_test_macros.hpp>
#include <catch2/matchers/catch_matchers_string.hpp>

#include <limits>

using Catch::Matchers::ContainsSubstring;
using Catch::Matchers::Equals;

TEMPLATE_TEST_CASE("eta outside the interval 0 < eta <= 1 is refused", "[bad-input]", float, double, long double) {
    using T = TestType;
    for (T eta : {T(0), T(-0.1), T(1.0001), std::numeric_limits<T>::quiet_NaN(), std::numeric_limits<T>::infinity()}) {
        REQUIRE_THROWS_WITH((emcv::emcm<T, 2>(eta)), ContainsSubstring("eta = ") && ContainsSubstring(" must lie in (0, 1]"));
        REQUIRE_THROWS_AS(emcv::moving_stats<T>(eta), std::invalid_argument);
        REQUIRE_THROWS_AS(emcv::control_variate<T>(emcv::residual_policy::emcm_sampled, eta),
                          std::invalid_argument);
    }
    REQUIRE_NOTHROW(emcv::emcm<T, 1>(T(1)));
    REQUIRE_NOTHROW(emcv::emcm<T, 1>(std::numeric_limits<T>::min()));
}

TEST_CASE("an invalid parameter's message names the public type, the parameter, its value and the rule",
          "[bad-input]") {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    REQUIRE_THROWS_WITH((emcv::emcm<double, 2>(2.0)), Equals("emcv::emcm: eta = 2 must lie in (0, 1]"));
    REQUIRE_THROWS_WITH((emcv::emcm<float, 2>(1.0001f)), Equals("emcv::emcm: eta = 1.0001 must lie in (0, 1]"));
    REQUIRE_THROWS_WITH((emcv::compensated_emcm<double, 2>(0.0)),
                        Equals("emcv::compensated_emcm: eta = 0 must lie in (0, 1]"));
    REQUIRE_THROWS_WITH((emcv::ewma_covariance<double, 2>(nan)),
                        Equals("emcv::ewma_covariance: eta = nan must lie in (0, 1]"));
    REQUIRE_THROWS_WITH(emcv::moving_stats<double>(-0.5), Equals("emcv::moving_stats: eta = -0.5 must lie in (0, 1]"));
    REQUIRE_THROWS_WITH(emcv::control_variate<double>(emcv::residual_policy::emcm_constant, 1.5),
                        Equals("emcv::control_variate: eta_cov = 1.5 must lie in (0, 1]"));
    REQUIRE_THROWS_WITH(emcv::control_variate<double>(emcv::residual_policy::single_frame_ema, 0.05, 0.0),
                        Equals("emcv::control_variate: eta_alpha = 0 must lie in (0, 1]"));
    REQUIRE_THROWS_WITH(emcv::control_variate<double>(emcv::residual_policy::single_frame, 0.05, 0.05, -1.0),
                        Equals("emcv::control_variate: var_floor = -1 must be >= 0 (and not NaN)"));
    REQUIRE_THROWS_WITH(emcv::sample_count(1.0, 0.0, 8, 64),
                        Equals("emcv::sample_count: target variance = 0 must be finite and > 0"));
    REQUIRE_THROWS_WITH(emcv::sample_count(1.0, 1e-4, 65, 64),
                        Equals("emcv::sample_count: n_min = 65 must not exceed n_max = 64"));
    REQUIRE_THROWS_WITH(emcv::batch_mean_covariance(1.0, 0),
                        Equals("emcv::batch_mean_covariance: batch size n = 0 must be at least 1"));
    double mean = 0.0, variance = 0.0;
    REQUIRE_THROWS_WITH(emcv::moving_stats_update(mean, variance, 1.0, 3.0),
                        Equals("emcv::moving_stats_update: eta = 3 must lie in (0, 1]"));
    emcv::running_covariance<double, 2>::state_type poisoned{};
    poisoned.count = 1;
    poisoned.total_weight = 1.0;
    poisoned.covariance[0] = -1.0;
    REQUIRE_THROWS_WITH((emcv::running_covariance<double, 2>(poisoned)),
                        Equals("emcv::running_covariance: restored state must have every variance >= 0"));
    REQUIRE_THROWS_WITH((emcv::emcm<double, 2>(0.1, poisoned)),
                        Equals("emcv::emcm: restored state must have every variance >= 0"));
    poisoned.covariance[0] = 0.0;
    poisoned.mean[1] = std::numeric_limits<double>::infinity();
    REQUIRE_THROWS_WITH((emcv::weighted_covariance<double, 2>(poisoned)),
                        Equals("emcv::weighted_covariance: restored state must be finite: the mean (or its low part) "
                               "is not"));
}

TEST_CASE("control_variate checks only the parameters its policy reads", "[bad-input]") {
    using emcv::residual_policy;
    const double bad_eta = 2.0, nan = std::numeric_limits<double>::quiet_NaN();
    // eta_alpha is read by single_frame_ema alone, eta_cov by the emcm_* policies alone, the floor by all but none
    REQUIRE_NOTHROW(emcv::control_variate<double>(residual_policy::emcm_sampled, 0.05, bad_eta));
    REQUIRE_NOTHROW(emcv::control_variate<double>(residual_policy::emcm_constant, 0.05, bad_eta));
    REQUIRE_NOTHROW(emcv::control_variate<double>(residual_policy::single_frame, bad_eta, bad_eta));
    REQUIRE_NOTHROW(emcv::control_variate<double>(residual_policy::single_frame_ema, bad_eta, 0.05));
    REQUIRE_NOTHROW(emcv::control_variate<double>(residual_policy::none, bad_eta, bad_eta, nan));
    REQUIRE_THROWS_AS(emcv::control_variate<double>(residual_policy::emcm_sampled, bad_eta), std::invalid_argument);
    REQUIRE_THROWS_AS(emcv::control_variate<double>(residual_policy::single_frame_ema, 0.05, bad_eta),
                      std::invalid_argument);
    REQUIRE_THROWS_AS(emcv::control_variate<double>(residual_policy::emcm_sampled, 0.05, 0.05, nan),
                      std::invalid_argument);
    // the policy that ignores eta_alpha still works
    emcv::control_variate<double> cv(residual_policy::emcm_sampled, 0.5, bad_eta);
    cv.push({1.0, 1.0, 1.0, 0.0, 0.0});
    cv.push({3.0, 2.0, 2.0, 0.0, 0.0});
    REQUIRE(cv.alpha() == 2.0);  // C_fG / C_GG of the frame means: d = (2, 1), one step
}

TEMPLATE_TEST_CASE("negative weights and decays outside 0..1 are refused", "[bad-input]", float, double,
                   long double) {
    using T = TestType;
    emcv::weighted_covariance<T, 2> e;
    const std::array<T, 2> x{T(1), T(2)};
    REQUIRE_THROWS_WITH(e.push(x, T(-1)), Equals("emcv::weighted_covariance::push: weight = -1 must be >= 0"));
    REQUIRE_THROWS_WITH(e.push(x, -std::numeric_limits<T>::infinity()),
                        Equals("emcv::weighted_covariance::push: weight = -inf must be >= 0"));
    REQUIRE_THROWS_WITH(e.push(x, -std::numeric_limits<T>::denorm_min()), ContainsSubstring("weight"));
    REQUIRE_THROWS_WITH(e.push(x, T(1), T(-0.5)),
                        Equals("emcv::weighted_covariance::push: decay = -0.5 must lie in [0, 1]"));
    REQUIRE_THROWS_WITH(e.push(x, T(1), T(1.5)), ContainsSubstring("decay = 1.5 must lie in [0, 1]"));
    REQUIRE_THROWS_WITH(e.push(x, T(1), std::numeric_limits<T>::quiet_NaN()), ContainsSubstring("decay"));
    REQUIRE(e.count() == 0);  // a refused call changes nothing
    REQUIRE(e.rejected() == 0);
}

TEMPLATE_TEST_CASE("a NaN or +Inf weight is rejected and counted like a non-finite sample", "[bad-input]", float,
                   double, long double) {
    // An importance weight f / pdf becomes Inf or NaN where the pdf reaches 0: the sample is refused, not the call.
    using T = TestType;
    emcv::weighted_covariance<T, 2> e;
    REQUIRE(e.push({T(1), T(2)}, T(2)));
    REQUIRE(e.push({T(3), T(-2)}, T(0.5), T(0.75)));
    const auto before = e.state();
    REQUIRE_FALSE(e.push({T(5), T(5)}, std::numeric_limits<T>::quiet_NaN()));
    REQUIRE_FALSE(e.push({T(5), T(5)}, std::numeric_limits<T>::infinity(), T(0.5)));
    REQUIRE(e.rejected() == 2);
    REQUIRE(e.count() == before.count);
    REQUIRE(e.total_weight() == before.total_weight);
    REQUIRE(e.state().mean == before.mean);
    REQUIRE(e.state().covariance == before.covariance);
}

TEMPLATE_TEST_CASE("push(x, 0, 0) empties the estimator and the next weighted push seeds it", "[bad-input]", float,
                   double) {
    using T = TestType;
    emcv::weighted_covariance<T, 1> e;
    REQUIRE(e.push(T(1)));
    REQUIRE(e.push(T(3)));
    REQUIRE(e.variance(0) == T(1));
    REQUIRE(e.push(T(7), T(0), T(0)));  // forget everything, give x no weight: W = 0 holds nothing
    REQUIRE(e.count() == 3);            // the call is counted (it was a finite sample)
    REQUIRE(e.total_weight() == T(0));
    REQUIRE(e.mean(0) == T(0));
    REQUIRE(e.variance(0) == T(0));
    REQUIRE(emcv::weighted_covariance<T, 1>::valid_state(e.state()));
    REQUIRE(e.push(T(5), T(2), T(1)));  // r = 2 / 2 = 1: x seeds the mean, covariance 0
    REQUIRE(e.mean(0) == T(5));
    REQUIRE(e.variance(0) == T(0));
    REQUIRE(e.push(T(9), T(2), T(1)));  // equal weights: mean 7, population variance 4
    REQUIRE(e.mean(0) == T(7));
    REQUIRE(e.variance(0) == T(4));
}

TEMPLATE_TEST_CASE("a restored state with count 0 must be empty", "[bad-input]", float, double) {
    // A texture that stores only mean and covariance must be restored with count >= 1: with count == 0 the next
    // push would seed the mean and silently drop what was stored, so such a state is refused.
    using T = TestType;
    using state = typename emcv::emcm<T, 2>::state_type;
    state s{};
    REQUIRE_NOTHROW((emcv::emcm<T, 2>(T(0.05), s)));  // the empty state
    s.rejected = 4;                                     // rejections alone keep it empty
    REQUIRE_NOTHROW((emcv::emcm<T, 2>(T(0.05), s)));
    auto with_mean = s;
    with_mean.mean = {T(0.5), T(1)};
    REQUIRE_THROWS_WITH((emcv::emcm<T, 2>(T(0.05), with_mean)), Equals("emcv::emcm: restored state must be all zero when count == 0 "
                                                                    "(restore a stored history with count >= 1)"));
    auto with_cov = s;
    with_cov.covariance[2] = T(0.25);
    REQUIRE_THROWS_AS((emcv::moving_stats<T>(T(0.2), typename emcv::moving_stats<T>::state_type{0, 0, T(0), {T(0)},
                                                                                                  {T(0.25)}})),
                      std::invalid_argument);
    REQUIRE_THROWS_AS((emcv::emcm<T, 2>(T(0.05), with_cov)), std::invalid_argument);
    auto with_weight = s;
    with_weight.total_weight = T(1);
    REQUIRE_THROWS_AS((emcv::weighted_covariance<T, 2>(with_weight)), std::invalid_argument);
    auto with_low = s;
    with_low.mean_compensation[1] = T(1e-9);
    REQUIRE_THROWS_AS((emcv::compensated_emcm<T, 2>(T(0.05), with_low)), std::invalid_argument);
    with_low = s;
    with_low.covariance_compensation[0] = T(1e-9);
    REQUIRE_THROWS_AS((emcv::compensated_emcm<T, 2>(T(0.05), with_low)), std::invalid_argument);
    // the same mean and covariance with count 1 is a defined history: the next push continues from it
    with_mean.count = 1;
    with_mean.total_weight = T(1);
    with_mean.covariance = {T(0.25), T(0), T(0.25)};
    emcv::emcm<T, 2> restored(T(0.5), with_mean);
    restored.push({T(1.5), T(1)});  // d = (1, 0): mean 1, Cov_00 = 0.5 (0.25 + 0.5 * 1) = 0.375
    REQUIRE(restored.mean(0) == T(1));
    REQUIRE(restored.variance(0) == T(0.375));
}

TEMPLATE_TEST_CASE("NaN and Inf samples are rejected and counted and leave the state untouched", "[bad-input]",
                   float, double, long double) {
    using T = TestType;
    const T nan = std::numeric_limits<T>::quiet_NaN();
    const T inf = std::numeric_limits<T>::infinity();
    const std::array<std::array<T, 2>, 3> bad{{{nan, T(1)}, {T(1), inf}, {-inf, nan}}};

    emcv::weighted_covariance<T, 2> w;
    emcv::running_covariance<T, 2> r;
    emcv::emcm<T, 2> e(T(0.1));
    emcv::ewma_covariance<T, 2> v(T(0.1));
    emcv::moving_stats<T> m(T(0.2));
    for (int i = 0; i < 5; ++i) {
        const std::array<T, 2> x{T(i), T(2 * i + 1)};
        w.push(x);
        r.push(x);
        e.push(x);
        v.push(x);
        m.push(x[0]);
    }
    const auto ws = w.state();
    const auto rs = r.state();
    const auto es = e.state();
    const auto vs = v.state();
    const auto ms = m.state();
    for (const auto& x : bad) {
        REQUIRE_FALSE(w.push(x));
        REQUIRE_FALSE(r.push(x));
        REQUIRE_FALSE(e.push(x));
        REQUIRE_FALSE(v.push(x));
        REQUIRE_FALSE(m.push(x[0] == x[0] ? x[1] : x[0]));
    }
    REQUIRE(w.rejected() == 3);
    REQUIRE(r.rejected() == 3);
    REQUIRE(e.rejected() == 3);
    REQUIRE(v.rejected() == 3);
    REQUIRE(m.rejected() == 3);
    REQUIRE(w.count() == 5);
    REQUIRE(m.count() == 5);
    REQUIRE(w.state().mean == ws.mean);
    REQUIRE(w.state().covariance == ws.covariance);
    REQUIRE(r.state().covariance == rs.covariance);
    REQUIRE(e.state().covariance == es.covariance);
    REQUIRE(e.state().mean == es.mean);
    REQUIRE(v.state().covariance == vs.covariance);
    REQUIRE(m.state().covariance == ms.covariance);
    REQUIRE(m.mean() == ms.mean[0]);
}

TEST_CASE("a non-finite first sample does not seed the estimator", "[bad-input]") {
    emcv::emcm<double, 1> e(0.5);
    REQUIRE_FALSE(e.push(std::numeric_limits<double>::quiet_NaN()));
    REQUIRE(e.count() == 0);
    REQUIRE(e.push(2.0));  // the first finite sample seeds
    REQUIRE(e.mean(0) == 2.0);
    REQUIRE(e.variance(0) == 0.0);
}

TEMPLATE_TEST_CASE("a zero-weight sample far from the mean changes nothing and stores no NaN", "[bad-input]", float,
                   double) {
    // d^2 overflows for d = 2 sqrt(max): with r = 0 the product 0 * Inf would be NaN.
    using T = TestType;
    const T far = std::sqrt(std::numeric_limits<T>::max()) * T(2);
    emcv::weighted_covariance<T, 2> e;
    REQUIRE(e.push({T(1), T(2)}));
    REQUIRE(e.push({T(3), T(4)}));
    const auto before = e.state();
    REQUIRE(e.push({-far, far}, T(0), T(0.5)));  // decays the weight, adds nothing
    REQUIRE(e.total_weight() == T(1));
    REQUIRE(e.state().mean == before.mean);
    REQUIRE(e.state().covariance == before.covariance);
    REQUIRE(emcv::weighted_covariance<T, 2>::valid_state(e.state()));
}
