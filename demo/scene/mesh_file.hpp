// SPDX-License-Identifier: MIT
// Triangle meshes from files (OBJ, PLY, glTF, ... whatever the distribution's assimp reads).
#pragma once

#include <filesystem>
#include <stdexcept>

#include "scene.hpp"

namespace emcv::demo {

class mesh_file_error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// Reads every mesh of the file into one triangle mesh, node transforms applied; normals computed (smooth)
/// where the file has none, then normalised; uv (0, 0) where the file has none. Throws mesh_file_error with
/// the reason (missing file, unreadable, no triangles, non-finite data).
mesh read_mesh_file(const std::filesystem::path& path);

}  // namespace emcv::demo
