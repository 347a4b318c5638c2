// SPDX-License-Identifier: MIT
// Every shader under shaders/ goes through demo/gl's preprocessor and then glslangValidator three ways:
// plain GLSL 4.50 validation, SPIR-V for OpenGL (-G) and SPIR-V for Vulkan 1.0 (-V). Plus the preprocessor's
// error paths: missing file, missing include, include cycle, and a syntax error in an included file whose
// glslang log, rewritten through the file table, names that file and line.
#include <catch2/catch_test_macros.hpp>
#include <catch2/matchers/catch_matchers_string.hpp>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "gl/shader_preprocessor.hpp"
#include "render/method.hpp"
#include "../support/run_command.hpp"
#include "../support/source_dirs.hpp"

namespace fs = std::filesystem;
using Catch::Matchers::ContainsSubstring;
using emcv::gl::preprocess_file;
using emcv::gl::preprocess_options;

namespace {

const fs::path source_dir = EMCV_SOURCE_DIR;
const fs::path output_dir = EMCV_TEST_OUTPUT_DIR;

preprocess_options project_options() {
    preprocess_options o;
    o.include_dirs = emcv_test::shader_include_dirs();
    return o;
}

emcv_test::command_result run(const std::string& command) { return emcv_test::run_command(command); }

/// "comp" from "name.comp.glsl".
std::string stage_of(const fs::path& p) {
    return p.stem().extension().string().substr(1);
}

/// Writes the flattened text to `relative` under the output folder.
fs::path write_preprocessed(const fs::path& relative, const std::string& text) {
    const fs::path out = output_dir / relative;
    fs::create_directories(out.parent_path());
    std::ofstream(out, std::ios::binary) << text;
    return out;
}

/// Sets an environment variable for one scope and puts back what was there.
class scoped_env {
public:
    scoped_env(const char* name, const std::string& value) : name_(name) {
        if (const char* old = std::getenv(name)) old_ = old;
        ::setenv(name, value.c_str(), 1);
    }
    ~scoped_env() {
        if (old_) ::setenv(name_, old_->c_str(), 1);
        else ::unsetenv(name_);
    }
    scoped_env(const scoped_env&) = delete;
    scoped_env& operator=(const scoped_env&) = delete;

private:
    const char* name_;
    std::optional<std::string> old_;
};

/// The defines a shader is built with by the renderer: a shader that includes the adaptive history
/// (adaptive/history_io.h, or adaptive/samples.h around it) once per adaptive method's define (method table);
/// the burley pass, which includes it only when one is defined, also once without (burley-N), and once more per
/// method as the budget's variant that plans the next frame (EMCV_ADAPTIVE_PLAN_NEXT); every other shader once
/// without.
std::vector<std::vector<std::pair<std::string, std::string>>> method_defines(const fs::path& shader) {
    const std::string text = emcv_test::read_file(shader);
    const bool includes_history = text.find("#include \"adaptive/history_io.h\"") != std::string::npos ||
                                  text.find("#include \"adaptive/samples.h\"") != std::string::npos;
    if (!includes_history) return {{}};
    std::vector<std::vector<std::pair<std::string, std::string>>> out;
    if (text.find("defined(EMCV_ADAPTIVE_SPVG)") != std::string::npos) out.emplace_back();
    for (const emcv::demo::method_row& r : emcv::demo::method_table()) {
        if (r.adaptive_define().empty()) continue;
        out.push_back({{std::string(r.adaptive_define()), "1"}});
        if (text.find("defined(EMCV_ADAPTIVE_PLAN_NEXT)") != std::string::npos)
            out.push_back({{std::string(r.adaptive_define()), "1"}, {"EMCV_ADAPTIVE_PLAN_NEXT", "1"},
                           {"EMCV_HISTORY_SPP_BUDGET", "8.0f"}});
    }
    return out;
}

}  // namespace

TEST_CASE("every shader preprocesses and validates with glslangValidator for OpenGL and Vulkan") {
    int shaders = 0;
    const fs::path root = emcv_test::shader_dir();
    for (const auto& entry : fs::recursive_directory_iterator(root)) {
        const fs::path p = entry.path();
        if (!entry.is_regular_file() || p.extension() != ".glsl" || p.stem().extension().empty()) continue;
        for (const auto& defines : method_defines(p)) {
            ++shaders;
            std::string with;
            for (const auto& [name, value] : defines) with += " " + name + "=" + value;
            INFO("shader " << p.string() << (with.empty() ? "" : " with" + with));
            preprocess_options options = project_options();
            options.defines = defines;
            const auto src = preprocess_file(p, options);
            const fs::path flat = write_preprocessed(fs::path("shaders") / fs::relative(p, root), src.text);
            const std::string stage = stage_of(p);
            const std::string tool = std::string(EMCV_GLSLANG_VALIDATOR) + " -S " + stage + " ";
            const fs::path spv = flat.string() + ".spv";
            for (const std::string& mode : {std::string(""), std::string("-G --target-env opengl -o ") + spv.string(),
                                            std::string("-V --target-env vulkan1.0 -o ") + spv.string()}) {
                const emcv_test::command_result r = run(tool + mode + " " + flat.string());
                INFO("glslangValidator " << mode << "\n" << src.rewrite_log(r.output()));
                CHECK(r.exit_code == 0);
            }
        }
    }
    CHECK(shaders >= 1);
}

TEST_CASE("every port header compiles alone as GLSL 4.50 (OpenGL and Vulkan SPIR-V), checked or not") {
    int headers = 0;
    for (const auto& entry : fs::directory_iterator(emcv_test::include_dir() / "emcv/port")) {
        const fs::path h = entry.path();
        if (h.extension() != ".h") continue;
        ++headers;
        // as shipped, and with the debug build's parameter checks (EMCV_PORT_CHECKS 1, port.h)
        for (const int checks : {0, 1}) {
            INFO("port header " << h.string() << ", EMCV_PORT_CHECKS " << checks);
            // A minimal compute shader that includes the header twice (the guard must hold) and nothing else.
            const fs::path wrapper =
                output_dir / "port_alone" / (h.stem().string() + (checks ? ".checked" : "") + ".comp.glsl");
            fs::create_directories(wrapper.parent_path());
            std::ofstream(wrapper) << "#version 450 core\n#define EMCV_PORT_CHECKS " << checks << "\n#include \"emcv/port/"
                                   << h.filename().string() << "\"\n#include \"emcv/port/" << h.filename().string()
                                   << "\"\nlayout(local_size_x = 1) in;\nvoid main() {}\n";
            const auto src = preprocess_file(wrapper, project_options());
            const fs::path flat = wrapper.string() + ".flat.comp";
            std::ofstream(flat, std::ios::binary) << src.text;
            for (const std::string& mode : {std::string("-G --target-env opengl -o ") + flat.string() + ".spv",
                                            std::string("-V --target-env vulkan1.0 -o ") + flat.string() + ".spv"}) {
                const emcv_test::command_result r = run(std::string(EMCV_GLSLANG_VALIDATOR) + " -S comp " + mode + " " + flat.string());
                INFO("glslangValidator " << mode << "\n" << src.rewrite_log(r.output()));
                CHECK(r.exit_code == 0);
            }
        }
    }
    CHECK(headers >= 7);
}

TEST_CASE("#version and #extension are hoisted, defines injected, #pragma once honoured") {
    preprocess_options o = project_options();
    o.defines = {{"INJECTED", "3"}};
    const fs::path shader = source_dir / "tests/shaders/data/hoist.comp.glsl";
    const auto src = preprocess_file(shader, o);
    CHECK(src.text.rfind("#version 450 core\n#extension GL_ARB_shader_ballot : enable\n#define INJECTED 3\n", 0) == 0);
    // once.h appears once in the file table and its body once in the text.
    CHECK(src.files.size() == 2);
    const auto first = src.text.find("float once_value()");
    REQUIRE(first != std::string::npos);
    CHECK(src.text.find("float once_value()", first + 1) == std::string::npos);
    const fs::path flat = write_preprocessed(fs::relative(shader, source_dir), src.text);
    const emcv_test::command_result r = run(std::string(EMCV_GLSLANG_VALIDATOR) + " -S comp " + flat.string());
    INFO(r.output());
    CHECK(r.exit_code == 0);
}

TEST_CASE("a guarded header is left out only where its macro is certainly defined: the compiler would drop it") {
    // guarded.h: #ifndef GUARDED_H / #define GUARDED_H ... #endif. The preprocessor does not evaluate #if: it
    // leaves a later inclusion out only when the first one lay in the same branches, so that the first was
    // reached wherever the later one is.
    const fs::path dir = output_dir / "include_guards";
    fs::create_directories(dir);
    preprocess_options o = project_options();
    o.include_dirs.push_back(source_dir / "tests/shaders/data");
    const auto copies = [&](const std::string& name, const std::string& body, const preprocess_options& options) {
        const fs::path main = dir / (name + ".comp.glsl");
        std::ofstream(main) << "#version 450 core\n" << body << "layout(local_size_x = 1) in;\nvoid main() {}\n";
        const std::string text = preprocess_file(main, options).text;
        std::size_t n = 0;
        for (std::size_t at = text.find("float guarded_value()"); at != std::string::npos;
             at = text.find("float guarded_value()", at + 1))
            ++n;
        return n;
    };
    const std::string twice = "#include \"guarded.h\"\n#include \"guarded.h\"\n";
    CHECK(copies("unconditional", twice, o) == 1);
    CHECK(copies("same_branch", "#ifdef SOMETHING\n" + twice + "#endif\n", o) == 1);
    CHECK(copies("inner_branch", "#ifdef A\n#include \"guarded.h\"\n#ifdef B\n#include \"guarded.h\"\n#endif\n#endif\n", o) == 1);
    // the first inclusion may not have been reached where the second is: both kept
    CHECK(copies("after_branch", "#if defined(NEVER)\n#include \"guarded.h\"\n#endif\n#include \"guarded.h\"\n", o) == 2);
    CHECK(copies("else_branch", "#ifdef X\n#include \"guarded.h\"\n#else\n#include \"guarded.h\"\n#endif\n", o) == 2);
    // kept where the first inclusion may not have been reached, left out after one that certainly was
    CHECK(copies("widened", "#ifdef X\n#include \"guarded.h\"\n#endif\n" + twice + "#include \"guarded.h\"\n", o) == 2);
    CHECK(copies("undefined", "#include \"guarded.h\"\n#undef GUARDED_H\n#include \"guarded.h\"\n", o) == 2);
    // outer_guarded.h includes guarded.h inside its own guard: certain on its first inclusion...
    CHECK(copies("nested", "#include \"outer_guarded.h\"\n#include \"guarded.h\"\n", o) == 1);
    // ...but not where its macro was defined before (the compiler drops outer_guarded.h, and guarded.h with it)
    CHECK(copies("nested_defined", "#define OUTER_GUARDED_H\n#include \"outer_guarded.h\"\n#include \"guarded.h\"\n", o) == 2);
    preprocess_options injected = o;
    injected.defines = {{"OUTER_GUARDED_H", "1"}};
    CHECK(copies("nested_injected", "#include \"outer_guarded.h\"\n#include \"guarded.h\"\n", injected) == 2);
    // what is kept still compiles: the compiler drops the second copy by its guard
    const fs::path flat = write_preprocessed("include_guards/after_branch.flat.comp",
                                             preprocess_file(dir / "after_branch.comp.glsl", o).text);
    const emcv_test::command_result r = run(std::string(EMCV_GLSLANG_VALIDATOR) + " -S comp " + flat.string());
    INFO(r.output());
    CHECK(r.exit_code == 0);
}

TEST_CASE("a missing shader file is a clear error") {
    REQUIRE_THROWS_AS(preprocess_file(emcv_test::shader_dir() / "no_such_shader.comp.glsl", project_options()),
                      emcv::gl::shader_error);
    REQUIRE_THROWS_WITH(preprocess_file(emcv_test::shader_dir() / "no_such_shader.comp.glsl", project_options()),
                        ContainsSubstring("shader file not found") && ContainsSubstring("no_such_shader.comp.glsl"));
}

TEST_CASE("a missing include names the including file, line and the searched paths") {
    REQUIRE_THROWS_WITH(preprocess_file(source_dir / "tests/shaders/data/missing_include.comp.glsl", project_options()),
                        ContainsSubstring("missing_include.comp.glsl:3") &&
                            ContainsSubstring("\"does_not_exist.h\" not found") && ContainsSubstring("searched:"));
}

TEST_CASE("an include cycle is an error, not a stack overflow") {
    REQUIRE_THROWS_WITH(preprocess_file(source_dir / "tests/shaders/data/cycle_a.h", project_options()),
                        ContainsSubstring("include cycle"));
}

TEST_CASE("glslang's error in an included file is reported at that file and line after rewriting") {
    const fs::path shader = source_dir / "tests/shaders/data/broken_main.comp.glsl";
    const auto src = preprocess_file(shader, project_options());
    const fs::path flat = write_preprocessed(fs::relative(shader, source_dir), src.text);
    const emcv_test::command_result r = run(std::string(EMCV_GLSLANG_VALIDATOR) + " -S comp " + flat.string());
    CHECK(r.exit_code != 0);
    const std::string log = src.rewrite_log(r.output());
    INFO("raw log:\n" << r.output() << "\nrewritten:\n" << log);
    CHECK_THAT(log, ContainsSubstring("broken_helper.h:5"));
}

TEST_CASE("rewrite_log maps Mesa and glslang locations through the file table") {
    emcv::gl::preprocessed_source src;
    src.files = {"main.comp.glsl", "inc/helper.h"};
    // Mesa: "<source>:<line>(<col>)", the file index also encoded in the line (index * 1000000 + n)
    CHECK(src.rewrite_log("0:1000005(48): error: syntax error\n0:7(3): warning: x\n") ==
          "inc/helper.h:5(48): error: syntax error\nmain.comp.glsl:7(3): warning: x\n");
    // glslang: "ERROR: <source>:<line>: "
    CHECK(src.rewrite_log("ERROR: 1:1000012: 'x' : undeclared\nWARNING: 0:2: y\n") ==
          "ERROR: inc/helper.h:12: 'x' : undeclared\nWARNING: main.comp.glsl:2: y\n");
    // text without locations, and unknown indices, pass through unchanged
    CHECK(src.rewrite_log("ERROR: 1 compilation errors.  No code generated.") ==
          "ERROR: 1 compilation errors.  No code generated.");
    CHECK(src.rewrite_log("9:4(1): error") == "9:4(1): error");
}

TEST_CASE("EMCV_SHADER_DIR and EMCV_INCLUDE_DIR point the tests at another copy, as they point the renderer") {
    // A copy holding a shader and a port header that the source tree lacks: preprocessing it through the tests'
    // folders succeeds only when both variables are honoured.
    const fs::path copy = output_dir / "environment_copy";
    fs::remove_all(copy);
    fs::create_directories(copy / "shaders");
    fs::create_directories(copy / "include/emcv/port");
    std::ofstream(copy / "shaders/probe.comp.glsl")
        << "#version 450 core\n#include \"emcv/port/probe_only_in_copy.h\"\nlayout(local_size_x = 1) in;\n"
           "void main() {}\n";
    std::ofstream(copy / "include/emcv/port/probe_only_in_copy.h") << "float probe_marker() { return 1.0; }\n";
    {
        const scoped_env shaders("EMCV_SHADER_DIR", (copy / "shaders").string());
        const scoped_env includes("EMCV_INCLUDE_DIR", (copy / "include").string());
        CHECK(emcv_test::shader_dir() == copy / "shaders");
        CHECK(emcv_test::include_dir() == copy / "include");
        const auto src = preprocess_file(emcv_test::shader_dir() / "probe.comp.glsl", project_options());
        CHECK(src.text.find("float probe_marker()") != std::string::npos);
    }
    {
        // set but empty reads as unset, as in the renderer
        const scoped_env shaders("EMCV_SHADER_DIR", "");
        const scoped_env includes("EMCV_INCLUDE_DIR", "");
        CHECK(emcv_test::shader_dir() == source_dir / "shaders");
        CHECK(emcv_test::include_dir() == source_dir / "include");
        CHECK_THROWS_AS(preprocess_file(copy / "shaders/probe.comp.glsl", project_options()), emcv::gl::shader_error);
    }
    fs::remove_all(copy);
}
