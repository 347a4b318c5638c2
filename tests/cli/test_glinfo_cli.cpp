// SPDX-License-Identifier: MIT
// emcv-glinfo's bad input: unknown flags, a flag without its value, a bad --platform, a bad --device, and no
// platform at all (EMCV_GL_PLATFORMS=none). A missing EGL device must fail, never fall back silently.
#include <catch2/catch_test_macros.hpp>

#include <string>

#include "cli_expect.hpp"

#ifdef EMCV_GLINFO

namespace {

std::string glinfo(const std::string& args) { return std::string("'") + EMCV_GLINFO + "' " + args; }

}  // namespace

TEST_CASE("emcv-glinfo: bad usage exits 2 and names the argument", "[cli][glinfo]") {
    emcv_cli_test::expect_errors("emcv-glinfo", glinfo(""), {
        {"--bogus", "unknown argument '--bogus'"},
        {"surfaceless", "unknown argument 'surfaceless'"},
        {"--platform", "--platform needs a value"},
        {"--platform vulkan", "unknown GL platform 'vulkan'"},
        {"--platform none", "--platform needs a platform name"},
        {"--device", "--device needs a value"},
        {"--device abc", "--device needs a device index 0, 1, ..., got 'abc'"},
        {"--device -1", "got '-1'"},
        {"--device 3x", "got '3x'"},
        {"--device 99999999999", "got '99999999999'"},
        {"--device 0 --platform surfaceless", "--device applies to the device platform only"},
    });
}

TEST_CASE("emcv-glinfo: no platform to try exits 1 with one line", "[cli][glinfo]") {
    const emcv_test::command_result r = emcv_test::run_command("EMCV_GL_PLATFORMS=none " + glinfo(""));
    INFO(r.err);
    CHECK(r.exit_code == 1);
    CHECK(r.out.empty());
    CHECK(r.err == "emcv-glinfo: cannot create an OpenGL 4.5 core context; platforms tried: none "
                   "(EMCV_GL_PLATFORMS names no platform)\n");
}

TEST_CASE("emcv-glinfo: a device that does not exist fails instead of falling back", "[cli][glinfo]") {
    // Without --platform, --device means the device platform only: surfaceless would succeed here and hide
    // the wrong index. With no EGL device at all the first line is the same, the reason differs.
    for (const char* args : {"--device 15", "--device 15 --platform device"})
        emcv_cli_test::expect_error("emcv-glinfo", glinfo(args), 1, "cannot create an OpenGL 4.5 core context");
}

#endif  // EMCV_GLINFO
