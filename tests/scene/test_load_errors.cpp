// SPDX-License-Identifier: MIT
// Every class of scene-file error gives "<file>: <json pointer>: <problem>", and a valid file loads whole.
#include <catch2/catch_test_macros.hpp>
#include <catch2/matchers/catch_matchers_exception.hpp>
#include <catch2/matchers/catch_matchers_string.hpp>

#include <functional>
#include <string>

#include "scene/load.hpp"
#include "scene_test_support.hpp"

using namespace emcv::demo;
using emcv::test::temp_folder;
using emcv::test::tetrahedron_obj;
using nlohmann::json;

namespace {

/// A valid scene using every section: a procedural mesh, a mesh file beside the scene (relative path), a
/// diffuse and an SSS material, a transform, each light type and a curve.
json valid_scene() {
    return json::parse(R"({
      "$schema": "./scene.schema.json",
      "description": "test scene",
      "mm_per_unit": 10,
      "frames": 12,
      "background": [0.1, 0.1, 0.1],
      "ambient": [0.02, 0.02, 0.02],
      "camera": {"position": [0, 0, 5], "target": [0, 0, 0], "fov_y_degrees": 40, "near": 0.1, "far": 50,
                 "keys": [{"frame": 0, "position": [0, 0, 5], "target": [0, 0, 0]},
                          {"frame": 10, "position": [5, 0, 0], "target": [0, 0, 0]}]},
      "meshes": [{"name": "ball", "type": "sphere", "radius": 0.5, "segments": 16, "rings": 8},
                 {"name": "tet", "type": "file", "path": "meshes/tet.obj"}],
      "materials": [{"name": "paint", "type": "diffuse", "albedo": [0.5, 0.5, 0.5], "specular": 0.2, "roughness": 0.4},
                    {"name": "skin", "type": "sss", "albedo": [0.8, 0.5, 0.4], "mean_free_path_mm": [3, 1.5, 0.7]}],
      "objects": [{"name": "a", "mesh": "ball", "material": "skin",
                   "transform": {"translate": [1, 2, 3], "rotate_degrees": [0, 90, 0], "scale": 2}},
                  {"name": "b", "mesh": 1, "material": 0}],
      "lights": [{"name": "key", "type": "directional", "direction": [0, -2, 0], "intensity":
                    {"type": "steps", "value": 2, "steps": [{"frame": 5, "value": 0}]}, "casts_shadow": true},
                 {"name": "bulb", "type": "point", "position": [0, 3, 0], "color": [1, 0.5, 0.2], "intensity": 4},
                 {"name": "cone", "type": "spot", "position": [0, 3, 3], "direction": [0, -1, -1],
                  "inner_cone_degrees": 10, "outer_cone_degrees": 20}]
    })");
}

struct scene_files {
    temp_folder dir;
    scene_files() { dir.write("meshes/tet.obj", tetrahedron_obj); }
    std::filesystem::path write(const json& scene_json) const { return dir.write_json("scene.json", scene_json); }
};

/// Loads `valid_scene()` after `edit` and expects exactly "<file>: <pointer>: <problem...>".
void expect_error(const std::function<void(json&)>& edit, const std::string& pointer, const std::string& problem) {
    const scene_files files;
    json j = valid_scene();
    edit(j);
    const auto file = files.write(j);
    INFO("expected: " << pointer << ": " << problem);
    CHECK_THROWS_MATCHES(load_scene(file), scene_error,
                         Catch::Matchers::MessageMatches(
                             Catch::Matchers::StartsWith(file.string() + ": " + pointer + ": ") &&
                             Catch::Matchers::ContainsSubstring(problem)));
}

}  // namespace

TEST_CASE("a valid scene loads whole, in world units") {
    const scene_files files;
    const auto file = files.write(valid_scene());
    const scene s = load_scene(file);
    CHECK(s.name == "scene");
    CHECK(s.source == file);
    CHECK(s.description == "test scene");
    CHECK(s.mm_per_unit == 10.0f);
    CHECK(s.frames == 12);
    CHECK(s.view.fov_y_degrees == 40.0f);
    CHECK(s.view.keys.size() == 2u);
    CHECK(s.view.at(5).first == glm::vec3(2.5f, 0.0f, 2.5f));
    REQUIRE(s.meshes.size() == 2u);
    CHECK(s.meshes[0].name == "ball");
    CHECK(s.meshes[1].name == "tet");
    CHECK(s.meshes[1].indices.size() == 12u);  // read from meshes/tet.obj beside the scene file
    REQUIRE(s.objects.size() == 2u);
    CHECK(s.objects[0].mesh == 0);
    CHECK(s.objects[0].material == 1);  // by name
    CHECK(s.objects[1].mesh == 1);      // by index
    // T * Ry(90) * S(2): object +x goes to world -z, scaled by 2, then moved to (1, 2, 3).
    const glm::vec4 moved = s.objects[0].model * glm::vec4(1.0f, 0.0f, 0.0f, 1.0f);
    CHECK(glm::length(glm::vec3(moved) - glm::vec3(1.0f, 2.0f, 1.0f)) < 1e-5f);
    CHECK(s.materials[1].scatters());
    CHECK(s.materials[1].mean_free_path_mm == glm::vec3(3.0f, 1.5f, 0.7f));
    CHECK(s.materials[0].specular == 0.2f);
    CHECK(s.has_sss_material());
    REQUIRE(s.lights.size() == 3u);
    CHECK(s.lights[0].direction == glm::vec3(0.0f, -1.0f, 0.0f));  // normalised
    CHECK(s.lights[0].casts_shadow);
    CHECK(s.lights[0].intensity.at(4) == 2.0f);
    CHECK(s.lights[0].intensity.at(5) == 0.0f);
    CHECK(s.lights[1].type == light::kind::point);
    CHECK(s.lights[1].intensity.is_constant());
    CHECK(s.lights[1].intensity.at(3) == 4.0f);
    CHECK_FALSE(s.lights[1].casts_shadow);
    CHECK(s.lights[2].type == light::kind::spot);
    CHECK(s.lights[2].outer_cone_degrees == 20.0f);
    CHECK(std::fabs(glm::length(s.lights[2].direction) - 1.0f) < 1e-6f);
}

TEST_CASE("a file that is not JSON names the line and column") {
    const temp_folder dir;
    const auto file = dir.write("broken.json", "{\n  \"mm_per_unit\": 1,\n  oops\n}\n");
    CHECK_THROWS_MATCHES(load_scene(file), scene_error,
                         Catch::Matchers::MessageMatches(Catch::Matchers::StartsWith(file.string() + ": /: not JSON: ") &&
                                                         Catch::Matchers::ContainsSubstring("line 3, column")));
    CHECK_THROWS_MATCHES(load_scene(dir.path() / "absent.json"), scene_error,
                         Catch::Matchers::MessageMatches(Catch::Matchers::EndsWith("absent.json: /: no such file")));
}

TEST_CASE("missing required keys") {
    expect_error([](json& j) { j.erase("camera"); }, "/", "missing required key \"camera\"");
    expect_error([](json& j) { j["materials"][1].erase("mean_free_path_mm"); }, "/materials/1",
                 "missing required key \"mean_free_path_mm\"");
    expect_error([](json& j) { j["lights"][0].erase("direction"); }, "/lights/0", "missing required key \"direction\"");
    expect_error([](json& j) { j["objects"][0].erase("mesh"); }, "/objects/0", "missing required key \"mesh\"");
    expect_error([](json& j) { j["lights"][0]["intensity"].erase("steps"); }, "/lights/0/intensity",
                 "missing required key \"steps\"");
}

TEST_CASE("wrong types") {
    expect_error([](json& j) { j["lights"][1]["intensity"] = "bright"; }, "/lights/1/intensity",
                 "expected a number or a curve");
    expect_error([](json& j) { j["camera"]["position"] = json::array({0, 1}); }, "/camera/position",
                 "expected an array of 3 numbers");
    expect_error([](json& j) { j["camera"]["target"][2] = "zero"; }, "/camera/target/2", "expected a number");
    expect_error([](json& j) { j["frames"] = 2.5; }, "/frames", "expected an integer");
    expect_error([](json& j) { j["lights"][0]["casts_shadow"] = 1; }, "/lights/0/casts_shadow", "expected true or false");
    expect_error([](json& j) { j["meshes"] = json::object(); }, "/meshes", "expected an array");
    expect_error([](json& j) { j["objects"][0]["mesh"] = 1.5; }, "/objects/0/mesh", "expected an index or the name");
    expect_error([](json& j) { j["objects"][0]["transform"] = json::array(); }, "/objects/0/transform",
                 "expected an object");
    expect_error([](json& j) { j["mm_per_unit"] = 1e39; }, "/mm_per_unit", "too large for fp32");
}

TEST_CASE("values out of range") {
    expect_error([](json& j) { j["materials"][1]["mean_free_path_mm"][0] = -1; }, "/materials/1/mean_free_path_mm/0",
                 "out of range: must be in (0, inf), got -1");
    expect_error([](json& j) { j["materials"][1]["mean_free_path_mm"][2] = 0; }, "/materials/1/mean_free_path_mm/2",
                 "out of range");
    expect_error([](json& j) { j["camera"]["fov_y_degrees"] = 180; }, "/camera/fov_y_degrees",
                 "out of range: must be in (0, 180), got 180");
    expect_error([](json& j) { j["camera"]["fov_y_degrees"] = 0; }, "/camera/fov_y_degrees", "out of range");
    expect_error([](json& j) { j["materials"][0]["albedo"][1] = 1.2; }, "/materials/0/albedo/1",
                 "out of range: must be in [0, 1], got 1.2");
    expect_error([](json& j) { j["objects"][0]["transform"]["scale"] = 0; }, "/objects/0/transform/scale", "out of range");
    expect_error([](json& j) { j["objects"][0]["transform"]["scale"] = json::array({1, -1, 1}); },
                 "/objects/0/transform/scale/1", "out of range");
    expect_error([](json& j) { j["mm_per_unit"] = 0; }, "/mm_per_unit", "out of range");
    expect_error([](json& j) { j["frames"] = 0; }, "/frames", "out of range: must be an integer in [1, 100000], got 0");
    expect_error([](json& j) { j["lights"][1]["intensity"] = -2; }, "/lights/1/intensity", "out of range");
    expect_error([](json& j) { j["lights"][1]["color"][0] = -0.1; }, "/lights/1/color/0", "out of range");
    expect_error([](json& j) { j["materials"][0]["roughness"] = 0; }, "/materials/0/roughness", "out of range");
    expect_error([](json& j) { j["meshes"][0]["segments"] = 2; }, "/meshes/0/segments", "out of range");
    expect_error([](json& j) { j["camera"]["far"] = 0.05; }, "/camera/far", "must be greater than near");
    expect_error([](json& j) { j["camera"]["target"] = json::array({0, 0, 5}); }, "/camera",
                 "position and target coincide");
    expect_error([](json& j) { j["camera"]["up"] = json::array({0, 0, 1}); }, "/camera",
                 "the view direction is parallel to up");
    expect_error([](json& j) { j["lights"][0]["direction"] = json::array({0, 0, 0}); }, "/lights/0/direction",
                 "must not be the zero vector");
    expect_error([](json& j) { j["lights"][2]["inner_cone_degrees"] = 30; }, "/lights/2/inner_cone_degrees",
                 "must not exceed outer_cone_degrees");
    expect_error([](json& j) { j["lights"][0]["intensity"]["steps"].push_back({{"frame", 5}, {"value", 1}}); },
                 "/lights/0/intensity/steps/1/frame", "increasing frame order");
    expect_error([](json& j) { j["camera"]["keys"][1]["frame"] = 0; }, "/camera/keys/1/frame", "increasing frame order");
    expect_error([](json& j) { j["lights"][1]["intensity"] = {{"type", "sinusoid"}, {"value", 1}, {"amplitude", 1}, {"period_frames", 0}}; },
                 "/lights/1/intensity/period_frames", "out of range");
    expect_error([](json& j) {
        j["meshes"][0] = {{"name", "ring"}, {"type", "torus"}, {"major_radius", 0.5}, {"minor_radius", 0.5}};
    }, "/meshes/0/minor_radius", "must be less than major_radius");
}

TEST_CASE("unknown keys and unknown enum values") {
    expect_error([](json& j) { j["lights"][1]["colour"] = json::array({1, 1, 1}); }, "/lights/1/colour",
                 "unknown key \"colour\" (allowed here: type, name, color, intensity, position, casts_shadow)");
    expect_error([](json& j) { j["mm_per_units"] = 1; }, "/mm_per_units", "unknown key");
    expect_error([](json& j) { j["lights"][0]["intensity"]["period_frames"] = 3; }, "/lights/0/intensity/period_frames",
                 "unknown key");
    // A key valid for one light type is unknown for another: a point light has no direction.
    expect_error([](json& j) { j["lights"][1]["direction"] = json::array({0, -1, 0}); }, "/lights/1/direction",
                 "unknown key");
    expect_error([](json& j) { j["a/b"] = 1; }, "/a~1b", "unknown key \"a/b\"");  // RFC 6901 escaping
    expect_error([](json& j) { j["lights"][0]["type"] = "area"; }, "/lights/0/type",
                 "unknown type \"area\" (expected one of: directional, point, spot)");
    expect_error([](json& j) { j["meshes"][0]["type"] = "cube"; }, "/meshes/0/type", "unknown type \"cube\"");
    expect_error([](json& j) { j["materials"][0]["type"] = "metal"; }, "/materials/0/type", "unknown type");
    expect_error([](json& j) { j["lights"][0]["intensity"]["type"] = "ramp"; }, "/lights/0/intensity/type",
                 "unknown type \"ramp\"");
}

TEST_CASE("references and files") {
    expect_error([](json& j) { j["objects"][1]["mesh"] = 7; }, "/objects/1/mesh",
                 "out of range: must be an integer in [0, 1], got 7");
    expect_error([](json& j) { j["objects"][1]["material"] = -1; }, "/objects/1/material", "out of range");
    expect_error([](json& j) { j["objects"][0]["material"] = "marble"; }, "/objects/0/material",
                 "no materials named \"marble\"");
    expect_error([](json& j) { j["materials"][1]["name"] = "paint"; }, "/materials/1/name", "duplicate name \"paint\"");
    expect_error([](json& j) { j["meshes"][1]["path"] = "meshes/absent.obj"; }, "/meshes/1/path", "mesh file not found");
    expect_error([](json& j) { j["materials"][0]["albedo_texture"] = "absent.png"; }, "/materials/0/albedo_texture",
                 "texture file not found");
    expect_error([](json& j) { j["objects"] = json::array(); }, "/objects", "expected at least one object");

    SECTION("an unreadable mesh file") {
        const scene_files files;
        files.dir.write("meshes/bad.ply", "ply\nformat ascii 1.0\nelement vertex two\nend_header\n");
        json j = valid_scene();
        j["meshes"][1]["path"] = "meshes/bad.ply";
        const auto file = files.write(j);
        CHECK_THROWS_MATCHES(load_scene(file), scene_error,
                             Catch::Matchers::MessageMatches(
                                 Catch::Matchers::StartsWith(file.string() + ": /meshes/1/path: cannot read mesh file")));
    }
    SECTION("an unreadable texture") {
        const scene_files files;
        files.dir.write("skin.png", "not a png");
        json j = valid_scene();
        j["materials"][1]["albedo_texture"] = "skin.png";
        const auto file = files.write(j);
        CHECK_THROWS_MATCHES(load_scene(file), scene_error,
                             Catch::Matchers::MessageMatches(Catch::Matchers::StartsWith(
                                 file.string() + ": /materials/1/albedo_texture: cannot read texture")));
    }
}

TEST_CASE("the scene argument takes a file or a built-in name") {
    const scene_files files;
    const auto file = files.write(valid_scene());
    CHECK(load_scene_argument(file.string()).name == "scene");
    CHECK(load_scene_argument("static").name == "static");
    CHECK_THROWS_MATCHES(load_scene_argument("statik"), scene_error,
                         Catch::Matchers::MessageMatches(
                             Catch::Matchers::StartsWith("statik: no such scene file or built-in scene") &&
                             Catch::Matchers::ContainsSubstring("light-off")));
}

TEST_CASE("a key repeated within an object is an error, not a silent overwrite") {
    const scene_files files;
    auto expect = [&](const std::string& from, const std::string& to, const std::string& pointer, const std::string& key) {
        std::string text = valid_scene().dump();  // compact, keys sorted
        const auto at = text.find(from);
        REQUIRE(at != std::string::npos);
        REQUIRE(text.find(from, at + 1) == std::string::npos);
        text.replace(at, from.size(), to);
        const auto file = files.dir.write("scene.json", text);
        CHECK_THROWS_MATCHES(load_scene(file), scene_error,
                             Catch::Matchers::MessageMatches(Catch::Matchers::Equals(
                                 file.string() + ": " + pointer + ": duplicate key \"" + key +
                                 "\" (JSON keeps only the last; say it once)")));
    };
    expect("\"intensity\":4", "\"intensity\":4,\"intensity\":5", "/lights/1/intensity", "intensity");
    expect("{\"frame\":5,\"value\":0}", "{\"frame\":5,\"frame\":6,\"value\":0}", "/lights/0/intensity/steps/0/frame", "frame");
    expect("\"frames\":12", "\"frames\":12,\"frames\":12", "/frames", "frames");  // even with the same value
    expect("\"frames\":12", "\"frames\":12,\"a/b\":1,\"a/b\":2", "/a~1b", "a/b");
    // Arrays of arrays count their elements: the pointer names the right object.
    expect("\"keys\":[{\"frame\":0,", "\"keys\":[{\"frame\":0,\"frame\":0,", "/camera/keys/0/frame", "frame");
    expect("{\"frame\":10,", "{\"frame\":10,\"frame\":10,", "/camera/keys/1/frame", "frame");
}
