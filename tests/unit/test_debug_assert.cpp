// EMCV_ASSERT, overridden before the first emcv include (docs/api.md, "Debug assertions"): an index past the
// estimator's dimension reaches the assertion instead of reading another entry or past the state.
#include <stdexcept>

#define EMCV_ASSERT(cond, msg) ((cond) ? static_cast<void>(0) : throw std::out_of_range(msg))

#include <emcv/emcv.hpp>

#include <catch2/catch_test_macros.hpp>
#include <catch2/matchers/catch_matchers_string.hpp>

using Catch::Matchers::ContainsSubstring;

TEST_CASE("an index past the dimension fires EMCV_ASSERT", "[assert]") {
    emcv::emcm<float, 2> e(0.5f);
    e.push({1.0f, 2.0f});
    e.push({3.0f, 1.0f});
    REQUIRE(e.mean(1) == 1.5f);  // in range: no assertion
    REQUIRE_NOTHROW(e.covariance(1, 0));
    REQUIRE_THROWS_WITH(e.mean(7), ContainsSubstring("mean(i) needs i < N"));
    REQUIRE_THROWS_WITH(e.mean(2), ContainsSubstring("mean(i) needs i < N"));
    // covariance(0, 2) of a 2 x 2 matrix is packed index 2, the valid entry (1, 1): not an out-of-bounds read,
    // a wrong answer, which only the assertion catches
    REQUIRE_THROWS_WITH(e.covariance(0, 2), ContainsSubstring("covariance(i, j) needs i < N and j < N"));
    REQUIRE_THROWS_WITH(e.covariance(2, 0), ContainsSubstring("covariance(i, j) needs i < N and j < N"));
    REQUIRE_THROWS_WITH(e.variance(2), ContainsSubstring("variance(i) needs i < N"));

    emcv::running_covariance<double, 3> r;
    r.push({1.0, 2.0, 3.0});
    REQUIRE_NOTHROW(r.sample_covariance(2, 2));
    REQUIRE_THROWS_AS(r.sample_covariance(0, 3), std::out_of_range);
    REQUIRE_THROWS_AS(r.variance(3), std::out_of_range);

    emcv::weighted_covariance<double, 1> w;
    REQUIRE_THROWS_AS(w.mean(1), std::out_of_range);
}
