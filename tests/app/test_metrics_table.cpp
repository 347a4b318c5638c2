// SPDX-License-Identifier: MIT
// metrics.csv / metrics.json text (column contract, inf and undefined values), the summary's aggregation
// and the progress line.
#include <catch2/catch_approx.hpp>
#include <catch2/catch_test_macros.hpp>

#include <cmath>
#include <filesystem>
#include <limits>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "../support/run_command.hpp"
#include "metrics_table.hpp"
#include "progress.hpp"
#include "summary.hpp"

namespace app = emcv::demo::app;

namespace {

std::vector<app::metrics_row> sample_rows() {
    const double inf = std::numeric_limits<double>::infinity();
    std::vector<app::metrics_row> rows;
    rows.push_back({0, "burley-16", 1.5, 4.0, 16.0, 16, 30.0, 25.0, 0.02, std::nullopt, 38.0, 33.0, std::nullopt,
                    0.00025, {{"gbuffer", 2.5}, {"sss-burley", 1.5}}});
    rows.push_back({0, "reference", 9.0, 12.0, 1024.0, 1024, inf, inf, 0.0, std::nullopt, inf, inf, std::nullopt, 0.0,
                    {}});
    rows.push_back({1, "burley-16", 2.5, 5.0, 16.0, 16, 32.0, std::nullopt, 0.01, 0.125, 40.5, std::nullopt, 0.0625,
                    std::nullopt, {}});
    rows.push_back({1, "reference", 9.0, 12.0, 1024.0, 1024, inf, inf, 0.0, 0.0, inf, inf, 0.0, 0.0, {}});
    return rows;
}

}  // namespace

TEST_CASE("metrics.csv has the contract's columns and writes inf and undefined values apart", "[app][metrics]") {
    std::istringstream csv(app::metrics_csv(sample_rows()));
    std::string line;
    std::getline(csv, line);
    CHECK(line == "frame,method,sss_ms,frame_ms,mean_spp,max_spp,psnr_db,psnr_sss_db,rel_mse,temporal_error,"
                  "psnr_resolved_db,psnr_sss_resolved_db,temporal_error_resolved,tracked_mse");
    std::getline(csv, line);
    CHECK(line == "0,burley-16,1.5,4,16,16,30,25,0.02,,38,33,,0.00025");
    std::getline(csv, line);
    CHECK(line == "0,reference,9,12,1024,1024,inf,inf,0,,inf,inf,,0");
    std::getline(csv, line);
    CHECK(line == "1,burley-16,2.5,5,16,16,32,,0.01,0.125,40.5,,0.0625,");
}

TEST_CASE("metrics.json carries every column, inf and undefined as null", "[app][metrics]") {
    const nlohmann::json j = nlohmann::json::parse(app::metrics_json(sample_rows()));
    REQUIRE(j["rows"].size() == 4);
    CHECK(j["columns"].size() == 14);
    for (const auto& row : j["rows"]) CHECK(row.size() == 15);  // the columns and the passes
    CHECK(j["rows"][0]["psnr_db"].get<double>() == 30.0);
    CHECK(j["rows"][0]["temporal_error"].is_null());
    CHECK(j["rows"][1]["psnr_db"].is_null());
    CHECK(j["rows"][2]["psnr_sss_db"].is_null());
    CHECK(j["rows"][2]["temporal_error"].get<double>() == 0.125);
    CHECK(j["rows"][0]["psnr_resolved_db"].get<double>() == 38.0);
    CHECK(j["rows"][2]["psnr_sss_resolved_db"].is_null());
    CHECK(j["rows"][2]["temporal_error_resolved"].get<double>() == 0.0625);
    CHECK(j["rows"][0]["tracked_mse"].get<double>() == 0.00025);
    CHECK(j["rows"][2]["tracked_mse"].is_null());
    CHECK(j["rows"][3]["method"] == "reference");
    CHECK_FALSE(j.contains("sampling"));
    CHECK_FALSE(j.contains("timing"));
    // each pass by name, in recording order
    REQUIRE(j["rows"][0]["passes"].size() == 2);
    CHECK(j["rows"][0]["passes"][0]["name"] == "gbuffer");
    CHECK(j["rows"][0]["passes"][0]["ms"].get<double>() == 2.5);
    CHECK(j["rows"][0]["passes"][1]["name"] == "sss-burley");
    CHECK(j["rows"][0]["passes"][1]["ms"].get<double>() == 1.5);
    CHECK(j["rows"][1]["passes"].empty());
    const nlohmann::json with_mode = nlohmann::json::parse(app::metrics_json(sample_rows(), "budget 8 spp", "gpu"));
    CHECK(with_mode["sampling"] == "budget 8 spp");
    CHECK(with_mode["timing"] == "gpu");
}

TEST_CASE("values round-trip through the CSV text", "[app][metrics]") {
    app::metrics_row r;
    r.rel_mse = 0.1 + 0.2;  // not representable in few digits
    r.sss_ms = 1.0 / 3.0;
    std::istringstream csv(app::metrics_csv({r}));
    std::string line;
    std::getline(csv, line);
    std::getline(csv, line);
    std::vector<std::string> fields;
    std::stringstream split(line);
    for (std::string f; std::getline(split, f, ',');) fields.push_back(f);
    REQUIRE(fields.size() >= 9);
    CHECK(std::stod(fields[2]) == r.sss_ms);
    CHECK(std::stod(fields[8]) == r.rel_mse);
}

TEST_CASE("atomic write leaves the file complete and no temporary behind", "[app][metrics]") {
    namespace fs = std::filesystem;
    const fs::path dir = fs::temp_directory_path() / "emcv-app-atomic";
    fs::remove_all(dir);
    fs::create_directories(dir);
    app::write_file_atomically(dir / "m.csv", "a,b\n1,2\n");
    CHECK(emcv_test::read_file(dir / "m.csv") == "a,b\n1,2\n");
    CHECK(std::distance(fs::directory_iterator(dir), fs::directory_iterator()) == 1);
    CHECK_THROWS_AS(app::write_file_atomically(dir / "missing" / "m.csv", "x"), app::output_error);
    fs::remove_all(dir);
}

TEST_CASE("percentile interpolates between order statistics", "[app][summary]") {
    CHECK(app::percentile({}, 95.0) == 0.0);
    CHECK(app::percentile({3.0, 1.0, 2.0}, 50.0) == 2.0);
    // 1..21: position 0.95 * 20 = 19, the 20th value.
    std::vector<double> v;
    for (int i = 21; i >= 1; --i) v.push_back(i);
    CHECK(app::percentile(v, 95.0) == Catch::Approx(20.0));
    // {0, 10}: position 0.95 -> 9.5.
    CHECK(app::percentile({10.0, 0.0}, 95.0) == Catch::Approx(9.5));
}

TEST_CASE("summary averages per method, keeps the maximum count, skips the reference's inf", "[app][summary]") {
    const auto s = app::summarize(sample_rows(), {"burley-16", "reference"}, 0);  // times over every frame
    REQUIRE(s.size() == 2);
    CHECK(s[0].frames == 2);
    CHECK(s[0].sss_ms_mean == Catch::Approx(2.0));
    CHECK(s[0].sss_ms_p95 == Catch::Approx(1.5 + 0.95 * 1.0));
    CHECK(s[0].frame_ms_mean == Catch::Approx(4.5));
    // The default leaves frame 0 (warm-up) out of the times, not out of the counts or the PSNR.
    const auto steady = app::summarize(sample_rows(), {"burley-16"});
    CHECK(steady[0].timed_frames == 1);
    CHECK(steady[0].sss_ms_mean == Catch::Approx(2.5));
    CHECK(steady[0].frame_ms_mean == Catch::Approx(5.0));
    CHECK(*steady[0].psnr_db == Catch::Approx(31.0));
    // A one-frame run has only the warm-up frame: timed anyway.
    const auto single = app::summarize({sample_rows()[0]}, {"burley-16"});
    CHECK(single[0].timed_frames == 1);
    CHECK(single[0].sss_ms_mean == Catch::Approx(1.5));
    CHECK(*s[0].psnr_db == Catch::Approx(31.0));
    CHECK(*s[0].psnr_sss_db == Catch::Approx(25.0));  // frame 1 has no SSS pixel: not averaged in
    CHECK(*s[0].psnr_resolved_db == Catch::Approx(39.25));  // (38 + 40.5) / 2
    CHECK(s[1].max_spp == 1024);
    CHECK(std::isinf(*s[1].psnr_db));
    const std::string table = app::format_summary(s, {"cv vs spvg after the switch: ..."});
    CHECK(table.find("burley-16") != std::string::npos);
    CHECK(table.find("inf") != std::string::npos);
    CHECK(table.find("psnr_resolved\n") != std::string::npos);  // the rows have resolved PSNRs: the column shows
    CHECK(table.find("39.25\n") != std::string::npos);
    std::vector<app::metrics_row> raw_only = sample_rows();
    for (app::metrics_row& r : raw_only) r.psnr_resolved_db.reset();  // --resolve none: no such column
    CHECK(app::format_summary(app::summarize(raw_only, {"burley-16"})).find("resolved") == std::string::npos);
    const std::string note = "\ncv vs spvg after the switch: ...\n";  // the last line, after the table
    CHECK(table.substr(table.size() - note.size()) == note);
}

TEST_CASE("a frame identical to the reference (+inf dB) does not make the mean infinite", "[app][summary]") {
    // diffuse on a frame without visible SSS equals the reference exactly; the mean is over the other frames.
    std::vector<app::metrics_row> rows(2);
    rows[0].method = rows[1].method = "diffuse";
    rows[0].psnr_db = std::numeric_limits<double>::infinity();
    rows[1].psnr_db = 40.0;
    const auto s = app::summarize(rows, {"diffuse"});
    REQUIRE(s.at(0).psnr_db.has_value());
    CHECK(*s[0].psnr_db == Catch::Approx(40.0));
    CHECK_FALSE(s[0].psnr_sss_db.has_value());
}

TEST_CASE("progress line shows frames done, rate and ETA", "[app][progress]") {
    const std::string line = app::progress_line(10, 40, 5.0, 20);
    CHECK(line.find("10/40 frames") != std::string::npos);
    CHECK(line.find("2.00 frames/s") != std::string::npos);
    CHECK(line.find("ETA 0m15s") != std::string::npos);
    CHECK(line.find("[#####...............]") == 0);
}
