// SPDX-License-Identifier: MIT
#include "gl_test_support.hpp"

#include <catch2/catch_test_macros.hpp>

// LeakSanitizer suppressions for Mesa's own allocations live in demo/gl/context.cpp (every emcv_gl user).

namespace emcv::test {

emcv::gl::context context_or_skip() {
    std::optional<emcv::gl::context> ctx;
    bool no_display = false;
    std::string why;
    try {
        ctx.emplace(emcv::gl::context_options{});
    } catch (const emcv::gl::context_error& e) {
        no_display = e.no_display();
        why = e.what();
    }
    if (!ctx) {
        if (no_display) SKIP("skipped: no EGL display\n" << why);
        FAIL(why);
    }
    return std::move(*ctx);
}

}  // namespace emcv::test
