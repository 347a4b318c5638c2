// SPDX-License-Identifier: MIT
// emcv-demo's command line: every bad-input path gives one line on stderr naming the problem, the documented
// exit status, and nothing under --out; a small headless run writes the documented files; --window runs a few
// frames under Xvfb.
#include <catch2/catch_test_macros.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "../support/run_command.hpp"
#include "gl/image_io.hpp"

namespace fs = std::filesystem;

namespace {

const std::string data_dir = EMCV_APP_TEST_DATA;

/// A fresh scratch folder; the --out given to a run is a child of it that must not exist afterwards on error.
fs::path scratch_dir(const std::string& name) {
    const fs::path dir = fs::temp_directory_path() / ("emcv-app-cli-" + name);
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

emcv_test::command_result run_demo(const std::string& args, const std::string& environment = "") {
    return emcv_test::run_command(environment + " '" + std::string(EMCV_DEMO_EXE) + "' " + args);
}

std::size_t count_lines(const std::string& text) {
    std::size_t n = 0;
    for (char c : text) n += c == '\n';
    return n;
}

/// The bad-input contract: exit status, exactly one stderr line starting "emcv-demo: " that contains
/// `must_name`, nothing on stdout, and `out` not created.
void check_rejected(const std::string& args, int status, const std::string& must_name, const fs::path& out,
                    const std::string& environment = "") {
    const emcv_test::command_result r = run_demo(args + " --out '" + out.string() + "'", environment);
    INFO("args: " << args << "\nstderr: " << r.err << "stdout: " << r.out);
    CHECK(r.exit_code == status);
    CHECK(count_lines(r.err) == 1);
    CHECK(r.err.rfind("emcv-demo: ", 0) == 0);
    CHECK(r.err.find(must_name) != std::string::npos);
    CHECK(r.out.empty());
    CHECK_FALSE(fs::exists(out));
}

}  // namespace

TEST_CASE("the help text (--help) lists every flag and exits 0", "[app][cli]") {
    const emcv_test::command_result r = run_demo("--help");
    REQUIRE(r.exit_code == 0);
    for (const char* flag : {"--scene", "--method", "--frames", "--size", "--out", "--seed", "--exr", "--window",
                             "--list-scenes", "--print-passes", "--approximate-cdf", "--define", "--list-methods",
                             "--help"})
        CHECK(r.out.find(flag) != std::string::npos);
}

TEST_CASE("unknown and malformed flags: one line, exit 2, nothing written", "[app][cli]") {
    const fs::path out = scratch_dir("flags") / "out";
    const std::string scene = "--scene '" + data_dir + "/tiny.json' ";
    check_rejected(scene + "--bogus", 2, "--bogus", out);
    check_rejected(scene + "--frames --size 16x16", 2, "--frames: expected an integer", out);
    const emcv_test::command_result last = run_demo(scene + "--frames");
    CHECK(last.exit_code == 2);
    CHECK(last.err == "emcv-demo: --frames: missing value\n");
    check_rejected(scene + "--frames abc", 2, "--frames", out);
    check_rejected(scene + "--frames 0", 2, "--frames", out);
    check_rejected(scene + "--frames -3", 2, "--frames", out);
    check_rejected(scene + "--seed 1.5", 2, "--seed", out);
    check_rejected(scene + "--seed 4294967296", 2, "--seed", out);
    check_rejected(scene + "--method bogus", 2, "--method: unknown method 'bogus'", out);
    check_rejected(scene + "--method burley-0", 2, "'burley-0'", out);
    check_rejected(scene + "--method burley-1025", 2, "'burley-1025'", out);
    check_rejected(scene + "--method separable-12", 2, "'separable-12'", out);
    check_rejected(scene + "--method diffuse,,reference", 2, "--method", out);
    check_rejected(scene + "--exr=yes", 2, "--exr: takes no value", out);
    check_rejected(scene + "--define EMCV_BOGUS=1", 2, "--define: unknown tunable 'EMCV_BOGUS'", out);
    check_rejected(scene + "--define EMCV_HISTORY_N_MAX=0", 2, "EMCV_HISTORY_N_MAX takes an integer in [1, 1024]", out);
    check_rejected(scene + "--define EMCV_HISTORY_TARGET=1e-4x", 2, "EMCV_HISTORY_TARGET takes a number in (0, 1]", out);
    check_rejected(scene + "--define EMCV_HISTORY_N_MAX", 2, "--define: expected NAME=VALUE", out);
    check_rejected(scene + "--spp-budget 8 --target-variance 1e-4", 2,
                   "--target-variance: cannot be combined with --spp-budget", out);
    check_rejected(scene + "--spp-budget 0", 2, "--spp-budget: expected a number in (0, 1024]", out);
    check_rejected(scene + "--spp-budget eight", 2, "--spp-budget: expected a number in (0, 1024]", out);
    check_rejected(scene + "--target-variance -1", 2, "--target-variance: expected a number in (0, 1]", out);
    check_rejected(scene + "--spp-budget 65", 2, "a budget of 65 samples per pixel exceeds EMCV_HISTORY_N_MAX (64)", out);
    check_rejected(scene + "--define EMCV_HISTORY_N_MIN=9 --define EMCV_HISTORY_N_MAX=8", 2,
                   "EMCV_HISTORY_N_MIN (9) exceeds EMCV_HISTORY_N_MAX (8)", out);
    check_rejected(scene + "--list-methods=yes", 2, "--list-methods: takes no value", out);
    check_rejected(scene + "--window", 2, "--window: cannot be combined with --out", out);
    check_rejected(scene + "--no-frames --exr", 2, "--no-frames: cannot be combined with --exr", out);
    const emcv_test::command_result alone = run_demo(scene + "--no-frames");
    CHECK(alone.exit_code == 2);
    CHECK(alone.err == "emcv-demo: --no-frames: needs --out (it only leaves out the frames)\n");
}

TEST_CASE("zero, malformed and absurd sizes: one line, exit 2, nothing written", "[app][cli]") {
    const fs::path out = scratch_dir("size") / "out";
    const std::string scene = "--scene '" + data_dir + "/tiny.json' ";
    for (const char* size : {"0x64", "64x0", "0x0", "64", "64x", "x64", "64x64x2", "-64x64", "64X64", "6 4x64"})
        check_rejected(scene + "--size '" + size + "'", 2, "--size", out);
    check_rejected(scene + "--size 8193x16", 2, "at most 8192", out);
    check_rejected(scene + "--size 8192x8192", 2, "pixels", out);  // 67.1 Mpixel > 64 Mpixel
    check_rejected(scene + "--size 99999999999x1", 2, "--size", out);
}

TEST_CASE("missing, malformed and inconsistent scenes: one line naming the file, exit 2", "[app][cli]") {
    const fs::path out = scratch_dir("scene") / "out";
    check_rejected("--scene /nonexistent/scene.json", 2, "/nonexistent/scene.json", out);
    check_rejected("--scene no-such-builtin-scene", 2, "no-such-builtin-scene", out);
    check_rejected("--scene '" + data_dir + "/malformed.json'", 2, "malformed.json", out);
    check_rejected("--scene '" + data_dir + "/unknown_mesh.json'", 2, "teapot", out);
    check_rejected("--scene '" + data_dir + "/missing_mesh_file.json'", 2, "no-such-mesh.obj", out);
}

TEST_CASE("an --out that cannot be created or written: one line, exit 2", "[app][cli]") {
    const fs::path dir = scratch_dir("unwritable");
    const fs::path file = dir / "a-file";
    std::ofstream(file) << "not a folder\n";
    const std::string scene = "--scene '" + data_dir + "/tiny.json' --frames 1 --size 16x16";
    // Under a regular file (root ignores permission bits, so a chmod would not make this fail).
    check_rejected(scene, 2, "--out", file / "out");
    CHECK(emcv_test::read_file(file) == "not a folder\n");
    // The file itself.
    const emcv_test::command_result r = run_demo(scene + " --out '" + file.string() + "'");
    CHECK(r.exit_code == 2);
    CHECK(r.err.find("is not a directory") != std::string::npos);
    CHECK(count_lines(r.err) == 1);
    // A read-only file system (EROFS applies to root too).
    check_rejected(scene, 2, "not writable", "/proc/emcv-demo-out");
}

TEST_CASE("no OpenGL platform: one line, exit 1, nothing written", "[app][cli]") {
    const fs::path out = scratch_dir("no-gl") / "out";
    check_rejected("--scene '" + data_dir + "/tiny.json' --frames 1 --size 16x16", 1, "no OpenGL context", out,
                   "EMCV_GL_PLATFORMS=none");
    // A platform that fails with a reason: the context's multi-line report is joined into the one line.
    check_rejected("--scene '" + data_dir + "/tiny.json' --frames 1 --size 16x16", 1, "window: glfwInit failed", out,
                   "env -u DISPLAY -u WAYLAND_DISPLAY EMCV_GL_PLATFORMS=window");
}

TEST_CASE("an image holding NaN or Inf stops the run: one line, exit 1, nothing written", "[app][cli][gl][image-files]") {
    // A valid scene whose light (3e38 x colour 3) overflows fp32 radiance: metrics would silently be NaN.
    const fs::path out = scratch_dir("overflow") / "out";
    const emcv_test::command_result r = run_demo("--scene '" + data_dir +
                                                 "/overflow.json' --size 32x32 --frames 2 --method diffuse --out '" +
                                                 out.string() + "'");
    if (emcv_test::no_display(r)) SKIP("no OpenGL display: " << r.err);
    INFO(r.err);
    CHECK(r.exit_code == 1);
    CHECK(count_lines(r.err) == 1);
    CHECK(r.err.find("NaN or infinite") != std::string::npos);
    CHECK_FALSE(fs::exists(out));
}

TEST_CASE("the scene list (--list-scenes) names every built-in scene file with a description",
          "[app][cli][image-files]") {
    const emcv_test::command_result r = run_demo("--list-scenes");
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    std::set<std::string> listed;
    std::istringstream lines(r.out);
    for (std::string line; std::getline(lines, line);) {
        const auto space = line.find(' ');
        REQUIRE(space != std::string::npos);                     // a name, then its description
        CHECK(line.find_first_not_of(' ', space) != std::string::npos);
        CHECK(line.find("does not load") == std::string::npos);
        listed.insert(line.substr(0, space));
    }
    std::set<std::string> files;
    for (const auto& entry : fs::directory_iterator(EMCV_BUILTIN_SCENE_DIR))
        if (entry.path().extension() == ".json" && entry.path().filename() != "scene.schema.json")
            files.insert(entry.path().stem().string());
    CHECK(listed == files);
    CHECK(listed.count("light-off") == 1);
}

TEST_CASE("the pass list (--print-passes) is printed per method without a GL context", "[app][cli]") {
    const std::string scene = "--scene '" + data_dir + "/tiny.json' --frames 3 --print-passes ";
    // The later --method wins (scripts/quickstart.sh relies on it).
    const emcv_test::command_result r =
        run_demo(scene + "--method reference --method diffuse,burley-8", "EMCV_GL_PLATFORMS=none");
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    // The temporal resolve (--resolve taa, the default) ends every list.
    CHECK(r.out.find("method diffuse:\n  frames 0-2: gbuffer, shadow:key, lighting, composite, resolve\n") !=
          std::string::npos);
    CHECK(r.out.find("method burley-8:\n  frames 0-2: gbuffer, shadow:key, lighting, sss-burley, "
                     "composite, resolve\n") != std::string::npos);
    CHECK(r.out.find("method reference") == std::string::npos);
    // Under a quality target (the default) the adaptive methods take burley's passes (their burley pass plans N
    // itself); under a budget one pass more, the samples pass that solves the frame's scale, on the first frame:
    // tiny.json's camera holds still, so each frame's burley pass plans the next frame and frames 1-2 record
    // burley's passes; with EMCV_HISTORY_PLAN_AHEAD=0 every frame records the samples pass.
    const emcv_test::command_result q = run_demo(scene + "--method cv,burley-8", "EMCV_GL_PLATFORMS=none");
    INFO(q.err);
    REQUIRE(q.exit_code == 0);
    CHECK(q.out.find("method cv:\n  frames 0-2: gbuffer, shadow:key, lighting, sss-burley, composite, resolve\n") !=
          std::string::npos);
    {
        const emcv_test::command_result b = run_demo(scene + "--method cv,burley-8 --spp-budget 8", "EMCV_GL_PLATFORMS=none");
        INFO(b.err);
        REQUIRE(b.exit_code == 0);
        CHECK(b.out.find("method cv:\n  frames 0-0: gbuffer, shadow:key, lighting, sss-adaptive-samples, "
                         "sss-burley, composite, resolve\n  frames 1-2: gbuffer, shadow:key, lighting, sss-burley, "
                         "composite, resolve\n") != std::string::npos);
        const emcv_test::command_result a = run_demo(scene + "--method cv --spp-budget 8 --define EMCV_HISTORY_PLAN_AHEAD=0",
                                                     "EMCV_GL_PLATFORMS=none");
        INFO(a.err);
        REQUIRE(a.exit_code == 0);
        CHECK(a.out == "method cv:\n  frames 0-2: gbuffer, shadow:key, lighting, sss-adaptive-samples, sss-burley, "
                       "composite, resolve\n");
    }
    const emcv_test::command_result b = run_demo(scene + "--method cv,burley-8 --spp-budget 8", "EMCV_GL_PLATFORMS=none");
    CHECK(b.out.find("method burley-8:\n  frames 0-2: gbuffer, shadow:key, lighting, sss-burley, "
                     "composite, resolve\n") != std::string::npos);
}

TEST_CASE("print-passes walks the renderer's planner: the reference records no SSS pass while it reuses", "[app][cli]") {
    // tiny.json's camera and lights do not change: frame 0 renders the reference, frames 1-2 show it again.
    const emcv_test::command_result r =
        run_demo("--scene '" + data_dir + "/tiny.json' --frames 3 --print-passes --method reference",
                 "EMCV_GL_PLATFORMS=none");
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    CHECK(r.out == "method reference:\n"
                   "  frames 0-0: gbuffer, shadow:key, lighting, sss-burley, composite\n"
                   "  frames 1-2: gbuffer, shadow:key, lighting, composite\n");
}

TEST_CASE("list-methods prints the method table: name, SSS passes, help", "[app][cli]") {
    const emcv_test::command_result r = run_demo("--list-methods", "EMCV_GL_PLATFORMS=none");
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    std::vector<std::string> names, passes;
    std::istringstream lines(r.out);
    for (std::string line; std::getline(lines, line);) {
        const std::size_t a = line.find('\t'), b = line.find('\t', a + 1);
        REQUIRE(b != std::string::npos);
        CHECK(b + 1 < line.size());  // a help line
        names.push_back(line.substr(0, a));
        passes.push_back(line.substr(a + 1, b - a - 1));
    }
    CHECK(names == std::vector<std::string>{"diffuse", "burley-16", "burley-sobol-N", "separable-17", "reference", "spvg",
                                            "cv", "cv-notex"});
    CHECK(passes == std::vector<std::string>{"none", "burley", "burley", "separable", "burley", "adaptive", "adaptive",
                                             "adaptive"});
}

TEST_CASE("a small headless run writes frames and complete metrics files", "[app][cli][gl][image-files]") {
    const fs::path out = scratch_dir("run") / "out";
    const emcv_test::command_result r = run_demo("--scene '" + data_dir +
                                                 "/tiny.json' --size 64x64 --frames 3 --method diffuse,burley-4 "
                                                 "--exr --seed 7 --out '" + out.string() + "'");
    if (emcv_test::no_display(r)) SKIP("no OpenGL display: " << r.err);
    INFO(r.err << r.out);
    REQUIRE(r.exit_code == 0);
    CHECK(r.err.empty());  // stderr is not a terminal here: no progress bar

    const std::vector<std::string> methods = {"diffuse", "burley-4", "reference"};  // the reference is added
    for (const std::string& m : methods) {
        CHECK(r.out.find(m) != std::string::npos);  // the summary has a line per method
        for (int f = 0; f < 3; ++f)
            for (const char* ext : {"png", "exr"}) {
                const fs::path frame = out / m / ("frame-000" + std::to_string(f) + "." + ext);
                INFO(frame);
                CHECK(fs::is_regular_file(frame));
            }
    }
    for (const auto& entry : fs::recursive_directory_iterator(out))  // no temporary left behind
        CHECK(entry.path().filename().string().find(".tmp") == std::string::npos);

    std::ifstream csv(out / "metrics.csv");
    std::string line;
    REQUIRE(std::getline(csv, line));
    CHECK(line == "frame,method,sss_ms,frame_ms,mean_spp,max_spp,psnr_db,psnr_sss_db,rel_mse,temporal_error,"
                  "psnr_resolved_db,psnr_sss_resolved_db,temporal_error_resolved,tracked_mse");
    std::size_t rows = 0;
    while (std::getline(csv, line)) {
        INFO(line);
        const std::vector<std::string> f = emcv_test::split_fields(line, ',');
        REQUIRE(f.size() == 14);
        ++rows;
        const bool reference = f[1] == "reference";
        for (std::size_t c : {2u, 3u, 4u, 5u, 8u}) CHECK(std::isfinite(std::stod(f[c])));
        CHECK(std::stod(f[3]) > 0.0);  // frame_ms
        if (reference) {
            CHECK(f[6] == "inf");
            CHECK(std::stod(f[8]) == 0.0);
        } else {
            CHECK(std::isfinite(std::stod(f[6])));
            CHECK(std::isfinite(std::stod(f[7])));  // the sphere fills part of the frame: SSS pixels exist
        }
        if (f[1] == "burley-4") {
            CHECK(std::stod(f[4]) == 4.0);
            CHECK(f[5] == "4");
            CHECK(std::stod(f[2]) > 0.0);
        }
        if (f[1] == "diffuse") CHECK(std::stod(f[2]) == 0.0);  // no SSS pass recorded
        if (f[0] == "0") CHECK(f[9].empty());                  // no previous frame
        else CHECK(std::stod(f[9]) >= 0.0);
        // --resolve taa by default: the shown image's PSNR (the reference shows its raw image: inf again)
        if (reference) CHECK(f[10] == "inf");
        else CHECK(std::isfinite(std::stod(f[10])));
        CHECK(f[12].empty() == (f[0] == "0"));
        // The tracked value's squared error: 0 for the reference, none without SSS passes, else a number
        if (reference) CHECK(std::stod(f[13]) == 0.0);
        else if (f[1] == "diffuse") CHECK(f[13].empty());
        else CHECK(std::stod(f[13]) >= 0.0);
    }
    CHECK(rows == 3 * methods.size());

    const nlohmann::json j = nlohmann::json::parse(emcv_test::read_file(out / "metrics.json"));
    REQUIRE(j["rows"].size() == rows);
    CHECK(j["timing"] == "wall");  // auto on llvmpipe
    CHECK(j["resolve"] == "taa");
    CHECK(r.out.find("clock: wall clock, glFinish at every pass boundary") != std::string::npos);
    for (const auto& row : j["rows"]) {
        CHECK(row.size() == 15);  // the columns and the passes
        if (row["method"] == "reference") CHECK(row["psnr_db"].is_null());
        else CHECK(row["psnr_db"].is_number());
        double sum = 0.0;  // frame_ms is the sum of the passes, added in recording order
        for (const auto& p : row["passes"]) sum += p["ms"].get<double>();
        CHECK(sum == row["frame_ms"].get<double>());
        CHECK(row["passes"].front()["name"] == "gbuffer");
    }
}

TEST_CASE("emcv-demo --timing gpu: each frame's times arrive late and land on their own rows", "[app][cli][gl]") {
    const fs::path out = scratch_dir("timing-gpu") / "out";
    const emcv_test::command_result r = run_demo("--scene '" + data_dir + "/tiny.json' --size 32x32 --frames 5 "
                                                 "--method burley-4 --timing gpu --no-frames --out '" + out.string() + "'");
    if (emcv_test::no_display(r)) SKIP("no OpenGL display: " << r.err);
    INFO(r.err << r.out);
    REQUIRE(r.exit_code == 0);
    CHECK(r.out.find("clock: GPU timestamps at every pass boundary") != std::string::npos);
    const nlohmann::json j = nlohmann::json::parse(emcv_test::read_file(out / "metrics.json"));
    CHECK(j["timing"] == "gpu");
    REQUIRE(j["rows"].size() == 10);  // burley-4 and the reference, 5 frames
    for (const auto& row : j["rows"]) {
        INFO(row.dump());
        REQUIRE(row["passes"].size() >= 3);  // every frame's passes were measured, none dropped
        double sum = 0.0, sss = 0.0;
        for (const auto& p : row["passes"]) {
            sum += p["ms"].get<double>();
            if (p["name"].get<std::string>().rfind("sss-", 0) == 0) sss += p["ms"].get<double>();
        }
        CHECK(sum == row["frame_ms"].get<double>());
        CHECK(sss == row["sss_ms"].get<double>());
    }
    const emcv_test::command_result bad = run_demo("--method burley-4 --timing=fast");
    CHECK(bad.exit_code == 2);
    CHECK(bad.err == "emcv-demo: --timing: expected auto, wall or gpu, got 'fast'\n");
}

TEST_CASE("emcv-demo --resolve: taa records the resolve pass and writes the shown frames, none neither; --jitter needs taa", "[app][cli][gl][image-files]") {
    for (const char* mode : {"taa", "none"}) {
        INFO(mode);
        const bool taa = std::string(mode) == "taa";
        const fs::path out = scratch_dir(std::string("resolve-") + mode) / "out";
        const emcv_test::command_result r = run_demo("--scene '" + data_dir + "/tiny.json' --size 32x32 --frames 3 "
                                                     "--method burley-4 --resolve " + mode + " --out '" + out.string() + "'");
        if (emcv_test::no_display(r)) SKIP("no OpenGL display: " << r.err);
        INFO(r.err << r.out);
        REQUIRE(r.exit_code == 0);
        const nlohmann::json j = nlohmann::json::parse(emcv_test::read_file(out / "metrics.json"));
        CHECK(j["resolve"] == mode);
        for (const auto& row : j["rows"]) {
            bool has_resolve = false;
            for (const auto& p : row["passes"]) has_resolve = has_resolve || p["name"] == "resolve";
            CHECK(has_resolve == (taa && row["method"] == "burley-4"));  // never the reference's
            CHECK(row["psnr_resolved_db"].is_null() == (!taa || row["method"] == "reference"));
        }
        CHECK(fs::is_regular_file(out / "burley-4" / "resolved-0002.png") == taa);
        CHECK_FALSE(fs::exists(out / "reference" / "resolved-0002.png"));
        const emcv_test::command_result passes = run_demo("--scene '" + data_dir + "/tiny.json' --method burley-4 "
                                                          "--print-passes --resolve " + mode);
        CHECK((passes.out.find("composite, resolve") != std::string::npos) == taa);
    }
    const emcv_test::command_result bad = run_demo("--method burley-4 --resolve fxaa");
    CHECK(bad.exit_code == 2);
    CHECK(bad.err == "emcv-demo: --resolve: expected none or taa, got 'fxaa'\n");
    // --jitter: only with the resolve, and named in metrics.json's "resolve"
    const fs::path out = scratch_dir("resolve-jitter") / "out";
    const emcv_test::command_result r = run_demo("--scene '" + data_dir + "/tiny.json' --size 32x32 --frames 2 "
                                                 "--method burley-4 --jitter --out '" + out.string() + "'");
    if (emcv_test::no_display(r)) SKIP("no OpenGL display: " << r.err);
    REQUIRE(r.exit_code == 0);
    CHECK(nlohmann::json::parse(emcv_test::read_file(out / "metrics.json"))["resolve"] == "taa+jitter");
    const fs::path none_out = scratch_dir("resolve-jitter-none") / "out";
    const emcv_test::command_result no_resolve = run_demo("--method burley-4 --resolve none --jitter --out '" +
                                                          none_out.string() + "'");
    CHECK(no_resolve.exit_code == 2);
    CHECK(no_resolve.err == "emcv-demo: --jitter: needs --resolve taa (the jitter is what the resolve accumulates; "
                            "the raw frame alone would only move)\n");
    CHECK_FALSE(fs::exists(none_out));
}

TEST_CASE("OpenImageIO is loaded only by a run that reads or writes an image file", "[app][cli][gl][image-files]") {
    // The image files go through a module loaded on first use (demo/image/oiio_module.hpp): the dynamic
    // loader's log (LD_DEBUG=libs, on stderr) names every library a process loads.
    const auto loads_oiio = [](const emcv_test::command_result& r) {
        return r.err.find("libOpenImageIO") != std::string::npos;
    };
    const emcv_test::command_result usage = run_demo("--size 0x0", "LD_DEBUG=libs");
    CHECK(usage.exit_code == 2);
    CHECK_FALSE(loads_oiio(usage));
    const std::string run = "--scene '" + data_dir + "/tiny.json' --size 32x32 --frames 1 --method burley-4";
    const emcv_test::command_result metrics =
        run_demo(run + " --no-frames --out '" + (scratch_dir("oiio-metrics") / "out").string() + "'", "LD_DEBUG=libs");
    if (emcv_test::no_display(metrics)) SKIP("no OpenGL display");
    CHECK(metrics.exit_code == 0);
    CHECK_FALSE(loads_oiio(metrics));
    const emcv_test::command_result frames =
        run_demo(run + " --out '" + (scratch_dir("oiio-frames") / "out").string() + "'", "LD_DEBUG=libs");
    CHECK(frames.exit_code == 0);
    CHECK(loads_oiio(frames));
}

TEST_CASE("a missing OpenImageIO module: one line naming it, exit 1, nothing written", "[app][cli][gl][image-files]") {
    // Checked once the context exists (a missing GL is named first), before anything is rendered or written.
    const fs::path out = scratch_dir("no-oiio-module") / "out";
    const std::string args = "--scene '" + data_dir + "/tiny.json' --size 32x32 --frames 1 --method burley-4";
    const std::string missing = "EMCV_IMAGE_MODULE=/nonexistent/libemcv_image_oiio.so";
    const emcv_test::command_result r = run_demo(args + " --out '" + out.string() + "'", missing);
    if (emcv_test::no_display(r)) SKIP("no OpenGL display: " << r.err);
    check_rejected(args, 1, "cannot load the OpenImageIO module", out, missing);
}

TEST_CASE("the metrics-only flag (--no-frames) writes metrics.csv and metrics.json and no frame", "[app][cli][gl]") {
    const fs::path out = scratch_dir("no-frames") / "out";
    const emcv_test::command_result r = run_demo("--scene '" + data_dir +
                                                 "/tiny.json' --size 32x32 --frames 2 --method burley-4 --no-frames --out '" +
                                                 out.string() + "'");
    if (emcv_test::no_display(r)) SKIP("no OpenGL display: " << r.err);
    INFO(r.err << r.out);
    REQUIRE(r.exit_code == 0);
    CHECK(fs::is_regular_file(out / "metrics.csv"));
    CHECK(fs::is_regular_file(out / "metrics.json"));
    std::size_t entries = 0;
    for (const auto& entry : fs::recursive_directory_iterator(out)) {
        INFO(entry.path());
        CHECK(entry.path().parent_path() == out);  // no per-method folder, no frame
        ++entries;
    }
    CHECK(entries == 2);
}

TEST_CASE("the progress bar is drawn when stderr is a terminal", "[app][cli][gl]") {
    if (std::system("command -v script >/dev/null 2>&1") != 0) SKIP("script(1) is missing (Debian package bsdutils)");
    // script(1) gives the command a pseudo-terminal; the headless run above (pipes) showed no bar.
    const emcv_test::command_result r = emcv_test::run_command(
        "script -qec \"'" + std::string(EMCV_DEMO_EXE) + "' --scene '" + data_dir +
        "/tiny.json' --size 16x16 --frames 3 --method diffuse\" /dev/null");
    if (emcv_test::no_display(r) || r.out.find("(no display)") != std::string::npos)
        SKIP("no OpenGL display: " << r.out);
    INFO(r.out << r.err);
    REQUIRE(r.exit_code == 0);
    CHECK(r.out.find("3/3 frames") != std::string::npos);
    CHECK(r.out.find("frames/s") != std::string::npos);
}

TEST_CASE("the window (--window) runs a few frames under Xvfb and its keys act", "[app][cli][gl][window]") {
    if (std::system("command -v xvfb-run >/dev/null 2>&1") != 0)
        SKIP("xvfb-run is missing (Debian package xvfb; scripts/install-deps.sh installs it)");
    // Keys pressed one per frame from frame 1 (EMCV_DEMO_KEYS): next method, heatmap, light 1, heatmap again,
    // and back to the first method (scattering -> diffuse -> scattering once corrupted the renderer's heap).
    // LeakSanitizer is off for this one run (ASan stays on): at exit GLFW's X11/GLX path unloads Mesa's GLX
    // driver, so its leftover allocations have stacks in an unloaded module that no suppression can name
    // (seen under the sanitize preset: 240 bytes in 3 allocations, "<unknown module>"). The headless runs keep
    // LSan on, with emcv-demo's suppressions for Mesa's loaded libraries (demo/gl/context.cpp).
    const emcv_test::command_result r = emcv_test::run_command(
        "ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 EMCV_DEMO_KEYS=M,H,1,H,N xvfb-run -a -s '-screen 0 320x240x24' '" + std::string(EMCV_DEMO_EXE) +
        "' --window --scene '" + data_dir + "/tiny.json' --size 64x64 --frames 7 --method burley-4,diffuse");
    INFO(r.err << r.out);
    REQUIRE(r.exit_code == 0);  // includes: no GL error reported by the debug messenger
    CHECK(r.out.find("frame 1: method diffuse\n") != std::string::npos);
    CHECK(r.out.find("frame 2: heatmap on\n") != std::string::npos);
    CHECK(r.out.find("frame 3: light key off\n") != std::string::npos);
    CHECK(r.out.find("frame 4: heatmap off\n") != std::string::npos);
    CHECK(r.out.find("frame 5: method burley-4\n") != std::string::npos);
    CHECK(r.out.find("window: 7 frames") != std::string::npos);
}

TEST_CASE("the window with a bad scripted key: one line, non-zero exit", "[app][cli][window]") {
    const emcv_test::command_result r =
        run_demo("--window --scene '" + data_dir + "/tiny.json' --size 16x16 --frames 2", "EMCV_DEMO_KEYS=X");
    CHECK(r.exit_code != 0);
    CHECK(count_lines(r.err) <= 2);  // the key help line, then the error (or no display at all)
    CHECK(r.err.find("emcv-demo: ") != std::string::npos);
}

namespace {

/// Distinct RGB colours of a heatmap PNG's heatmap (its top-left `size` x `size` pixels, above the legend),
/// over all its pixels and over the pixels that are not black (N > 0).
struct colour_counts {
    std::size_t all = 0, non_black = 0;
};

colour_counts distinct_colours(const fs::path& png, int size) {
    const emcv::gl::float_image image = emcv::gl::read_image(png);
    std::set<std::vector<float>> all, non_black;
    const auto channels = static_cast<std::size_t>(image.channels);
    for (int y = image.height - size; y < image.height; ++y)  // rows are bottom first: the top ones are last
        for (int x = 0; x < size; ++x) {
            const std::size_t p =
                (static_cast<std::size_t>(y) * static_cast<std::size_t>(image.width) + static_cast<std::size_t>(x)) *
                channels;
            const std::vector<float> rgb(image.pixels.begin() + static_cast<std::ptrdiff_t>(p),
                                         image.pixels.begin() + static_cast<std::ptrdiff_t>(p + 3));
            all.insert(rgb);
            if (rgb[0] + rgb[1] + rgb[2] > 0.0f) non_black.insert(rgb);
        }
    return {all.size(), non_black.size()};
}

}  // namespace

TEST_CASE("adaptive methods write N heatmaps and cv alpha heatmaps and a static scene's N is not uniform",
          "[app][cli][gl][image-files]") {
    const fs::path out = scratch_dir("heatmaps") / "out";
    const emcv_test::command_result r = run_demo("--scene '" + data_dir +
                                                 "/tiny.json' --size 48x48 --frames 4 --method diffuse,spvg,cv "
                                                 "--seed 7 --out '" + out.string() + "'");
    if (emcv_test::no_display(r)) SKIP("no OpenGL display: " << r.err);
    INFO(r.err << r.out);
    REQUIRE(r.exit_code == 0);
    for (int f = 0; f < 4; ++f) {
        const std::string n = "000" + std::to_string(f);
        for (const char* m : {"spvg", "cv"}) CHECK(fs::is_regular_file(out / m / ("samples-" + n + ".png")));
        CHECK(fs::is_regular_file(out / "cv" / ("alpha-" + n + ".png")));
        for (const char* m : {"spvg", "diffuse", "reference"}) CHECK_FALSE(fs::exists(out / m / ("alpha-" + n + ".png")));
        for (const char* m : {"diffuse", "reference"}) CHECK_FALSE(fs::exists(out / m / ("samples-" + n + ".png")));
    }
    // Frames 0 and 1 take N_max everywhere (no history yet); from frame 2 SPVG's count follows each pixel's
    // variance, so the sphere's pixels do not all take one N, and the background takes none. (cv's static
    // pixels all sit at the shared floor of 8 at this size: only the background differs.)
    for (const char* m : {"spvg", "cv"}) {
        INFO(m);
        CHECK(distinct_colours(out / m / "samples-0003.png", 48).all >= 2);
    }
    CHECK(distinct_colours(out / "spvg" / "samples-0003.png", 48).non_black >= 2);
    // Each heatmap explains itself (docs/demo.md, Outputs): a 32-row legend below the 48x48 heatmap, the legend
    // at least 192 pixels wide, the scale in the file's ImageDescription and in the line naming the files.
    for (const fs::path& png : {out / "spvg" / "samples-0003.png", out / "cv" / "alpha-0003.png"}) {
        INFO(png);
        const emcv::gl::float_image image = emcv::gl::read_image(png);
        CHECK(image.width == 192);
        CHECK(image.height == 48 + 32);
    }
    CHECK(emcv::image::read_image_description(out / "spvg" / "samples-0003.png").find("N 0..64 (samples per pixel)") !=
          std::string::npos);
    CHECK(emcv::image::read_image_description(out / "cv" / "alpha-0003.png").find("alpha 0..2") != std::string::npos);
    CHECK(emcv::image::read_image_description(out / "spvg" / "frame-0003.png").empty());
    CHECK(r.out.find("samples-*.png, N 0..64 (samples per pixel); cv: alpha-*.png, alpha 0..2)") != std::string::npos);
    // The line names, before each kind of file, exactly the rendered methods whose directory holds that kind.
    for (const std::string kind : {"samples", "alpha"}) {
        const std::size_t end = r.out.find(": " + kind + "-*.png");
        REQUIRE(end != std::string::npos);
        const std::size_t begin = r.out.rfind("; ", end) + 2;
        std::set<std::string> named;
        std::istringstream names(r.out.substr(begin, end - begin));
        for (std::string name; std::getline(names >> std::ws, name, ',');) named.insert(name);
        for (const char* m : {"diffuse", "spvg", "cv"}) {
            INFO(kind << " files of " << m << ", the line names: " << r.out.substr(begin, end - begin));
            CHECK(fs::exists(out / m / (kind + "-0003.png")) == (named.count(m) == 1));
        }
    }
    CHECK(r.err.find("legends have no text") == std::string::npos);
    // The static light never changes: no cv vs spvg line.
    CHECK(r.out.find("cv vs spvg") == std::string::npos);
}

TEST_CASE("with spvg and cv on a light switch the summary compares them from the switch frame", "[app][cli][gl]") {
    const emcv_test::command_result r =
        run_demo("--scene '" + data_dir + "/switch.json' --size 32x32 --method spvg,cv --seed 7");
    if (emcv_test::no_display(r)) SKIP("no OpenGL display: " << r.err);
    INFO(r.err << r.out);
    REQUIRE(r.exit_code == 0);
    // switch.json's key light steps 3 -> 0 at frame 3, and the scene has 6 frames: the window is frames 3-5.
    CHECK(r.out.find("cv vs spvg, frames 3-5 (from the first light change at frame 3): samples ") !=
          std::string::npos);
    CHECK(r.out.find("SSS pass time ") != std::string::npos);
    CHECK(r.out.find(" dB (cv ") != std::string::npos);
    // The default quality target: each adaptive method's tracked error against V, from the switch and every frame.
    CHECK(r.out.find("target variance V = 1.00e-04, frames 3-5 (from the first light change at frame 3): squared "
                     "error of the tracked value per SSS pixel against the reference, mean over frames: spvg ") !=
          std::string::npos);  // the adaptive methods in the method table's order
    CHECK(r.out.find("target variance V = 1.00e-04, frames 0-5 (every frame): ") != std::string::npos);
    CHECK(r.out.find("; cv ") != std::string::npos);
    CHECK(r.out.find("vs burley-N") == std::string::npos);  // no burley-N run: no equal-time line

    const emcv_test::command_result without_cv =
        run_demo("--scene '" + data_dir + "/switch.json' --size 32x32 --method spvg --seed 7");
    REQUIRE(without_cv.exit_code == 0);
    CHECK(without_cv.out.find("cv vs spvg") == std::string::npos);
}
