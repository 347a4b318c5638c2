// SPDX-License-Identifier: MIT
// emcv-eval's bad input: unknown flags, malformed values, a missing --method, a bad scene, an --heatmap-dir
// that cannot be made: one line naming the problem, exit 2 (usage, scene) or 1 (output), nothing on stdout and
// no heatmap file. Every case fails before the GL context is made: no GL needed.
#include <catch2/catch_test_macros.hpp>

#include <filesystem>
#include <string>

#include "cli_expect.hpp"

#ifdef EMCV_EVAL

namespace fs = std::filesystem;
using emcv_cli_test::quoted;

namespace {

std::string eval(const std::string& args) { return std::string("'") + EMCV_EVAL + "' " + args; }

}  // namespace

TEST_CASE("emcv-eval: bad usage exits 2 and names the argument", "[cli][eval]") {
    const fs::path dir = emcv_cli_test::scratch_dir("eval-usage");
    emcv_cli_test::expect_errors("emcv-eval", "cd " + quoted(dir) + " && " + eval(""), {
        {"--bogus", "unknown option '--bogus'"},
        {"--method spvg --bogus 3", "unknown option '--bogus'"},
        {"spvg", "unexpected argument 'spvg'"},
        {"", "--method: required"},
        {"--method", "--method: missing value"},
        {"--method spvg,bogus", "--method: unknown method 'bogus'"},
        {"--method spvg --size 64", "--size: expected WxH, got '64'"},
        {"--method spvg --size 0x64", "--size: expected an integer in 1..8192, got '0'"},
        {"--method spvg --size 64x", "--size: expected an integer in 1..8192, got ''"},
        {"--method spvg --frames 0", "--frames: expected an integer in 1..100000, got '0'"},
        {"--method spvg --frames 2.5", "got '2.5'"},
        {"--method spvg --seed -1", "--seed: expected an integer in 0..2147483647, got '-1'"},
        {"--method spvg --seed 99999999999999999999", "got '99999999999999999999'"},
        {"--method spvg --sss-scale nan", "--sss-scale: expected a number in (0, 1000], got 'nan'"},
        {"--method spvg --sss-scale 0", "got '0'"},
        {"--method spvg --sss-scale 2x", "got '2x'"},
        {"--method spvg --heatmaps 1,x --heatmap-dir d", "--heatmaps: expected an integer in 0..100000, got 'x'"},
        {"--method spvg --heatmaps 1", "--heatmaps needs --heatmap-dir DIR"},
        {"--method spvg --define EMCV_BOGUS=1", "--define: unknown tunable 'EMCV_BOGUS'"},
        {"--method spvg --define EMCV_HISTORY_ETA_EMCM=0", "EMCV_HISTORY_ETA_EMCM takes a number in (0, 0.5]"},
        {"--method spvg --spp-budget 8 --target-variance 1e-4", "cannot be combined with --spp-budget"},
        {"--method spvg --spp-budget 0", "--spp-budget: expected a number in (0, 1024]"},
        {"--method spvg --spp-budget 100", "exceeds EMCV_HISTORY_N_MAX (64)"},
        {"--method spvg --target-variance 2", "--target-variance: expected a number in (0, 1]"},
        {"--method spvg --define", "--define: missing value"},
    });
    CHECK(emcv_cli_test::entries(dir) == 0);
    fs::remove_all(dir);
}

TEST_CASE("emcv-eval: a missing, folder or malformed scene exits 2 and names the file", "[cli][eval]") {
    const fs::path dir = emcv_cli_test::scratch_dir("eval-scene");
    const fs::path heatmaps = dir / "heatmaps";
    const fs::path malformed = fs::path(EMCV_CLI_APP_DATA) / "malformed.json";
    const std::string flags = "--method spvg --heatmaps 0 --heatmap-dir " + quoted(heatmaps) + " --scene ";
    emcv_cli_test::expect_error("emcv-eval", eval(flags + quoted(dir / "no-such.json")), 2,
                                "--scene: " + (dir / "no-such.json").string() + ": no such scene file or built-in");
    emcv_cli_test::expect_error("emcv-eval", eval(flags + quoted(dir)), 2,
                                "--scene: " + dir.string() + ": no such scene file or built-in");
    emcv_cli_test::expect_error("emcv-eval", eval(flags + quoted(malformed)), 2,
                                "--scene: " + malformed.string() + ": /: ");
    CHECK(emcv_cli_test::entries(dir) == 0);  // the heatmap folder is not made for a scene that fails
    fs::remove_all(dir);
}

TEST_CASE("emcv-eval: an --heatmap-dir that cannot be made exits 1 and names it", "[cli][eval]") {
    const fs::path dir = emcv_cli_test::scratch_dir("eval-heatmap-dir");
    const fs::path blocked = emcv_cli_test::make_blocker(dir) / "heatmaps";
    emcv_cli_test::expect_error("emcv-eval",
                                eval("--method spvg --scene static --heatmaps 0 --heatmap-dir " + quoted(blocked)), 1,
                                blocked.string());
    CHECK(emcv_cli_test::entries(dir) == 1);  // only the blocker
    fs::remove_all(dir);
}

#endif  // EMCV_EVAL
