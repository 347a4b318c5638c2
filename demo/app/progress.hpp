// SPDX-License-Identifier: MIT
// A one-line progress bar on stderr (frames done, frames/s, ETA), drawn only when stderr is a terminal so
// that logs and CTest output stay clean.
#pragma once

#include <chrono>
#include <cstdio>
#include <string>

namespace emcv::demo::app {

/// The bar's text for `done` of `total` steps after `elapsed_s` seconds, `width` characters of bar.
std::string progress_line(int done, int total, double elapsed_s, int width = 30);

class progress_bar {
public:
    /// Enabled when `stream` is a terminal (isatty).
    progress_bar(int total, std::FILE* stream = stderr);
    ~progress_bar();  ///< ends the line
    progress_bar(const progress_bar&) = delete;
    progress_bar& operator=(const progress_bar&) = delete;

    void update(int done);
    bool enabled() const { return enabled_; }

private:
    int total_;
    std::FILE* stream_;
    bool enabled_;
    bool drawn_ = false;
    std::chrono::steady_clock::time_point start_;
    std::chrono::steady_clock::time_point last_draw_;
};

}  // namespace emcv::demo::app
