// SPDX-License-Identifier: MIT
// The facts the reference docs state about the code, read from the docs and checked against the code itself:
// struct sizes (sizeof of the port's structs and host mirrors), tunable defaults (the port's #ifndef blocks),
// the installed port headers (the include tree), and the prose numbers that restate a printed table. A fact
// that drifts from the code fails here, with the doc, the line and both values named.
#include <catch2/catch_test_macros.hpp>

#include <emcv/port/history.h>
#include <emcv/port/host.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace {

std::string read_doc(const std::string& name) {
    const std::string path = std::string(EMCV_SOURCE_DIR) + "/docs/" + name;
    std::ifstream in(path);
    REQUIRE(in.good());
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

// Every match's first group of `pattern` in `text`.
std::vector<std::string> matches(const std::string& text, const std::string& pattern) {
    std::vector<std::string> out;
    const std::regex re(pattern);
    for (auto it = std::sregex_iterator(text.begin(), text.end(), re); it != std::sregex_iterator(); ++it)
        out.push_back((*it)[1].str());
    return out;
}

}  // namespace

TEST_CASE("integration.md's layout table gives each struct's size as sizeof does") {
    const std::string doc = read_doc("integration.md");
    const auto budget = matches(doc, R"(\| `EmcvBudgetBlock` \| (\d+) bytes)");
    REQUIRE(budget.size() == 1);
    CHECK(std::stoul(budget[0]) == sizeof(emcv::port::EmcvBudgetBlock));
    const auto emcm = matches(doc, R"(\| `EmcvEmcm2` \| (\d+) bytes)");
    REQUIRE(emcm.size() == 1);
    CHECK(std::stoul(emcm[0]) == sizeof(emcv::port::host::EmcvEmcm2));
    const auto emcm_cpp = matches(doc, R"(\| `EmcvEmcm2` \| \d+ bytes[^|]*\| (\d+) bytes)");
    REQUIRE(emcm_cpp.size() == 1);
    CHECK(std::stoul(emcm_cpp[0]) == sizeof(emcv::port::EmcvEmcm2));
    const auto stats = matches(doc, R"(\| `EmcvMovingStats` \| (\d+) bytes)");
    REQUIRE(stats.size() == 1);
    CHECK(std::stoul(stats[0]) == sizeof(emcv::port::EmcvMovingStats));
}

TEST_CASE("integration.md states cv's eta as the port's EMCV_HISTORY_ETA_EMCM") {
    const std::string doc = read_doc("integration.md");
    // the recipe's comment and the defaults paragraph
    const auto in_example = matches(doc, R"(eta EMCV_HISTORY_ETA_EMCM \(([0-9.]+)\))");
    const auto in_defaults = matches(doc, R"(n_max \d+, eta ([0-9.]+)\s+for every estimator)");
    REQUIRE(in_example.size() == 1);
    REQUIRE(in_defaults.size() == 1);
    CHECK(std::stof(in_example[0]) == EMCV_HISTORY_ETA_EMCM);
    CHECK(std::stof(in_defaults[0]) == EMCV_HISTORY_ETA_EMCM);
    CHECK(std::stof(in_defaults[0]) == EMCV_HISTORY_ETA_MOVING);
    // no "eta 0.05" comment on cv's estimator line (the paper's value, not the default)
    CHECK(matches(doc, R"(sampling_estimator::cv;\s*//[^\n]*eta (0\.0\d+))").empty());
}

TEST_CASE("integration.md's header table names every installed port header") {
    const std::string doc = read_doc("integration.md");
    const std::filesystem::path port = std::filesystem::path(EMCV_SOURCE_DIR) / "include/emcv/port";
    std::size_t headers = 0;
    for (const auto& entry : std::filesystem::directory_iterator(port)) {
        const std::string name = entry.path().filename().string();
        if (entry.path().extension() != ".h" && entry.path().extension() != ".hpp") continue;
        ++headers;
        INFO("include/emcv/port/" << name << " is installed but not in docs/integration.md's header table");
        CHECK(doc.find("| `" + name + "` |") != std::string::npos);
    }
    CHECK(headers >= 10);
}

TEST_CASE("python.md's prose restates its printed table: samples saved and variance added, in percent") {
    const std::string doc = read_doc("python.md");
    // "saves P% of the samples (A against B) while the predicted variance rises by Q% only (C against D)"
    const std::regex claim(R"(saves (\d+)% of the samples \(([0-9.]+) against ([0-9.]+)\)\s+while the predicted\s+variance rises by (\d+)% only \(([0-9.]+) against ([0-9.]+)\))");
    std::smatch m;
    REQUIRE(std::regex_search(doc, m, claim));
    const double fewer = 100.0 * (1.0 - std::stod(m[2]) / std::stod(m[3]));
    const double more = 100.0 * (std::stod(m[5]) / std::stod(m[6]) - 1.0);
    CHECK(std::stoi(m[1]) == static_cast<int>(std::lround(fewer)));
    CHECK(std::stoi(m[4]) == static_cast<int>(std::lround(more)));
    // the four numbers are the table's (the example's printed output above the prose)
    for (std::size_t i : {std::size_t{2}, std::size_t{3}, std::size_t{5}, std::size_t{6}}) {
        INFO(m[i].str() << " is not in python.md's printed table");
        CHECK(std::regex_search(doc, std::regex("\\n(spvg|cv)[^\\n]* " + std::regex_replace(m[i].str(), std::regex("\\."), "\\.") + "(\\s|\\n)")));
    }
    // "0.05 spends about as many samples as 0.2 (A against B) for a lower predicted variance (C against D)"
    const std::regex eta(R"(0\.05 spends about as many samples as 0\.2 \(([0-9.]+) against ([0-9.]+)\)\s+for a (lower|higher) predicted variance \(([0-9.]+) against ([0-9.]+)\))");
    REQUIRE(std::regex_search(doc, m, eta));
    CHECK(std::fabs(std::stod(m[1]) / std::stod(m[2]) - 1.0) < 0.05);
    CHECK((m[3] == "lower") == (std::stod(m[4]) < std::stod(m[5])));
}
