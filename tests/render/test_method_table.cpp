// SPDX-License-Identifier: MIT
// The method table (render/method.hpp) and the tunables (render/tunables.hpp): names round-trip through the
// parser, each row's SSS passes are the ones the planner lists, the tunables list equals the port headers'
// #ifndef blocks, --define values are validated, and a define reaches the shaders.
#include <catch2/catch_approx.hpp>
#include <catch2/catch_test_macros.hpp>
#include <catch2/matchers/catch_matchers_string.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <emcv/adaptive_sampling.hpp>

#include "../gpu/gl_test_support.hpp"
#include "gl/debug.hpp"
#include "render/program_cache.hpp"
#include "render/renderer.hpp"
#include "render/resources.hpp"
#include "render/tunables.hpp"
#include "render_test_support.hpp"
#include "scene/load.hpp"

using namespace emcv::demo;
using Catch::Matchers::ContainsSubstring;

TEST_CASE("every method's name parses back to the method, and the parameters' edges are enforced") {
    for (const method_row& r : method_table()) {
        INFO("row " << r.name);
        // `all`'s value, else the bare name's, else the smallest the parameter takes
        const method m{r.type, r.in_all >= 0                    ? r.in_all
                               : r.parameter.default_value != 0 ? r.parameter.default_value
                                                                : r.parameter.minimum};
        const std::optional<method> back = parse_method(m.name());
        REQUIRE(back);
        CHECK(*back == m);
        // an adaptive row's estimator decides its passes, layout, define and heatmaps, and they agree with the
        // library's estimator and the port's layouts (cv's EMCM is the one layout that holds alpha)
        CHECK(is_adaptive(m) == (r.history() != history_layout::none));
        CHECK(is_adaptive(m) == (r.passes() == sss_passes::adaptive));
        CHECK(is_adaptive(m) == !r.adaptive_define().empty());
        if (r.estimator) {
            CHECK(emcv::sampling_estimator_name(*r.estimator) == r.name);
            CHECK(emcv::parse_sampling_estimator(r.name) == r.estimator);
            CHECK((r.history() == history_layout::emcm2) == (*r.estimator == emcv::sampling_estimator::cv));
        }
        // the summary's list of adaptive methods (emcv-demo's equal-time lines) names exactly the adaptive rows
        const std::vector<std::string> adaptive = adaptive_method_names();
        CHECK(std::count(adaptive.begin(), adaptive.end(), m.name()) == (is_adaptive(m) ? 1 : 0));
    }
    CHECK(parse_method("burley-1") == method{method::kind::burley, 1});
    CHECK(parse_method("burley-1024") == method{method::kind::burley, 1024});
    CHECK_FALSE(parse_method("burley-0"));
    CHECK_FALSE(parse_method("burley-1025"));
    CHECK_FALSE(parse_method("burley"));
    CHECK(parse_method("separable") == method{method::kind::separable, 17});
    CHECK(parse_method("separable-25") == method{method::kind::separable, 25});
    CHECK_FALSE(parse_method("separable-13"));
    CHECK_FALSE(parse_method("reference-64"));  // tests set other counts in code, the command line cannot
    CHECK_FALSE(parse_method("cv-1"));
    CHECK_FALSE(parse_method("cv-"));
    CHECK(make_reference(256).name() == "reference-256");
    CHECK(accepted_method_names() ==
          "diffuse, burley-N (N = 1..1024), burley-sobol-N (N = 1..1024), separable[-11|-17|-25], reference, spvg, cv, "
          "cv-notex");
}

TEST_CASE("the planner lists each row's SSS passes, and only for a scene that calls for them") {
    const scene sphere = emcv::test::sphere_on_floor();
    const std::vector<std::pair<sss_passes, std::vector<std::string>>> expected{
        {sss_passes::none, {}},
        {sss_passes::burley, {"sss-burley"}},
        {sss_passes::separable, {"sss-separable-h", "sss-separable-v"}},
        {sss_passes::adaptive, {"sss-burley"}},  // a quality target: the burley program plans N itself
    };
    const sampling_mode budget{true, 8.0};
    for (const method& m : all_methods()) {
        INFO("method " << m.name());
        const auto sss_of = [&](const sampling_mode& sampling) {
            std::vector<std::string> sss;
            for (const std::string& p : pass_list(sphere, m, 0, 64, 48, resolve_mode::none, sampling))
                if (p.rfind("sss-", 0) == 0) sss.push_back(p);
            return sss;
        };
        for (const auto& [passes, names] : expected)
            if (row_of(m).passes() == passes) CHECK(sss_of({}) == names);
        // A budget adds the samples pass before an adaptive method's burley program, and nothing elsewhere.
        if (row_of(m).passes() == sss_passes::adaptive)
            CHECK(sss_of(budget) == std::vector<std::string>{"sss-adaptive-samples", "sss-burley"});
        else
            CHECK(sss_of(budget) == sss_of({}));
        for (const std::string& p : pass_list(emcv::test::no_sss(), m, 0, 64, 48, resolve_mode::none))
            CHECK(p.rfind("sss-", 0) != 0);
    }
}

TEST_CASE("the reference's planner drops its SSS passes while its inputs hold, as the renderer does") {
    const scene s = emcv::test::sphere_on_floor();
    frame_planner planner(s, make_reference(64), 48, 32, resolve_mode::none, sampling_mode{});
    const auto sss_passes_of = [&](const std::vector<planned_pass>& plan) {
        int n = 0;
        for (const planned_pass& p : plan) n += is_sss_pass(p.id) ? 1 : 0;
        return n;
    };
    CHECK(sss_passes_of(planner.plan(0)) == 1);
    CHECK_FALSE(planner.reuses_result());
    CHECK(sss_passes_of(planner.plan(1)) == 0);  // same camera and lights
    CHECK(planner.reuses_result());
    CHECK(sss_passes_of(planner.plan(2, {0.0f})) == 1);  // the first light off: new inputs
    planner.reset();
    CHECK(sss_passes_of(planner.plan(3, {0.0f})) == 1);  // nothing held after a reset
}

TEST_CASE("one row is the ground truth: it holds its result and a resolving run never resolves it") {
    int truths = 0;
    for (const method_row& r : method_table()) truths += r.ground_truth ? 1 : 0;
    CHECK(truths == 1);  // headless_run measures every method against the one it adds
    const method truth = ground_truth_method();
    CHECK(row_of(truth).holds_result());
    CHECK_FALSE(row_of(truth).resolves());
    const std::vector<method> run{*parse_method("cv"), *parse_method("burley-8"), truth};
    // the planner of a resolving run records the resolve for every method but the ground truth
    const scene s = emcv::test::sphere_on_floor();
    for (const method& m : run) {
        frame_planner planner(s, m, 48, 32, resolve_mode::taa, sampling_mode{});
        bool resolve = false;
        for (const planned_pass& p : planner.plan(0)) resolve = resolve || p.id == pass_id::resolve;
        CHECK(resolve == (m != truth));
    }
}

TEST_CASE("the tunables are exactly the #ifndef blocks of the port headers") {
    // Every `#ifndef NAME` line followed by `#define NAME value` that is not an include guard (NAME ends in _H).
    std::set<std::string> in_headers;
    for (const auto& e : std::filesystem::directory_iterator(std::string(EMCV_SOURCE_DIR) + "/include/emcv/port")) {
        if (e.path().filename() == "port.h") continue;  // the dialect's qualifier macros, not tunables
        std::ifstream in(e.path());
        std::string previous, line;
        while (std::getline(in, line)) {
            const std::string guard = "#ifndef EMCV_";
            if (previous.rfind(guard, 0) == 0) {
                const std::string name = previous.substr(8);
                const bool defines_value = line.rfind("#define " + name + " ", 0) == 0 &&
                                           line.size() > 9 + name.size();
                if (defines_value && name.substr(name.size() - 2) != "_H") in_headers.insert(name);
            }
            previous = line;
        }
    }
    std::set<std::string> listed;
    for (const tunable& t : tunables()) listed.insert(std::string(t.name));
    CHECK(listed == in_headers);
}

TEST_CASE("docs/renderer.md's tunables table gives each history tunable's type, range and default as the code") {
    // Rows "| `EMCV_HISTORY_X` | type | range | default | meaning |": range "[a, b]" or "(a, b]" (the tunable's
    // bounds and whether the lower one is open), or a list "1, 2 or 4" within them; default a number.
    std::ifstream in(std::string(EMCV_SOURCE_DIR) + "/docs/renderer.md");
    REQUIRE(in.good());
    const std::regex row(R"(^\| `(EMCV_HISTORY_[A-Z_]+)` \| (float|int|uint) \| ([^|]+) \| ([^|]+) \|)");
    const std::regex interval(R"(^([\[(])([-0-9.e]+), ([-0-9.e]+)\]$)");
    std::set<std::string> documented;
    for (std::string line; std::getline(in, line);) {
        std::smatch m;
        if (!std::regex_search(line, m, row)) continue;
        const std::string name = m[1], type = m[2], range = m[3], value = m[4];
        INFO(name << ": " << line.substr(0, 120));
        CHECK(documented.insert(name).second);
        const auto t = std::find_if(tunables().begin(), tunables().end(),
                                    [&](const tunable& x) { return x.name == name; });
        REQUIRE(t != tunables().end());
        CHECK(type == (t->kind == tunable::type::real ? "float" : t->kind == tunable::type::integer ? "int" : "uint"));
        CHECK(std::stod(value) == Catch::Approx(t->default_value).epsilon(1e-6));
        std::smatch bounds;
        const std::string trimmed = range.substr(0, range.find_last_not_of(' ') + 1);
        if (std::regex_match(trimmed, bounds, interval)) {
            CHECK((bounds[1] == "(") == t->minimum_exclusive);
            CHECK(std::stod(bounds[2]) == t->minimum);
            CHECK(std::stod(bounds[3]) == t->maximum);
        } else {  // a list of allowed values: each within the bounds, the ends the bounds
            std::vector<double> allowed;
            const std::regex number("[0-9.]+");
            for (auto it = std::sregex_iterator(trimmed.begin(), trimmed.end(), number);
                 it != std::sregex_iterator(); ++it)
                allowed.push_back(std::stod(it->str()));
            REQUIRE(allowed.size() >= 2);
            CHECK(allowed.front() == t->minimum);
            CHECK(allowed.back() == t->maximum);
        }
    }
    // every history tunable has its row
    for (const tunable& t : tunables()) {
        if (std::string(t.name).rfind("EMCV_HISTORY_", 0) != 0) continue;
        INFO(t.name << " has no row in docs/renderer.md's tunables table");
        CHECK(documented.count(std::string(t.name)) == 1);
    }
}

TEST_CASE("define values are validated and written as GLSL literals of the tunable's type") {
    CHECK(parse_define("EMCV_HISTORY_N_MAX=32") == std::pair<std::string, std::string>{"EMCV_HISTORY_N_MAX", "32"});
    CHECK(parse_define("EMCV_HISTORY_MAX_COUNT=512").second == "512u");
    CHECK(parse_define("EMCV_HISTORY_TARGET=2.5e-5").second == "2.500000000e-05f");
    CHECK(parse_define("EMCV_HISTORY_ETA_EMCM=0.5").second == "5.000000000e-01f");
    const auto fails = [](const char* text, const char* why) {
        INFO(text);
        CHECK_THROWS_WITH(parse_define(text), ContainsSubstring(why));
    };
    fails("EMCV_HISTORY_NMAX=3", "unknown tunable 'EMCV_HISTORY_NMAX'");
    fails("EMCV_HISTORY_N_MAX", "expected NAME=VALUE");
    fails("=3", "expected NAME=VALUE");
    fails("EMCV_HISTORY_N_MAX=", "expected NAME=VALUE");
    fails("EMCV_HISTORY_N_MAX=0", "an integer in [1, 1024]");
    fails("EMCV_HISTORY_N_MAX=2.5", "an integer in [1, 1024]");
    fails("EMCV_HISTORY_N_MAX=-4", "an integer in [1, 1024]");
    fails("EMCV_HISTORY_TARGET=0", "a number in (0, 1]");
    fails("EMCV_HISTORY_TARGET=1e400", "a number in (0, 1]");
    fails("EMCV_HISTORY_TARGET=nan", "a number in (0, 1]");
    fails("EMCV_HISTORY_ETA_EMCM=0.05;", "a number in (0, 0.5]");
    fails("EMCV_HISTORY_ETA_EMCM=0.6", "a number in (0, 0.5]");  // the unbias factor needs eta < 1
    std::vector<std::pair<std::string, std::string>> defines;
    add_define(defines, "EMCV_HISTORY_N_MAX=32");
    add_define(defines, "EMCV_HISTORY_N_MIN=4");
    add_define(defines, "EMCV_HISTORY_N_MAX=16");  // a later value wins
    CHECK(defines == std::vector<std::pair<std::string, std::string>>{{"EMCV_HISTORY_N_MIN", "4"},
                                                                        {"EMCV_HISTORY_N_MAX", "16"}});
    CHECK(tunable_value(defines, "EMCV_HISTORY_N_MAX") == 16.0);
    CHECK(tunable_value(defines, "EMCV_HISTORY_ETA_EMCM") == double(0.2f));  // not set: the header's default
    CHECK_FALSE(sampling_mode_of(defines).budget);
    add_define(defines, "EMCV_HISTORY_N_MIN=20");
    CHECK_THROWS_WITH(check_tunables(defines), ContainsSubstring("EMCV_HISTORY_N_MIN (20) exceeds EMCV_HISTORY_N_MAX (16)"));
    {  // the statistics' grain divides the 8x8 tile: 3 is in the tunable's range [1, 4] but refused
        std::vector<std::pair<std::string, std::string>> block;
        add_define(block, "EMCV_HISTORY_BLOCK=4");
        CHECK_NOTHROW(check_tunables(block));
        add_define(block, "EMCV_HISTORY_BLOCK=3");
        CHECK_THROWS_WITH(check_tunables(block), ContainsSubstring("EMCV_HISTORY_BLOCK (3) is not 1, 2 or 4"));
        fails("EMCV_HISTORY_BLOCK=8", "an integer in [1, 4]");
    }
    std::string seen;
    add_sampling_flag(defines, "--spp-budget", "12", seen);
    CHECK(sampling_mode_of(defines).budget);
    CHECK(sampling_mode_of(defines).value == 12.0);
    CHECK_THROWS_WITH(add_sampling_flag(defines, "--target-variance", "1e-4", seen),
                      ContainsSubstring("cannot be combined with --spp-budget"));
}

TEST_CASE("a --define reaches the shaders: the floor and cap move spvg's sample counts") {
    emcv::gl::context ctx = emcv::test::context_or_skip();
    emcv::gl::debug_messenger messenger;
    const scene s = load_scene_argument("static");
    const auto spp = [&](const std::vector<std::pair<std::string, std::string>>& defines) {
        render_options o;
        o.width = 48;
        o.height = 48;
        o.defines = defines;
        renderer r(s, *parse_method("spvg"), o);
        frame_stats last;
        for (int frame = 0; frame < 4; ++frame) last = r.render(frame);
        return last;
    };
    // Defaults: a static light's per-sample variance over the target stays well under 20 once the history has
    // two frames.
    const frame_stats plain = spp({});
    CHECK(plain.mean_spp < 20.0);
    const frame_stats floor20 = spp({parse_define("EMCV_HISTORY_N_MIN=20")});
    CHECK(floor20.mean_spp >= 20.0);
    const frame_stats cap4 = spp({parse_define("EMCV_HISTORY_N_MAX=4"), parse_define("EMCV_HISTORY_N_MIN=2")});
    CHECK(cap4.max_spp <= 4);
    CHECK(cap4.max_spp >= 2);
    CHECK(messenger.error_count() == 0);
}

TEST_CASE("the program cache builds a program once per file and defines, and keeps nothing that failed") {
    emcv::gl::context ctx = emcv::test::context_or_skip();
    render_options o;
    const shader_setup setup = make_shader_setup(o);
    program_cache cache(setup.preprocess, setup.shader_dir);
    const emcv::gl::program& lighting = cache.compute("render/lighting.comp.glsl");
    CHECK(&cache.compute("render/lighting.comp.glsl") == &lighting);  // asked again: the same program
    CHECK(cache.size() == 1);
    const emcv::gl::program& sobol = cache.compute("render/sss_burley.comp.glsl", {{"EMCV_BURLEY_SOBOL", "1"}});
    const emcv::gl::program& r2 = cache.compute("render/sss_burley.comp.glsl");
    CHECK(&sobol != &r2);  // the defines are part of the key
    CHECK(sobol.id() != r2.id());
    CHECK(cache.size() == 3);
    CHECK_THROWS(cache.compute("render/no_such_pass.comp.glsl"));
    CHECK(cache.size() == 3);
    // a pass whose program was not prepared says so instead of drawing with whatever is bound
    program_ref unset{nullptr, "sss-separable"};
    CHECK_THROWS_WITH(unset.use(), ContainsSubstring("sss-separable"));
}
