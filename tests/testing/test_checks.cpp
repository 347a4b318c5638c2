// Each check of emcv/testing passes a correct sampler or estimator and rejects a wrong one, with fixed seeds.
// The wrong ones are chosen so that rejection is certain in practice: their statistics sit tens of standard
// deviations away (the message of each result, printed on failure, shows how far).
#include <emcv/running_covariance.hpp>
#include <emcv/testing/catch2.hpp>

#include <catch2/catch_approx.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include <catch2/matchers/catch_matchers_string.hpp>

namespace et = emcv::testing;
using Catch::Matchers::ContainsSubstring;
using Catch::Matchers::StartsWith;

TEST_CASE("t-test and z-test: a correct mean passes, a shifted one is rejected") {
    std::mt19937_64 rng(11);
    std::normal_distribution<double> normal(3.0, 2.0);
    emcv::running_covariance<double, 1> acc;
    for (int i = 0; i < 10000; ++i) acc.push(normal(rng));
    // shift 0.2 = 10 standard errors (2 / sqrt(1e4) = 0.02)
    EMCV_CHECK_STAT(et::t_test_mean(acc, 3.0, 0.01));
    const auto shifted = et::t_test_mean(acc, 3.2, 0.01);
    CHECK_FALSE(shifted.passed);
    CHECK(std::fabs(shifted.statistic) > 7.0);
    CHECK(shifted.p_value < 1e-10);
    CHECK(shifted.message.find("REJECTED") != std::string::npos);
    EMCV_CHECK_STAT(et::z_test_mean(10000, acc.mean(0), 2.0, 3.0, 0.01));
    CHECK_FALSE(et::z_test_mean(10000, acc.mean(0), 2.0, 2.8, 0.01).passed);
    // the Sidak level is smaller than alpha and used in the verdict
    CHECK(et::t_test_mean(acc, 3.0, 0.01, 10).alpha < 0.01 / 9.9);
}

TEST_CASE("t-test edge cases: no spread, NaN, bad parameters") {
    CHECK(et::t_test_mean(5, 1.0, 0.0, 1.0).passed);
    CHECK_FALSE(et::t_test_mean(5, 1.0, 0.0, 1.5).passed);
    CHECK_FALSE(et::t_test_mean(5, std::nan(""), 1.0, 1.0).passed);
    CHECK_FALSE(et::t_test_mean(5, 1.0, std::numeric_limits<double>::infinity(), 1.0).passed);
    CHECK_THROWS_AS(et::t_test_mean(1, 1.0, 1.0, 1.0), std::invalid_argument);
    CHECK_THROWS_AS(et::t_test_mean(5, 1.0, 1.0, 1.0, 0.0), std::invalid_argument);
    CHECK_THROWS_AS(et::t_test_mean(5, 1.0, 1.0, 1.0, 0.01, 0), std::invalid_argument);
    CHECK_THROWS_AS(et::z_test_mean(5, 1.0, 0.0, 1.0), std::invalid_argument);
}

TEST_CASE("chi-square 1-D by CDF: exponential sampler against its CDF, and against a 5 % wrong rate") {
    std::mt19937_64 rng(12);
    std::exponential_distribution<double> expo(1.0);
    auto sample = [&] { return expo(rng); };
    auto cdf = [](double x) { return x <= 0 ? 0.0 : -std::expm1(-x); };
    EMCV_CHECK_STAT(et::chi2_test_1d_cdf(sample, cdf, 40, 200000));
    auto wrong_cdf = [](double x) { return x <= 0 ? 0.0 : -std::expm1(-1.05 * x); };
    const auto wrong = et::chi2_test_1d_cdf(sample, wrong_cdf, 40, 200000);
    CHECK_FALSE(wrong.passed);
    CHECK(wrong.p_value < 1e-12);
}

TEST_CASE("chi-square 1-D by pdf: normal sampler, pooled tails, and a wrong width") {
    std::mt19937_64 rng(13);
    std::normal_distribution<double> normal(0.0, 1.0);
    auto sample = [&] { return normal(rng); };
    auto pdf = [](double x) { return std::exp(-0.5 * x * x) / std::sqrt(2.0 * 3.14159265358979323846); };
    // [-6, 6] in 60 bins: the outer bins expect far fewer than 5 samples and get pooled
    const auto right = et::chi2_test_1d_pdf(sample, pdf, -6.0, 6.0, 60, 100000);
    INFO(right.message);
    CHECK(right.passed);
    CHECK(right.message.find("pooled") != std::string::npos);
    auto wide_pdf = [&](double x) { return pdf(x / 1.03) / 1.03; };
    CHECK_FALSE(et::chi2_test_1d_pdf(sample, wide_pdf, -6.0, 6.0, 60, 100000).passed);
}

TEST_CASE("chi-square 2-D by pdf: a correlated Gaussian against its density, and against the uncorrelated one") {
    std::mt19937_64 rng(14);
    std::normal_distribution<double> normal(0.0, 1.0);
    const double rho = 0.3;
    auto sample = [&] {
        const double a = normal(rng), b = normal(rng);
        return std::array<double, 2>{a, rho * a + std::sqrt(1 - rho * rho) * b};
    };
    auto density = [](double r) {
        return [r](double x, double y) {
            const double q = (x * x - 2 * r * x * y + y * y) / (1 - r * r);
            return std::exp(-0.5 * q) / (2 * 3.14159265358979323846 * std::sqrt(1 - r * r));
        };
    };
    EMCV_CHECK_STAT(et::chi2_test_2d_pdf(sample, density(rho), {-4, 4, -4, 4}, 16, 16, 200000));
    CHECK_FALSE(et::chi2_test_2d_pdf(sample, density(0.25), {-4, 4, -4, 4}, 16, 16, 200000).passed);
}

TEST_CASE("chi-square: samples outside the support or not finite reject outright") {
    std::mt19937_64 rng(15);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    auto uniform_cdf = [](double x) { return std::clamp(x, 0.0, 1.0); };
    int calls = 0;
    auto with_nan = [&] { return ++calls == 500 ? std::nan("") : u(rng); };
    const auto r = et::chi2_test_1d_cdf(with_nan, uniform_cdf, 10, 1000);
    CHECK_FALSE(r.passed);
    CHECK(r.p_value == 0.0);
    CHECK_THAT(r.message, StartsWith("chi-square: sampler returned 1 non-finite sample (first: nan at draw 500 of 1000)"));
    auto uniform_pdf = [](double x) { return x >= 0 && x <= 1 ? 1.0 : 0.0; };
    auto stretched = [&] { return 1.01 * u(rng); };
    const auto outside = et::chi2_test_1d_pdf(stretched, uniform_pdf, 0.0, 1.0, 10, 1000);
    CHECK_FALSE(outside.passed);
    CHECK(outside.message.find("expected count is 0") != std::string::npos);
    CHECK_THROWS_AS(et::chi2_test({1, 2}, {1.5}), std::invalid_argument);
    CHECK_THROWS_AS(et::chi2_test_1d_pdf(stretched, uniform_pdf, 1.0, 0.0, 10, 1000), std::invalid_argument);
}

TEST_CASE("convergence: a Monte Carlo mean falls like n^-1/2; a biased one and an n^-1 one are rejected") {
    std::mt19937_64 rng(16);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const std::vector<std::size_t> counts{16, 32, 64, 128, 256, 512, 1024};
    auto mc_error = [&](std::size_t n, double bias) {
        double s = 0;
        for (std::size_t i = 0; i < n; ++i) s += u(rng) * u(rng);  // E = 1/4
        return s / static_cast<double>(n) - 0.25 + bias;
    };
    const auto unbiased = et::convergence_test([&](std::size_t n) { return mc_error(n, 0.0); }, counts);
    INFO(unbiased.message);
    CHECK(unbiased.passed);
    CHECK(std::fabs(unbiased.statistic - 0.5) < 0.1);
    // a bias of 0.01 is as large as the standard error at n = 36: the error stops falling
    CHECK_FALSE(et::convergence_test([&](std::size_t n) { return mc_error(n, 0.01); }, counts).passed);
    // stratified (one jittered sample per stratum of [0, 1]) estimate of E[y^2] = 1/3: error ~ n^-3/2
    auto stratified = [&](std::size_t n) {
        double s = 0;
        for (std::size_t i = 0; i < n; ++i) {
            const double y = (static_cast<double>(i) + u(rng)) / static_cast<double>(n);
            s += y * y;
        }
        return s / static_cast<double>(n) - 1.0 / 3.0;
    };
    const auto fast = et::convergence_test(stratified, counts);
    CHECK_FALSE(fast.passed);
    CHECK(fast.statistic > 1.3);
    CHECK_THROWS_AS(et::convergence_test(stratified, {16}), std::invalid_argument);
}

TEST_CASE("chi-square pools the cells expected to get fewer than min_expected samples") {
    // 20 cells expecting 0.25 each (5 in all) with all 5 samples in one of them, beside 3 exact large cells:
    // cell by cell that is chi2 = (5 - 0.25)^2 / 0.25 + 19 * 0.25 = 95 on 22 dof (p ~ 1e-10); pooled it is
    // one cell of 5 expected and 5 observed, chi2 = 0
    std::vector<double> observed(20, 0.0), expected(20, 0.25);
    observed[7] = 5;
    for (int i = 0; i < 3; ++i) observed.push_back(100), expected.push_back(100);
    const auto r = et::chi2_test(observed, expected);
    INFO(r.message);
    CHECK(r.passed);
    CHECK(r.statistic == 0.0);
    CHECK(r.message.find("(20 pooled into one), 3 dof") != std::string::npos);
}

TEST_CASE("chi-square: each kind of sampler names its non-finite samples: how many, the first and its draw") {
    std::mt19937_64 rng(17);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    int calls = 0;
    auto sometimes_inf = [&] {
        ++calls;
        return calls % 100 == 17 ? -std::numeric_limits<double>::infinity() : u(rng);
    };
    auto uniform_pdf = [](double x) { return x >= 0 && x <= 1 ? 1.0 : 0.0; };
    const auto one_d = et::chi2_test_1d_pdf(sometimes_inf, uniform_pdf, 0.0, 1.0, 10, 1000);
    CHECK_FALSE(one_d.passed);
    CHECK_THAT(one_d.message, StartsWith("chi-square: sampler returned 10 non-finite samples (first: -inf at draw 17 "
                                         "of 1000)"));
    calls = 0;
    auto pair_with_nan = [&] {
        ++calls;
        return std::array<double, 2>{u(rng), calls == 3 ? std::nan("") : u(rng)};
    };
    const auto two_d =
        et::chi2_test_2d_pdf(pair_with_nan, [](double, double) { return 1.0; }, {0, 1, 0, 1}, 4, 4, 1000);
    CHECK_THAT(two_d.message, ContainsSubstring("sampler returned 1 non-finite sample (first: ("));
    CHECK_THAT(two_d.message, ContainsSubstring(", nan) at draw 3 of 1000)"));
}

TEST_CASE("chi-square: a rejection lists the worst cells, largest contribution first") {
    // contributions (O - E)^2 / E with E = 100: 0, 9, 0, 25, 4 -> chi2 = 38 on 4 dof, rejected
    const std::vector<double> observed{100, 130, 100, 50, 120}, expected(5, 100.0);
    et::chi2_options o;
    o.worst_cells = 3;
    const auto r = et::chi2_test(observed, expected, o);
    REQUIRE_FALSE(r.passed);
    CHECK(r.statistic == 38.0);
    CHECK_THAT(r.message, ContainsSubstring("REJECTED\n  largest contributions to chi2 (3 of 5 cells):\n"
                                            "    cell                              observed  expected  (O-E)^2/E\n"
                                            "    cell 3                                  50       100         25\n"
                                            "    cell 1                                 130       100          9\n"
                                            "    cell 4                                 120       100          4"));
    CHECK(r.message.find("cell 0:") == std::string::npos);  // only the three worst
    o.worst_cells = 0;
    CHECK(et::chi2_test(observed, expected, o).message.find("largest contributions") == std::string::npos);
    // a passing test keeps its one line
    CHECK(et::chi2_test({100, 101, 99}, {100, 100, 100}).message.find('\n') == std::string::npos);
}

TEST_CASE("chi-square: the worst cells of a sampler are named by their place") {
    // uniform samples against the pdf 2x on [0, 1] in 4 bins: bin k expects (2k + 1) / 16 of the samples, so the
    // first bin ([0, 0.25), 1/16 expected, 1/4 observed) contributes most, (3/16)^2 / (1/16) = 9/16 per sample
    std::mt19937_64 rng(18);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const auto r = et::chi2_test_1d_pdf([&] { return u(rng); }, [](double x) { return x >= 0 && x <= 1 ? 2 * x : 0.0; },
                                        0.0, 1.0, 4, 1000);
    REQUIRE_FALSE(r.passed);
    CHECK_THAT(r.message, ContainsSubstring("(O-E)^2/E\n    x in [0, 0.25)                   "));
    auto exponential = [&] { return -std::log1p(-u(rng)); };
    auto wrong_cdf = [](double x) { return x <= 0 ? 0.0 : -std::expm1(-2.0 * x); };  // rate 2, sampler rate 1
    const auto by_cdf = et::chi2_test_1d_cdf(exponential, wrong_cdf, 8, 1000);
    REQUIRE_FALSE(by_cdf.passed);
    CHECK_THAT(by_cdf.message, ContainsSubstring("x in [1.03972, inf)    "));  // F^-1(7/8) = ln(8) / 2
}

TEST_CASE("chi-square: histogram_csv writes every cell with its place, counts and contribution") {
    // in the temporary directory: a run from the repository root leaves nothing behind
    const std::string path = (std::filesystem::temp_directory_path() / "emcv-test-testing-histogram.csv").string();
    std::mt19937_64 rng(19);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    et::chi2_options o;
    o.histogram_csv = path;
    const auto r = et::chi2_test_2d_pdf([&] { return std::array<double, 2>{u(rng), u(rng)}; },
                                        [](double x, double y) { return x >= 0 && x <= 1 && y >= 0 && y <= 1 ? 1.0 : 0.0; },
                                        {0, 1, 0, 1}, 2, 2, 400, o);
    CHECK_THAT(r.message, ContainsSubstring("histogram written to " + path));
    std::ifstream in(path);
    REQUIRE(in);
    std::string line;
    std::getline(in, line);
    CHECK(line == "cell,kind,x_lo,x_hi,y_lo,y_hi,observed,expected,contribution,pooled");
    std::vector<std::string> rows;
    while (std::getline(in, line)) rows.push_back(line);
    REQUIRE(rows.size() == 5);  // 2 x 2 bins and the outside cell
    CHECK_THAT(rows[1], StartsWith("1,bin,0.5,1,0,0.5,"));  // cell (i = 1, j = 0)
    CHECK_THAT(rows[1], ContainsSubstring(",100,"));         // expected 400 / 4
    CHECK(rows[4] == "4,outside,,,,,0,0,,1");                // nothing outside: expectation 0, pooled
    double observed_sum = 0.0, chi2 = 0.0;
    for (std::size_t k = 0; k < 4; ++k) {
        std::vector<std::string> fields;
        std::stringstream row(rows[k]);
        for (std::string field; std::getline(row, field, ',');) fields.push_back(field);
        REQUIRE(fields.size() == 10);
        observed_sum += std::stod(fields[6]);
        chi2 += std::stod(fields[8]);
    }
    CHECK(observed_sum == 400.0);
    CHECK(chi2 == Catch::Approx(r.statistic));
}
