// SPDX-License-Identifier: MIT
#include "summary.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

namespace emcv::demo::app {
namespace {

/// Mean of the finite values; +inf when every defined value is +inf; empty when none is defined.
std::optional<double> mean_psnr(const std::vector<std::optional<double>>& values) {
    double sum = 0.0;
    int finite = 0, infinite = 0;
    for (const std::optional<double>& v : values) {
        if (!v) continue;
        if (std::isfinite(*v)) {
            sum += *v;
            ++finite;
        } else {
            ++infinite;
        }
    }
    if (finite > 0) return sum / finite;
    if (infinite > 0) return std::numeric_limits<double>::infinity();
    return std::nullopt;
}

std::string psnr_text(const std::optional<double>& v) {
    if (!v) return "-";
    if (std::isinf(*v)) return "inf";
    char b[32];
    std::snprintf(b, sizeof b, "%.2f", *v);
    return b;
}

}  // namespace

double percentile(std::vector<double> values, double p) {
    if (values.empty()) return 0.0;
    std::sort(values.begin(), values.end());
    const double position = std::clamp(p, 0.0, 100.0) / 100.0 * static_cast<double>(values.size() - 1);
    const auto below = static_cast<std::size_t>(std::floor(position));
    const std::size_t above = std::min(below + 1, values.size() - 1);
    const double t = position - static_cast<double>(below);
    return values[below] + t * (values[above] - values[below]);
}

std::vector<method_summary> summarize(const std::vector<metrics_row>& rows, const std::vector<std::string>& methods,
                                      int timing_from_frame) {
    std::vector<method_summary> out;
    for (const std::string& name : methods) {
        method_summary s;
        s.method = name;
        bool late_frames = false;
        for (const metrics_row& r : rows) late_frames = late_frames || (r.method == name && r.frame >= timing_from_frame);
        std::vector<double> sss_ms;
        std::vector<std::optional<double>> psnr, psnr_sss, psnr_resolved;
        double frame_ms = 0.0, spp = 0.0;
        for (const metrics_row& r : rows) {
            if (r.method != name) continue;
            ++s.frames;
            if (!late_frames || r.frame >= timing_from_frame) {
                ++s.timed_frames;
                sss_ms.push_back(r.sss_ms);
                frame_ms += r.frame_ms;
            }
            spp += r.mean_spp;
            s.max_spp = std::max(s.max_spp, r.max_spp);
            psnr.push_back(r.psnr_db);
            psnr_sss.push_back(r.psnr_sss_db);
            psnr_resolved.push_back(r.psnr_resolved_db);
        }
        if (s.frames > 0) {
            double sum = 0.0;
            for (double v : sss_ms) sum += v;
            s.sss_ms_mean = sum / s.timed_frames;
            s.sss_ms_p95 = percentile(sss_ms, 95.0);
            s.frame_ms_mean = frame_ms / s.timed_frames;
            s.mean_spp = spp / s.frames;
        }
        s.psnr_db = mean_psnr(psnr);
        s.psnr_sss_db = mean_psnr(psnr_sss);
        s.psnr_resolved_db = mean_psnr(psnr_resolved);
        out.push_back(s);
    }
    return out;
}

std::optional<std::string> compare_after_change(const std::vector<metrics_row>& rows, int first_change,
                                                const std::string& name, const std::string& baseline, int window,
                                                int timing_from_frame) {
    struct window_means {
        int frames = 0, timed_frames = 0;
        double spp = 0.0, sss_ms = 0.0, all_sss_ms = 0.0;
        std::vector<std::optional<double>> psnr, psnr_resolved;
    };
    const int end = window > 0 ? first_change + window : std::numeric_limits<int>::max();
    auto means_of = [&](const std::string& method) {
        window_means m;
        for (const metrics_row& r : rows) {
            if (r.method != method || r.frame < first_change || r.frame >= end) continue;
            ++m.frames;
            m.spp += r.mean_spp;
            m.all_sss_ms += r.sss_ms;
            if (r.frame >= timing_from_frame) {
                ++m.timed_frames;
                m.sss_ms += r.sss_ms;
            }
            m.psnr.push_back(r.psnr_db);
            m.psnr_resolved.push_back(r.psnr_resolved_db);
        }
        // As summarize: over every frame of the window when none is late enough (a one-frame run).
        if (m.timed_frames == 0) m.timed_frames = m.frames, m.sss_ms = m.all_sss_ms;
        return m;
    };
    const window_means base = means_of(baseline), cand = means_of(name);
    if (base.frames == 0 || cand.frames == 0) return std::nullopt;
    // The warm-up frames the time ratio leaves out (the table's times leave them out too).
    const bool warm_up_left_out = cand.timed_frames < cand.frames || base.timed_frames < base.frames;
    int last = first_change;
    for (const metrics_row& r : rows)
        if (r.method == name && r.frame >= first_change && r.frame < end) last = std::max(last, r.frame);

    auto ratio = [](double a, double b) -> std::string {
        if (!(b > 0.0)) return "-";
        char t[32];
        std::snprintf(t, sizeof t, "%.3fx", a / b);
        return t;
    };
    auto gap_of = [](const std::optional<double>& a, const std::optional<double>& b) -> std::string {
        if (!(a && b && std::isfinite(*a) && std::isfinite(*b))) return "-";
        char t[32];
        std::snprintf(t, sizeof t, "%+.2f dB", *a - *b);
        return t;
    };
    const std::optional<double> db_name = mean_psnr(cand.psnr), db_baseline = mean_psnr(base.psnr);
    const std::string gap = gap_of(db_name, db_baseline);
    char span[96];
    if (window > 0)
        std::snprintf(span, sizeof span, "frames %d-%d (from the first light change at frame %d)", first_change, last,
                      first_change);
    else
        std::snprintf(span, sizeof span, "frames %d-%d (every frame)", first_change, last);
    char line[400];
    char time_span[48] = "";
    if (warm_up_left_out) std::snprintf(time_span, sizeof time_span, " (from frame %d)", timing_from_frame);
    std::snprintf(line, sizeof line, "%s vs %s, %s: samples %s, SSS pass time %s%s, PSNR %s (%s %s, %s %s)",
                  name.c_str(), baseline.c_str(), span,
                  ratio(cand.spp / cand.frames, base.spp / base.frames).c_str(),
                  ratio(cand.sss_ms / cand.timed_frames, base.sss_ms / base.timed_frames).c_str(), time_span,
                  gap.c_str(), name.c_str(), psnr_text(db_name).c_str(), baseline.c_str(),
                  psnr_text(db_baseline).c_str());
    std::string out(line);
    const std::optional<double> resolved_name = mean_psnr(cand.psnr_resolved),
                                resolved_baseline = mean_psnr(base.psnr_resolved);
    if (resolved_name && resolved_baseline) {
        std::snprintf(line, sizeof line, ", resolved %s (%s %s, %s %s)", gap_of(resolved_name, resolved_baseline).c_str(),
                      name.c_str(), psnr_text(resolved_name).c_str(), baseline.c_str(),
                      psnr_text(resolved_baseline).c_str());
        out += line;
    }
    return out;
}

std::string format_summary(const std::vector<method_summary>& summaries, const std::vector<std::string>& notes) {
    std::ostringstream out;
    char line[256];
    // The resolved column only when the run resolved (--resolve taa).
    bool resolved = false;
    for (const method_summary& s : summaries) resolved = resolved || s.psnr_resolved_db.has_value();
    std::snprintf(line, sizeof line, "%-14s %6s %9s %9s %9s %9s %8s %9s %10s", "method", "frames", "sss_ms",
                  "sss_p95", "frame_ms", "mean_spp", "max_spp", "psnr_db", "psnr_sss");
    out << line << (resolved ? "  psnr_resolved\n" : "\n");
    for (const method_summary& s : summaries) {
        std::snprintf(line, sizeof line, "%-14s %6d %9.3f %9.3f %9.3f %9.1f %8d %9s %10s", s.method.c_str(),
                      s.frames, s.sss_ms_mean, s.sss_ms_p95, s.frame_ms_mean, s.mean_spp, s.max_spp,
                      psnr_text(s.psnr_db).c_str(), psnr_text(s.psnr_sss_db).c_str());
        out << line;
        if (resolved) {
            std::snprintf(line, sizeof line, " %14s", psnr_text(s.psnr_resolved_db).c_str());
            out << line;
        }
        out << '\n';
    }
    for (const std::string& note : notes) out << note << '\n';
    return out.str();
}

}  // namespace emcv::demo::app
