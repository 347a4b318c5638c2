// SPDX-License-Identifier: MIT
// Scene files -> emcv::demo::scene (scene.hpp). The loader is all-or-nothing: it returns a complete scene or
// throws scene_error; nothing is ever half-loaded. The schema is docs/scenes.md and demo/scenes/scene.schema.json.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "scene.hpp"

namespace emcv::demo {

/// Every problem with a scene file. what() is "<file>: <json pointer>: <problem>", e.g.
/// "scenes/x.json: /lights/1/intensity: expected a number or a curve".
class scene_error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// Reads and validates a scene file (JSON), loads its mesh files and textures (paths relative to the
/// file's folder). Throws scene_error.
scene load_scene(const std::filesystem::path& file);

/// The built-in scene folder: $EMCV_SCENE_DIR when set, else demo/scenes in the source tree.
std::filesystem::path builtin_scene_dir();

/// Stems of the built-in scene files (builtin_scene_dir()/*.json, the schema excluded), sorted.
std::vector<std::string> builtin_scene_names();

/// `--scene FILE|NAME`: an existing file path, else the name of a built-in scene. Throws scene_error naming
/// the argument and the built-in names when it is neither.
scene load_scene_argument(const std::string& file_or_name);

}  // namespace emcv::demo
