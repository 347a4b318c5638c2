// SPDX-License-Identifier: MIT
// The golden cases file: what it accepts, each malformed line's message, and the committed file itself.
#include <catch2/catch_test_macros.hpp>
#include <catch2/matchers/catch_matchers_string.hpp>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "golden_cases.hpp"

namespace fs = std::filesystem;
using Catch::Matchers::ContainsSubstring;
using emcv::image::read_cases;

namespace {

fs::path cases_file(const std::string& text) {
    static int serial = 0;
    const fs::path p = fs::temp_directory_path() /
                       ("emcv-test-cases-" + std::to_string(::getpid()) + "-" + std::to_string(serial++) + ".txt");
    std::ofstream(p) << text;
    return p;
}

std::string error_of(const std::string& text) {
    try {
        read_cases(cases_file(text));
    } catch (const emcv::image::cases_error& e) {
        return e.what();
    }
    return "(no error)";
}

}  // namespace

TEST_CASE("a cases file: comments, blank lines, stems named after the last frame") {
    const auto cases = read_cases(cases_file("# header\n\nstatic diffuse 1 96x64\nlight-off cv 24 128x128  # after the switch\n"));
    REQUIRE(cases.size() == 2);
    CHECK(cases[0].stem() == "static.diffuse.f0");
    CHECK(cases[0].width == 96);
    CHECK(cases[0].height == 64);
    CHECK(cases[1].stem() == "light-off.cv.f23");
    CHECK(cases[1].display_file() == "light-off.cv.f23.png");
    CHECK(cases[1].samples_file() == "light-off.cv.f23.spp.png");
}

TEST_CASE("each malformed line is named with its file, line and problem") {
    CHECK_THAT(error_of("static diffuse\n"), ContainsSubstring(":1: expected '<scene> <method> <frames> <W>x<H>'"));
    CHECK_THAT(error_of("\nstatic diffuse 0 96x96\n"), ContainsSubstring(":2: frames must be in 1..1000"));
    CHECK_THAT(error_of("static diffuse 1 96y96\n"), ContainsSubstring(":1: size '96y96' is not WxH"));
    CHECK_THAT(error_of("static diffuse 1 512x96\n"), ContainsSubstring("sides in 1..256"));
    CHECK_THAT(error_of("static diffuse 1 96x96 extra\n"), ContainsSubstring("unexpected 'extra'"));
    CHECK_THAT(error_of("static diffuse 2 96x96\nstatic diffuse 2 64x64\n"),
               ContainsSubstring(":2: duplicate case static.diffuse.f1"));
    CHECK_THAT(error_of("static diffuse 1 96x\n"), ContainsSubstring("is not WxH"));
}

TEST_CASE("the committed cases file reads, and every case is small") {
    const auto cases = read_cases(fs::path(EMCV_IMAGE_DIR) / "golden" / "cases.txt");
    CHECK_FALSE(cases.empty());
    for (const auto& c : cases) CHECK(c.width * c.height <= 128 * 128);
}
