// SPDX-License-Identifier: MIT
// The headless run: every method over the frames, metrics against the reference, frames and metrics files.
#pragma once

#include <string>
#include <vector>

#include "metrics_table.hpp"
#include "options.hpp"
#include "scene/scene.hpp"

namespace emcv::demo::app {

struct run_result {
    std::vector<metrics_row> rows;          ///< frame-major, methods in run order
    std::vector<std::string> method_names;  ///< run order (the requested methods, then the reference if added)
    bool heatmap_text_missing = false;      ///< a heatmap PNG's legend lacks its text (heatmap_font not found)
};

/// The methods a run renders: the requested ones, plus the reference when it was not requested (PSNR,
/// relative MSE and temporal error are all measured against it).
std::vector<method> methods_to_render(const std::vector<method>& requested);

/// Renders `frames` frames of each method (needs a current GL context), timing passes on `clock`. With o.out,
/// writes DIR/<method>/frame-NNNN.png (and .exr with o.exr, the heatmaps with their legends), DIR/metrics.csv and DIR/metrics.json, each
/// through a temporary name. Throws output_error when a file cannot be written, std::runtime_error from the
/// renderer.
run_result run_headless(const scene& s, const options& o, int frames, timing clock);

}  // namespace emcv::demo::app
