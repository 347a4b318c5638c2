// SPDX-License-Identifier: MIT
// Samples per pixel as colours (the window's heatmap view).
#pragma once

#include <emcv/port/history.h>

#include "image/image_file.hpp"

namespace emcv::demo::app {

/// RGBA display colours (alpha 1) for a one-channel count image: 0 is black, then blue, green, yellow, red
/// at `max_count` and above. Same size and row order as `counts`. The values are display-encoded already:
/// the window shows them and a PNG stores them as they are.
image::float_image sample_heatmap(const image::float_image& counts, float max_count);

/// Colour scales of the heatmaps (docs/demo.md, Outputs): N over the adaptive methods' most samples per pixel,
/// so the top colour is the cap; alpha over [0, 2], so alpha = 1 (f follows G one to one) is the middle colour.
inline constexpr float samples_heatmap_max = float(EMCV_HISTORY_N_MAX);
inline constexpr float alpha_heatmap_max = 2.0f;

}  // namespace emcv::demo::app
