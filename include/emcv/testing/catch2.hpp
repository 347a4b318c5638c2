// SPDX-License-Identifier: MIT
// emcv/testing/catch2.hpp — Catch2 v3 adapter for emcv/testing (include it only from Catch2 tests):
//   EMCV_CHECK_STAT(emcv::testing::t_test_mean(acc, 1.0));   // on failure, prints the result's message
//   EMCV_REQUIRE_STAT(...)                                  // same, aborting the test case
// and a StringMaker so that a test_result printed by Catch2 shows its message.
#pragma once

#include <catch2/catch_test_macros.hpp>
#include <catch2/catch_tostring.hpp>

#include "../testing.hpp"

namespace Catch {
/// Prints a test_result as its message when Catch2 shows a value.
template <>
struct StringMaker<emcv::testing::test_result> {
    /// The result's one-line message.
    static std::string convert(const emcv::testing::test_result& r) { return r.message; }
};
}  // namespace Catch

#define EMCV_TESTING_ASSERT_STAT_(macro, ...)                                \
    do {                                                                     \
        const ::emcv::testing::test_result emcv_testing_result_ = (__VA_ARGS__); \
        INFO(emcv_testing_result_.message);                                  \
        macro(emcv_testing_result_.passed);                                  \
    } while (false)

#define EMCV_CHECK_STAT(...) EMCV_TESTING_ASSERT_STAT_(CHECK, __VA_ARGS__)
#define EMCV_REQUIRE_STAT(...) EMCV_TESTING_ASSERT_STAT_(REQUIRE, __VA_ARGS__)
