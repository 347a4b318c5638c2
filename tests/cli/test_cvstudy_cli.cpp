// SPDX-License-Identifier: MIT
// emcv-cvstudy's bad input: unknown flags and arguments, a flag without its value, malformed or out-of-range
// counts, an unknown --half-state: one line naming the flag and the value, exit 2, nothing on stdout.
#include <catch2/catch_test_macros.hpp>

#include <string>

#include "cli_expect.hpp"

#ifdef EMCV_CVSTUDY
TEST_CASE("emcv-cvstudy: bad usage exits 2 and names the argument", "[cli][cvstudy]") {
    emcv_cli_test::expect_errors("emcv-cvstudy", std::string("'") + EMCV_CVSTUDY + "'", {
        {"--bogus", "unknown flag '--bogus'"},
        {"400", "unknown flag '400'"},
        {"--pixels", "--pixels: missing value"},
        {"--pixels 0", "--pixels: expected a whole number in 1..1000000, got '0'"},
        {"--pixels -5", "got '-5'"},
        {"--pixels 1e3", "got '1e3'"},
        {"--pixels 1000001", "got '1000001'"},
        {"--pixels ''", "got ''"},
        {"--seed abc", "--seed: expected a whole number in 1..18446744073709551615, got 'abc'"},
        {"--seed 18446744073709551616", "got '18446744073709551616'"},
        {"--half-state", "--half-state: missing value"},
        {"--half-state none", "--half-state: expected all or means, got 'none'"},
        {"--pixels 10 --bogus", "unknown flag '--bogus'"},
    });
}
#endif
