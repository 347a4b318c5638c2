// SPDX-License-Identifier: MIT
#include "summary.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>
#include <stdexcept>

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

namespace {

/// A method's frames in a window: sample and time sums, PSNRs and the tracked value's squared errors.
struct window_means {
    int frames = 0, timed_frames = 0;
    int last_frame = 0;
    double spp = 0.0, sss_ms = 0.0, all_sss_ms = 0.0;
    std::vector<std::optional<double>> psnr, psnr_resolved;
    std::vector<double> tracked_mse;

    double mean_sss_ms() const { return timed_frames > 0 ? sss_ms / timed_frames : 0.0; }
    bool warm_up_left_out() const { return timed_frames < frames; }
};

/// `method`'s frames from `first_change` up to the window's end (window 0: every frame from it). Times over the
/// frames from `timing_from_frame` on, as summarize takes the table's; over every frame of the window when none
/// is that late (a one-frame run).
window_means means_in_window(const std::vector<metrics_row>& rows, const std::string& method, int first_change,
                             int window, int timing_from_frame) {
    const int end = window > 0 ? first_change + window : std::numeric_limits<int>::max();
    window_means m;
    m.last_frame = first_change;
    for (const metrics_row& r : rows) {
        if (r.method != method || r.frame < first_change || r.frame >= end) continue;
        ++m.frames;
        m.last_frame = std::max(m.last_frame, r.frame);
        m.spp += r.mean_spp;
        m.all_sss_ms += r.sss_ms;
        if (r.frame >= timing_from_frame) {
            ++m.timed_frames;
            m.sss_ms += r.sss_ms;
        }
        m.psnr.push_back(r.psnr_db);
        m.psnr_resolved.push_back(r.psnr_resolved_db);
        if (r.tracked_mse) m.tracked_mse.push_back(*r.tracked_mse);
    }
    if (m.timed_frames == 0) m.timed_frames = m.frames, m.sss_ms = m.all_sss_ms;
    return m;
}

/// "frames A-B (from the first light change at frame A)" for a window after a change, "frames A-B (every frame)"
/// for window 0.
std::string span_text(int first_change, int last, int window) {
    char span[96];
    if (window > 0)
        std::snprintf(span, sizeof span, "frames %d-%d (from the first light change at frame %d)", first_change, last,
                      first_change);
    else
        std::snprintf(span, sizeof span, "frames %d-%d (every frame)", first_change, last);
    return span;
}

std::string gap_text(const std::optional<double>& a, const std::optional<double>& b) {
    if (!(a && b && std::isfinite(*a) && std::isfinite(*b))) return "-";
    char t[32];
    std::snprintf(t, sizeof t, "%+.2f dB", *a - *b);
    return t;
}

std::string ms_text(double ms) {
    char t[32];
    std::snprintf(t, sizeof t, "%.3f ms", ms);
    return t;
}

/// N of a burley-N method name; empty for any other name.
std::optional<int> burley_samples(const std::string& method) {
    const std::string prefix = "burley-";
    if (method.compare(0, prefix.size(), prefix) != 0 || method.size() == prefix.size()) return std::nullopt;
    int n = 0;
    for (std::size_t i = prefix.size(); i < method.size(); ++i) {
        if (method[i] < '0' || method[i] > '9' || n > 100000) return std::nullopt;
        n = n * 10 + (method[i] - '0');
    }
    return n;
}

/// A burley-N run of the window: its mean SSS time and mean PSNRs (raw, resolved).
struct burley_point {
    std::string method;
    double sss_ms = 0.0;
    double psnr_db = 0.0;
    std::optional<double> psnr_resolved_db;
};

/// The PSNR at time t on the line through (t1, p1) and (t2, p2) in log time:
/// p1 + (p2 - p1) ln(t / t1) / ln(t2 / t1); p1 when the two times are equal.
double psnr_at_log_time(double t, double t1, double p1, double t2, double p2) {
    if (t2 == t1) return p1;
    return p1 + (p2 - p1) * std::log(t / t1) / std::log(t2 / t1);
}

/// What an image of PSNR `db` is worth in burley samples: the N of the burley runs' line through the two that bracket
/// it in PSNR, ln N linear in dB (N_1 (N_2 / N_1)^((db - p_1) / (p_2 - p_1))), as "burley-20.2"; outside the runs
/// "more than burley-64" or "less than burley-4", not an extrapolation. `psnr_of` picks the raw or resolved PSNR.
template <class PsnrOf>
std::string worth_text(std::vector<burley_point> curve, double db, PsnrOf psnr_of) {
    curve.erase(std::remove_if(curve.begin(), curve.end(),
                               [&](const burley_point& b) { return !psnr_of(b) || !burley_samples(b.method); }),
                curve.end());
    if (curve.empty()) return "n/a";
    std::sort(curve.begin(), curve.end(),
              [&](const burley_point& a, const burley_point& b) { return *psnr_of(a) < *psnr_of(b); });
    if (db > *psnr_of(curve.back())) return "more than " + curve.back().method;
    if (db < *psnr_of(curve.front())) return "less than " + curve.front().method;
    std::size_t upper = 0;
    while (upper + 1 < curve.size() && *psnr_of(curve[upper]) < db) ++upper;
    const burley_point& above = curve[upper];
    const burley_point& below = curve[upper == 0 ? 0 : upper - 1];
    const double n1 = *burley_samples(below.method), n2 = *burley_samples(above.method);
    const double p1 = *psnr_of(below), p2 = *psnr_of(above);
    const double n = p2 == p1 ? n1 : n1 * std::pow(n2 / n1, (db - p1) / (p2 - p1));
    char t[48];
    std::snprintf(t, sizeof t, "burley-%.1f", n);
    return t;
}

}  // namespace

std::optional<std::string> compare_after_change(const std::vector<metrics_row>& rows, int first_change,
                                                const std::string& name, const std::string& baseline, int window,
                                                int timing_from_frame) {
    const window_means base = means_in_window(rows, baseline, first_change, window, timing_from_frame),
                       cand = means_in_window(rows, name, first_change, window, timing_from_frame);
    if (base.frames == 0 || cand.frames == 0) return std::nullopt;
    // The warm-up frames the time ratio leaves out (the table's times leave them out too).
    const bool warm_up_left_out = cand.warm_up_left_out() || base.warm_up_left_out();

    auto ratio = [](double a, double b) -> std::string {
        if (!(b > 0.0)) return "-";
        char t[32];
        std::snprintf(t, sizeof t, "%.3fx", a / b);
        return t;
    };
    const std::optional<double> db_name = mean_psnr(cand.psnr), db_baseline = mean_psnr(base.psnr);
    const std::string span = span_text(first_change, cand.last_frame, window);
    char line[400];
    char time_span[48] = "";
    if (warm_up_left_out) std::snprintf(time_span, sizeof time_span, " (from frame %d)", timing_from_frame);
    std::snprintf(line, sizeof line, "%s vs %s, %s: samples %s, SSS pass time %s%s, PSNR %s (%s %s, %s %s)",
                  name.c_str(), baseline.c_str(), span.c_str(),
                  ratio(cand.spp / cand.frames, base.spp / base.frames).c_str(),
                  ratio(cand.mean_sss_ms(), base.mean_sss_ms()).c_str(), time_span,
                  gap_text(db_name, db_baseline).c_str(), name.c_str(), psnr_text(db_name).c_str(), baseline.c_str(),
                  psnr_text(db_baseline).c_str());
    std::string out(line);
    const std::optional<double> resolved_name = mean_psnr(cand.psnr_resolved),
                                resolved_baseline = mean_psnr(base.psnr_resolved);
    if (resolved_name && resolved_baseline) {
        std::snprintf(line, sizeof line, ", resolved %s (%s %s, %s %s)",
                      gap_text(resolved_name, resolved_baseline).c_str(), name.c_str(),
                      psnr_text(resolved_name).c_str(), baseline.c_str(), psnr_text(resolved_baseline).c_str());
        out += line;
    }
    return out;
}

std::optional<std::string> compare_at_equal_time(const std::vector<metrics_row>& rows, int first_change,
                                                 const std::string& name, int window, int timing_from_frame) {
    const window_means cand = means_in_window(rows, name, first_change, window, timing_from_frame);
    const std::optional<double> db_name = mean_psnr(cand.psnr);
    const double t = cand.mean_sss_ms();
    if (cand.frames == 0 || !(t > 0.0) || !db_name || !std::isfinite(*db_name)) return std::nullopt;

    // The burley-N runs of the same rows, sorted by time: a PSNR needs a positive time to sit on a log axis.
    std::vector<std::string> seen;
    std::vector<burley_point> curve;
    bool warm_up_left_out = cand.warm_up_left_out();
    for (const metrics_row& r : rows) {
        if (!burley_samples(r.method) || std::find(seen.begin(), seen.end(), r.method) != seen.end()) continue;
        seen.push_back(r.method);
        const window_means m = means_in_window(rows, r.method, first_change, window, timing_from_frame);
        const std::optional<double> db = mean_psnr(m.psnr);
        if (m.frames == 0 || !(m.mean_sss_ms() > 0.0) || !db || !std::isfinite(*db)) continue;
        warm_up_left_out = warm_up_left_out || m.warm_up_left_out();
        const std::optional<double> resolved = mean_psnr(m.psnr_resolved);
        curve.push_back({r.method, m.mean_sss_ms(), *db,
                         resolved && std::isfinite(*resolved) ? resolved : std::optional<double>()});
    }
    if (curve.empty()) return std::nullopt;
    std::sort(curve.begin(), curve.end(),
              [](const burley_point& a, const burley_point& b) { return a.sss_ms < b.sss_ms; });

    std::string out = name + " vs burley-N at " + name + "'s SSS time, " +
                      span_text(first_change, cand.last_frame, window) + ": ";
    const std::string from_frame = warm_up_left_out ? ", from frame " + std::to_string(timing_from_frame) : "";
    // What the method's image is worth in burley samples (equal PSNR): quality alone, so it holds on any device; the
    // method wins at equal time wherever its pass costs less than that many burley samples.
    const std::optional<double> resolved_name = mean_psnr(cand.psnr_resolved);
    std::string worth = "; its image is worth " +
                        worth_text(curve, *db_name, [](const burley_point& b) { return std::optional<double>(b.psnr_db); });
    if (resolved_name && std::isfinite(*resolved_name))
        worth += " (resolved " +
                 worth_text(curve, *resolved_name, [](const burley_point& b) { return b.psnr_resolved_db; }) + ")";
    // Outside the burley runs' times the curve is not known: say so rather than extrapolate.
    const burley_point &fastest = curve.front(), &slowest = curve.back();
    if (t > slowest.sss_ms || t < fastest.sss_ms) {
        const burley_point& edge = t > slowest.sss_ms ? slowest : fastest;
        return out + name + "'s SSS time is " + (t > slowest.sss_ms ? "beyond " : "below ") + edge.method + "'s (" +
               ms_text(t) + " against " + ms_text(edge.sss_ms) + from_frame + "): no equal-time comparison" + worth;
    }
    std::size_t upper = 1;
    while (upper < curve.size() && curve[upper].sss_ms < t) ++upper;
    const burley_point& below = curve[upper < curve.size() ? upper - 1 : 0];
    const burley_point& above = curve[upper < curve.size() ? upper : 0];
    const double burley_db = psnr_at_log_time(t, below.sss_ms, below.psnr_db, above.sss_ms, above.psnr_db);
    out += ms_text(t) + from_frame + ", ";
    out += curve.size() == 1 ? "burley-N: " + below.method + " alone (" + ms_text(below.sss_ms) + ")"
                             : "between " + below.method + " (" + ms_text(below.sss_ms) + ") and " + above.method +
                                   " (" + ms_text(above.sss_ms) + ")";
    out += ", PSNR " + gap_text(db_name, burley_db) + " (" + name + " " + psnr_text(db_name) + ", burley-N there " +
           psnr_text(burley_db) + ")";
    if (resolved_name && below.psnr_resolved_db && above.psnr_resolved_db) {
        const double burley_resolved =
            psnr_at_log_time(t, below.sss_ms, *below.psnr_resolved_db, above.sss_ms, *above.psnr_resolved_db);
        out += ", resolved " + gap_text(resolved_name, burley_resolved) + " (" + name + " " +
               psnr_text(resolved_name) + ", burley-N there " + psnr_text(burley_resolved) + ")";
    }
    return out + worth;
}

std::optional<std::string> compare_with_target(const std::vector<metrics_row>& rows, int first_change,
                                               const std::vector<std::string>& names, double target_variance,
                                               int window) {
    if (!(target_variance > 0.0) || !std::isfinite(target_variance))
        throw std::invalid_argument("compare_with_target: the target variance must be finite and > 0");
    std::string verdicts;
    int last = first_change;
    for (const std::string& name : names) {
        const window_means m = means_in_window(rows, name, first_change, window, 0);
        if (m.tracked_mse.empty()) continue;
        last = std::max(last, m.last_frame);
        double sum = 0.0;
        int frames_under = 0;
        for (double v : m.tracked_mse) {
            sum += v;
            frames_under += v <= target_variance ? 1 : 0;
        }
        const double mse = sum / static_cast<double>(m.tracked_mse.size());
        char verdict[160];
        std::snprintf(verdict, sizeof verdict, "%s%s %.2e = %.2f V: %s (under V on %d of %zu frames)",
                      verdicts.empty() ? "" : "; ", name.c_str(), mse, mse / target_variance,
                      mse <= target_variance ? "met" : "missed", frames_under, m.tracked_mse.size());
        verdicts += verdict;
    }
    if (verdicts.empty()) return std::nullopt;
    char head[96];
    std::snprintf(head, sizeof head, "target variance V = %.2e, ", target_variance);
    return head + span_text(first_change, last, window) +
           ": squared error of the tracked value per SSS pixel against the reference, mean over frames: " + verdicts;
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
