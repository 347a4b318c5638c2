// SPDX-License-Identifier: MIT
// demo/scenes/scene.schema.json documents exactly what the loader accepts: the same kinds of object, the
// same property names and the same required keys as the loader's one table (schema_keys.cpp).
#include <catch2/catch_test_macros.hpp>

#include <fstream>
#include <set>
#include <string>

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
