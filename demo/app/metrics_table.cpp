// SPDX-License-Identifier: MIT
#include "metrics_table.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <system_error>

#include <nlohmann/json.hpp>

namespace emcv::demo::app {
namespace {

/// Shortest text that reads back to the same double (max_digits10).
std::string number_text(double v) {
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    if (std::isnan(v)) return "";
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.17g", v);
    double back = 0.0;
    for (int digits = 6; digits <= 17; ++digits) {
        std::snprintf(buffer, sizeof buffer, "%.*g", digits, v);
        if (std::sscanf(buffer, "%lf", &back) == 1 && back == v) break;
    }
    return buffer;
}

std::string optional_text(const std::optional<double>& v) { return v ? number_text(*v) : ""; }

nlohmann::json json_number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }
nlohmann::json json_number(const std::optional<double>& v) {
    return v ? json_number(*v) : nlohmann::json(nullptr);
}

}  // namespace

std::string metrics_csv(const std::vector<metrics_row>& rows) {
    std::ostringstream out;
    for (std::size_t i = 0; i < metrics_columns.size(); ++i) out << (i ? "," : "") << metrics_columns[i];
    out << '\n';
    for (const metrics_row& r : rows)
        out << r.frame << ',' << r.method << ',' << number_text(r.sss_ms) << ',' << number_text(r.frame_ms) << ','
            << number_text(r.mean_spp) << ',' << r.max_spp << ',' << optional_text(r.psnr_db) << ','
            << optional_text(r.psnr_sss_db) << ',' << number_text(r.rel_mse) << ','
            << optional_text(r.temporal_error) << ',' << optional_text(r.psnr_resolved_db) << ','
            << optional_text(r.psnr_sss_resolved_db) << ',' << optional_text(r.temporal_error_resolved) << ','
            << optional_text(r.tracked_mse) << '\n';
    return out.str();
}

std::string metrics_json(const std::vector<metrics_row>& rows, const std::string& sampling, const std::string& timing,
                         const std::string& resolve) {
    nlohmann::json j;
    if (!sampling.empty()) j["sampling"] = sampling;
    if (!timing.empty()) j["timing"] = timing;
    if (!resolve.empty()) j["resolve"] = resolve;
    j["columns"] = metrics_columns;
    j["rows"] = nlohmann::json::array();
    for (const metrics_row& r : rows) {
        j["rows"].push_back({{"frame", r.frame},
                             {"method", r.method},
                             {"sss_ms", json_number(r.sss_ms)},
                             {"frame_ms", json_number(r.frame_ms)},
                             {"mean_spp", json_number(r.mean_spp)},
                             {"max_spp", r.max_spp},
                             {"psnr_db", json_number(r.psnr_db)},
                             {"psnr_sss_db", json_number(r.psnr_sss_db)},
                             {"rel_mse", json_number(r.rel_mse)},
                             {"temporal_error", json_number(r.temporal_error)},
                             {"psnr_resolved_db", json_number(r.psnr_resolved_db)},
                             {"psnr_sss_resolved_db", json_number(r.psnr_sss_resolved_db)},
                             {"temporal_error_resolved", json_number(r.temporal_error_resolved)},
                             {"tracked_mse", json_number(r.tracked_mse)}});
        nlohmann::json passes = nlohmann::json::array();
        for (const auto& [name, ms] : r.passes) passes.push_back({{"name", name}, {"ms", json_number(ms)}});
        j["rows"].back()["passes"] = std::move(passes);
    }
    return j.dump(1) + "\n";
}

void write_file_atomically(const std::filesystem::path& path, const std::string& text) {
    namespace fs = std::filesystem;
    const fs::path tmp = path.string() + ".tmp-" + std::to_string(::getpid());
    {
        std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
        if (!out) throw output_error("cannot write '" + tmp.string() + "'");
        out << text;
        out.flush();
        if (!out) {
            std::error_code ignored;
            fs::remove(tmp, ignored);
            throw output_error("cannot write '" + tmp.string() + "' (disk full?)");
        }
    }
    std::error_code ec;
    fs::rename(tmp, path, ec);
    if (ec) {
        std::error_code ignored;
        fs::remove(tmp, ignored);
        throw output_error("cannot rename '" + tmp.string() + "' to '" + path.string() + "': " + ec.message());
    }
}

}  // namespace emcv::demo::app
