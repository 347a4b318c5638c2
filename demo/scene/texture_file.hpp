// SPDX-License-Identifier: MIT
// Albedo textures: an sRGB-encoded image file (PNG, JPEG, ... through OpenImageIO) -> linear RGBA texels.
#pragma once

#include <filesystem>
#include <stdexcept>

#include "scene.hpp"

namespace emcv::demo {

class texture_file_error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// The inverse of the sRGB transfer function (IEC 61966-2-1), for one encoded value in [0, 1].
float srgb_to_linear(float encoded) noexcept;

/// Reads the image (1 to 4 channels; grey is replicated, alpha 1 where absent), linearises colour (not
/// alpha), rows bottom first. Throws texture_file_error with the reason.
texture read_texture_file(const std::filesystem::path& path);

}  // namespace emcv::demo
