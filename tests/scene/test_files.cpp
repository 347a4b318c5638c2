// SPDX-License-Identifier: MIT
// Mesh and texture files: every committed asset loads with the properties demo/assets/CREDITS.md states,
// OBJ / PLY / glTF all go through the one loader, and textures are linearised from sRGB.
#include <catch2/catch_approx.hpp>
#include <catch2/catch_test_macros.hpp>
#include <catch2/matchers/catch_matchers_string.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

#include "scene/mesh_file.hpp"
#include "scene/texture_file.hpp"
#include "scene_test_support.hpp"

using namespace emcv::demo;
using emcv::test::source_dir;
using emcv::test::temp_folder;
using emcv::test::tetrahedron_obj;

namespace {

struct bounds {
    glm::vec3 lo{std::numeric_limits<float>::max()};
    glm::vec3 hi{-std::numeric_limits<float>::max()};
};

bounds box(const mesh& m) {
    bounds b;
    for (const vertex& v : m.vertices) {
        b.lo = glm::min(b.lo, v.position);
        b.hi = glm::max(b.hi, v.position);
    }
    return b;
}

/// Sum over triangles of (area-weighted normal . (centroid - box centre)): > 0 when the faces wind outwards.
double outwardness(const mesh& m) {
    const bounds b = box(m);
    const glm::dvec3 centre = glm::dvec3(0.5f * (b.lo + b.hi));
    double sum = 0.0;
    for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3) {
        const glm::dvec3 a(m.vertices[m.indices[t]].position), c1(m.vertices[m.indices[t + 1]].position),
            c2(m.vertices[m.indices[t + 2]].position);
        sum += glm::dot(glm::cross(c1 - a, c2 - a), (a + c1 + c2) / 3.0 - centre);
    }
    return sum;
}

void check_well_formed(const mesh& m) {
    REQUIRE(m.indices.size() % 3u == 0u);
    for (std::uint32_t i : m.indices) REQUIRE(i < m.vertices.size());
    for (const vertex& v : m.vertices) {
        REQUIRE(std::isfinite(v.position.x + v.position.y + v.position.z));
        REQUIRE(std::fabs(glm::length(v.normal) - 1.0f) < 1e-5f);
    }
}

}  // namespace

TEST_CASE("every committed asset loads as CREDITS.md describes it") {
    struct asset {
        const char* file;
        std::size_t triangles;
        bool has_uv;
    };
    for (const asset& a : {asset{"bunny.ply", 11999, false}, asset{"igea.ply", 12000, false}, asset{"spot.ply", 5856, true}}) {
        INFO(a.file);
        const mesh m = read_mesh_file(source_dir() / "demo/assets" / a.file);
        check_well_formed(m);
        CHECK(m.indices.size() / 3u == a.triangles);
        // --fit-height 1: bottom at y = 0, height 1, centred in x and z.
        const bounds b = box(m);
        CHECK(b.lo.y == Catch::Approx(0.0f).margin(1e-5));
        CHECK(b.hi.y == Catch::Approx(1.0f).margin(1e-5));
        CHECK(b.lo.x + b.hi.x == Catch::Approx(0.0f).margin(1e-5));
        CHECK(b.lo.z + b.hi.z == Catch::Approx(0.0f).margin(1e-5));
        CHECK(outwardness(m) > 0.0);
        const bool any_uv = std::any_of(m.vertices.begin(), m.vertices.end(), [](const vertex& v) { return v.uv != glm::vec2(0.0f); });
        CHECK(any_uv == a.has_uv);
        // Smooth normals agree with the winding: on average a vertex normal points the way its faces do.
        double agreement = 0.0;
        for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3) {
            const vertex &v0 = m.vertices[m.indices[t]], &v1 = m.vertices[m.indices[t + 1]], &v2 = m.vertices[m.indices[t + 2]];
            const glm::vec3 face = glm::cross(v1.position - v0.position, v2.position - v0.position);
            agreement += static_cast<double>(glm::dot(face, v0.normal + v1.normal + v2.normal));
        }
        CHECK(agreement > 0.0);
    }
}

TEST_CASE("OBJ, PLY and glTF files load through the same reader") {
    const temp_folder dir;
    const auto obj = dir.write("tet.obj", tetrahedron_obj);
    const auto ply = dir.write("tet.ply",
                               "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                               "property float z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n"
                               "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n");
    // glTF 2.0 with the buffer inline (base64 of 4 float3 positions then 12 uint16 indices).
    const auto gltf = dir.write("tet.gltf", R"({
      "asset": {"version": "2.0"},
      "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
      "buffers": [{"byteLength": 72, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAAAAAAAAAAAAIA/AAACAAEAAAABAAMAAAADAAIAAQACAAMA"}],
      "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 24}],
      "accessors": [
        {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 1]},
        {"bufferView": 1, "componentType": 5123, "count": 12, "type": "SCALAR"}]
    })");
    for (const auto& file : {obj, ply, gltf}) {
        INFO(file.filename().string());
        const mesh m = read_mesh_file(file);
        check_well_formed(m);
        CHECK(m.indices.size() == 12u);
        CHECK(m.name == file.filename().string());
        double volume = 0.0;
        for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3)
            volume += static_cast<double>(glm::dot(m.vertices[m.indices[t]].position,
                                                   glm::cross(m.vertices[m.indices[t + 1]].position,
                                                              m.vertices[m.indices[t + 2]].position))) / 6.0;
        CHECK(volume == Catch::Approx(1.0 / 6.0).epsilon(1e-6));
    }
}

TEST_CASE("mesh file errors name the problem") {
    const temp_folder dir;
    using Catch::Matchers::ContainsSubstring;
    CHECK_THROWS_WITH(read_mesh_file(dir.path() / "absent.obj"), ContainsSubstring("mesh file not found"));
    CHECK_THROWS_WITH(read_mesh_file(dir.write("garbage.ply", "ply\nthis is not a mesh\n")),
                      ContainsSubstring("cannot read mesh file"));
    CHECK_THROWS_WITH(read_mesh_file(dir.write("points.obj", "v 0 0 0\nv 1 0 0\n")),
                      ContainsSubstring("cannot read mesh file") || ContainsSubstring("no triangles"));
    CHECK_THROWS_WITH(read_mesh_file(dir.path()), ContainsSubstring("not a regular file"));
}

TEST_CASE("the sRGB decoding is IEC 61966-2-1") {
    CHECK(srgb_to_linear(0.0f) == 0.0f);
    CHECK(srgb_to_linear(1.0f) == Catch::Approx(1.0f).epsilon(1e-6));
    CHECK(srgb_to_linear(0.5f) == Catch::Approx(0.2140411f).epsilon(1e-5));   // the standard mid-grey
    CHECK(srgb_to_linear(0.04045f) == Catch::Approx(0.04045f / 12.92f).epsilon(1e-6));  // linear segment
    // The two pieces meet at the threshold (continuous to within the standard's rounding).
    CHECK(std::fabs(srgb_to_linear(0.040451f) - srgb_to_linear(0.040449f)) < 1e-6f);
}

TEST_CASE("textures load linearised from sRGB, opaque where the file has no alpha", "[image-files]") {
    const texture t = read_texture_file(source_dir() / "demo/assets/spot_texture.png");
    REQUIRE(t.width == 1024);
    REQUIRE(t.height == 1024);
    REQUIRE(t.rgba.size() == 1024u * 1024u * 4u);
    for (std::size_t i = 0; i < t.rgba.size(); ++i) {
        REQUIRE(t.rgba[i] >= 0.0f);
        REQUIRE(t.rgba[i] <= 1.0f);
        if (i % 4u == 3u) REQUIRE(t.rgba[i] == 1.0f);  // RGB file: opaque
    }
    // An 8-bit value decodes through the sRGB curve, not as value / 255.
    const temp_folder dir;
    const auto png = dir.write("two.ppm", std::string("P6\n2 1\n255\n") + std::string("\x80\x80\x80\xff\x00\x00", 6));
    const texture two = read_texture_file(png);
    REQUIRE(two.width == 2);
    // File rows are top-down and GL rows bottom-up: a one-row image reads the same either way; the pixel
    // order within the row is kept.
    CHECK(two.rgba[0] == Catch::Approx(srgb_to_linear(128.0f / 255.0f)).epsilon(1e-6));
    CHECK(two.rgba[4] == Catch::Approx(1.0f));
    CHECK(two.rgba[5] == 0.0f);
}

TEST_CASE("texture rows are flipped to bottom first", "[image-files]") {
    const temp_folder dir;
    // 1 x 2 image: top pixel white, bottom pixel black.
    const auto file = dir.write("column.ppm", std::string("P6\n1 2\n255\n") + std::string("\xff\xff\xff\x00\x00\x00", 6));
    const texture t = read_texture_file(file);
    REQUIRE(t.height == 2);
    CHECK(t.rgba[0] == 0.0f);                         // first row in memory: the bottom (black)
    CHECK(t.rgba[4] == Catch::Approx(1.0f));          // second: the top (white)
    CHECK_THROWS_WITH(read_texture_file(dir.path() / "absent.png"),
                      Catch::Matchers::ContainsSubstring("texture file not found"));
}
