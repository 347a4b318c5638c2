// SPDX-License-Identifier: MIT
// GL error paths: no EGL display, no OpenGL 4.5 (here: 4.7) context, a syntax error in an included shader file
// (Mesa's log must name that file and line), a missing shader file, and GL errors counted by KHR_debug.
#include <catch2/catch_test_macros.hpp>
#include <catch2/matchers/catch_matchers_string.hpp>

#include <array>
#include <cstdio>
#include <string>

#include "gl/debug.hpp"
#include "gl/program.hpp"
#include "gl_test_support.hpp"
#include "../support/run_command.hpp"
#include "../support/source_dirs.hpp"

using Catch::Matchers::ContainsSubstring;

namespace {

emcv_test::command_result run(const std::string& command) { return emcv_test::run_command(command); }

emcv::gl::preprocess_options test_options() {
    emcv::gl::preprocess_options o;
    o.include_dirs = emcv_test::shader_include_dirs();
    return o;
}

}  // namespace

TEST_CASE("emcv-glinfo prints the context it gets") {
    const emcv_test::command_result r = run(EMCV_GLINFO);
    if (r.exit_code != 0 && r.output().find("platforms tried") != std::string::npos &&
        r.output().find("no OpenGL") == std::string::npos)
        emcv::test::skip_without_gl(r.output());
    INFO(r.output());
    CHECK(r.exit_code == 0);
    CHECK_THAT(r.output(), ContainsSubstring("platform: ") && ContainsSubstring("version:  4."));
}

TEST_CASE("without a display a context test skips by hand and fails under EMCV_REQUIRE_GL=1") {
    // Runs one context test of this executable again with no platform to try (EMCV_GL_PLATFORMS=none).
    const std::string test = " '[needs-context]' ";
    const emcv_test::command_result by_hand =
        run(std::string("env -u EMCV_REQUIRE_GL EMCV_GL_PLATFORMS=none ") + EMCV_GL_ERRORS_EXE + test);
    INFO(by_hand.output());
    CHECK_THAT(by_hand.output(), ContainsSubstring("skipped: no EGL display"));
    CHECK_THAT(by_hand.output(), ContainsSubstring("platforms tried: none"));  // the reason travels with the skip
    CHECK(by_hand.output().find("FAILED") == std::string::npos);
    const emcv_test::command_result required =
        run(std::string("EMCV_REQUIRE_GL=1 EMCV_GL_PLATFORMS=none ") + EMCV_GL_ERRORS_EXE + test);
    INFO(required.output());
    CHECK(required.exit_code != 0);
    CHECK_THAT(required.output(), ContainsSubstring("EMCV_REQUIRE_GL=1 but no EGL display"));
    CHECK_THAT(required.output(), ContainsSubstring("FAILED"));
}

TEST_CASE("no EGL display: the error lists every platform tried and why it failed") {
    // GLVND finds no vendor library, which is what a machine without Mesa or a driver looks like.
    const emcv_test::command_result r = run(std::string("__EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent.json ") + EMCV_GLINFO +
                             " --platform device,surfaceless");
    INFO(r.output());
    CHECK(r.exit_code == 1);
    CHECK_THAT(r.output(), ContainsSubstring("cannot create an OpenGL 4.5 core context; platforms tried:"));
    CHECK_THAT(r.output(), ContainsSubstring("device: ") && ContainsSubstring("surfaceless: "));
    CHECK_THAT(r.output(), ContainsSubstring("not supported"));
}

TEST_CASE("EMCV_GL_PLATFORMS=none and an unknown platform are clear errors") {
    const emcv_test::command_result none = run(std::string("EMCV_GL_PLATFORMS=none ") + EMCV_GLINFO);
    INFO(none.output());
    CHECK(none.exit_code == 1);
    CHECK_THAT(none.output(), ContainsSubstring("platforms tried: none"));
    const emcv_test::command_result bad = run(std::string(EMCV_GLINFO) + " --platform vulkan");
    INFO(bad.output());
    CHECK(bad.exit_code == 2);
    CHECK_THAT(bad.output(), ContainsSubstring("unknown GL platform 'vulkan'"));
}

TEST_CASE("no OpenGL 4.5 context: asking for 4.7 fails on every platform with the reason") {
    { auto probe = emcv::test::context_or_skip(); }  // a 4.5 context exists here, else SKIP
    emcv::gl::context_options o;
    o.platforms = {emcv::gl::platform::egl_device, emcv::gl::platform::egl_surfaceless};
    o.major = 4;
    o.minor = 7;
    try {
        emcv::gl::context c(o);
        FAIL("a 4.7 context was created: " << c.version());
    } catch (const emcv::gl::context_error& e) {
        const std::string m = e.what();
        INFO(m);
        CHECK_FALSE(e.no_display());
        CHECK_THAT(m, ContainsSubstring("cannot create an OpenGL 4.7 core context"));
        CHECK_THAT(m, ContainsSubstring("device: ") && ContainsSubstring("surfaceless: "));
        CHECK_THAT(m, ContainsSubstring("no OpenGL 4.7 core context (eglCreateContext: EGL_"));
    }
    // the environment variable gives the same through emcv-glinfo
    const emcv_test::command_result r = run(std::string("EMCV_GL_VERSION=4.7 ") + EMCV_GLINFO);
    INFO(r.output());
    CHECK(r.exit_code == 1);
    CHECK_THAT(r.output(), ContainsSubstring("no OpenGL 4.7 core context"));
}

TEST_CASE("a syntax error in an included file: Mesa's log names that file and line") {
    auto ctx = emcv::test::context_or_skip();
    emcv::gl::debug_messenger debug;
    const std::string shader = std::string(EMCV_SOURCE_DIR) + "/tests/shaders/data/broken_main.comp.glsl";
    try {
        (void)emcv::gl::program::compute(shader, test_options());
        FAIL("the broken shader compiled");
    } catch (const emcv::gl::shader_error& e) {
        const std::string m = e.what();
        INFO(m);
        CHECK_THAT(m, ContainsSubstring("broken_main.comp.glsl failed to compile"));
        CHECK_THAT(m, ContainsSubstring("broken_helper.h:5"));
    }
}

TEST_CASE("a missing shader file is a clear error before any GL call") {
    // no context needed: the preprocessor fails before the first GL call
    CHECK_THROWS_WITH(emcv::gl::program::compute(emcv_test::shader_dir() / "missing.comp.glsl", test_options()),
                      ContainsSubstring("shader file not found") && ContainsSubstring("missing.comp.glsl"));
}

TEST_CASE("using a program that was never built is a clear error, not a bare GL error") {
    // no context needed: use() refuses before glUseProgram(0), after which the next dispatch would fail unnamed
    const emcv::gl::program never_built;
    CHECK(never_built.id() == 0u);
    CHECK_THROWS_WITH(never_built.use(), ContainsSubstring("never built"));
}

TEST_CASE("KHR_debug counts GL errors so that programs can exit non-zero", "[needs-context]") {
    auto ctx = emcv::test::context_or_skip();
    emcv::gl::debug_messenger debug;
    CHECK(debug.error_count() == 0);
    CHECK(debug.exit_status() == 0);
    {
        emcv::gl::debug_group group("deliberate error");
        emcv::gl::texture_2d tex = emcv::gl::texture_2d::create();
        glTextureStorage2D(tex.id(), 1, GL_RGBA32F, 4, 4);
        glTextureStorage2D(tex.id(), 1, GL_RGBA32F, 4, 4);  // immutable storage twice: GL_INVALID_OPERATION
    }
    CHECK(debug.error_count() == 1);
    CHECK(debug.exit_status() == 1);
    CHECK_THAT(debug.last_error(), ContainsSubstring("GL_INVALID_OPERATION"));
    while (glGetError() != GL_NO_ERROR) {
    }
}
