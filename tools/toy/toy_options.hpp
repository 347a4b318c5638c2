// SPDX-License-Identifier: MIT
// emcv-toy command line: parsing and validation only.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "toy_simulation.hpp"

namespace emcv::toy {

struct toy_options {
    bool run_static = true;
    bool run_dynamic = true;
    std::size_t seeds = 1000;
    std::uint64_t first_seed = 1;
    toy_config config;
    std::string csv_dir;  ///< empty: no CSV
    bool json = false;
    bool help = false;
};

/// Bad command-line input; what() names the flag. main() prints it and exits with status 2.
class usage_error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// Parses argv[1..]; throws usage_error on an unknown flag, a missing or malformed value, or a value out of range.
toy_options parse_options(const std::vector<std::string>& args);

/// The --help text.
std::string usage_text();

}  // namespace emcv::toy
