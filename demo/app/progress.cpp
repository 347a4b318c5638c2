// SPDX-License-Identifier: MIT
#include "progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>

namespace emcv::demo::app {

std::string progress_line(int done, int total, double elapsed_s, int width) {
    const double fraction = total > 0 ? std::clamp(static_cast<double>(done) / total, 0.0, 1.0) : 1.0;
    const int filled = static_cast<int>(std::lround(fraction * width));
    std::string bar = "[" + std::string(static_cast<std::size_t>(filled), '#') +
                      std::string(static_cast<std::size_t>(width - filled), '.') + "]";
    const double rate = elapsed_s > 0.0 ? done / elapsed_s : 0.0;
    char text[160];
    if (rate > 0.0) {
        const double eta = (total - done) / rate;
        std::snprintf(text, sizeof text, " %d/%d frames  %.2f frames/s  ETA %dm%02ds", done, total, rate,
                      static_cast<int>(eta) / 60, static_cast<int>(eta) % 60);
    } else {
        std::snprintf(text, sizeof text, " %d/%d frames", done, total);
    }
    return bar + text;
}

progress_bar::progress_bar(int total, std::FILE* stream)
    : total_(total), stream_(stream), enabled_(::isatty(::fileno(stream)) == 1),
      start_(std::chrono::steady_clock::now()), last_draw_(start_) {}

progress_bar::~progress_bar() {
    if (drawn_) std::fputc('\n', stream_);
}

void progress_bar::update(int done) {
    if (!enabled_) return;
    const auto now = std::chrono::steady_clock::now();
    // At most ~10 redraws a second, and always the last one.
    if (drawn_ && done < total_ && now - last_draw_ < std::chrono::milliseconds(100)) return;
    last_draw_ = now;
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    std::fprintf(stream_, "\r%s\033[K", progress_line(done, total_, elapsed).c_str());
    std::fflush(stream_);
    drawn_ = true;
}

}  // namespace emcv::demo::app
