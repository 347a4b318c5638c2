// SPDX-License-Identifier: MIT
// emcv-eval's numbers (the cost side of scripts/eval/run_eval.py), on a small headless run through llvmpipe:
//   layout     one row per frame and method, frame-major (each frame renders every method in turn, so that the
//              machine's load hits them alike), the scene's light curves in the `lights` column
//   counts     a fixed burley-N takes exactly N samples; diffuse records no SSS pass; the adaptive methods'
//              per-frame mean and max of N equal the dumped per-pixel heatmap's, reduced here on the CPU from
//              the sample-count and SSS-mask images (the row comes from the GPU's own reduction)
//   sss-scale  shrinking every mean free path to sub-pixel kernels takes cv to 0 samples, while SPVG keeps its
//              floor of 8 (the flag reaches the scene's materials)
#include <catch2/catch_test_macros.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "../support/run_command.hpp"

namespace fs = std::filesystem;

namespace {

const std::string data_dir = EMCV_APP_TEST_DATA;

struct row {
    std::string method, lights, sampling, timing, resolve;
    int frame = 0, max_spp = 0;
    double sss_ms = 0.0, frame_ms = 0.0, mean_spp = 0.0;
    std::size_t sss_pixels = 0;
};

/// Runs emcv-eval; skips when there is no OpenGL display at all (as tests/gpu does).
std::vector<row> run_eval(const std::string& args) {
    const emcv_test::command_result r = emcv_test::run_command("'" + std::string(EMCV_EVAL_EXE) + "' " + args);
    if (emcv_test::no_display(r)) SKIP("no OpenGL display: " << r.err);
    INFO("emcv-eval " << args << "\n" << r.err);
    REQUIRE(r.exit_code == 0);
    std::istringstream in(r.out);
    std::string line;
    REQUIRE(std::getline(in, line));
    REQUIRE(line == "scene,width,height,sss_scale,method,frame,sss_ms,frame_ms,mean_spp,max_spp,sss_pixels,lights,sampling,"
                    "timing,resolve");
    std::vector<row> rows;
    while (std::getline(in, line)) {
        const std::vector<std::string> f = emcv_test::split_fields(line, ',');
        INFO(line);
        REQUIRE(f.size() == 15);
        row x;
        x.method = f[4];
        x.frame = std::stoi(f[5]);
        x.sss_ms = std::stod(f[6]);
        x.frame_ms = std::stod(f[7]);
        x.mean_spp = std::stod(f[8]);
        x.max_spp = std::stoi(f[9]);
        x.sss_pixels = static_cast<std::size_t>(std::stoull(f[10]));
        x.lights = f[11];
        x.sampling = f[12];
        x.timing = f[13];
        x.resolve = f[14];
        rows.push_back(x);
    }
    return rows;
}

std::vector<double> read_csv_image(const fs::path& file) {
    std::ifstream in(file);
    std::vector<double> v;
    for (std::string line; std::getline(in, line);)
        for (const std::string& cell : emcv_test::split_fields(line, ',')) v.push_back(std::stod(cell));
    return v;
}

}  // namespace

TEST_CASE("emcv-eval: rows are frame-major, fixed counts are exact, and the light curve is reported",
          "[app][eval][gl]") {
    const std::vector<std::string> methods = {"diffuse", "burley-4", "spvg", "cv"};
    const std::vector<row> rows =
        run_eval("--scene '" + data_dir + "/switch.json' --size 48x48 --method diffuse,burley-4,spvg,cv --seed 3");
    REQUIRE(rows.size() == 6 * methods.size());  // the scene's 6 frames
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const row& x = rows[i];
        INFO("row " << i << ": " << x.method << " frame " << x.frame);
        CHECK(x.frame == int(i / methods.size()));      // every method of a frame before the next frame
        CHECK(x.method == methods[i % methods.size()]);
        CHECK(x.frame_ms > 0.0);
        CHECK(x.timing == "wall");  // auto on llvmpipe: its timer queries miss compute dispatches
        CHECK(x.resolve == "taa");  // the default: the frame an engine shows, its resolve in frame_ms
        // The key light steps 3 -> 0 at frame 3 (switch.json); the fill light stays at 1.
        CHECK(x.lights == (x.frame < 3 ? "key=3.000000;fill=1.000000" : "key=0.000000;fill=1.000000"));
        if (x.method == "diffuse") {
            CHECK(x.sss_ms == 0.0);  // no SSS pass is recorded for a method that does not scatter
            CHECK(x.mean_spp == 0.0);
            CHECK(x.max_spp == 0);
        } else {
            CHECK(x.sss_pixels > 0);  // the sphere is on screen
            CHECK(x.sss_ms > 0.0);
        }
        if (x.method == "burley-4") {
            CHECK(x.mean_spp == 4.0);
            CHECK(x.max_spp == 4);
        }
        if ((x.method == "spvg" || x.method == "cv") && x.frame < 2) CHECK(x.mean_spp == 64.0);  // no history yet
    }
}

TEST_CASE("emcv-eval --timing gpu: every frame's row once, frame-major, once its stamps arrived", "[app][eval][gl]") {
    const std::vector<std::string> methods = {"burley-4", "cv"};
    const std::vector<row> rows = run_eval("--scene '" + data_dir + "/switch.json' --size 48x48 --method burley-4,cv "
                                           "--seed 3 --timing gpu");
    REQUIRE(rows.size() == 6 * methods.size());
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const row& x = rows[i];
        INFO("row " << i << ": " << x.method << " frame " << x.frame);
        CHECK(x.frame == int(i / methods.size()));
        CHECK(x.method == methods[i % methods.size()]);
        CHECK(x.timing == "gpu");
        CHECK(x.frame_ms >= x.sss_ms);
        CHECK(x.sss_ms >= 0.0);
    }
    const emcv_test::command_result bad = emcv_test::run_command(
        "'" + std::string(EMCV_EVAL_EXE) + "' --method burley-4 --timing cpu");
    CHECK(bad.exit_code == 2);
    CHECK(bad.err == "emcv-eval: --timing: expected auto, wall or gpu, got 'cpu'\n");
    CHECK(bad.out.empty());
}

TEST_CASE("emcv-eval --resolve none: no resolve in the rows; the reference never resolves; a bad value; --jitter", "[app][eval][gl]") {
    for (const row& x : run_eval("--scene '" + data_dir + "/switch.json' --size 48x48 --method burley-4,reference "
                                 "--seed 3 --resolve none"))
        CHECK(x.resolve == "none");
    for (const row& x : run_eval("--scene '" + data_dir + "/switch.json' --size 48x48 --method burley-4,reference "
                                 "--seed 3 --resolve taa"))
        CHECK(x.resolve == (x.method == "reference" ? "none" : "taa"));
    const emcv_test::command_result bad = emcv_test::run_command(
        "'" + std::string(EMCV_EVAL_EXE) + "' --method burley-4 --resolve yes");
    CHECK(bad.exit_code == 2);
    CHECK(bad.err == "emcv-eval: --resolve: expected none or taa, got 'yes'\n");
    CHECK(bad.out.empty());
    for (const row& x : run_eval("--scene '" + data_dir + "/switch.json' --size 48x48 --frames 2 --method "
                                 "burley-4,reference --seed 3 --jitter"))
        CHECK(x.resolve == (x.method == "reference" ? "none" : "taa+jitter"));
    const emcv_test::command_result no_resolve = emcv_test::run_command(
        "'" + std::string(EMCV_EVAL_EXE) + "' --method burley-4 --resolve none --jitter");
    CHECK(no_resolve.exit_code == 2);
    CHECK(no_resolve.err == "emcv-eval: --jitter: needs --resolve taa (the jitter is what the resolve accumulates; "
                            "the raw frame alone would only move)\n");
    CHECK(no_resolve.out.empty());
}

TEST_CASE("emcv-eval: the adaptive rows' mean and max of N equal the dumped heatmaps'", "[app][eval][gl]") {
    const fs::path dir = fs::temp_directory_path() / "emcv-app-eval-heatmaps";
    fs::remove_all(dir);
    const std::vector<row> rows = run_eval("--scene '" + data_dir + "/switch.json' --size 48x48 --method spvg,cv "
                                           "--seed 3 --heatmaps 2,4 --heatmap-dir '" + dir.string() + "'");
    int compared = 0;
    for (const row& x : rows) {
        if (x.frame != 2 && x.frame != 4) continue;
        const std::string stem = x.method + ".f" + std::to_string(x.frame);
        INFO(stem);
        const std::vector<double> n = read_csv_image(dir / (stem + ".samples.csv"));
        const std::vector<double> mask = read_csv_image(dir / (stem + ".mask.csv"));
        REQUIRE(n.size() == 48u * 48u);
        REQUIRE(mask.size() == n.size());
        double sum = 0.0, max_n = 0.0, sss = 0.0;
        for (std::size_t i = 0; i < n.size(); ++i) {
            if (mask[i] == 0.0) CHECK(n[i] == 0.0);  // no samples outside SSS pixels
            sss += mask[i] != 0.0 ? 1.0 : 0.0;
            sum += n[i];
            max_n = std::max(max_n, n[i]);
        }
        CHECK(sss == double(x.sss_pixels));
        CHECK(std::fabs(sum / sss - x.mean_spp) <= 0.0005);  // the row prints mean_spp with 3 decimals
        CHECK(max_n == double(x.max_spp));
        CHECK(fs::exists(dir / (stem + ".alpha.csv")) == (x.method == "cv"));
        ++compared;
    }
    CHECK(compared == 4);
    fs::remove_all(dir);
}

TEST_CASE("emcv-eval: --sss-scale shrinks the kernels under a pixel and cv takes no samples", "[app][eval][gl]") {
    const std::string args = "--scene '" + data_dir + "/tiny.json' --size 48x48 --method spvg,cv --seed 3 --frames 4";
    std::map<std::string, double> full, shrunk;  // method -> mean N over frames 2 and 3
    for (const row& x : run_eval(args))
        if (x.frame >= 2) full[x.method] += x.mean_spp / 2.0;
    for (const row& x : run_eval(args + " --sss-scale 0.001"))
        if (x.frame >= 2) shrunk[x.method] += x.mean_spp / 2.0;
    INFO("cv " << full["cv"] << " -> " << shrunk["cv"] << "; spvg " << full["spvg"] << " -> " << shrunk["spvg"]);
    CHECK(full["cv"] >= 1.0);  // tiny.json's kernels cover pixels at this size: at least the floor N_MIN
    CHECK(shrunk["cv"] == 0.0);
    CHECK(shrunk["spvg"] >= 1.0);  // spvg has no control to stand in: it keeps sampling
}

TEST_CASE("emcv-eval: a budget run spends B per SSS pixel and every row names the mode", "[app][eval][gl]") {
    const std::string args = "--scene '" + data_dir + "/tiny.json' --size 48x48 --method spvg,cv --seed 3 --frames 4";
    for (const row& x : run_eval(args)) CHECK(x.sampling == "target variance 0.0001");
    for (const row& x : run_eval(args + " --spp-budget 6")) {
        INFO(x.method << " frame " << x.frame);
        CHECK(x.sampling == "budget 6 spp");
        // Every frame spends B (the first frames' pixels without a variance take B; from frame 2 the solve):
        // a few hundred SSS pixels round stochastically within a few hundredths of a sample.
        if (x.sss_pixels > 0) CHECK(std::fabs(x.mean_spp - 6.0) <= 0.12);
    }
}
