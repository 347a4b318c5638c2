// SPDX-License-Identifier: MIT
// The summary's equal-time lines (each adaptive method against burley-N interpolated in log SSS time at its own
// SSS time) and quality-target lines (each adaptive method's tracked error against V), on hand-made rows whose
// means are known exactly: the expected numbers are worked by hand below.
#include <catch2/catch_test_macros.hpp>

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "metrics_table.hpp"
#include "summary.hpp"

namespace app = emcv::demo::app;

namespace {

constexpr int change_frame = 30, frame_count = 60;

/// One method's rows over frames [0, frame_count): from the change on `sss_ms`, `psnr` and `resolved` (the
/// resolved PSNR, none when empty) every frame; before it 100 ms and 0 dB, so that a window reaching before the
/// change shows.
void add_method(std::vector<app::metrics_row>& rows, const std::string& method, double sss_ms, double psnr,
                std::optional<double> resolved, std::optional<double> tracked_mse = std::nullopt) {
    for (int f = 0; f < frame_count; ++f) {
        const bool after = f >= change_frame;
        app::metrics_row r;
        r.frame = f;
        r.method = method;
        r.sss_ms = after ? sss_ms : 100.0;
        r.mean_spp = 8.0;
        r.psnr_db = after ? psnr : 0.0;
        r.psnr_resolved_db = after ? resolved : std::optional<double>(0.0);
        if (!resolved) r.psnr_resolved_db.reset();
        r.tracked_mse = after ? tracked_mse : std::optional<double>(1.0);
        if (!tracked_mse) r.tracked_mse.reset();
        rows.push_back(r);
    }
}

/// burley-4, -8, -32 and -64 at 1, 2, 8 and 16 ms with 37, 40, 46 and 48 dB (resolved 47, 50, 53, 55), listed out
/// of time order.
std::vector<app::metrics_row> burley_runs() {
    std::vector<app::metrics_row> rows;
    add_method(rows, "burley-32", 8.0, 46.0, 53.0);
    add_method(rows, "burley-4", 1.0, 37.0, 47.0);
    add_method(rows, "burley-64", 16.0, 48.0, 55.0);
    add_method(rows, "burley-8", 2.0, 40.0, 50.0);
    return rows;
}

}  // namespace

TEST_CASE("the equal-time line interpolates the burley runs' PSNR in log time at cv's own time", "[app][summary]") {
    std::vector<app::metrics_row> rows = burley_runs();
    add_method(rows, "cv", 3.0, 44.0, 52.0);
    const std::optional<std::string> line = app::compare_at_equal_time(rows, change_frame, "cv");
    REQUIRE(line);
    INFO(*line);
    // cv's 3 ms lies between burley-8 (t1 = 2 ms, p1 = 40 dB) and burley-32 (t2 = 8 ms, p2 = 46 dB):
    //   p(3) = p1 + (p2 - p1) ln(t / t1) / ln(t2 / t1) = 40 + 6 ln(1.5) / ln(4) = 40 + 6 x 0.405465 / 1.386294
    //        = 40 + 6 x 0.292481 = 41.754888 dB, so cv's gap is 44 - 41.754888 = +2.245 dB.
    // (Linear in time: 40 + 6 x (3 - 2) / (8 - 2) = 41 dB, +3.00 dB; t1 and t2 swapped, 40 + 6 ln(3/8) / ln(2/8)
    // = 44.245 dB, -0.25 dB.)
    // Resolved: 50 + 3 x 0.292481 = 50.877444 dB, cv 52: +1.12 dB.
    CHECK(line->find("cv vs burley-N at cv's SSS time, frames 30-59 (from the first light change at frame 30): "
                     "3.000 ms, between burley-8 (2.000 ms) and burley-32 (8.000 ms), "
                     "PSNR +2.25 dB (cv 44.00, burley-N there 41.75), "
                     "resolved +1.12 dB (cv 52.00, burley-N there 50.88); "
                     // What cv's image is worth: raw 44 dB between burley-8 (40) and burley-32 (46), ln N linear in
                     // dB: N = 8 x (32 / 8)^((44 - 40) / (46 - 40)) = 8 x 4^(2/3) = 20.16 (linear in N: 24.0;
                     // the runs swapped: 8 x 4^(1/3) = 12.7). Resolved 52 between 50 (burley-8) and 53 (burley-32):
                     // the same 2/3, 20.16.
                     "its image is worth burley-20.2 (resolved burley-20.2)") == 0);
    CHECK(line->size() == line->find("(resolved burley-20.2)") + 22);  // nothing after it
}

TEST_CASE("the every-frame equal-time line takes its times from frame 1, as the table does", "[app][summary]") {
    // Every frame, frames 1-59: cv (29 x 100 + 30 x 3) / 59 = 50.678 ms; burley-32 (29 x 100 + 30 x 8) / 59 =
    // 53.220 ms and burley-8 (29 x 100 + 30 x 2) / 59 = 50.169 ms bracket it. PSNR over frames 0-59: burley-8
    // (30 x 0 + 30 x 40) / 60 = 20, burley-32 23, cv 22. p = 20 + 3 ln(50.678 / 50.169) / ln(53.220 / 50.169)
    // = 20 + 3 x 0.010084 / 0.059033 = 20 + 3 x 0.17082 = 20.5125: cv +1.49 dB.
    std::vector<app::metrics_row> rows = burley_runs();
    add_method(rows, "cv", 3.0, 44.0, std::nullopt);
    for (app::metrics_row& r : rows)
        if (r.frame == 0) r.sss_ms = 1000.0;  // the warm-up frame: left out of every time
    const std::optional<std::string> line = app::compare_at_equal_time(rows, 0, "cv", 0);
    REQUIRE(line);
    INFO(*line);
    CHECK(line->find("cv vs burley-N at cv's SSS time, frames 0-59 (every frame): 50.678 ms, from frame 1, between "
                     "burley-8 (50.169 ms) and burley-32 (53.220 ms), PSNR +1.49 dB (cv 22.00, burley-N there 20.51)") ==
          0);
    CHECK(line->find("resolved") == std::string::npos);  // cv has no resolved PSNR (--resolve none)
}

TEST_CASE("outside the burley runs' times the equal-time line says so instead of extrapolating", "[app][summary]") {
    std::vector<app::metrics_row> rows = burley_runs();
    add_method(rows, "cv", 20.0, 49.0, 56.0);
    add_method(rows, "spvg", 0.5, 30.0, 40.0);
    const std::optional<std::string> beyond = app::compare_at_equal_time(rows, change_frame, "cv");
    REQUIRE(beyond);
    CHECK(*beyond == "cv vs burley-N at cv's SSS time, frames 30-59 (from the first light change at frame 30): "
                     "cv's SSS time is beyond burley-64's (20.000 ms against 16.000 ms): no equal-time comparison; "
                     "its image is worth more than burley-64 (resolved more than burley-64)");
    const std::optional<std::string> below = app::compare_at_equal_time(rows, change_frame, "spvg");
    REQUIRE(below);
    CHECK(*below == "spvg vs burley-N at spvg's SSS time, frames 30-59 (from the first light change at frame 30): "
                    "spvg's SSS time is below burley-4's (0.500 ms against 1.000 ms): no equal-time comparison; "
                    "its image is worth less than burley-4 (resolved less than burley-4)");
}

TEST_CASE("the equal-time line says what the method's image is worth in burley samples, raw and resolved",
          "[app][summary]") {
    std::vector<app::metrics_row> rows = burley_runs();
    add_method(rows, "cv", 3.0, 43.0, 54.0);
    const std::optional<std::string> line = app::compare_at_equal_time(rows, change_frame, "cv");
    REQUIRE(line);
    INFO(*line);
    // Raw 43 dB halfway between burley-8 (40) and burley-32 (46): N = 8 x 4^(1/2) = 16.0. Resolved 54 dB halfway
    // between burley-32 (53) and burley-64 (55): N = 32 x 2^(1/2) = 45.25 (linear in N: 48.0).
    CHECK(line->find("; its image is worth burley-16.0 (resolved burley-45.3)") != std::string::npos);
}

TEST_CASE("no equal-time line without a burley run or without the method", "[app][summary]") {
    std::vector<app::metrics_row> rows;
    add_method(rows, "cv", 3.0, 44.0, 52.0);
    add_method(rows, "burley-16x", 3.0, 44.0, 52.0);  // not a burley-N name
    CHECK_FALSE(app::compare_at_equal_time(rows, change_frame, "cv"));
    CHECK_FALSE(app::compare_at_equal_time(burley_runs(), change_frame, "cv"));
    CHECK_FALSE(app::compare_at_equal_time(burley_runs(), frame_count, "burley-8"));  // no frame in the window
}

TEST_CASE("the quality-target line says which adaptive method met the target and which missed it", "[app][summary]") {
    std::vector<app::metrics_row> rows;
    add_method(rows, "spvg", 4.0, 55.0, std::nullopt, 2.0e-5);
    add_method(rows, "cv", 2.0, 44.0, std::nullopt, 1.5e-4);
    add_method(rows, "cv-notex", 2.0, 45.0, std::nullopt, 9.0e-5);
    add_method(rows, "burley-16", 2.0, 45.0, std::nullopt, 1.0e-5);  // not asked for: not in the line
    const std::optional<std::string> line =
        app::compare_with_target(rows, change_frame, {"cv", "spvg", "cv-notex", "absent"}, 1.0e-4);
    REQUIRE(line);
    // From the change: spvg 2e-5 / 1e-4 = 0.20 V, cv 1.5e-4 / 1e-4 = 1.50 V, cv-notex 0.90 V.
    CHECK(*line == "target variance V = 1.00e-04, frames 30-59 (from the first light change at frame 30): squared "
                   "error of the tracked value per SSS pixel against the reference, mean over frames: cv 1.50e-04 = "
                   "1.50 V: missed (under V on 0 of 30 frames); spvg 2.00e-05 = 0.20 V: met (under V on 30 of 30 "
                   "frames); cv-notex 9.00e-05 = 0.90 V: met (under V on 30 of 30 frames)");
    // Every frame: 30 frames at 1 (before the change) and 30 at spvg's 2e-5: (30 + 30 x 2e-5) / 60 = 0.50001.
    const std::optional<std::string> every = app::compare_with_target(rows, 0, {"spvg"}, 1.0e-4, 0);
    REQUIRE(every);
    CHECK(every->find("frames 0-59 (every frame)") != std::string::npos);
    CHECK(every->find("spvg 5.00e-01 = 5000.10 V: missed (under V on 30 of 60 frames)") != std::string::npos);

    CHECK_FALSE(app::compare_with_target(rows, change_frame, {"absent"}, 1.0e-4));
    CHECK_THROWS_AS(app::compare_with_target(rows, change_frame, {"cv"}, 0.0), std::invalid_argument);
}
