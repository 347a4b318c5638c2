// SPDX-License-Identifier: MIT
// emcv-golden's bad input: a missing or unknown command, unknown options, malformed values, misplaced flags,
// an --only that matches nothing, compare's missing or unreadable images, a render --out that cannot be made:
// a first line naming the problem (usage follows for usage errors), exit 2 (usage) or 1, nothing on stdout, no
// file written. Every case fails before the GL context is made and never touches the goldens.
#include <catch2/catch_test_macros.hpp>

#include <filesystem>
#include <fstream>
#include <string>

#include "cli_expect.hpp"

#ifdef EMCV_GOLDEN

namespace fs = std::filesystem;
using emcv_cli_test::quoted;

namespace {

std::string golden(const std::string& args) { return std::string("'") + EMCV_GOLDEN + "' " + args; }

}  // namespace

TEST_CASE("emcv-golden: bad usage exits 2 and names the argument", "[cli][golden]") {
    const fs::path dir = emcv_cli_test::scratch_dir("golden-usage");
    const std::string out = " --out " + quoted(dir / "out");
    emcv_cli_test::expect_errors("emcv-golden", golden(""), {
        {"", "missing command (update, render or compare)"},
        {"frobnicate", "unknown command 'frobnicate' (update, render or compare)"},
        {"render --bogus" + out, "unknown option '--bogus'"},
        {"render --seed" , "--seed: missing value"},
        {"render --seed x" + out, "--seed: expected 0..4294967295, got 'x'"},
        {"render --seed 4294967296" + out, "got '4294967296'"},
        {"render --out", "--out: missing value"},
        {"render --only ''" + out, "--only: missing value"},
        {"render", "render: --out DIR is required"},
        {"render extra" + out, "render: unexpected argument 'extra'"},
        {"render --only NO_CASE_HAS_THIS" + out, "--only 'NO_CASE_HAS_THIS' matches no case of "},
        {"update" + out, "--out is for render"},
        {"update --seed 7", "--seed is for render"},
        {"compare a.png", "compare: expected ACTUAL EXPECTED"},
        {"compare a.png b.png c.png", "compare: expected ACTUAL EXPECTED"},
    });
    CHECK(emcv_cli_test::entries(dir) == 0);
    fs::remove_all(dir);
}

TEST_CASE("emcv-golden: compare of a missing or unreadable image exits 1 and names it", "[cli][golden]") {
    const fs::path dir = emcv_cli_test::scratch_dir("golden-compare");
    const fs::path text = dir / "not-an-image.png";
    std::ofstream(text) << "not an image\n";
    emcv_cli_test::expect_error("emcv-golden", golden("compare " + quoted(dir / "no.png") + " " + quoted(text)), 1,
                                (dir / "no.png").string() + ": no such image file");
    emcv_cli_test::expect_error("emcv-golden", golden("compare " + quoted(text) + " " + quoted(text)), 1,
                                text.string() + ": ");
    fs::remove_all(dir);
}

TEST_CASE("emcv-golden: a render --out that cannot be made exits 1 before rendering", "[cli][golden]") {
    const fs::path dir = emcv_cli_test::scratch_dir("golden-out");
    const fs::path blocked = emcv_cli_test::make_blocker(dir) / "out";
    // EMCV_GL_PLATFORMS=none: were a GL context made first, this would fail with another message
    emcv_cli_test::expect_error("emcv-golden", "EMCV_GL_PLATFORMS=none " + golden("render --out " + quoted(blocked)),
                                1, "--out '" + blocked.string() + "': cannot create the folder");
    CHECK(emcv_cli_test::entries(dir) == 1);  // only the blocker
    fs::remove_all(dir);
}

#endif  // EMCV_GOLDEN
