// SPDX-License-Identifier: MIT
#include "gl_test_support.hpp"

#include <catch2/catch_test_macros.hpp>

#include <cstdlib>
#include <cstring>
#include <stdexcept>

// LeakSanitizer: Mesa keeps some allocations until exit (driver caches, LLVM); suppress reports whose stack goes
// through Mesa's libraries only. Harmless when not built with sanitizers.
extern "C" const char* __lsan_default_suppressions() {
    return "leak:libEGL_mesa\nleak:libgallium\nleak:libglapi\nleak:swrast_dri\nleak:libLLVM\nleak:libGLX_mesa\n";
}

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
