// SPDX-License-Identifier: MIT
// The port's checked variant (EMCV_PORT_CHECKS 1, include/emcv/port/port.h): an invalid eta or batch size is
// refused like a non-finite sample and an invalid sample budget returns -1, each reported through EMCV_ASSERT
// (recorded here instead of aborting). Its own executable: the checks change the port's inline functions.
#include <string>
#include <vector>

/// Every failed check's message, in order.
inline std::vector<std::string>& failed_port_checks() {
    static std::vector<std::string> messages;
    return messages;
}
#define EMCV_ASSERT(cond, msg) ((cond) ? static_cast<void>(0) : failed_port_checks().push_back(msg))
#define EMCV_PORT_CHECKS 1

#include <emcv/port/ema.h>
#include <emcv/port/samples.h>

#include <catch2/catch_test_macros.hpp>
#include <catch2/matchers/catch_matchers_string.hpp>

#include <limits>

namespace port = emcv::port;
using Catch::Matchers::ContainsSubstring;

TEST_CASE("checked port: an eta outside 0 < eta <= 1 or a batch below 1 is refused and reported") {
    failed_port_checks().clear();
    port::EmcvEmcm2 s = port::emcv_emcm2_init();
    REQUIRE(port::emcv_emcm2_push(s, glm::vec2(1.0f, 2.0f), 0.5f));
    REQUIRE(port::emcv_emcm2_push(s, glm::vec2(3.0f, 1.0f), 0.5f));
    REQUIRE(failed_port_checks().empty());
    // d = (2, -1), r = 0.5: mean (2, 1.5), Cov = 0.25 d d^T, exact in fp32: the checks change no valid result
    CHECK(s.mean == glm::vec2(2.0f, 1.5f));
    CHECK(s.cov == glm::vec3(1.0f, -0.5f, 0.25f));
    const port::EmcvEmcm2 before = s;
    for (float eta : {2.0f, 0.0f, -0.5f, std::numeric_limits<float>::quiet_NaN()}) {
        CHECK_FALSE(port::emcv_emcm2_push(s, glm::vec2(5.0f, 5.0f), eta));
    }
    CHECK_FALSE(port::emcv_emcm2_push_batch(s, glm::vec2(5.0f, 5.0f), 0.5f, 0.0f));
    CHECK(s.rejected == before.rejected + 5u);
    CHECK(s.count == before.count);
    CHECK(s.mean == before.mean);
    CHECK(s.cov == before.cov);
    REQUIRE(failed_port_checks().size() == 5);
    CHECK_THAT(failed_port_checks()[0], ContainsSubstring("eta > 0.0f && eta <= 1.0f"));
    CHECK_THAT(failed_port_checks()[4], ContainsSubstring("n >= 1.0f"));

    failed_port_checks().clear();
    port::EmcvMovingStats m = port::emcv_moving_stats_init();
    REQUIRE(port::emcv_moving_stats_push(m, 1.0f, 0.2f));
    CHECK_FALSE(port::emcv_moving_stats_push(m, 3.0f, 2.0f));  // unchecked: variance 0 + 2 (-1 * 4) = -8
    CHECK(m.variance == 0.0f);
    CHECK(m.mean == 1.0f);
    CHECK(m.rejected == 1u);
    CHECK(failed_port_checks().size() == 1);
}

TEST_CASE("checked port: a sample budget the C++ API refuses returns -1 and is reported") {
    failed_port_checks().clear();
    CHECK(port::emcv_sample_count(0.5f, 0.125f, 1, 64) == 4);  // exact: 0.5 / 0.125 = 4
    REQUIRE(failed_port_checks().empty());
    CHECK(port::emcv_sample_count(1e-3f, 0.0f, 8, 64) == -1);  // unchecked: n_max
    CHECK(port::emcv_sample_count(1e-3f, std::numeric_limits<float>::infinity(), 8, 64) == -1);
    CHECK(port::emcv_sample_count(1e-3f, 1e-4f, -1, 64) == -1);
    CHECK(port::emcv_sample_count(1e-3f, 1e-4f, 65, 64) == -1);
    REQUIRE(failed_port_checks().size() == 4);
    CHECK_THAT(failed_port_checks()[0], ContainsSubstring("emcv port: parameter check failed: "));
    CHECK_THAT(failed_port_checks()[0], ContainsSubstring("target > 0.0f"));
    CHECK_THAT(failed_port_checks()[3], ContainsSubstring("n_min <= n_max"));
}
