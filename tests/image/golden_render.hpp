// SPDX-License-Identifier: MIT
// Renders one golden case in-process through the renderer library (demo/render): the images the goldens
// hold, in file form (top row first). Needs a current OpenGL 4.5 context.
#pragma once

#include <cstdint>
#include <optional>

#include <OpenImageIO/imagebuf.h>

#include "golden_cases.hpp"

namespace emcv::image {

struct golden_images {
    OIIO::ImageBuf display;                      ///< RGB, UINT8, sRGB-encoded (the renderer's display())
    std::optional<OIIO::ImageBuf> sample_counts;  ///< adaptive methods: one channel UINT16 holding the count
};

/// Loads the built-in scene, renders frames 0..last_frame with `seed` (the goldens: golden_seed) and returns
/// the last frame's images. Throws std::runtime_error naming the case (unknown scene or method, renderer errors).
golden_images render_case(const golden_case& c, std::uint32_t seed = golden_seed);

}  // namespace emcv::image
