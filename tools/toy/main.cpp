// SPDX-License-Identifier: MIT
// emcv-toy: the supplementary's toy experiment (Table 1, Figs. 1 and 2) over many seeds.
#include <chrono>
#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include "toy_options.hpp"
#include "toy_report.hpp"
#include "toy_simulation.hpp"

int main(int argc, char** argv) {
    using namespace emcv::toy;
    toy_options options;
    try {
        options = parse_options(std::vector<std::string>(argv + 1, argv + argc));
    } catch (const usage_error& e) {
        std::cerr << "emcv-toy: " << e.what() << '\n';
        return 2;
    }
    if (options.help) {
        std::cout << usage_text();
        return 0;
    }
    try {
        const auto start = std::chrono::steady_clock::now();
        toy_results results;
        if (options.run_static)
            results.static_light =
                simulate_scenario(scenario::static_light, options.config, options.first_seed, options.seeds);
        if (options.run_dynamic)
            results.dynamic_light =
                simulate_scenario(scenario::dynamic_light, options.config, options.first_seed, options.seeds);
        const double elapsed_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

        if (!options.csv_dir.empty()) write_csv(options.csv_dir, results);
        if (options.json)
            std::cout << to_json(options, results).dump(2) << '\n';
        else
            std::cout << format_table(options, results, elapsed_s);
    } catch (const output_error& e) {
        std::cerr << "emcv-toy: " << e.what() << '\n';
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "emcv-toy: " << e.what() << '\n';
        return 1;
    }
    return 0;
}
