// SPDX-License-Identifier: MIT
// demo/scenes/scene.schema.json documents exactly what the loader accepts: the same kinds of object, the
// same property names and the same required keys as the loader's one table (schema_keys.cpp).
#include <catch2/catch_approx.hpp>
#include <catch2/catch_test_macros.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <set>
#include <string>

#include "scene/load.hpp"
#include "scene/schema_keys.hpp"
#include "scene_test_support.hpp"

using namespace emcv::demo;
using nlohmann::json;

namespace {

json read_schema() {
    std::ifstream in(emcv::test::source_dir() / "demo/scenes/scene.schema.json");
    REQUIRE(in);
    return json::parse(in);  // throws (fails the test) when it is not JSON
}

std::set<std::string> keys_of(const json& properties) {
    std::set<std::string> out;
    for (const auto& [k, v] : properties.items()) out.insert(k);
    return out;
}

std::set<std::string> table_keys(const schema_object& o, bool required_only) {
    std::set<std::string> out;
    for (const schema_key& k : o.keys)
        if (!required_only || k.required) out.insert(std::string(k.name));
    return out;
}

std::set<std::string> required_of(const json& def) {
    std::set<std::string> out;
    if (def.contains("required"))
        for (const auto& r : def["required"]) out.insert(r.get<std::string>());
    return out;
}

}  // namespace

TEST_CASE("the schema file is a draft 2020-12 JSON Schema") {
    const json schema = read_schema();
    CHECK(schema.at("$schema") == "https://json-schema.org/draft/2020-12/schema");
    CHECK(schema.at("type") == "object");
}

TEST_CASE("the schema's properties are exactly the loader's keys, kind by kind") {
    const json schema = read_schema();
    std::set<std::string> kinds_in_table;
    for (const schema_object& o : scene_schema()) {
        INFO("kind " << o.kind);
        kinds_in_table.insert(std::string(o.kind));
        const json& def = o.kind == "scene" ? schema : schema.at("$defs").at(std::string(o.kind));
        CHECK(keys_of(def.at("properties")) == table_keys(o, false));
        CHECK(required_of(def) == table_keys(o, true));
        CHECK(def.at("additionalProperties") == false);  // unknown keys are errors in both
    }
    // Every object definition of the schema is a kind the loader checks (no documented-only kinds).
    for (const auto& [name, def] : schema.at("$defs").items()) {
        INFO("$defs/" << name);
        if (def.contains("properties")) CHECK(kinds_in_table.count(name) == 1u);
    }
}

TEST_CASE("each typed kind's schema pins its type name") {
    const json schema = read_schema();
    for (const schema_object& o : scene_schema()) {
        const std::string kind(o.kind);
        const auto underscore = kind.find('_');
        if (underscore == std::string::npos || kind == "camera_key" || kind == "curve_step") continue;
        INFO(kind);
        // "light_spot" -> {"const": "spot"}: the loader dispatches on the same name (load.cpp, type_of).
        CHECK(schema.at("$defs").at(kind).at("properties").at("type").at("const") == kind.substr(underscore + 1));
    }
}

TEST_CASE("the schema's defaults are the loader's defaults") {
    const json schema = read_schema();
    const json& defs = schema.at("$defs");
    auto default_of = [&](const json& def, const char* key) {
        const json& p = def.at("properties").at(key);
        REQUIRE(p.contains("default"));
        return p.at("default");
    };
    auto vec3_of = [](const json& j) { return glm::vec3(j.at(0).get<float>(), j.at(1).get<float>(), j.at(2).get<float>()); };
    // Every optional key left out: what the loader fills in must be what the schema documents.
    emcv::test::temp_folder dir;
    const auto file = dir.write_json("defaults.json", json::parse(R"({
      "mm_per_unit": 1,
      "camera": {"position": [0, 0, 5], "target": [0, 0, 0]},
      "meshes": [{"name": "s", "type": "sphere"}, {"name": "t", "type": "torus"}, {"name": "c", "type": "slab"},
                 {"name": "p", "type": "plane"}],
      "materials": [{"name": "d", "type": "diffuse"}, {"name": "k", "type": "sss", "mean_free_path_mm": [1, 1, 1]}],
      "objects": [{"name": "o", "mesh": 0, "material": 0}],
      "lights": [{"name": "l", "type": "spot", "position": [0, 1, 0], "direction": [0, -1, 0]}]
    })"));
    const scene s = load_scene(file);
    CHECK(s.frames == default_of(schema, "frames").get<int>());
    CHECK(s.background == vec3_of(default_of(schema, "background")));
    CHECK(s.ambient == vec3_of(default_of(schema, "ambient")));
    CHECK(s.view.up == vec3_of(default_of(defs.at("camera"), "up")));
    CHECK(s.view.fov_y_degrees == default_of(defs.at("camera"), "fov_y_degrees").get<float>());
    CHECK(s.view.near_plane == default_of(defs.at("camera"), "near").get<float>());
    CHECK(s.view.far_plane == default_of(defs.at("camera"), "far").get<float>());
    // Procedural meshes: the defaults decide the vertex count and the extent.
    const json& sphere = defs.at("mesh_sphere");
    const auto segments = default_of(sphere, "segments").get<std::size_t>(), rings = default_of(sphere, "rings").get<std::size_t>();
    CHECK(s.meshes[0].vertices.size() == (segments + 1u) * (rings + 1u));
    CHECK(glm::length(s.meshes[0].vertices[1].position) == Catch::Approx(default_of(sphere, "radius").get<float>()));
    const json& torus = defs.at("mesh_torus");
    CHECK(s.meshes[1].vertices.size() == (default_of(torus, "segments").get<std::size_t>() + 1u) *
                                             (default_of(torus, "sides").get<std::size_t>() + 1u));
    CHECK(s.meshes[1].vertices[0].position.z ==
          Catch::Approx(default_of(torus, "major_radius").get<float>() + default_of(torus, "minor_radius").get<float>()));
    const json& slab = defs.at("mesh_slab");
    float slab_top = 0.0f, slab_out = 0.0f;
    for (const vertex& v : s.meshes[2].vertices) {
        slab_top = std::max(slab_top, v.position.y);
        slab_out = std::max(slab_out, glm::length(glm::vec2(v.position.x, v.position.z)));
    }
    CHECK(2.0f * slab_top == Catch::Approx(default_of(slab, "height").get<float>()));
    CHECK(slab_out == Catch::Approx(default_of(slab, "radius").get<float>() + 0.5f * default_of(slab, "thickness").get<float>()));
    // Outer face: 2 rows of (segments + 1) vertices (procedural.cpp), so the default segment count shows.
    CHECK(s.meshes[2].vertices.size() == 2u * 2u * (default_of(slab, "segments").get<std::size_t>() + 1u) +
                                             4u * (2u * default_of(slab, "segments").get<std::size_t>() + 2u));
    const json& plane = defs.at("mesh_plane");
    CHECK(s.meshes[3].vertices.back().position.x == Catch::Approx(0.5f * default_of(plane, "width").get<float>()));
    CHECK(s.meshes[3].indices.size() == 6u * static_cast<std::size_t>(std::pow(default_of(plane, "subdivisions").get<double>(), 2.0)));
    for (const char* kind : {"material_diffuse", "material_sss"}) {
        INFO(kind);
        const material& m = s.materials[std::string(kind) == "material_sss" ? 1u : 0u];
        CHECK(m.albedo == vec3_of(default_of(defs.at(kind), "albedo")));
        CHECK(m.specular == default_of(defs.at(kind), "specular").get<float>());
        CHECK(m.roughness == default_of(defs.at(kind), "roughness").get<float>());
        CHECK(m.albedo_texture == -1);
    }
    const json& spot = defs.at("light_spot");
    const light& l = s.lights[0];
    CHECK(l.color == vec3_of(default_of(spot, "color")));
    CHECK(l.intensity.is_constant());
    CHECK(l.intensity.at(0) == defs.at("intensity").at("default").get<float>());
    CHECK(l.inner_cone_degrees == default_of(spot, "inner_cone_degrees").get<float>());
    CHECK(l.outer_cone_degrees == default_of(spot, "outer_cone_degrees").get<float>());
    CHECK(l.casts_shadow == default_of(spot, "casts_shadow").get<bool>());
    CHECK(s.objects[0].model == glm::mat4(1.0f));  // translate / rotate / scale defaults: identity
}

TEST_CASE("the worked example in docs/scenes.md loads") {
    std::ifstream in(emcv::test::source_dir() / "docs/scenes.md");
    REQUIRE(in);
    const std::string doc((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const auto begin = doc.find("```json\n");
    REQUIRE(begin != std::string::npos);
    const auto end = doc.find("```", begin + 8);
    REQUIRE(end != std::string::npos);
    emcv::test::temp_folder dir;
    const auto file = dir.write("example.json", doc.substr(begin + 8, end - begin - 8));
    const scene s = load_scene(file);
    // What the text around the example says about it.
    CHECK(s.objects.size() == 3u);
    CHECK(s.lights.at(0).intensity.at(19) == 3.0f);
    CHECK(s.lights.at(0).intensity.at(20) == 0.0f);
    CHECK(s.lights.at(1).intensity.at(4) == Catch::Approx(1.5f));    // crest: a quarter of 16 frames
    CHECK(s.lights.at(1).intensity.at(12) == Catch::Approx(0.5f));   // trough
    CHECK(std::count_if(s.lights.begin(), s.lights.end(), [](const light& x) { return x.casts_shadow; }) == 1);
}
