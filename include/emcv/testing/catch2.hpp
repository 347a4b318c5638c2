// SPDX-License-Identifier: MIT
// emcv/testing/catch2.hpp — Catch2 v3 adapter for emcv/testing (include it only from Catch2 tests):
//   EMCV_CHECK_STAT(emcv::testing::t_test_mean(acc, 1.0));   // a Catch2 assertion on the result
//   EMCV_REQUIRE_STAT(...)                                  // same, aborting the test case
// A failure shows the macro with the expression as written and, as its expansion, the result's message:
//   test_my_sampler.cpp:21: FAILED:
//     EMCV_CHECK_STAT( emcv::testing::t_test_mean(acc, 1.0) )
//   with expansion:
//     t-test: mean 1.02 vs expected 1 over 10000 samples (...), p = 3.1e-09, alpha = 0.01: REJECTED
// and a StringMaker so that a test_result printed by Catch2 shows its message.
#pragma once

#include <catch2/catch_test_macros.hpp>
#include <catch2/catch_tostring.hpp>

#include "../testing.hpp"

namespace Catch {
/// Prints a test_result as its message when Catch2 shows a value.
template <>
struct StringMaker<emcv::testing::test_result> {
    /// The result's message.
    static std::string convert(const emcv::testing::test_result& r) { return r.message; }
};
}  // namespace Catch

namespace emcv::testing::detail {
/// Compiles only for a test_result: EMCV_CHECK_STAT(x > 0) is a mistake (use CHECK).
inline void stat_macro_argument_must_be_a_test_result(const test_result&) noexcept {}
}  // namespace emcv::testing::detail

// Catch2's own assertion machinery (the macro behind CHECK and REQUIRE), under this macro's name: the
// reporter prints "EMCV_CHECK_STAT( <expression> )" and expands the result through the StringMaker above.
// The never-taken branch only type-checks the argument (a decltype would refuse the lambdas a sampler is
// often written as, in C++17).
#define EMCV_TESTING_ASSERT_STAT_(macro_name, disposition, ...)                                \
    do {                                                                                       \
        if (false) ::emcv::testing::detail::stat_macro_argument_must_be_a_test_result(__VA_ARGS__); \
        INTERNAL_CATCH_TEST(macro_name, disposition, __VA_ARGS__);                            \
    } while (false)

/// Checks an emcv::testing::test_result; on failure Catch2 shows the expression and the result's message.
#define EMCV_CHECK_STAT(...) \
    EMCV_TESTING_ASSERT_STAT_("EMCV_CHECK_STAT", ::Catch::ResultDisposition::ContinueOnFailure, __VA_ARGS__)
/// As EMCV_CHECK_STAT, and a failure ends the test case (like REQUIRE).
#define EMCV_REQUIRE_STAT(...) \
    EMCV_TESTING_ASSERT_STAT_("EMCV_REQUIRE_STAT", ::Catch::ResultDisposition::Normal, __VA_ARGS__)
