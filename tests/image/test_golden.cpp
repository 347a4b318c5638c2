// SPDX-License-Identifier: MIT
// Regression renders: every case of golden/cases.txt rendered headless (EGL, llvmpipe) and compared with its
// committed golden image (image_compare.hpp: idiff semantics). A failing image leaves
// <output>/<stem>.{actual,expected,diff}.png and the message names them. And determinism: two separate runs
// of emcv-golden give bit-identical files.
#include <catch2/catch_test_macros.hpp>

#include <unistd.h>

#include <filesystem>
#include <string>

#include "gl/debug.hpp"
#include "golden_cases.hpp"
#include "golden_render.hpp"
#include "image_compare.hpp"
#include "../gpu/gl_test_support.hpp"
#include "../support/run_command.hpp"

namespace fs = std::filesystem;
using namespace emcv::image;

namespace {

const fs::path golden_dir = fs::path(EMCV_IMAGE_DIR) / "golden";
const fs::path output_dir = fs::path(EMCV_IMAGE_OUTPUT_DIR);

/// Compares one rendered image with its golden; on failure writes the three images and fails the check
/// with their names.
void check_against_golden(const OIIO::ImageBuf& rendered, const std::string& file, const tolerance& t) {
    const fs::path golden = golden_dir / file;
    if (!fs::exists(golden)) {
        write(rendered, output_dir / (file + ".actual.png"));
        FAIL_CHECK(file << ": no golden image; run scripts/update-golden.sh (this render: "
                        << (output_dir / (file + ".actual.png")).string() << ")");
        return;
    }
    const OIIO::ImageBuf expected = read(golden);
    const comparison c = compare(rendered, expected, t);
    if (c.result == verdict::fail) {
        const std::string stem = fs::path(file).replace_extension().string();
        const failure_images out = write_failure_images(rendered, expected, t, output_dir, stem);
        FAIL_CHECK(file << ": " << c.summary(t) << "\n  actual:   " << out.actual.string()
                        << "\n  expected: " << out.expected.string() << "\n  diff:     " << out.diff.string());
    } else {
        SUCCEED(file << ": " << c.summary(t));
    }
}

}  // namespace

TEST_CASE("every golden case renders as its golden image") {
    auto context = emcv::test::context_or_skip();
    emcv::gl::debug_messenger messenger;
    const auto cases = read_cases(golden_dir / "cases.txt");
    for (const golden_case& c : cases) {
        INFO("case " << c.stem());
        const golden_images images = render_case(c);
        check_against_golden(images.display, c.display_file(), display_tolerance());
        if (images.sample_counts) check_against_golden(*images.sample_counts, c.samples_file(), samples_tolerance());
    }
    CHECK(messenger.error_count() == 0);
}

TEST_CASE("the same build renders bit-identical images, run after run") {
    // Two separate processes (fresh contexts, fresh shader compiles) over the cases with temporal state.
    const fs::path base = fs::temp_directory_path() / ("emcv-test-determinism-" + std::to_string(::getpid()));
    const std::string only = EMCV_DETERMINISM_CASES;
    for (const char* run : {"a", "b"}) {
        const auto r = emcv_test::run_command(std::string("'") + EMCV_GOLDEN_EXE + "' render --only '" + only +
                                              "' --out '" + (base / run).string() + "'");
        INFO(r.output());
        REQUIRE(r.exit_code == 0);
    }
    int files = 0;
    for (const auto& entry : fs::directory_iterator(base / "a")) {
        const fs::path other = base / "b" / entry.path().filename();
        const comparison c = compare_files(entry.path(), other, tolerance::exact());
        INFO(entry.path().filename().string() << ": " << c.summary(tolerance::exact()));
        CHECK(c.result == verdict::pass);
        CHECK(c.max_error == 0.0);
        ++files;
    }
    CHECK(files > 0);
    fs::remove_all(base);
}

TEST_CASE("emcv-golden: bad arguments get one line naming the problem and exit code 2") {
    const std::string exe = std::string("'") + EMCV_GOLDEN_EXE + "'";
    const auto missing = emcv_test::run_command(exe + " render");
    CHECK(missing.exit_code == 2);
    CHECK(missing.err.rfind("emcv-golden: render: --out DIR is required\n", 0) == 0);
    const auto unknown = emcv_test::run_command(exe + " render --out /tmp/x --frobnicate");
    CHECK(unknown.exit_code == 2);
    CHECK(unknown.err.rfind("emcv-golden: unknown option '--frobnicate'\n", 0) == 0);
    const auto nothing = emcv_test::run_command(exe + " render --out /tmp/emcv-never --only no-such-case");
    CHECK(nothing.exit_code == 2);
    CHECK(nothing.err.find("matches no case") != std::string::npos);
    CHECK_FALSE(fs::exists("/tmp/emcv-never"));
}
