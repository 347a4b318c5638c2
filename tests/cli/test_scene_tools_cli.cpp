// SPDX-License-Identifier: MIT
// emcv-scene-info and emcv-light-curves (the tools that read a scene): unknown flags, malformed values, a
// missing, folder or malformed scene: one line naming the problem, exit 2, nothing on stdout.
#include <catch2/catch_test_macros.hpp>

#include <filesystem>
#include <string>
#include <vector>

#include "cli_expect.hpp"

namespace fs = std::filesystem;
using emcv_cli_test::quoted;

// Both tools come with the demo's scene library: without it neither is built, and an unused helper would
// be a warning (an error here).
#if defined(EMCV_SCENE_INFO) || defined(EMCV_LIGHT_CURVES)
namespace {

/// The scene problems every scene-reading tool must name, with the file first (load.hpp's scene_error).
std::vector<emcv_cli_test::bad_usage> bad_scenes(const fs::path& dir) {
    const fs::path malformed = fs::path(EMCV_CLI_APP_DATA) / "malformed.json";
    return {
        {quoted(dir / "no-such.json"), (dir / "no-such.json").string() + ": no such scene file or built-in"},
        {quoted(dir), dir.string() + ": no such scene file or built-in"},  // a folder is not a scene file
        {quoted(malformed), malformed.string() + ": /: "},
        {"no-such-builtin", "no-such-builtin: no such scene file or built-in scene (built-in: "},
    };
}

}  // namespace
#endif

#ifdef EMCV_SCENE_INFO
TEST_CASE("emcv-scene-info: bad usage and bad scenes exit 2 with one line", "[cli][scene-info]") {
    const std::string tool = std::string("'") + EMCV_SCENE_INFO + "'";
    emcv_cli_test::expect_errors("emcv-scene-info", tool, {
        {"--bogus", "unknown flag --bogus"},
        {"--size", "--size expects WxH"},
        {"--size 256", "--size expects WxH"},
        {"--size 0x256", "--size expects WxH"},
        {"--size 256x256x3", "--size expects WxH"},
        {"--size 99999x2", "--size expects WxH"},
    });
    const fs::path dir = emcv_cli_test::scratch_dir("scene-info");
    // a good built-in scene first: a later bad one must still leave no partial table
    emcv_cli_test::expect_errors("emcv-scene-info", tool + " static", bad_scenes(dir));
    fs::remove_all(dir);
}
#endif

#ifdef EMCV_LIGHT_CURVES
TEST_CASE("emcv-light-curves: bad usage and bad scenes exit 2 with one line", "[cli][light-curves]") {
    const std::string tool = std::string("'") + EMCV_LIGHT_CURVES + "'";
    emcv_cli_test::expect_errors("emcv-light-curves", tool, {
        {"", "missing SCENE"},
        {"--bogus", "unknown flag '--bogus'"},
        {"static --bogus", "unknown flag '--bogus'"},
        {"static light-off", "one SCENE only, got also 'light-off'"},
    });
    const fs::path dir = emcv_cli_test::scratch_dir("light-curves");
    emcv_cli_test::expect_errors("emcv-light-curves", tool, bad_scenes(dir));
    fs::remove_all(dir);
}

TEST_CASE("emcv-light-curves: --help is usage on stdout, exit 0", "[cli][light-curves]") {
    const emcv_test::command_result r = emcv_test::run_command(std::string("'") + EMCV_LIGHT_CURVES + "' --help");
    CHECK(r.exit_code == 0);
    CHECK(r.out.rfind("usage: emcv-light-curves SCENE", 0) == 0);
    CHECK(r.err.empty());
}
#endif
