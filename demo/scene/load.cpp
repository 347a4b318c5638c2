// SPDX-License-Identifier: MIT
// The scene loader: JSON (nlohmann-json) -> scene, every value checked where it is read, with its JSON
// pointer in the message. The keys accepted per object are the table in schema_keys.cpp; units and ranges
// are documented in docs/scenes.md and demo/scenes/scene.schema.json.
#include "load.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "duplicate_keys.hpp"
#include "json_node.hpp"
#include "mesh_file.hpp"
#include "procedural.hpp"
#include "texture_file.hpp"

#ifndef EMCV_SCENE_DIR
#error "EMCV_SCENE_DIR (the built-in scene folder) must be defined by the build"
#endif

namespace emcv::demo {
namespace {

constexpr double inf = std::numeric_limits<double>::infinity();
constexpr bool open = true, closed = false;
constexpr int max_frames = 100000;        // a sequence, not a film: catches a frame count typed as a time
constexpr int max_tessellation = 4096;    // segments/rings/... per mesh axis

struct context {
    std::string file;                    ///< as given, for messages
    std::filesystem::path folder;        ///< relative paths resolve here
    std::map<std::filesystem::path, int> texture_index;
};

std::filesystem::path resolve(const context& ctx, const std::string& relative) {
    const std::filesystem::path p(relative);
    return p.is_absolute() ? p : ctx.folder / p;
}

/// "type" of a JSON object, checked against the allowed names.
std::string type_of(const json_node& node, std::initializer_list<const char*> allowed) {
    if (!node.is_object()) node.fail("expected an object, got " + json_type_phrase(node.json()));
    const json_node type = node.at("type");
    const std::string t = type.string();
    std::string list;
    for (const char* a : allowed) {
        if (t == a) return t;
        list += (list.empty() ? "" : ", ") + std::string(a);
    }
    type.fail("unknown type \"" + t + "\" (expected one of: " + list + ")");
}

// ---- curves ----

curve read_curve(const json_node& node) {
    curve c;
    if (node.is_number()) {
        c.value = static_cast<float>(node.number_in(0.0, inf, closed, open));
        return c;
    }
    if (!node.is_object()) node.fail("expected a number or a curve, got " + json_type_phrase(node.json()));
    const std::string type = type_of(node, {"constant", "steps", "flicker", "sinusoid"});
    node.check_keys("curve_" + type);
    c.value = static_cast<float>(node.at("value").number_in(0.0, inf, closed, open));
    if (type == "constant") {
        c.type = curve::kind::constant;
    } else if (type == "steps") {
        c.type = curve::kind::steps;
        const json_node steps = node.at("steps");
        const std::size_t n = steps.array_size();
        if (n == 0) steps.fail("expected at least one step");
        for (std::size_t i = 0; i < n; ++i) {
            const json_node step = steps.element(i);
            step.check_keys("curve_step");
            const json_node frame = step.at("frame");
            const int f = frame.integer_in(0, max_frames);
            if (!c.steps.empty() && f <= c.steps.back().first)
                frame.fail("steps must be in increasing frame order (frame " + std::to_string(f) +
                           " after frame " + std::to_string(c.steps.back().first) + ")");
            c.steps.emplace_back(f, static_cast<float>(step.at("value").number_in(0.0, inf, closed, open)));
        }
    } else if (type == "flicker") {
        c.type = curve::kind::flicker;
        c.peak = static_cast<float>(node.at("peak").number_in(0.0, inf, closed, open));
        if (auto length = node.find("burst_length")) c.burst_length = length->integer_in(1, max_frames);
        const json_node bursts = node.at("bursts");
        const std::size_t n = bursts.array_size();
        for (std::size_t i = 0; i < n; ++i) {
            const json_node start = bursts.element(i);
            const int f = start.integer_in(0, max_frames);
            if (!c.bursts.empty() && f <= c.bursts.back())
                start.fail("bursts must be in increasing frame order (frame " + std::to_string(f) + " after frame " +
                           std::to_string(c.bursts.back()) + ")");
            c.bursts.push_back(f);
        }
    } else {
        c.type = curve::kind::sinusoid;
        c.amplitude = static_cast<float>(node.at("amplitude").number_in(0.0, inf, closed, open));
        c.period_frames = static_cast<float>(node.at("period_frames").number_in(0.0, inf, open, open));
        if (auto phase = node.find("phase")) c.phase = static_cast<float>(phase->number());
    }
    return c;
}

// ---- camera ----

camera read_camera(const json_node& node) {
    node.check_keys("camera");
    camera cam;
    cam.position = node.at("position").vec3();
    cam.target = node.at("target").vec3();
    if (auto up = node.find("up")) {
        cam.up = up->vec3();
        if (glm::length(cam.up) == 0.0f) up->fail("up must not be the zero vector");
        cam.up = glm::normalize(cam.up);
    }
    if (auto fov = node.find("fov_y_degrees")) cam.fov_y_degrees = static_cast<float>(fov->number_in(0.0, 180.0, open, open));
    if (auto near = node.find("near")) cam.near_plane = static_cast<float>(near->number_in(0.0, inf, open, open));
    if (auto far = node.find("far")) {
        cam.far_plane = static_cast<float>(far->number_in(0.0, inf, open, open));
        if (cam.far_plane <= cam.near_plane)
            far->fail("far (" + std::to_string(cam.far_plane) + ") must be greater than near (" +
                      std::to_string(cam.near_plane) + ")");
    } else if (cam.far_plane <= cam.near_plane) {
        node.at("near").fail("near must be less than far (" + std::to_string(cam.far_plane) + ")");
    }
    auto check_view = [&](const json_node& where, glm::vec3 position, glm::vec3 target) {
        const glm::vec3 forward = target - position;
        if (glm::length(forward) == 0.0f) where.fail("position and target coincide");
        // |forward x up| / (|forward| |up|) = sin of the angle between them; near 0 the view basis is undefined.
        if (glm::length(glm::cross(glm::normalize(forward), cam.up)) < 1e-4f)
            where.fail("the view direction is parallel to up");
    };
    check_view(node, cam.position, cam.target);
    if (auto keys = node.find("keys")) {
        const std::size_t n = keys->array_size();
        for (std::size_t i = 0; i < n; ++i) {
            const json_node k = keys->element(i);
            k.check_keys("camera_key");
            camera::key key;
            const json_node frame = k.at("frame");
            key.frame = frame.integer_in(0, max_frames);
            if (!cam.keys.empty() && key.frame <= cam.keys.back().frame)
                frame.fail("keys must be in increasing frame order (frame " + std::to_string(key.frame) +
                           " after frame " + std::to_string(cam.keys.back().frame) + ")");
            key.position = k.at("position").vec3();
            key.target = k.at("target").vec3();
            check_view(k, key.position, key.target);
            cam.keys.push_back(key);
        }
    }
    return cam;
}

// ---- meshes ----

mesh read_mesh(const json_node& node, const context& ctx) {
    const std::string type = type_of(node, {"sphere", "torus", "slab", "plane", "file"});
    node.check_keys("mesh_" + type);
    auto number_or = [&](const char* key, double fallback, double low, double high, bool low_open, bool high_open) {
        auto v = node.find(key);
        return static_cast<float>(v ? v->number_in(low, high, low_open, high_open) : fallback);
    };
    auto count_or = [&](const char* key, int fallback, int low) {
        auto v = node.find(key);
        return v ? v->integer_in(low, max_tessellation) : fallback;
    };
    mesh m;
    if (type == "sphere") {
        m = make_sphere(number_or("radius", 1.0, 0.0, inf, open, open), count_or("segments", 64, 3),
                        count_or("rings", 32, 2));
    } else if (type == "torus") {
        const float major = number_or("major_radius", 1.0, 0.0, inf, open, open);
        const float minor = number_or("minor_radius", 0.25, 0.0, inf, open, open);
        if (minor >= major)
            (node.find("minor_radius") ? *node.find("minor_radius") : node)
                .fail("minor_radius must be less than major_radius (a torus without a hole)");
        m = make_torus(major, minor, count_or("segments", 64, 3), count_or("sides", 32, 3));
    } else if (type == "slab") {
        const float radius = number_or("radius", 1.0, 0.0, inf, open, open);
        const float thickness = number_or("thickness", 0.05, 0.0, inf, open, open);
        if (thickness >= 2.0f * radius)
            (node.find("thickness") ? *node.find("thickness") : node)
                .fail("thickness must be less than twice the radius");
        m = make_slab(radius, number_or("angle_degrees", 90.0, 0.0, 360.0, open, open), thickness,
                      number_or("height", 1.0, 0.0, inf, open, open), count_or("segments", 32, 1));
    } else if (type == "plane") {
        m = make_plane(number_or("width", 1.0, 0.0, inf, open, open), number_or("depth", 1.0, 0.0, inf, open, open),
                       count_or("subdivisions", 1, 1));
    } else {
        const json_node path = node.at("path");
        try {
            m = read_mesh_file(resolve(ctx, path.non_empty_string()));
        } catch (const mesh_file_error& e) {
            path.fail(e.what());
        }
    }
    m.name = node.at("name").non_empty_string();
    return m;
}

// ---- materials ----

material read_material(const json_node& node, context& ctx, std::vector<texture>& textures) {
    const std::string type = type_of(node, {"diffuse", "sss"});
    node.check_keys("material_" + type);
    material mat;
    mat.name = node.at("name").non_empty_string();
    mat.type = type == "sss" ? material::kind::sss : material::kind::diffuse;
    if (auto albedo = node.find("albedo")) mat.albedo = albedo->vec3_in(0.0, 1.0, closed, closed);
    if (auto path = node.find("albedo_texture")) {
        const std::filesystem::path file = resolve(ctx, path->non_empty_string());
        const auto known = ctx.texture_index.find(file);
        if (known != ctx.texture_index.end()) {
            mat.albedo_texture = known->second;
        } else {
            try {
                textures.push_back(read_texture_file(file));
            } catch (const texture_file_error& e) {
                path->fail(e.what());
            }
            mat.albedo_texture = static_cast<int>(textures.size() - 1);
            ctx.texture_index.emplace(file, mat.albedo_texture);
        }
    }
    if (mat.scatters()) mat.mean_free_path_mm = node.at("mean_free_path_mm").vec3_in(0.0, inf, open, open);
    if (auto s = node.find("specular")) mat.specular = static_cast<float>(s->number_in(0.0, 1.0, closed, closed));
    if (auto r = node.find("roughness")) mat.roughness = static_cast<float>(r->number_in(0.0, 1.0, open, closed));
    return mat;
}

// ---- objects ----

/// An object's "mesh" / "material": an index, or the name of an entry.
template <class Named>
int reference_to(const json_node& node, const std::vector<Named>& entries, const char* what) {
    if (node.json().is_number_integer()) {
        if (entries.empty()) node.fail(std::string("index out of range: there are no ") + what);
        return node.integer_in(0, static_cast<int>(entries.size()) - 1);
    }
    if (!node.json().is_string())
        node.fail(std::string("expected an index or the name of one of the ") + what + ", got " +
                  json_type_phrase(node.json()));
    const std::string name = node.string();
    for (std::size_t i = 0; i < entries.size(); ++i)
        if (entries[i].name == name) return static_cast<int>(i);
    node.fail("no " + std::string(what) + " named \"" + name + "\"");
}

glm::mat4 read_transform(const json_node& node) {
    node.check_keys("transform");
    glm::vec3 translate(0.0f), rotate_degrees(0.0f), scale(1.0f);
    if (auto t = node.find("translate")) translate = t->vec3();
    if (auto r = node.find("rotate_degrees")) rotate_degrees = r->vec3();
    if (auto s = node.find("scale")) {
        // A zero scale collapses the mesh; a negative one mirrors it and flips its winding: both refused.
        if (s->is_number()) scale = glm::vec3(static_cast<float>(s->number_in(0.0, inf, open, open)));
        else scale = s->vec3_in(0.0, inf, open, open);
    }
    // model = T * Rz * Ry * Rx * S: scale first, then rotate about x, y, z (degrees), then translate.
    glm::mat4 m = glm::translate(glm::mat4(1.0f), translate);
    m = glm::rotate(m, glm::radians(rotate_degrees.z), glm::vec3(0.0f, 0.0f, 1.0f));
    m = glm::rotate(m, glm::radians(rotate_degrees.y), glm::vec3(0.0f, 1.0f, 0.0f));
    m = glm::rotate(m, glm::radians(rotate_degrees.x), glm::vec3(1.0f, 0.0f, 0.0f));
    return glm::scale(m, scale);
}

object read_object(const json_node& node, const scene& s) {
    node.check_keys("object");
    object o;
    o.name = node.at("name").non_empty_string();
    o.mesh = reference_to(node.at("mesh"), s.meshes, "meshes");
    o.material = reference_to(node.at("material"), s.materials, "materials");
    if (auto t = node.find("transform")) o.model = read_transform(*t);
    return o;
}

// ---- lights ----

glm::vec3 unit_direction(const json_node& node) {
    const glm::vec3 d = node.vec3();
    if (glm::length(d) == 0.0f) node.fail("direction must not be the zero vector");
    return glm::normalize(d);
}

light read_light(const json_node& node) {
    const std::string type = type_of(node, {"directional", "point", "spot"});
    node.check_keys("light_" + type);
    light l;
    l.name = node.at("name").non_empty_string();
    l.type = type == "directional" ? light::kind::directional : type == "point" ? light::kind::point : light::kind::spot;
    if (auto c = node.find("color")) l.color = c->vec3_in(0.0, inf, closed, open);
    if (auto i = node.find("intensity")) l.intensity = read_curve(*i);
    if (l.type != light::kind::point) l.direction = unit_direction(node.at("direction"));
    if (l.type != light::kind::directional) l.position = node.at("position").vec3();
    if (l.type == light::kind::spot) {
        // Half-angles from the spot axis.
        if (auto inner = node.find("inner_cone_degrees"))
            l.inner_cone_degrees = static_cast<float>(inner->number_in(0.0, 90.0, closed, open));
        if (auto outer = node.find("outer_cone_degrees"))
            l.outer_cone_degrees = static_cast<float>(outer->number_in(0.0, 90.0, open, open));
        if (l.inner_cone_degrees > l.outer_cone_degrees)
            (node.find("inner_cone_degrees") ? *node.find("inner_cone_degrees") : node)
                .fail("inner_cone_degrees must not exceed outer_cone_degrees");
    }
    if (auto s = node.find("casts_shadow")) l.casts_shadow = s->boolean();
    return l;
}

/// A named list ("meshes", "materials", ...) read entry by entry; names must be unique within it.
template <class Read>
void read_list(const json_node& root, const char* key, bool required, Read read_entry) {
    const std::optional<json_node> list = required ? std::optional<json_node>(root.at(key)) : root.find(key);
    if (!list) return;
    const std::size_t n = list->array_size();
    for (std::size_t i = 0; i < n; ++i) read_entry(list->element(i));
}

template <class Named>
void check_unique_name(const json_node& entry, const std::vector<Named>& before) {
    const std::string name = entry.at("name").string();
    for (const auto& other : before)
        if (other.name == name) entry.at("name").fail("duplicate name \"" + name + "\"");
}

std::string parse_error_problem(const nlohmann::json::parse_error& e) {
    // nlohmann's what(): "[json.exception.parse_error.101] parse error at line 3, column 5: <reason>"
    std::string what = e.what();
    const auto at = what.find(" at ");
    if (at != std::string::npos) what = what.substr(at + 4);
    return "not JSON: " + what;
}

}  // namespace

scene load_scene(const std::filesystem::path& file) {
    context ctx;
    ctx.file = file.string();
    ctx.folder = file.parent_path();
    const nlohmann::json root_value;  // for messages about the file itself
    const json_node whole_file(root_value, "", ctx.file);

    std::error_code ec;
    if (!std::filesystem::exists(file, ec)) whole_file.fail("no such file");
    if (std::filesystem::is_directory(file, ec)) whole_file.fail("is a folder, not a scene file");
    std::ifstream in(file, std::ios::binary);
    if (!in) whole_file.fail("cannot open for reading");
    std::ostringstream text;
    text << in.rdbuf();
    if (in.bad()) whole_file.fail("read error");

    nlohmann::json json;
    try {
        json = nlohmann::json::parse(text.str());
    } catch (const nlohmann::json::parse_error& e) {
        whole_file.fail(parse_error_problem(e));
    }
    if (const auto duplicate = find_duplicate_key(text.str()))
        json_node(json, duplicate->pointer, ctx.file)
            .fail("duplicate key \"" + duplicate->key + "\" (JSON keeps only the last; say it once)");
    const json_node root(json, "", ctx.file);
    root.check_keys("scene");

    scene s;
    s.name = file.stem().string();
    s.source = file;
    if (auto d = root.find("description")) s.description = d->string();
    if (auto schema = root.find("$schema")) schema->string();
    s.mm_per_unit = static_cast<float>(root.at("mm_per_unit").number_in(0.0, inf, open, open));
    if (auto f = root.find("frames")) s.frames = f->integer_in(1, max_frames);
    if (auto b = root.find("background")) s.background = b->vec3_in(0.0, inf, closed, open);
    if (auto a = root.find("ambient")) s.ambient = a->vec3_in(0.0, inf, closed, open);
    s.view = read_camera(root.at("camera"));

    read_list(root, "meshes", true, [&](const json_node& entry) {
        mesh m = read_mesh(entry, ctx);
        check_unique_name(entry, s.meshes);
        s.meshes.push_back(std::move(m));
    });
    read_list(root, "materials", true, [&](const json_node& entry) {
        material m = read_material(entry, ctx, s.textures);
        check_unique_name(entry, s.materials);
        s.materials.push_back(std::move(m));
    });
    read_list(root, "objects", true, [&](const json_node& entry) {
        object o = read_object(entry, s);
        check_unique_name(entry, s.objects);
        s.objects.push_back(std::move(o));
    });
    if (s.objects.empty()) root.at("objects").fail("expected at least one object");
    read_list(root, "lights", false, [&](const json_node& entry) {
        light l = read_light(entry);
        check_unique_name(entry, s.lights);
        s.lights.push_back(std::move(l));
    });
    return s;
}

std::filesystem::path builtin_scene_dir() {
    if (const char* dir = std::getenv("EMCV_SCENE_DIR"); dir && *dir) return dir;
    return EMCV_SCENE_DIR;
}

std::vector<std::string> builtin_scene_names() {
    std::vector<std::string> names;
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator(builtin_scene_dir(), ec)) {
        const auto& p = entry.path();
        // The schema lives beside the scenes; it is not a scene.
        if (entry.is_regular_file() && p.extension() == ".json" && p.filename() != "scene.schema.json")
            names.push_back(p.stem().string());
    }
    std::sort(names.begin(), names.end());
    return names;
}

scene load_scene_argument(const std::string& file_or_name) {
    std::error_code ec;
    if (std::filesystem::is_regular_file(file_or_name, ec)) return load_scene(file_or_name);
    const auto names = builtin_scene_names();
    if (std::find(names.begin(), names.end(), file_or_name) != names.end())
        return load_scene(builtin_scene_dir() / (file_or_name + ".json"));
    std::string list;
    for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
    throw scene_error(file_or_name + ": no such scene file or built-in scene (built-in: " +
                      (list.empty() ? "none found in " + builtin_scene_dir().string() : list) + ")");
}

}  // namespace emcv::demo
