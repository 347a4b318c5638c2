// SPDX-License-Identifier: MIT
// Samples per pixel as colours (the window's heatmap view).
#pragma once

#include "image/image_file.hpp"

namespace emcv::demo::app {

/// RGBA display colours (alpha 1) for a one-channel count image: 0 is black, then blue, green, yellow, red
/// at `max_count` and above. Same size and row order as `counts`. The values are display-encoded already:
/// the window shows them and a PNG stores them as they are.
image::float_image sample_heatmap(const image::float_image& counts, float max_count);

}  // namespace emcv::demo::app
