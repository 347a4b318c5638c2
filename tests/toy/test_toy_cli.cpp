// SPDX-License-Identifier: MIT
// emcv-toy's command line: the --json contract, the CSV files, and bad input (exit status 2, the flag named,
// no CSV left behind).
#include <catch2/catch_test_macros.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "../support/run_command.hpp"

namespace fs = std::filesystem;

namespace {

fs::path scratch_dir(const std::string& name) {
    const fs::path dir = fs::temp_directory_path() / ("emcv-toy-cli-" + name);
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

emcv_test::command_result run_toy(const std::string& args) {
    return emcv_test::run_command(std::string("'") + EMCV_TOY_EXE + "' " + args);
}

}  // namespace

TEST_CASE("json output is exactly the documented object", "[toy][cli]") {
    const emcv_test::command_result o = run_toy("--json --seeds 20");
    REQUIRE(o.exit_code == 0);
    const nlohmann::json j = nlohmann::json::parse(o.out);
    REQUIRE(j.is_object());
    CHECK(j.size() == 4);
    for (const char* scenario : {"static", "dynamic"}) {
        REQUIRE(j.contains(scenario));
        CHECK(j[scenario].size() == 6);
        for (const char* key : {"f", "SF", "SF_EMA", "EMCM", "EMCM_hat", "GT"}) {
            INFO(scenario << '.' << key);
            REQUIRE(j[scenario].contains(key));
            CHECK(j[scenario][key].size() == 2);
            CHECK(j[scenario][key]["mean"].get<double>() > 0.0);
            CHECK(j[scenario][key]["sd"].get<double>() >= 0.0);
        }
    }
    CHECK(j["alpha_star"].size() == 2);
    CHECK(j["alpha_star"]["static"].is_number());
    CHECK(j["alpha_star"]["dynamic"].is_number());
    CHECK(j["seeds"].get<int>() == 20);
}

TEST_CASE("the text table names every residual and prints the time", "[toy][cli]") {
    const emcv_test::command_result o = run_toy("--seeds 5 --scenario dynamic");
    REQUIRE(o.exit_code == 0);
    for (const char* title : {"Res_f", "Res_SF", "Res_SF+EMA", "Res_EMCM", "ResHat_EMCM", "Res_GT", "dynamic h2",
                              "elapsed:"})
        CHECK(o.out.find(title) != std::string::npos);
    CHECK(o.out.find("static h1") == std::string::npos);
}

TEST_CASE("csv output writes one complete per-frame file per scenario", "[toy][cli]") {
    const fs::path dir = scratch_dir("csv");
    const fs::path csv = dir / "new" / "sub";  // created on demand
    const emcv_test::command_result o = run_toy("--seeds 3 --frames 40 --csv '" + csv.string() + "'");
    REQUIRE(o.exit_code == 0);
    for (const char* name : {"static.csv", "dynamic.csv"}) {
        INFO(name);
        std::ifstream in(csv / name);
        REQUIRE(in);
        std::string line;
        std::size_t rows = 0;
        std::getline(in, line);
        CHECK(line.rfind("frame,t,h,fbar,gbar,G,alpha_f", 0) == 0);
        while (std::getline(in, line)) ++rows;
        CHECK(rows == 40);
    }
    std::size_t entries = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(csv)) ++entries;
    CHECK(entries == 2);  // no temporary file left
    fs::remove_all(dir);
}

TEST_CASE("bad input exits with status 2, names the flag and writes no CSV", "[toy][cli]") {
    struct bad_case {
        const char* args;
        const char* names;
    };
    const bad_case cases[] = {
        {"--bogus", "--bogus"},
        {"--seeds abc", "--seeds"},
        {"--seeds 0", "--seeds"},
        {"--seeds -3", "--seeds"},
        {"--seeds", "--seeds"},
        {"--seed 1.5", "--seed"},
        {"--frames 10", "--frames"},
        {"--spp 1", "--spp"},
        {"--eta-cov 0", "--eta-cov"},
        {"--eta-cov 1.5", "--eta-cov"},
        {"--eta-res -0.2", "--eta-res"},
        {"--eta-res nan", "--eta-res"},
        {"--sf-ema-eta x", "--sf-ema-eta"},
        {"--scenario sometimes", "--scenario"},
        {"--t0 2", "--t0"},
        {"--first-frame later", "--first-frame"},
        {"--gt-alpha exact", "--gt-alpha"},
        {"--json=yes", "--json"},
    };
    for (const bad_case& c : cases) {
        const fs::path dir = scratch_dir("bad");
        const fs::path csv = dir / "csv";
        const emcv_test::command_result o = run_toy(std::string(c.args) + " --csv '" + csv.string() + "'");
        INFO("args: " << c.args << "\nstderr: " << o.err);
        CHECK(o.exit_code == 2);
        CHECK(o.err.find(c.names) != std::string::npos);
        CHECK(o.out.empty());
        CHECK_FALSE(fs::exists(csv));
        fs::remove_all(dir);
    }
}

TEST_CASE("an unwritable csv directory exits with status 2 and leaves nothing", "[toy][cli]") {
    const fs::path dir = scratch_dir("unwritable");
    const fs::path blocker = dir / "a-file";
    std::ofstream(blocker) << "not a directory\n";
    const emcv_test::command_result o = run_toy("--seeds 2 --csv '" + (blocker / "csv").string() + "'");
    INFO("stderr: " << o.err);
    CHECK(o.exit_code == 2);
    CHECK(o.err.find("--csv") != std::string::npos);
    CHECK(o.out.empty());
    std::size_t entries = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++entries;
    CHECK(entries == 1);  // only the blocker
    fs::remove_all(dir);
}
