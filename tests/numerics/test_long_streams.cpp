// SPDX-License-Identifier: MIT
// Very long streams (1e8 updates, label "slow"): the drift of the stored mean and variance stays inside the
// running bound B1-B3 of docs/numerics.md section 2 for the whole stream. For the exponential estimators
// that bound is stationary (it stops growing after ~1/eta steps); for the cumulative ones it grows like
// n u, which docs/numerics.md section 3.4 turns into the advice to use double (or eta) beyond ~2^24 samples.
#include <catch2/catch_test_macros.hpp>

#include <cmath>
#include <string>

#include "numerics_support.hpp"

using namespace emcv_numerics;

namespace {

constexpr std::uint64_t long_stream = 100000000;  // 1e8 updates

struct drift_report {
    bool ok = true;
    std::uint64_t failed_at = 0;
    ld worst_mean_error = 0, worst_variance_error = 0;  // relative to the final exact values
    ld final_mean_bound = 0, final_variance_bound = 0;
    ld final_variance = 0;
};

/// Pushes offset + spread U(-1, 1) through `e` and the long-double reference; checks the invariants on every
/// step and the bound every 1024 steps (and at the end).
template <class T, class E>
drift_report run_long(E e, schedule sch, bool compensated, double offset, double spread) {
    reference_with_bound<1> ref(sch, model_of<T>(false, compensated, sch.kind == schedule_kind::cumulative),
                                long_double_model());
    uniform_source u(2024);
    drift_report rep;
    for (std::uint64_t n = 1; n <= long_stream && rep.ok; ++n) {
        const T x = static_cast<T>(offset + spread * u.next());
        e.push(x);
        ref.push({static_cast<ld>(x)});
        const T v = e.variance(0);
        if (!(v >= T(0)) || !std::isfinite(v) || !std::isfinite(e.mean(0))) {
            rep.ok = false;
            rep.failed_at = n;
        }
        if ((n & 1023) == 0 || n == long_stream) {
            const ld mean_error = std::fabs(static_cast<ld>(e.mean(0)) - ref.mean(0));
            // the compensated covariance() reads its rounding to T (+ u |Cov|)
            const ld var_error = std::fabs(static_cast<ld>(v) - ref.cov(0));
            const ld var_allow = ref.cov_bound(0) + (compensated ? unit_roundoff<T>() * ref.cov(0) * 1.01L : 0);
            // mean(): the compensated mean reads its rounding to T (+ u |mu|)
            const ld mean_allow = ref.mean_bound(0) + (compensated ? unit_roundoff<T>() * std::fabs(ref.mean(0)) * 1.01L : 0);
            if (mean_error > mean_allow || var_error > var_allow) {
                rep.ok = false;
                rep.failed_at = n;
            }
            rep.worst_mean_error = std::max(rep.worst_mean_error, mean_error / std::fabs(ref.mean(0)));
            rep.worst_variance_error = std::max(rep.worst_variance_error, var_error / ref.cov(0));
            rep.final_mean_bound = ref.mean_bound(0) / std::fabs(ref.mean(0));
            rep.final_variance_bound = ref.cov_bound(0) / ref.cov(0);
            rep.final_variance = ref.cov(0);
        }
    }
    return rep;
}

void report(const char* what, const drift_report& r) {
    INFO(what << ": " << (r.failed_at == 0 ? std::string("held at every step")
                                           : "failed at step " + std::to_string(r.failed_at))
              << ", worst relative mean error "
              << static_cast<double>(r.worst_mean_error) << " (bound " << static_cast<double>(r.final_mean_bound)
              << "), worst relative variance error " << static_cast<double>(r.worst_variance_error) << " (bound "
              << static_cast<double>(r.final_variance_bound) << ")");
    CHECK(r.ok);
    WARN(what << ": worst relative mean error " << static_cast<double>(r.worst_mean_error) << " (final bound "
              << static_cast<double>(r.final_mean_bound) << "), worst relative variance error "
              << static_cast<double>(r.worst_variance_error) << " (final bound "
              << static_cast<double>(r.final_variance_bound) << ")");
}

schedule exponential(ld eta) {
    schedule s;
    s.kind = schedule_kind::exponential;
    s.eta = eta;
    return s;
}

}  // namespace

TEST_CASE("1e8 updates of a float emcm (eta 0.05) on 1e3 +- 1: drift stays inside the stationary bound") {
    const float eta = 0.05f;
    report("emcm<float> eta 0.05",
           run_long<float>(emcv::emcm<float, 1>(eta), exponential(static_cast<ld>(eta)), false, 1e3, 1.0));
}

TEST_CASE("1e8 updates of a float compensated_emcm (eta 0.05) on 1e3 +- 1: drift stays inside its bound") {
    const float eta = 0.05f;
    report("compensated_emcm<float> eta 0.05",
           run_long<float>(emcv::compensated_emcm<float, 1>(eta), exponential(static_cast<ld>(eta)), true, 1e3, 1.0));
}

TEST_CASE("1e8 updates of a double running_covariance on 1e3 +- 1: drift stays inside the n u bound") {
    report("running_covariance<double>", run_long<double>(emcv::running_covariance<double, 1>(), schedule{}, false, 1e3, 1.0));
}

TEST_CASE("1e8 updates of a float running_covariance on 1 +- 0.5: invariants hold, error inside the n u bound") {
    report("running_covariance<float>", run_long<float>(emcv::running_covariance<float, 1>(), schedule{}, false, 1.0, 0.5));
}

TEST_CASE("1e8 updates of a float compensated_running_covariance on 1 +- 0.5: stays accurate past 2^24 samples") {
    report("compensated_running_covariance<float>",
           run_long<float>(emcv::compensated_running_covariance<float, 1>(), schedule{}, true, 1.0, 0.5));
}
