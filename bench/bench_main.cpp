// SPDX-License-Identifier: MIT
// emcv-bench: nanoseconds per update of every estimator variant beside its error on the hard cases, the
// per-pixel batch beside a same-bytes copy, and Boost.Accumulators on the same streams.
// scripts/bench_tables.py runs it with --benchmark_format=json and writes docs/results/accuracy-vs-time.md.
#include <benchmark/benchmark.h>

#include <boost/accumulators/accumulators.hpp>
#include <boost/accumulators/statistics/rolling_variance.hpp>
#include <boost/accumulators/statistics/stats.hpp>
#include <boost/accumulators/statistics/variance.hpp>
#include <boost/accumulators/statistics/variates/covariate.hpp>
#include <boost/accumulators/statistics/weighted_covariance.hpp>
#include <boost/accumulators/statistics/weighted_variance.hpp>

#include <emcv/adaptive_sampling.hpp>
#include <emcv/emcv.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <map>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "bench_cli.hpp"
#include "numerics_support.hpp"
#include "raw_moments.hpp"

namespace acc = boost::accumulators;
using emcv_numerics::ld;

namespace {

constexpr double bench_eta = 0.05;            // the paper's EMCM weight
constexpr std::size_t rolling_window = 39;    // 2 / eta - 1: the same effective memory as eta = 0.05
constexpr std::size_t timing_length = 1 << 14;
constexpr std::size_t error_length = 20000;

// ---------------------------------------------------------------------------------------------------------
// streams
// ---------------------------------------------------------------------------------------------------------

struct pair_stream {
    std::vector<double> x, y, w;
};

pair_stream make_stream(const std::string& kind, bool is_float, std::size_t n) {
    pair_stream s;
    emcv_numerics::uniform_source u(kind.size() * 7919 + (is_float ? 1 : 2));
    for (std::size_t i = 0; i < n; ++i) {
        const double z1 = u.next(), z2 = u.next(), z3 = u.next();
        double x = 0, y = 0;
        if (kind == "timing") {
            x = 1e3 + z1;
            y = 5e2 + 0.6 * z1 + 0.8 * z2;
        } else if (kind == "offset") {  // large offset, small spread (float 1e4 +- 0.1, double 1e9 +- 0.1)
            const double m = is_float ? 1e4 : 1e9;
            x = m + 0.1 * z1;
            y = 0.5 * m + 0.1 * (0.6 * z1 + 0.8 * z2);
        } else if (kind == "step") {  // light 1e3 -> 0 -> 1e3 in thirds
            const bool on = i < n / 3 || i >= 2 * n / 3;
            x = on ? 1e3 * (1 + 0.01 * z1) : 0.0;
            y = on ? 5e2 * (1 + 0.01 * z2) : 0.0;
        } else if (kind == "numacc3") {  // NIST StRD NumAcc3 pattern: 1000000.2, then 1000000.1 / .3 alternating
            x = i == 0 ? 1000000.2 : (i % 2 == 1 ? 1000000.1 : 1000000.3);
            y = x - 1000000.0;
        }
        s.x.push_back(x);
        s.y.push_back(y);
        s.w.push_back(1.25 + 0.75 * z3);
    }
    return s;
}

template <class T>
std::vector<T> as(const std::vector<double>& v) {
    std::vector<T> out;
    out.reserve(v.size());
    for (double e : v) out.push_back(static_cast<T>(e));
    return out;
}

// ---------------------------------------------------------------------------------------------------------
// variants: each is a function that feeds a stream and returns the final statistic
// ---------------------------------------------------------------------------------------------------------

enum class statistic { variance, covariance, rolling_variance };
enum class exact_kind { exponential, cumulative, weighted, rolling };

template <class T>
struct variant {
    std::string name;
    std::string family;  // which statistic it estimates, for the table
    statistic stat;
    exact_kind exact;
    std::function<T(const std::vector<T>&, const std::vector<T>&, const std::vector<T>&)> run;
};

/// EMCM variance of a stream by the bare step: the first sample seeds (mean = x, variance 0), then r = eta.
template <emcv::detail::range_check Range, class T>
T one_stream_step(const std::vector<T>& x, T eta) {
    T mean = x[0], variance = T(0);
    for (std::size_t i = 1; i < x.size(); ++i)
        emcv::detail::comoment_step<emcv::mean_accuracy::plain, 1, Range>(&mean, static_cast<T*>(nullptr), &variance,
                                                                          static_cast<T*>(nullptr), &x[i], eta,
                                                                          emcv::comoment_form::current_mean);
    return variance;
}

template <class T>
std::vector<variant<T>> variants() {
    const T eta = static_cast<T>(bench_eta);
    using V = std::vector<T>;
    std::vector<variant<T>> out;
    out.push_back({"emcm", "exponential variance", statistic::variance, exact_kind::exponential,
                   [eta](const V& x, const V&, const V&) {
                       emcv::emcm<T, 1> e(eta);
                       for (T v : x) e.push(v);
                       return e.variance(0);
                   }});
    out.push_back({"compensated_emcm", "exponential variance", statistic::variance, exact_kind::exponential,
                   [eta](const V& x, const V&, const V&) {
                       emcv::compensated_emcm<T, 1> e(eta);
                       for (T v : x) e.push(v);
                       return e.variance(0);
                   }});
    out.push_back({"moving_stats", "exponential variance", statistic::variance, exact_kind::exponential,
                   [eta](const V& x, const V&, const V&) {
                       emcv::moving_stats<T> e(eta);
                       for (T v : x) e.push(v);
                       return e.variance();
                   }});
    // The one-stream step alone (no finiteness test, no count), with the range clamps of x - mu and of the
    // variance evaluated as selects (the vectorisable form the batch uses, on the dependent chain) and behind
    // predicted branches (the form emcm's push uses since issue 12): same results, side by side in one run.
    out.push_back({"emcm step, range clamps as selects", "exponential variance", statistic::variance,
                   exact_kind::exponential, [eta](const V& x, const V&, const V&) {
                       return one_stream_step<emcv::detail::range_check::select>(x, eta);
                   }});
    out.push_back({"emcm step, range clamps behind branches", "exponential variance", statistic::variance,
                   exact_kind::exponential, [eta](const V& x, const V&, const V&) {
                       return one_stream_step<emcv::detail::range_check::branch>(x, eta);
                   }});
    out.push_back({"raw moments (exponential E[x^2]-E[x]^2)", "exponential variance", statistic::variance,
                   exact_kind::exponential, [eta](const V& x, const V&, const V&) {
                       emcv_numerics::raw_moments<T> m;
                       bool first = true;
                       for (T v : x) {
                           m.push(v, T(0), first ? T(1) : eta);
                           first = false;
                       }
                       return m.variance_x();
                   }});
    out.push_back({"emcm 2-D covariance", "exponential covariance", statistic::covariance, exact_kind::exponential,
                   [eta](const V& x, const V& y, const V&) {
                       emcv::emcm<T, 2> e(eta);
                       for (std::size_t i = 0; i < x.size(); ++i) e.push({x[i], y[i]});
                       return e.covariance(0, 1);
                   }});
    out.push_back({"ewma_covariance 2-D", "EWMA covariance (Eq. 22)", statistic::covariance, exact_kind::exponential,
                   [eta](const V& x, const V& y, const V&) {
                       emcv::ewma_covariance<T, 2> e(eta);
                       for (std::size_t i = 0; i < x.size(); ++i) e.push({x[i], y[i]});
                       return e.covariance(0, 1);
                   }});
    out.push_back({"Boost rolling_variance (window 39)", "windowed variance", statistic::rolling_variance,
                   exact_kind::rolling, [](const V& x, const V&, const V&) {
                       acc::accumulator_set<T, acc::stats<acc::tag::rolling_variance>> a(
                           acc::tag::rolling_window::window_size = rolling_window);
                       for (T v : x) a(v);
                       return static_cast<T>(acc::rolling_variance(a));
                   }});
    out.push_back({"running_covariance", "cumulative variance", statistic::variance, exact_kind::cumulative,
                   [](const V& x, const V&, const V&) {
                       emcv::running_covariance<T, 1> e;
                       for (T v : x) e.push(v);
                       return e.variance(0);
                   }});
    out.push_back({"compensated_running_covariance", "cumulative variance", statistic::variance,
                   exact_kind::cumulative, [](const V& x, const V&, const V&) {
                       emcv::compensated_running_covariance<T, 1> e;
                       for (T v : x) e.push(v);
                       return e.variance(0);
                   }});
    out.push_back({"raw moments (cumulative E[x^2]-E[x]^2)", "cumulative variance", statistic::variance,
                   exact_kind::cumulative, [](const V& x, const V&, const V&) {
                       emcv_numerics::raw_moments<T> m;
                       std::uint64_t n = 0;
                       for (T v : x) m.push(v, T(0), T(1) / static_cast<T>(++n));
                       return m.variance_x();
                   }});
    out.push_back({"Boost variance (immediate)", "cumulative variance", statistic::variance, exact_kind::cumulative,
                   [](const V& x, const V&, const V&) {
                       acc::accumulator_set<T, acc::stats<acc::tag::variance>> a;
                       for (T v : x) a(v);
                       return static_cast<T>(acc::variance(a));
                   }});
    out.push_back({"Boost lazy_variance (raw moments)", "cumulative variance", statistic::variance,
                   exact_kind::cumulative, [](const V& x, const V&, const V&) {
                       acc::accumulator_set<T, acc::stats<acc::tag::lazy_variance>> a;
                       for (T v : x) a(v);
                       return static_cast<T>(acc::variance(a));
                   }});
    out.push_back({"weighted_covariance 2-D", "weighted covariance", statistic::covariance, exact_kind::weighted,
                   [](const V& x, const V& y, const V& w) {
                       emcv::weighted_covariance<T, 2> e;
                       for (std::size_t i = 0; i < x.size(); ++i) e.push({x[i], y[i]}, w[i]);
                       return e.covariance(0, 1);
                   }});
    out.push_back({"Boost weighted_covariance", "weighted covariance", statistic::covariance, exact_kind::weighted,
                   [](const V& x, const V& y, const V& w) {
                       acc::accumulator_set<T, acc::stats<acc::tag::weighted_covariance<T, acc::tag::covariate1>>, T> a;
                       for (std::size_t i = 0; i < x.size(); ++i) a(x[i], acc::weight = w[i], boost::accumulators::covariate1 = y[i]);
                       return static_cast<T>(acc::weighted_covariance(a));
                   }});
    out.push_back({"Boost weighted_covariance + 2 weighted_variance (same 2x2 matrix)", "weighted covariance",
                   statistic::covariance, exact_kind::weighted, [](const V& x, const V& y, const V& w) {
                       acc::accumulator_set<T, acc::stats<acc::tag::weighted_covariance<T, acc::tag::covariate1>,
                                                          acc::tag::weighted_variance>,
                                            T>
                           a;
                       acc::accumulator_set<T, acc::stats<acc::tag::weighted_variance>, T> b;
                       for (std::size_t i = 0; i < x.size(); ++i) {
                           a(x[i], acc::weight = w[i], boost::accumulators::covariate1 = y[i]);
                           b(y[i], acc::weight = w[i]);
                       }
                       const T var_sum = static_cast<T>(acc::weighted_variance(a)) + static_cast<T>(acc::weighted_variance(b));
                       benchmark::DoNotOptimize(var_sum);
                       return static_cast<T>(acc::weighted_covariance(a));
                   }});
    return out;
}

/// The exact final statistic of a stream (long double; the recurrences are exact in exact arithmetic, and the
/// windowed variance is a two-pass sum over the last window), and the reference's own error bound relative to
/// it (docs/numerics.md section 2; 0 for the two-pass window, which carries no bound).
struct exact_result {
    ld value = 0, relative_bound = 0;
};

template <class T>
exact_result exact_value(const variant<T>& v, const std::vector<T>& x, const std::vector<T>& y, const std::vector<T>& w) {
    if (v.exact == exact_kind::rolling) {
        const std::size_t n = x.size(), k = std::min(rolling_window, n);
        ld mean = 0, s = 0;
        for (std::size_t i = n - k; i < n; ++i) mean += static_cast<ld>(x[i]);
        mean /= static_cast<ld>(k);
        for (std::size_t i = n - k; i < n; ++i) s += (static_cast<ld>(x[i]) - mean) * (static_cast<ld>(x[i]) - mean);
        return {s / static_cast<ld>(k - 1), 0};  // Boost's rolling variance is the unbiased one
    }
    emcv_numerics::schedule sch;
    if (v.exact == exact_kind::exponential) {
        sch.kind = emcv_numerics::schedule_kind::exponential;
        sch.eta = static_cast<ld>(static_cast<T>(bench_eta));
        if (v.family == "EWMA covariance (Eq. 22)") sch.form = emcv::comoment_form::previous_mean;
    } else if (v.exact == exact_kind::weighted) {
        sch.kind = emcv_numerics::schedule_kind::weighted;
    }
    emcv_numerics::reference_with_bound<2> ref(sch, emcv_numerics::long_double_model(), emcv_numerics::long_double_model());
    for (std::size_t i = 0; i < x.size(); ++i)
        ref.push({static_cast<ld>(x[i]), static_cast<ld>(y[i])}, static_cast<ld>(w[i]));
    // Boost's cumulative variance is the population one, like ours
    const std::size_t k = v.stat == statistic::covariance ? 1 : 0;
    const ld value = ref.cov(k);
    return {value, value != 0 ? ref.cov_bound(k) / std::fabs(value) : ref.cov_bound(k)};
}

/// Relative error of a variant on a stream, and the relative bound of the reference it is measured against.
template <class T>
std::pair<double, double> relative_error(const variant<T>& v, const std::string& kind) {
    const pair_stream s = make_stream(kind, sizeof(T) == sizeof(float), error_length);
    const auto x = as<T>(s.x), y = as<T>(s.y), w = as<T>(s.w);
    const exact_result exact = exact_value(v, x, y, w);
    const double bound = static_cast<double>(exact.relative_bound);
    const ld got = static_cast<ld>(v.run(x, y, w));
    if (!std::isfinite(static_cast<double>(got))) return {std::numeric_limits<double>::infinity(), bound};
    if (exact.value == 0) return {static_cast<double>(std::fabs(got)), bound};
    return {static_cast<double>(std::fabs(got - exact.value) / std::fabs(exact.value)), bound};
}

template <class T>
void register_scalar(const char* precision) {
    for (const variant<T>& v : variants<T>()) {
        std::map<std::string, double> errors, bounds;
        for (const char* kind : {"offset", "step", "numacc3"}) std::tie(errors[kind], bounds[kind]) = relative_error(v, kind);
        const pair_stream s = make_stream("timing", sizeof(T) == sizeof(float), timing_length);
        const auto x = as<T>(s.x), y = as<T>(s.y), w = as<T>(s.w);
        const std::string name = std::string("scalar/") + precision + "/" + v.name;
        benchmark::RegisterBenchmark(name.c_str(), [v, x, y, w, errors, bounds](benchmark::State& state) {
            for (auto _ : state) {
                T result = v.run(x, y, w);
                benchmark::DoNotOptimize(result);
            }
            state.counters["updates"] = static_cast<double>(x.size());
            for (const auto& e : errors) state.counters["err_" + e.first] = e.second;
            for (const auto& b : bounds) state.counters["refbound_" + b.first] = b.second;
            state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * static_cast<std::int64_t>(x.size())));
        });
    }
}

/// cv_coefficient and sample_count are closed forms with one rounding each (no error column): time per call on
/// the timing stream read as (cov_fg, var_g) and (variance) values.
template <class T>
void register_closed_forms(const char* precision) {
    const pair_stream s = make_stream("timing", sizeof(T) == sizeof(float), timing_length);
    std::vector<T> cov, var;
    for (std::size_t i = 0; i < s.x.size(); ++i) {
        cov.push_back(static_cast<T>(s.y[i] - 500.0));
        var.push_back(static_cast<T>((s.x[i] - 1000.0) * (s.x[i] - 1000.0)));
    }
    benchmark::RegisterBenchmark((std::string("scalar/") + precision + "/cv_coefficient").c_str(),
                                 [cov, var](benchmark::State& state) {
                                     for (auto _ : state) {
                                         T sum = T(0);
                                         for (std::size_t i = 0; i < cov.size(); ++i)
                                             sum += emcv::cv_coefficient(cov[i], var[i]);
                                         benchmark::DoNotOptimize(sum);
                                     }
                                     state.counters["updates"] = static_cast<double>(cov.size());
                                 });
    benchmark::RegisterBenchmark((std::string("scalar/") + precision + "/sample_count").c_str(),
                                 [var](benchmark::State& state) {
                                     for (auto _ : state) {
                                         int sum = 0;
                                         for (std::size_t i = 0; i < var.size(); ++i)
                                             sum += emcv::sample_count(var[i], T(1e-2), 0, 64);
                                         benchmark::DoNotOptimize(sum);
                                     }
                                     state.counters["updates"] = static_cast<double>(var.size());
                                 });
}

// ---------------------------------------------------------------------------------------------------------
// per-pixel structure-of-arrays batch over a 1920 x 1080 history
// ---------------------------------------------------------------------------------------------------------

constexpr std::size_t pixels = 1920 * 1080;

/// The library's batch update behind a call boundary, as a renderer calls it once per frame from its own
/// code.
template <class T>
[[gnu::noinline]] std::size_t batch_update(T* mean, T* mean_low, T* variance, T* variance_low, const T* frame,
                                           std::size_t count, T eta) {
    return emcv::moving_stats_update(mean, mean_low, variance, variance_low, frame, count, eta).rejected;
}

template <class T>
struct soa_history {
    std::vector<T> frame, mean, mean_low, variance, variance_low;
    explicit soa_history(bool is_float)
        : frame(pixels), mean(pixels), mean_low(pixels, T(0)), variance(pixels, T(0)), variance_low(pixels, T(0)) {
        emcv_numerics::uniform_source u(is_float ? 3 : 4);
        for (std::size_t i = 0; i < pixels; ++i) {
            frame[i] = static_cast<T>(1.0 + 0.5 * u.next());
            mean[i] = static_cast<T>(1.0 + 0.5 * u.next());
        }
    }
};

template <class T>
void register_batch(const char* precision) {
    const bool is_float = sizeof(T) == sizeof(float);
    // One EMCM update per pixel: reads frame, mean, variance; writes mean, variance. The compensated form
    // also reads and writes mean_low and variance_low (9 arrays' worth of bytes instead of 5).
    for (const bool compensated : {false, true}) {
        const std::string name = std::string("batch/") + precision + "/moving_stats_update" +
                                 (compensated ? " compensated" : "");
        benchmark::RegisterBenchmark(name.c_str(), [is_float, compensated](benchmark::State& state) {
            soa_history<T> h(is_float);
            volatile double eta_at_run_time = bench_eta;  // as in a renderer
            const T eta = static_cast<T>(eta_at_run_time);
            T* mean_low = compensated ? h.mean_low.data() : nullptr;
            T* variance_low = compensated ? h.variance_low.data() : nullptr;
            for (auto _ : state) {
                const std::size_t rejected =
                    batch_update(h.mean.data(), mean_low, h.variance.data(), variance_low, h.frame.data(), pixels, eta);
                benchmark::DoNotOptimize(rejected);
                benchmark::ClobberMemory();
            }
            state.counters["updates"] = static_cast<double>(pixels);
            // distinct bytes touched per frame (3 or 5 arrays), to tell an in-cache run from a DRAM-bound one
            state.counters["working_set_bytes"] = static_cast<double>((compensated ? 5 : 3) * sizeof(T) * pixels);
            const std::size_t arrays = compensated ? 9 : 5;
            state.SetBytesProcessed(state.iterations() * static_cast<std::int64_t>(arrays * sizeof(T) * pixels));
        });
    }
    // the bandwidth bound: the same bytes (3 arrays read, 2 written) with no arithmetic beyond one add
    benchmark::RegisterBenchmark((std::string("batch/") + precision + "/copy (same bytes)").c_str(),
                                 [is_float](benchmark::State& state) {
                                     soa_history<T> h(is_float);
                                     for (auto _ : state) {
                                         T* mean = h.mean.data();
                                         T* variance = h.variance.data();
                                         const T* frame = h.frame.data();
                                         for (std::size_t i = 0; i < pixels; ++i) {
                                             const T f = frame[i], m = mean[i], v = variance[i];
                                             mean[i] = f;
                                             variance[i] = m + v;
                                         }
                                         benchmark::ClobberMemory();
                                     }
                                     state.counters["updates"] = static_cast<double>(pixels);
                                     state.counters["working_set_bytes"] = static_cast<double>(3 * sizeof(T) * pixels);
                                     state.SetBytesProcessed(state.iterations() * static_cast<std::int64_t>(5 * sizeof(T) * pixels));
                                 });
    benchmark::RegisterBenchmark((std::string("batch/") + precision + "/copy compensated (same bytes)").c_str(),
                                 [is_float](benchmark::State& state) {
                                     soa_history<T> h(is_float);
                                     for (auto _ : state) {
                                         T* mean = h.mean.data();
                                         T* low = h.mean_low.data();
                                         T* variance = h.variance.data();
                                         T* variance_low = h.variance_low.data();
                                         const T* frame = h.frame.data();
                                         for (std::size_t i = 0; i < pixels; ++i) {
                                             const T f = frame[i], m = mean[i], l = low[i], v = variance[i],
                                                     vl = variance_low[i];
                                             mean[i] = f;
                                             low[i] = m;
                                             variance[i] = l + v;
                                             variance_low[i] = vl;
                                         }
                                         benchmark::ClobberMemory();
                                     }
                                     state.counters["updates"] = static_cast<double>(pixels);
                                     state.counters["working_set_bytes"] = static_cast<double>(5 * sizeof(T) * pixels);
                                     state.SetBytesProcessed(state.iterations() * static_cast<std::int64_t>(9 * sizeof(T) * pixels));
                                 });
}

// ---------------------------------------------------------------------------------------------------------
// the adaptive-sampling policy per frame (emcv/adaptive_sampling.hpp) over a 1920 x 1080 SSS frame
// ---------------------------------------------------------------------------------------------------------

/// The policy cases' counters: the median frame time over the run (the table's number), the pixels updated
/// per frame and the bytes of their state.
void set_policy_counters(benchmark::State& state, std::vector<double>& frame_ms, std::size_t state_size) {
    std::sort(frame_ms.begin(), frame_ms.end());
    state.counters["median_frame_ms"] = frame_ms.empty() ? 0.0 : frame_ms[frame_ms.size() / 2];
    state.counters["updates"] = static_cast<double>(pixels);
    state.counters["state_bytes"] = static_cast<double>(state_size * pixels);
}

/// One frame of the policy: plan (variance codes; under a budget the shrinkage, histogram and solve; counts), then the
/// update with this frame's (f, G) and counts. Timed with std::chrono::steady_clock per frame (manual time);
/// the counter median_frame_ms is the median over the run's frames.
template <class State>
void register_policy(const char* name, emcv::sampling_estimator estimator, emcv::sampling_mode mode, State init) {
    benchmark::RegisterBenchmark(name, [estimator, mode, init](benchmark::State& state) {
        emcv::sampling_params p;
        p.estimator = estimator;
        p.mode = mode;
        constexpr std::size_t width = 1920;
        std::vector<State> states(pixels, init);
        std::vector<float> sigma2(pixels), f(pixels), g(pixels);
        std::vector<int> n(pixels, 8);
        emcv_numerics::uniform_source u(5);
        for (std::size_t i = 0; i < pixels; ++i) g[i] = static_cast<float>(0.5 + 0.25 * u.next());
        std::vector<double> frame_ms;
        std::uint32_t frame = 0;
        emcv::budget_prior prior;  // the budget's shrinkage statistics, carried from frame to frame as an engine does
        for (auto _ : state) {
            for (std::size_t i = 0; i < pixels; ++i)  // a new noisy f each frame, outside the timed region
                f[i] = g[i] * static_cast<float>(1.0 + 0.05 * u.next());
            const auto start = std::chrono::steady_clock::now();
            const emcv::frame_plan plan = emcv::plan_frame(p, states.data(), pixels, width, nullptr, nullptr, frame++,
                                                           1u, sigma2.data(), n.data(), prior);
            emcv::sampling_update(p, states.data(), pixels, width, nullptr, f.data(), g.data(), n.data());
            const std::chrono::duration<double> took = std::chrono::steady_clock::now() - start;
            benchmark::DoNotOptimize(plan.samples);
            benchmark::ClobberMemory();
            state.SetIterationTime(took.count());
            frame_ms.push_back(took.count() * 1e3);
        }
        set_policy_counters(state, frame_ms, sizeof(State));
    })->UseManualTime()->Unit(benchmark::kMillisecond);
}

/// The copy bound of the policy: the same state bytes read and written once per frame (memcpy between two
/// state arrays), plus the frame's f, G and count arrays read and the counts written.
template <class State>
void register_policy_copy(const char* name) {
    benchmark::RegisterBenchmark(name, [](benchmark::State& state) {
        std::vector<State> a(pixels), b(pixels);
        std::vector<float> f(pixels, 0.5f), g(pixels, 0.5f), sigma2(pixels);
        std::vector<int> n(pixels, 8), m(pixels);
        std::vector<double> frame_ms;
        for (auto _ : state) {
            const auto start = std::chrono::steady_clock::now();
            std::memcpy(b.data(), a.data(), sizeof(State) * pixels);
            std::memcpy(sigma2.data(), f.data(), sizeof(float) * pixels);
            std::memcpy(m.data(), n.data(), sizeof(int) * pixels);
            std::memcpy(sigma2.data(), g.data(), sizeof(float) * pixels);
            std::swap(a, b);
            const std::chrono::duration<double> took = std::chrono::steady_clock::now() - start;
            benchmark::ClobberMemory();
            state.SetIterationTime(took.count());
            frame_ms.push_back(took.count() * 1e3);
        }
        set_policy_counters(state, frame_ms, sizeof(State));
    })->UseManualTime()->Unit(benchmark::kMillisecond);
}

void register_policies() {
    using emcv::sampling_estimator;
    using emcv::sampling_mode;
    register_policy("policy/spvg quality/update + plan_frame", sampling_estimator::spvg, sampling_mode::quality_target,
                    emcv::port::emcv_moving_stats_init());
    register_policy("policy/spvg budget/update + plan_frame", sampling_estimator::spvg, sampling_mode::budget,
                    emcv::port::emcv_moving_stats_init());
    register_policy_copy<emcv::port::EmcvMovingStats>("policy/spvg/copy (same bytes)");
    register_policy("policy/cv quality/update + plan_frame", sampling_estimator::cv, sampling_mode::quality_target,
                    emcv::port::emcv_emcm2_init());
    register_policy("policy/cv budget/update + plan_frame", sampling_estimator::cv, sampling_mode::budget,
                    emcv::port::emcv_emcm2_init());
    register_policy_copy<emcv::port::EmcvEmcm2>("policy/cv/copy (same bytes)");
}

}  // namespace

int main(int argc, char** argv) {
    register_scalar<float>("float");
    register_scalar<double>("double");
    register_closed_forms<float>("float");
    register_closed_forms<double>("double");
    register_batch<float>("float");
    register_batch<double>("double");
    register_policies();
    emcv_bench::command_line cli = emcv_bench::parse_command_line(argc, argv);
    auto drop_partial = [&] {
        if (!cli.partial_path.empty()) std::remove(cli.partial_path.c_str());
    };
    if (!cli.error.empty()) {
        std::fprintf(stderr, "emcv-bench: %s (see --help)\n", cli.error.c_str());
        drop_partial();
        return 2;
    }
    std::vector<char*> args;
    for (std::string& a : cli.args) args.push_back(a.data());
    int count = static_cast<int>(args.size());
    args.push_back(nullptr);
    benchmark::Initialize(&count, args.data());
    if (benchmark::ReportUnrecognizedArguments(count, args.data())) {  // a flag value of the wrong type
        drop_partial();
        return 2;
    }
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    if (!cli.out_path.empty() && std::rename(cli.partial_path.c_str(), cli.out_path.c_str()) != 0) {
        std::fprintf(stderr, "emcv-bench: cannot rename %s to %s\n", cli.partial_path.c_str(), cli.out_path.c_str());
        drop_partial();
        return 1;
    }
    return 0;
}
