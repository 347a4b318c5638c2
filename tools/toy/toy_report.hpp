// SPDX-License-Identifier: MIT
// emcv-toy output: the Table 1 text layout, the one JSON object, and the per-frame CSV files.
#pragma once

#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "toy_options.hpp"
#include "toy_simulation.hpp"

namespace emcv::toy {

struct toy_results {
    std::optional<scenario_summary> static_light;
    std::optional<scenario_summary> dynamic_light;
};

/// Table 1 laid out as in the paper (rows h, columns residuals): "mean ± sd (paper)" per cell.
std::string format_table(const toy_options& options, const toy_results& results, double elapsed_s);

/// {"static": {"f": {"mean", "sd"}, ...}, "dynamic": {...}, "alpha_star": {"static", "dynamic"}, "seeds": N}
nlohmann::ordered_json to_json(const toy_options& options, const toy_results& results);

/// Thrown when the CSV files cannot be written; nothing is left behind.
class output_error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// Creates the directory if needed and writes <dir>/static.csv and/or <dir>/dynamic.csv from the first seed's
/// run. Every file is written to a temporary name first and renamed only when all of them are complete.
void write_csv(const std::string& dir, const toy_results& results);

}  // namespace emcv::toy
