// SPDX-License-Identifier: MIT
// Hard-case suite (docs/numerics.md): every estimator, in float and double, with its state kept in T or
// rounded to binary16 after every update, over the families of hard_case_streams.hpp. On every step:
// outputs finite, variances >= 0, |cov_xy| within the Cauchy-Schwarz bound, and the error against the
// long-double reference within the derived running bound (B1-B3).
#include <catch2/catch_test_macros.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "hard_case_streams.hpp"

namespace {

using namespace emcv_numerics;

enum class estimator_id { weighted, weighted_decay, running, running_compensated, emcm, emcm_compensated, ewma, moving_stats };

const char* name_of(estimator_id id) {
    switch (id) {
        case estimator_id::weighted: return "weighted_covariance (decay 1)";
        case estimator_id::weighted_decay: return "weighted_covariance (decay 0.9)";
        case estimator_id::running: return "running_covariance";
        case estimator_id::running_compensated: return "compensated_running_covariance";
        case estimator_id::emcm: return "emcm";
        case estimator_id::emcm_compensated: return "compensated_emcm";
        case estimator_id::ewma: return "ewma_covariance";
        case estimator_id::moving_stats: return "moving_stats";
    }
    return "?";
}

bool is_exponential(estimator_id id) {
    return id == estimator_id::emcm || id == estimator_id::emcm_compensated || id == estimator_id::ewma ||
           id == estimator_id::moving_stats;
}
bool is_compensated(estimator_id id) {
    return id == estimator_id::running_compensated || id == estimator_id::emcm_compensated;
}

// Uniform read access (moving_stats is the scalar interface of emcm<T, 1>).
template <class E>
auto mean_of(const E& e, std::size_t i) -> decltype(e.mean(i)) { return e.mean(i); }
template <class T>
T mean_of(const emcv::moving_stats<T>& e, std::size_t) { return e.mean(); }
template <class E>
auto cov_of(const E& e, std::size_t i, std::size_t j) -> decltype(e.covariance(i, j)) { return e.covariance(i, j); }
template <class T>
T cov_of(const emcv::moving_stats<T>& e, std::size_t, std::size_t) { return e.variance(); }

template <class E>
ld compensation_of(const E& e, std::size_t i) { return static_cast<ld>(e.state().mean_compensation[i]); }
template <class T>
ld compensation_of(const emcv::moving_stats<T>& e, std::size_t) { return static_cast<ld>(e.state().mean_compensation[0]); }

template <class E>
ld cov_compensation_of(const E& e, std::size_t k) { return static_cast<ld>(e.state().covariance_compensation[k]); }

struct case_report {
    bool ok = true;
    std::string failure;      // first broken invariant, with the step
    ld worst_ratio = 0;       // max over steps and outputs of |error| / bound
};

template <class T>
struct case_setup {
    estimator_id id;
    T eta = T(0);
    bool half_state = false;
    half_overflow overflow = half_overflow::to_infinity;
};

/// Runs one estimator over one stream; `make` builds it from nothing (nullptr) or from a saved state.
template <class T, std::size_t N, class E, class Make, class Push>
case_report drive(const stream<T>& s, const case_setup<T>& c, Make make, Push push_one) {
    schedule sch;
    if (c.id == estimator_id::running || c.id == estimator_id::running_compensated) {
        sch.kind = schedule_kind::cumulative;
    } else if (c.id == estimator_id::weighted || c.id == estimator_id::weighted_decay) {
        sch.kind = schedule_kind::weighted;
        sch.decay = c.id == estimator_id::weighted ? 1 : static_cast<ld>(T(0.9));
    } else {
        sch.kind = schedule_kind::exponential;
        sch.eta = static_cast<ld>(c.eta);
        sch.form = c.id == estimator_id::ewma ? emcv::comoment_form::previous_mean : emcv::comoment_form::current_mean;
    }
    const bool counted = sch.kind == schedule_kind::cumulative;
    reference_with_bound<N> ref(sch, model_of<T>(c.half_state, is_compensated(c.id), counted), long_double_model());

    case_report rep;
    E e = make(nullptr);
    auto fail = [&](std::size_t step, const std::string& what) {
        if (!rep.ok) return;
        rep.ok = false;
        std::ostringstream os;
        os << "step " << step << ": " << what;
        rep.failure = os.str();
    };
    for (std::size_t n = 0; n < s.x.size() && rep.ok; ++n) {
        std::array<T, N> x{};
        std::array<ld, N> xl{};
        for (std::size_t i = 0; i < N; ++i) {
            x[i] = s.x[n][i];
            xl[i] = static_cast<ld>(x[i]);
        }
        if (!push_one(e, x, s.weight[n])) fail(n, "a finite sample was rejected");
        ref.push(xl, static_cast<ld>(s.weight[n]));
        if (c.half_state) {
            const auto q = round_state_to_half(e.state(), c.overflow);
            try {
                auto restored = make(&q);
                e = restored;
            } catch (const std::invalid_argument& ex) {
                fail(n, std::string("half-float state refused: ") + ex.what());
                break;
            }
        }
        // ---- invariants ----
        std::array<T, N> mean{};
        std::array<T, N * (N + 1) / 2> cov{};
        std::size_t k = 0;
        for (std::size_t i = 0; i < N; ++i) {
            mean[i] = mean_of(e, i);
            for (std::size_t j = i; j < N; ++j, ++k) cov[k] = cov_of(e, i, j);
        }
        for (T v : mean)
            if (!std::isfinite(v)) fail(n, "mean not finite");
        for (T v : cov)
            if (!std::isfinite(v)) fail(n, "covariance not finite");
        for (std::size_t i = 0; i < N; ++i)
            if (cov[emcv::detail::packed_index(i, i, N)] < T(0)) fail(n, "negative variance");
        if (s.constant) {
            for (T v : cov)
                if (v != T(0)) fail(n, "constant stream with non-zero covariance");
            for (std::size_t i = 0; i < N; ++i)
                if (mean[i] != s.x[0][i]) fail(n, "constant stream whose mean moved");
        }
        if (N == 2) {
            // |c01| <= sqrt(c00 c11) holds exactly for the reference; with |computed - exact| <= B it gives
            // |c01^| <= sqrt((c00^ + B00)(c11^ + B11)) + B01 (docs/numerics.md, Eq. B4).
            const ld c00 = static_cast<ld>(cov[0]), c01 = static_cast<ld>(cov[1]), c11 = static_cast<ld>(cov[2]);
            const ld allowance = s.check_bound ? std::sqrt((c00 + ref.cov_bound(0)) * (c11 + ref.cov_bound(2))) + ref.cov_bound(1)
                                               : std::sqrt(c00 * c11) * (1 + 4 * unit_roundoff<T>());
            if (std::fabs(c01) > allowance) fail(n, "Cauchy-Schwarz |cov_xy|^2 <= var_x var_y broken");
            const T alpha = emcv::cv_coefficient(cov[1], cov[2]);
            if (!std::isfinite(alpha)) fail(n, "cv_coefficient not finite");
            const int count = emcv::sample_count(cov[0], T(1e-3), 0, 64);
            if (count < 0 || count > 64) fail(n, "sample_count outside [n_min, n_max]");
        }
        if (s.check_bound) {
            k = 0;
            for (std::size_t i = 0; i < N; ++i) {
                ld err = std::fabs(static_cast<ld>(mean[i]) - ref.mean(i));
                ld b = ref.mean_bound(i);
                if (is_compensated(c.id)) {
                    // the stored two-term mean meets the bound; mean() reads its rounding to T (+ u |mu|)
                    if (err > b + unit_roundoff<T>() * std::fabs(static_cast<ld>(mean[i])))
                        fail(n, "rounded compensated mean error above the bound");
                    err = std::fabs(static_cast<ld>(mean[i]) + compensation_of(e, i) - ref.mean(i));
                }
                if (err > b) fail(n, "mean error above the bound");
                if (b > 0) rep.worst_ratio = std::max(rep.worst_ratio, err / b);
                for (std::size_t j = i; j < N; ++j, ++k) {
                    ld cerr = std::fabs(static_cast<ld>(cov[k]) - ref.cov(k));
                    const ld cb = ref.cov_bound(k);
                    if (is_compensated(c.id)) {
                        // covariance() reads the rounding of the two-term value to T (+ u |Cov|)
                        if (cerr > cb + unit_roundoff<T>() * std::fabs(static_cast<ld>(cov[k])))
                            fail(n, "rounded compensated covariance error above the bound");
                        cerr = std::fabs(static_cast<ld>(cov[k]) + cov_compensation_of(e, k) - ref.cov(k));
                    }
                    if (cerr > cb) {
                        std::ostringstream os;
                        os << "covariance (" << i << "," << j << ") error " << static_cast<double>(cerr) << " above the bound "
                           << static_cast<double>(cb) << " (exact " << static_cast<double>(ref.cov(k)) << ")";
                        fail(n, os.str());
                    }
                    if (cb > 0) rep.worst_ratio = std::max(rep.worst_ratio, cerr / cb);
                }
            }
        } else {
            // saturation: every exact variance here exceeds max(T), so the stored one must be exactly max(T);
            // the mean is a convex combination of the samples
            for (std::size_t i = 0; i < N; ++i) {
                if (n > 0 && cov[emcv::detail::packed_index(i, i, N)] != std::numeric_limits<T>::max() &&
                    !(is_exponential(c.id) && c.eta == T(1) && c.id != estimator_id::ewma))
                    fail(n, "variance beyond the range did not saturate at max");
                if (std::fabs(mean[i]) > std::numeric_limits<T>::max()) fail(n, "mean overflowed");
            }
        }
    }
    return rep;
}

template <class T, std::size_t N>
case_report run_case(const stream<T>& s, const case_setup<T>& c) {
    using vec = std::array<T, N>;
    switch (c.id) {
        case estimator_id::weighted:
        case estimator_id::weighted_decay: {
            using E = emcv::weighted_covariance<T, N>;
            const T decay = c.id == estimator_id::weighted ? T(1) : T(0.9);
            return drive<T, N, E>(s, c, [](const typename E::state_type* st) { return st ? E(*st) : E(); },
                                  [decay](E& e, const vec& x, T w) { return e.push(x, w, decay); });
        }
        case estimator_id::running: {
            using E = emcv::running_covariance<T, N>;
            return drive<T, N, E>(s, c, [](const typename E::state_type* st) { return st ? E(*st) : E(); },
                                  [](E& e, const vec& x, T) { return e.push(x); });
        }
        case estimator_id::running_compensated: {
            using E = emcv::compensated_running_covariance<T, N>;
            return drive<T, N, E>(s, c, [](const typename E::state_type* st) { return st ? E(*st) : E(); },
                                  [](E& e, const vec& x, T) { return e.push(x); });
        }
        case estimator_id::emcm: {
            using E = emcv::emcm<T, N>;
            const T eta = c.eta;
            return drive<T, N, E>(s, c, [eta](const typename E::state_type* st) { return st ? E(eta, *st) : E(eta); },
                                  [](E& e, const vec& x, T) { return e.push(x); });
        }
        case estimator_id::emcm_compensated: {
            using E = emcv::compensated_emcm<T, N>;
            const T eta = c.eta;
            return drive<T, N, E>(s, c, [eta](const typename E::state_type* st) { return st ? E(eta, *st) : E(eta); },
                                  [](E& e, const vec& x, T) { return e.push(x); });
        }
        case estimator_id::ewma: {
            using E = emcv::ewma_covariance<T, N>;
            const T eta = c.eta;
            return drive<T, N, E>(s, c, [eta](const typename E::state_type* st) { return st ? E(eta, *st) : E(eta); },
                                  [](E& e, const vec& x, T) { return e.push(x); });
        }
        case estimator_id::moving_stats: {
            using E = emcv::moving_stats<T>;
            const T eta = c.eta;
            return drive<T, 1, E>(s, c, [eta](const typename E::state_type* st) { return st ? E(eta, *st) : E(eta); },
                                  [](E& e, const std::array<T, 1>& x, T) { return e.push(x[0]); });
        }
    }
    return {};
}

template <class T>
std::vector<T> etas_for(std::size_t n) {
    return {T(1e-6), T(1) / static_cast<T>(n), T(0.05), T(0.2), T(1)};
}

template <class T>
void run_all(const std::vector<stream<T>>& families, bool half_state, const char* precision) {
    const estimator_id ids[] = {estimator_id::weighted, estimator_id::weighted_decay, estimator_id::running,
                                estimator_id::running_compensated, estimator_id::emcm, estimator_id::emcm_compensated,
                                estimator_id::ewma, estimator_id::moving_stats};
    for (const auto& s : families) {
        for (estimator_id id : ids) {
            if (half_state && is_compensated(id)) continue;  // a two-term mean needs a split store (docs)
            std::vector<T> etas = is_exponential(id) ? etas_for<T>(s.x.size()) : std::vector<T>{T(0)};
            for (T eta : etas) {
                case_setup<T> c{id, eta, half_state, half_overflow::to_infinity};
                const case_report rep = id == estimator_id::moving_stats ? run_case<T, 1>(s, c) : run_case<T, 2>(s, c);
                INFO(precision << (half_state ? " (binary16 state)" : "") << " | " << s.name << " | " << name_of(id)
                               << " | eta " << static_cast<double>(eta) << " | " << rep.failure);
                CHECK(rep.ok);
                if (std::getenv("EMCV_NUMERICS_VERBOSE"))
                    std::printf("%s%s | %s | %s | eta %g | worst error/bound %.3g\n", precision,
                                half_state ? " binary16" : "", s.name.c_str(), name_of(id), static_cast<double>(eta),
                                static_cast<double>(rep.worst_ratio));
            }
        }
    }
}

constexpr std::size_t stream_length = 3000;

}  // namespace

TEST_CASE("float estimators keep every invariant and stay within the derived bound on the hard cases") {
    run_all(native_families<float>(stream_length), false, "float");
}

TEST_CASE("double estimators keep every invariant and stay within the derived bound on the hard cases") {
    run_all(native_families<double>(stream_length), false, "double");
}

TEST_CASE("float estimators with their state rounded to binary16 after every update stay within the bound") {
    run_all(half_families<float>(stream_length), true, "float");
}

TEST_CASE("double estimators with their state rounded to binary16 after every update stay within the bound") {
    run_all(half_families<double>(stream_length), true, "double");
}
