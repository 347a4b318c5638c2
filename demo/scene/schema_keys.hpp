// SPDX-License-Identifier: MIT
// The one table of keys the scene loader accepts, per kind of JSON object. The loader checks every object
// against it (unknown key, missing required key); tests/scene checks that demo/scenes/scene.schema.json
// declares exactly these properties (root: "scene"; the others: "$defs/<kind>"), so the two cannot drift.
#pragma once

#include <string_view>
#include <vector>

namespace emcv::demo {

struct schema_key {
    std::string_view name;
    bool required;
};

struct schema_object {
    std::string_view kind;  ///< "scene", "camera", "light_spot", ... (the schema's $defs name)
    std::vector<schema_key> keys;
};

/// Every kind of object a scene file holds, with its keys.
const std::vector<schema_object>& scene_schema();

/// The entry for one kind; std::out_of_range for an unknown kind (a programming error).
const schema_object& scene_schema_object(std::string_view kind);

}  // namespace emcv::demo
