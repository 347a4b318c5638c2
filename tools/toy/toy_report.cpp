// SPDX-License-Identifier: MIT
#include "toy_report.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>
#include <tuple>
#include <utility>
#include <vector>

namespace emcv::toy {
namespace {

constexpr std::array<const char*, residual_count> column_titles = {"Res_f", "Res_SF", "Res_SF+EMA", "Res_EMCM",
                                                                   "ResHat_EMCM", "Res_GT"};

std::string format_cell(const mean_sd& cell, double paper) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.4f ± %.4f (%.4f)", cell.mean, cell.sd, paper);
    return buf;
}

void append_row(std::ostringstream& out, const char* title, const scenario_summary& summary,
                const std::array<double, residual_count>& paper) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%-11s", title);
    out << buf;
    for (std::size_t k = 0; k < residual_count; ++k) {
        // "±" is two bytes in UTF-8 and one column on screen: pad one byte more than the header cells.
        std::snprintf(buf, sizeof buf, " | %-28s", format_cell(summary.cells[k], paper[k]).c_str());
        out << buf;
    }
    out << '\n';
}

const char* first_frame_name(first_frame f) { return f == first_frame::primed ? "primed" : "zero"; }
const char* gt_name(gt_alpha_source g) { return g == gt_alpha_source::analytic ? "analytic" : "paper"; }

nlohmann::ordered_json cells_json(const scenario_summary& summary) {
    nlohmann::ordered_json j = nlohmann::ordered_json::object();
    for (std::size_t k = 0; k < residual_count; ++k)
        j[residual_keys[k]] = {{"mean", summary.cells[k].mean}, {"sd", summary.cells[k].sd}};
    return j;
}

std::string csv_text(const run_result& run) {
    std::ostringstream out;
    out.precision(10);
    out << "frame,t,h,fbar,gbar,G";
    for (const char* prefix : {"alpha_", "residual_", "remse_"})
        for (const char* key : residual_keys) out << ',' << prefix << key;
    out << ",inframe_alpha_emcm,inframe_alpha_ewma,inframe_cov_emcm,inframe_var_emcm,inframe_cov_ewma,"
           "inframe_var_ewma,inframe_residual\n";
    for (const frame_record& r : run.frames) {
        out << r.frame << ',' << r.t << ',' << r.h << ',' << r.fbar << ',' << r.gbar << ',' << r.g_expected;
        for (const auto* column : {&r.alpha, &r.residual, &r.remse})
            for (double v : *column) out << ',' << v;
        out << ',' << r.inframe_alpha_emcm << ',' << r.inframe_alpha_ewma << ',' << r.inframe_cov_emcm << ','
            << r.inframe_var_emcm << ',' << r.inframe_cov_ewma << ',' << r.inframe_var_ewma << ','
            << r.inframe_residual << '\n';
    }
    return out.str();
}

}  // namespace

std::string format_table(const toy_options& o, const toy_results& results, double elapsed_s) {
    std::ostringstream out;
    const toy_config& c = o.config;
    out << "emcv-toy: supplementary Table 1, ReMSE averaged over frames " << c.window_first << ".." << c.frames
        << ", mean ± sd over " << o.seeds << " seeds (" << o.first_seed << ".." << o.first_seed + o.seeds - 1
        << "), paper's single run in parentheses\n";
    out << "settings: " << c.frames << " frames x " << c.spp << " spp, eta_cov " << c.eta_cov << ", eta_res "
        << c.eta_res << ", SF+EMA eta " << c.eta_sf_ema << ", t0 " << c.t0 << ", first frame "
        << first_frame_name(c.first) << ", GT alpha " << gt_name(c.gt) << "\n\n";
    char buf[64];
    std::snprintf(buf, sizeof buf, "%-11s", "h");
    out << buf;
    for (const char* title : column_titles) {
        std::snprintf(buf, sizeof buf, " | %-27s", title);
        out << buf;
    }
    out << '\n';
    if (results.static_light) append_row(out, "static h1", *results.static_light, paper_static);
    if (results.dynamic_light) append_row(out, "dynamic h2", *results.dynamic_light, paper_dynamic);
    out << "\n(mean - paper) / sd, how far the paper's run sits from our mean in seed-to-seed spreads:\n";
    for (const auto& [title, summary, paper] :
         {std::tuple{"static h1", &results.static_light, &paper_static},
          std::tuple{"dynamic h2", &results.dynamic_light, &paper_dynamic}}) {
        if (!*summary) continue;
        std::snprintf(buf, sizeof buf, "%-11s", title);
        out << buf;
        for (std::size_t k = 0; k < residual_count; ++k) {
            const mean_sd& cell = (*summary)->cells[k];
            char z[32];
            std::snprintf(z, sizeof z, "%+.2f", cell.sd > 0 ? (cell.mean - (*paper)[k]) / cell.sd : 0.0);
            std::snprintf(buf, sizeof buf, " | %-27s", z);
            out << buf;
        }
        out << '\n';
    }
    out << '\n';
    if (results.static_light)
        out << "alpha* static: pooled Cov(f,g)/Var(g) over " << results.static_light->pooled_samples
            << " samples = " << results.static_light->pooled_alpha << " (analytic " << analytic_alpha_static()
            << ")\n";
    if (results.dynamic_light)
        out << "alpha* in-frame constant (dynamic, EMCM over (fbar, G), frames " << c.window_first << ".."
            << c.frames << ") = " << results.dynamic_light->inframe_alpha.mean << " ± "
            << results.dynamic_light->inframe_alpha.sd << " (analytic 2 ln 2 = " << analytic_alpha_dynamic()
            << ")\n";
    std::snprintf(buf, sizeof buf, "%.3f", elapsed_s);
    out << "elapsed: " << buf << " s (simulation of all seeds and scenarios)\n";
    return out.str();
}

nlohmann::ordered_json to_json(const toy_options& o, const toy_results& results) {
    nlohmann::ordered_json j = nlohmann::ordered_json::object();
    nlohmann::ordered_json alpha = nlohmann::ordered_json::object();
    if (results.static_light) {
        j["static"] = cells_json(*results.static_light);
        alpha["static"] = results.static_light->pooled_alpha;
    }
    if (results.dynamic_light) {
        j["dynamic"] = cells_json(*results.dynamic_light);
        alpha["dynamic"] = results.dynamic_light->inframe_alpha.mean;
    }
    j["alpha_star"] = alpha;
    j["seeds"] = o.seeds;
    return j;
}

void write_csv(const std::string& dir, const toy_results& results) {
    namespace fs = std::filesystem;
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec || !fs::is_directory(dir, ec))
        throw output_error("--csv: cannot create directory '" + dir + "'" + (ec ? ": " + ec.message() : ""));

    std::vector<std::pair<fs::path, std::string>> files;
    if (results.static_light)
        files.emplace_back(fs::path(dir) / "static.csv", csv_text(results.static_light->first_run));
    if (results.dynamic_light)
        files.emplace_back(fs::path(dir) / "dynamic.csv", csv_text(results.dynamic_light->first_run));

    std::vector<fs::path> written;
    const auto discard = [&] {
        for (const fs::path& p : written) fs::remove(p, ec);
    };
    for (const auto& [path, text] : files) {
        fs::path tmp = path;
        tmp += ".tmp";
        written.push_back(tmp);
        std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
        out << text;
        out.close();
        if (!out) {
            discard();
            throw output_error("--csv: cannot write '" + tmp.string() + "' in '" + dir + "'");
        }
    }
    for (const auto& [path, text] : files) {
        fs::path tmp = path;
        tmp += ".tmp";
        fs::rename(tmp, path, ec);
        if (ec) {
            discard();
            throw output_error("--csv: cannot rename '" + tmp.string() + "': " + ec.message());
        }
    }
}

}  // namespace emcv::toy
