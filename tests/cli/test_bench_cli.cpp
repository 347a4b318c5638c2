// SPDX-License-Identifier: MIT
// emcv-bench's bad input: unknown arguments, bad enumerated and typed flag values, an unwritable or empty
// --benchmark_out; and --benchmark_out itself: complete or absent, never half-written.
#include <catch2/catch_test_macros.hpp>

#include <filesystem>
#include <string>

#include "cli_expect.hpp"

#ifdef EMCV_BENCH

namespace fs = std::filesystem;
using emcv_cli_test::entries;
using emcv_cli_test::scratch_dir;

namespace {

// no benchmark matches: the error paths run nothing
std::string bench(const std::string& args) {
    return std::string("'") + EMCV_BENCH + "' --benchmark_filter=NO_BENCHMARK_HAS_THIS_NAME " + args;
}

}  // namespace

TEST_CASE("emcv-bench: bad usage exits 2 with one line and writes no file", "[cli][bench]") {
    const emcv_cli_test::bad_usage cases[] = {
        {"--bogus", "unknown argument '--bogus'"},
        {"scalar", "unknown argument 'scalar'"},
        {"--benchmark_format=xml", "--benchmark_format must be console, json or csv, got 'xml'"},
        {"--benchmark_out_format=yaml", "--benchmark_out_format must be console, json or csv, got 'yaml'"},
        {"--benchmark_time_unit=h", "--benchmark_time_unit must be ns, us, ms or s, got 'h'"},
        {"--benchmark_out=", "--benchmark_out needs a file name"},
    };
    const fs::path dir = scratch_dir("bench-bad");
    const fs::path out = dir / "out.json";
    for (const emcv_cli_test::bad_usage& c : cases) {
        // --benchmark_out first, so that a later bad argument must also remove the partial file
        emcv_cli_test::expect_error("emcv-bench", bench("--benchmark_out='" + out.string() + "' " + c.args), 2,
                                    c.names);
        CHECK(entries(dir) == 0);
    }
    fs::remove_all(dir);
}

TEST_CASE("emcv-bench: a flag value of the wrong type exits 2", "[cli][bench]") {
    // Google Benchmark's own message, prefixed by the program path, names the flag and the value
    const emcv_test::command_result r = emcv_test::run_command(bench("--benchmark_min_time=abc"));
    INFO(r.err);
    CHECK(r.exit_code == 2);
    CHECK(r.out.empty());
    CHECK(emcv_cli_test::first_line(r.err).find("--benchmark_min_time") != std::string::npos);
}

TEST_CASE("emcv-bench: an unwritable --benchmark_out exits 2 and leaves nothing", "[cli][bench]") {
    const fs::path dir = scratch_dir("bench-unwritable");
    const fs::path blocker = emcv_cli_test::make_blocker(dir);
    emcv_cli_test::expect_error("emcv-bench", bench("--benchmark_out='" + (blocker / "out.json").string() + "'"), 2,
                                "cannot write --benchmark_out '" + (blocker / "out.json").string() + "'");
    CHECK(entries(dir) == 1);  // only the blocker
    fs::remove_all(dir);
}

TEST_CASE("emcv-bench: --benchmark_out appears complete, under its own name only", "[cli][bench]") {
    const fs::path dir = scratch_dir("bench-out");
    const fs::path out = dir / "out.json";
    const emcv_test::command_result r = emcv_test::run_command(
        std::string("'") + EMCV_BENCH + "' --benchmark_filter='^scalar/float/emcm$' --benchmark_min_time=0.001 "
        "--benchmark_out_format=json --benchmark_out='" + out.string() + "'");
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    CHECK(entries(dir) == 1);  // no .partial left
    const std::string json = emcv_test::read_file(out);
    CHECK(json.find("\"name\": \"scalar/float/emcm\"") != std::string::npos);
    CHECK(json.rfind("}") == json.find_last_not_of(" \n"));  // the closing brace of a finished document
    fs::remove_all(dir);
}

#endif  // EMCV_BENCH
