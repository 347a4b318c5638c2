// A program outside the emcv tree: it sees only the installed headers, uses every public name, and checks
// the EMCM against its own brute-force long double evaluation of the geometric weights (supp. Eq. 18, 24).
#include <emcv/emcv.hpp>

#include <cmath>
#include <cstdio>
#include <vector>

int main() {
    const double eta = 0.1;
    std::vector<double> xs, ys;
    for (int i = 0; i < 50; ++i) {
        xs.push_back(std::sin(0.3 * i) + 2.0);
        ys.push_back(std::cos(0.7 * i) - 1.0);
    }
    emcv::emcm<double, 2> e(eta);
    emcv::ewma_covariance<double, 2> w(eta);
    emcv::weighted_covariance<double, 2> wc;
    emcv::running_covariance<double, 2> rc;
    emcv::moving_stats<double> ms(eta);
    for (std::size_t i = 0; i < xs.size(); ++i) {
        e.push({xs[i], ys[i]});
        w.push({xs[i], ys[i]});
        wc.push({xs[i], ys[i]}, 1.0 + static_cast<double>(i % 3), 0.9);
        rc.push({xs[i], ys[i]});
        ms.push(xs[i]);
    }
    // independent reference: weights (1-eta)^n for x_0, eta (1-eta)^(n-i) after
    const std::size_t n = xs.size() - 1;
    std::vector<long double> wt(xs.size());
    for (std::size_t i = 0; i <= n; ++i)
        wt[i] = (i == 0 ? 1.0L : static_cast<long double>(eta)) * std::pow(1.0L - eta, static_cast<long double>(n - i));
    long double mx = 0, my = 0, cxy = 0;
    for (std::size_t i = 0; i <= n; ++i) mx += wt[i] * xs[i], my += wt[i] * ys[i];
    for (std::size_t i = 0; i <= n; ++i) cxy += wt[i] * (xs[i] - mx) * (ys[i] - my);
    const double err = std::fabs(e.covariance(0, 1) - static_cast<double>(cxy));
    const double ratio = w.covariance(0, 1) / e.covariance(0, 1) * (1 - eta);

    emcv::control_variate<double> cv(emcv::residual_policy::emcm_constant, 0.05);
    const emcv::cv_frame<double> frame{1.0, 0.5, 0.5, 0.0, 0.0};
    cv.push(frame);
    const double alpha = emcv::cv_coefficient(e.covariance(0, 1), e.variance(1));
    const double batch = emcv::batch_mean_covariance(1.6, 16u);
    const int samples = emcv::sample_count(ms.variance(), 1e-4, 0, 64);
    const int samples_td = emcv::sample_count_true_distribution(ms.variance(), 1e-4, 0.2, 1e-4, 0, 64);
    std::printf("emcv %d.%d.%d: |emcm - reference| = %.3g, ewma ratio %.15f, alpha %.4f, batch %.3f, N %d/%d, "
                "sample var %.4f, weighted mean %.4f\n",
                EMCV_VERSION_MAJOR, EMCV_VERSION_MINOR, EMCV_VERSION_PATCH, err, ratio, alpha, batch, samples,
                samples_td, rc.sample_variance(0), wc.mean(0));
    const bool ok = err < 1e-13 && std::fabs(ratio - 1) < 1e-12 && std::fabs(batch - 0.1) < 1e-15 &&
                    samples == 64 && cv.alpha() == 0.0 && rc.count() == 50;
    std::puts(ok ? "consumer: OK" : "consumer: MISMATCH");
    return ok ? 0 : 1;
}
