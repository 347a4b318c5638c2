// SPDX-License-Identifier: MIT
// The summary's cv-against-baseline line after a light change: which frames it averages, and the three
// numbers it prints, on hand-made rows whose means are known exactly.
#include <catch2/catch_test_macros.hpp>

#include <optional>
#include <string>
#include <vector>

#include "metrics_table.hpp"
#include "summary.hpp"

namespace app = emcv::demo::app;

namespace {

/// Rows for frames [0, frames): spvg takes 40 spp at 4 ms and 30 dB from `change` on, 8 spp at 1 ms and 40 dB
/// before; cv takes 10 spp at 2 ms and 29 dB from `change` on and, before it, the same as spvg. A frame at or
/// after change + 30 is set far off (1000 spp, 0 dB) so that a window that runs past 30 frames shows.
std::vector<app::metrics_row> rows_with_change(int change, int frames) {
    std::vector<app::metrics_row> rows;
    for (int f = 0; f < frames; ++f) {
        const bool after = f >= change, outside = f >= change + app::switch_window_frames;
        app::metrics_row spvg{f, "spvg", after ? 4.0 : 1.0, 5.0, after ? 40.0 : 8.0, 64, after ? 30.0 : 40.0,
                              std::nullopt, 0.0, std::nullopt, std::nullopt, std::nullopt, std::nullopt, std::nullopt, {}};
        app::metrics_row cv{f, "cv", after ? 2.0 : 1.0, 5.0, after ? 10.0 : 8.0, 64, after ? 29.0 : 40.0,
                            std::nullopt, 0.0, std::nullopt, std::nullopt, std::nullopt, std::nullopt, std::nullopt, {}};
        if (outside) cv.mean_spp = 1000.0, cv.psnr_db = 0.0, cv.sss_ms = 100.0;
        rows.push_back(spvg);
        rows.push_back(cv);
        rows.push_back({f, "reference", 9.0, 12.0, 1024.0, 1024, std::nullopt, std::nullopt, 0.0, std::nullopt, std::nullopt, std::nullopt, std::nullopt, std::nullopt, {}});
    }
    return rows;
}

}  // namespace

TEST_CASE("the cv vs spvg line averages the 30 frames from the change and prints ratios and the gap",
          "[app][summary]") {
    const std::optional<std::string> line = app::compare_after_change(rows_with_change(20, 60), 20, "cv", "spvg");
    REQUIRE(line);
    INFO(*line);
    // Frames 20..49 only: 10 / 40 spp, 2 / 4 ms, 29 - 30 dB. Frames before 20 or from 50 on would move each.
    CHECK(line->find("frames 20-49") != std::string::npos);
    CHECK(line->find("frame 20") != std::string::npos);
    CHECK(line->find("samples 0.250x") != std::string::npos);
    CHECK(line->find("SSS pass time 0.500x") != std::string::npos);
    CHECK(line->find("PSNR -1.00 dB") != std::string::npos);
    CHECK(line->find("cv 29.00, spvg 30.00") != std::string::npos);
    CHECK(line->find("resolved") == std::string::npos);  // the rows have no resolved PSNR (--resolve none)
}

TEST_CASE("the comparison line adds the resolved images' gap when the rows have one", "[app][summary]") {
    std::vector<app::metrics_row> rows = rows_with_change(20, 60);
    for (app::metrics_row& r : rows) {
        if (r.method == "cv") r.psnr_resolved_db = r.frame >= 20 ? 36.0 : 45.0;
        if (r.method == "spvg") r.psnr_resolved_db = r.frame >= 20 ? 35.5 : 45.0;
    }
    const std::optional<std::string> line = app::compare_after_change(rows, 20, "cv", "spvg");
    REQUIRE(line);
    INFO(*line);
    CHECK(line->find("PSNR -1.00 dB (cv 29.00, spvg 30.00), resolved +0.50 dB (cv 36.00, spvg 35.50)") !=
          std::string::npos);
}

TEST_CASE("the cv vs spvg line is cut at the last frame rendered", "[app][summary]") {
    const std::optional<std::string> line = app::compare_after_change(rows_with_change(5, 12), 5, "cv", "spvg");
    REQUIRE(line);
    INFO(*line);
    CHECK(line->find("frames 5-11") != std::string::npos);
    CHECK(line->find("samples 0.250x") != std::string::npos);
}

TEST_CASE("no cv vs spvg line without both methods or without frames after the change", "[app][summary]") {
    std::vector<app::metrics_row> rows = rows_with_change(20, 60);
    CHECK_FALSE(app::compare_after_change(rows, 60, "cv", "spvg"));  // no frame in the window
    std::vector<app::metrics_row> without_cv;
    for (const app::metrics_row& r : rows)
        if (r.method != "cv") without_cv.push_back(r);
    CHECK_FALSE(app::compare_after_change(without_cv, 20, "cv", "spvg"));
}

TEST_CASE("the every-frame line leaves the warm-up frame out of the time ratio, as the table does", "[app][summary]") {
    // Frame 0 compiles and first touches the driver's resources: here cv's costs 1000 ms. From frame 1 on cv takes
    // 1 ms on frames 1-19, 2 ms on 20-49 and 100 ms on 50-59 (1079 ms), spvg 1 ms on 1-19 and 4 ms on 20-59
    // (179 ms): 6.028x. With frame 0 the ratio would be 2079 / 180 = 11.55x.
    std::vector<app::metrics_row> rows = rows_with_change(20, 60);
    for (app::metrics_row& r : rows)
        if (r.method == "cv" && r.frame == 0) r.sss_ms = 1000.0;
    const std::optional<std::string> line = app::compare_after_change(rows, 0, "cv", "spvg", 0);
    REQUIRE(line);
    INFO(*line);
    CHECK(line->find("frames 0-59 (every frame)") != std::string::npos);
    CHECK(line->find("SSS pass time 6.028x (from frame 1)") != std::string::npos);
    // Samples still over every frame, frame 0 included: cv 20 x 8 + 30 x 10 + 10 x 1000, spvg 20 x 8 + 40 x 40.
    CHECK(line->find("samples 5.943x") != std::string::npos);
    // A window that starts after the warm-up leaves nothing out and says nothing of it.
    const std::optional<std::string> after = app::compare_after_change(rows, 20, "cv", "spvg");
    REQUIRE(after);
    CHECK(after->find("from frame") == std::string::npos);
    CHECK(after->find("SSS pass time 0.500x,") != std::string::npos);
}
