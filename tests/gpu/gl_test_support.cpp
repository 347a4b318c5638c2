// SPDX-License-Identifier: MIT
#include "gl_test_support.hpp"

#include <catch2/catch_test_macros.hpp>

#include <cstdlib>
#include <cstring>
#include <stdexcept>

// LeakSanitizer suppressions for Mesa's own allocations live in demo/gl/context.cpp (every emcv_gl user).

namespace emcv::test {

bool gl_required() {
    const char* v = std::getenv("EMCV_REQUIRE_GL");
    return v != nullptr && std::strcmp(v, "1") == 0;
}

void skip_without_gl(const std::string& why) {
    if (gl_required()) FAIL("EMCV_REQUIRE_GL=1 but no EGL display: this GL test cannot run\n" << why);
    SKIP("skipped: no EGL display (set EMCV_REQUIRE_GL=1 to make this a failure)\n" << why);
    throw std::logic_error("unreachable: SKIP returned");  // SKIP and FAIL throw; keeps [[noreturn]] honest
}

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
        if (no_display) skip_without_gl(why);
        FAIL(why);
    }
    return std::move(*ctx);
}

}  // namespace emcv::test
