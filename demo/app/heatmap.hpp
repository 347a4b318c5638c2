// SPDX-License-Identifier: MIT
// Per-pixel values as colours (the window's heatmap view), and the heatmap PNGs that carry their own legend:
// a colour bar with ticks and the scale written under the image and stored in the file's metadata.
#pragma once

#include <string>

#include <emcv/port/history.h>

#include "image/image_file.hpp"

namespace emcv::demo::app {

/// What a heatmap's colours mean: the quantity, its unit and the range the colour map spans. The colour map has
/// heatmap_ticks stops evenly spaced over [min, max] (black, blue, green, yellow, red); values below min are
/// black, values above max (and NaN or Inf) red. docs/demo.md, Outputs.
struct heatmap_scale {
    const char* quantity;  ///< the name a reader sees, e.g. "N"
    const char* unit;      ///< "" when the quantity has none
    float min;             ///< the first stop (black)
    float max;             ///< the last stop (red)
};

/// N over the adaptive methods' most samples per pixel: the top colour is the cap.
inline constexpr heatmap_scale samples_heatmap_scale{"N", "samples per pixel", 0.0f, float(EMCV_HISTORY_N_MAX)};
/// alpha over [0, 2], so alpha = 1 (f follows G one to one) is the middle colour.
inline constexpr heatmap_scale alpha_heatmap_scale{"alpha", "", 0.0f, 2.0f};

/// The colour map's stops, which are also the colour bar's ticks: min, 1/4, 1/2, 3/4 of the range, max.
inline constexpr int heatmap_ticks = 5;

/// Legend of a heatmap PNG, below the image (top to bottom): a black gap, the colour bar (its columns go from
/// min at the left edge to max at the right edge), the tick marks (white, one pixel wide, under the bar at
/// the ticks), the scale text. The PNG is max(W, heatmap_legend_min_width) wide and H + heatmap_legend_height
/// tall; the heatmap sits at its top left, black beside it where the legend is wider.
inline constexpr int heatmap_gap_height = 2;
inline constexpr int heatmap_bar_height = 12;
inline constexpr int heatmap_tick_height = 4;
inline constexpr int heatmap_text_height = 14;
inline constexpr int heatmap_legend_height =
    heatmap_gap_height + heatmap_bar_height + heatmap_tick_height + heatmap_text_height;
/// Wide enough for the scale text at heatmap_font_px (longer text shrinks to fit).
inline constexpr int heatmap_legend_min_width = 192;
/// The font of the scale text: DejaVu Sans (Debian's fonts-dejavu-core, scripts/install-deps.sh), found by
/// OpenImageIO under /usr/share/fonts; at 11 pixels.
inline constexpr const char* heatmap_font = "DejaVuSans";
inline constexpr int heatmap_font_px = 11;

/// RGBA display colours (alpha 1) of a one-channel image through `scale`'s colour map. Same size and row order
/// as `values`. The colours are display-encoded already: the window shows them and a PNG stores them as they are.
image::float_image sample_heatmap(const image::float_image& values, const heatmap_scale& scale);

/// The tick values of `scale`: heatmap_ticks values evenly spaced from min to max.
float heatmap_tick(const heatmap_scale& scale, int tick);

/// The scale as one line, e.g. "N 0..64 (samples per pixel)" or "alpha 0..2": what the legend writes.
std::string heatmap_scale_text(const heatmap_scale& scale);

/// The scale with its ticks and their colours: the PNG's ImageDescription, e.g. "heatmap of N 0..64 (samples
/// per pixel); colour bar along the bottom, min at the left: 0 black, 16 blue, 32 green, 48 yellow, 64 red".
std::string heatmap_description(const heatmap_scale& scale);

/// A heatmap with its legend, ready for image::write_image(path, image, description).
struct heatmap_png {
    image::float_image image;  ///< RGBA, bottom row first; the layout of heatmap_legend_height
    std::string description;   ///< heatmap_description(scale)
    bool text_drawn = false;   ///< false when `font` was not found: the legend has its bar and ticks only
};

/// sample_heatmap(values, scale) with the legend below it. `font` is a font name OpenImageIO searches for (or
/// a font file's path); when it is missing the text is left out, nothing else changes.
heatmap_png heatmap_with_legend(const image::float_image& values, const heatmap_scale& scale,
                                const char* font = heatmap_font);

}  // namespace emcv::demo::app
