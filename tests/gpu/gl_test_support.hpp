// SPDX-License-Identifier: MIT
// Shared by the gpu tests: a context or a Catch2 SKIP("skipped: no EGL display"), which becomes a failure when
// the environment sets EMCV_REQUIRE_GL=1 (scripts/test.sh and CI do: there a GL test that cannot run is an error).
#pragma once

#include <optional>
#include <string>

#include "gl/context.hpp"

namespace emcv::test {

/// True when the environment sets EMCV_REQUIRE_GL=1: a GL test that cannot get a context fails instead of skipping.
bool gl_required();

/// Ends the test case because no GL display exists: SKIP with the reason, or FAIL when gl_required().
[[noreturn]] void skip_without_gl(const std::string& why);

/// Creates the default headless context; without any display it calls skip_without_gl, on other errors it fails.
emcv::gl::context context_or_skip();

}  // namespace emcv::test
