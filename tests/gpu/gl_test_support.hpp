// SPDX-License-Identifier: MIT
// Shared by the gpu tests: a context or a Catch2 SKIP("skipped: no EGL display").
#pragma once

#include <optional>

#include "gl/context.hpp"

namespace emcv::test {

/// Creates the default headless context; SKIPs the test case when no display exists at all, fails otherwise.
emcv::gl::context context_or_skip();

}  // namespace emcv::test
