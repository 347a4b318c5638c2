// SPDX-License-Identifier: MIT
#include "procedural.hpp"

#include <emcv/port/port.h>

#include <cmath>
#include <cstddef>
#include <cstdint>

namespace emcv::demo {
namespace {

constexpr float pi = float(EMCV_PI);

std::uint32_t index_of(std::size_t i) { return static_cast<std::uint32_t>(i); }

/// Quads of a (columns + 1) x (rows + 1) vertex grid starting at `first`, row-major; counter-clockwise when
/// the grid's column direction x row direction points outwards.
void add_grid_quads(mesh& m, std::size_t first, int columns, int rows) {
    const auto stride = static_cast<std::size_t>(columns) + 1u;
    for (int r = 0; r < rows; ++r) {
        for (int c = 0; c < columns; ++c) {
            const std::size_t a = first + static_cast<std::size_t>(r) * stride + static_cast<std::size_t>(c);
            const std::size_t b = a + 1u;
            const std::size_t d = a + stride;
            const std::size_t e = d + 1u;
            m.indices.insert(m.indices.end(), {index_of(a), index_of(b), index_of(e), index_of(a), index_of(e), index_of(d)});
        }
    }
}

/// One flat quad (p0, p1, p2, p3 counter-clockwise seen from outside), its own four vertices.
void add_flat_quad(mesh& m, glm::vec3 p0, glm::vec3 p1, glm::vec3 p2, glm::vec3 p3) {
    const glm::vec3 n = glm::normalize(glm::cross(p1 - p0, p3 - p0));
    const std::size_t first = m.vertices.size();
    m.vertices.push_back({p0, n, {0.0f, 0.0f}});
    m.vertices.push_back({p1, n, {1.0f, 0.0f}});
    m.vertices.push_back({p2, n, {1.0f, 1.0f}});
    m.vertices.push_back({p3, n, {0.0f, 1.0f}});
    m.indices.insert(m.indices.end(), {index_of(first), index_of(first + 1u), index_of(first + 2u),
                                       index_of(first), index_of(first + 2u), index_of(first + 3u)});
}

}  // namespace

mesh make_sphere(float radius, int segments, int rings) {
    mesh m;
    m.name = "sphere";
    // Rows run from the south pole (v = 0) to the north pole (v = 1); columns around +y (u). Pole rows are
    // degenerate quads whose zero-area triangles are dropped.
    for (int r = 0; r <= rings; ++r) {
        const float v = static_cast<float>(r) / static_cast<float>(rings);
        const float polar = pi * (1.0f - v);  // angle from +y
        for (int s = 0; s <= segments; ++s) {
            const float u = static_cast<float>(s) / static_cast<float>(segments);
            const float azimuth = 2.0f * pi * u;
            // Exact poles and an exact seam keep the mesh closed (seam vertices coincide).
            const float sin_polar = (r == 0 || r == rings) ? 0.0f : std::sin(polar);
            const float cos_polar = r == 0 ? -1.0f : (r == rings ? 1.0f : std::cos(polar));
            const float ca = s == segments ? 1.0f : std::cos(azimuth);
            const float sa = s == segments ? 0.0f : std::sin(azimuth);
            const glm::vec3 n{sin_polar * sa, cos_polar, sin_polar * ca};
            m.vertices.push_back({radius * n, n, {u, v}});
        }
    }
    const auto stride = static_cast<std::size_t>(segments) + 1u;
    for (int r = 0; r < rings; ++r) {
        for (int s = 0; s < segments; ++s) {
            const std::size_t a = static_cast<std::size_t>(r) * stride + static_cast<std::size_t>(s);
            const std::size_t b = a + 1u, d = a + stride, e = d + 1u;
            // Outward: columns grow with azimuth (towards +x from +z), rows grow towards +y.
            if (r != 0) m.indices.insert(m.indices.end(), {index_of(a), index_of(b), index_of(e)});
            if (r != rings - 1) m.indices.insert(m.indices.end(), {index_of(a), index_of(e), index_of(d)});
        }
    }
    return m;
}

mesh make_torus(float major_radius, float minor_radius, int segments, int sides) {
    mesh m;
    m.name = "torus";
    for (int t = 0; t <= sides; ++t) {
        const float v = static_cast<float>(t) / static_cast<float>(sides);
        const float tube = 2.0f * pi * v;  // 0 on the outer equator, then up over the top
        const float ct = t == sides ? 1.0f : std::cos(tube);
        const float st = t == sides ? 0.0f : std::sin(tube);
        for (int s = 0; s <= segments; ++s) {
            const float u = static_cast<float>(s) / static_cast<float>(segments);
            const float azimuth = 2.0f * pi * u;
            const float ca = s == segments ? 1.0f : std::cos(azimuth);
            const float sa = s == segments ? 0.0f : std::sin(azimuth);
            const glm::vec3 radial{sa, 0.0f, ca};
            const glm::vec3 n = ct * radial + glm::vec3(0.0f, st, 0.0f);
            const glm::vec3 centre = major_radius * radial;
            m.vertices.push_back({centre + minor_radius * n, n, {u, v}});
        }
    }
    add_grid_quads(m, 0, segments, sides);
    return m;
}

mesh make_slab(float radius, float angle_degrees, float thickness, float height, int segments) {
    mesh m;
    m.name = "slab";
    const float half_angle = 0.5f * angle_degrees * pi / 180.0f;
    const float r_in = radius - 0.5f * thickness;
    const float r_out = radius + 0.5f * thickness;
    const float y0 = -0.5f * height, y1 = 0.5f * height;
    auto at = [&](float r, float azimuth, float y) { return glm::vec3(r * std::sin(azimuth), y, r * std::cos(azimuth)); };
    auto azimuth_of = [&](int s) {
        return -half_angle + 2.0f * half_angle * static_cast<float>(s) / static_cast<float>(segments);
    };
    // Outer (normal = radial) and inner (normal = -radial) faces: smooth along the arc.
    for (int side = 0; side < 2; ++side) {
        const bool outer = side == 0;
        const float r = outer ? r_out : r_in;
        const std::size_t first = m.vertices.size();
        for (int row = 0; row <= 1; ++row) {
            const float y = row == 0 ? y0 : y1;
            for (int s = 0; s <= segments; ++s) {
                // Inner face: columns run backwards so that the winding faces the axis.
                const int column = outer ? s : segments - s;
                const float a = azimuth_of(column);
                const glm::vec3 radial{std::sin(a), 0.0f, std::cos(a)};
                const float u = static_cast<float>(column) / static_cast<float>(segments);
                m.vertices.push_back({at(r, a, y), outer ? radial : -radial, {u, static_cast<float>(row)}});
            }
        }
        add_grid_quads(m, first, segments, 1);
    }
    // Top and bottom: flat rings of quads; the two ends: flat quads.
    for (int s = 0; s < segments; ++s) {
        const float a0 = azimuth_of(s), a1 = azimuth_of(s + 1);
        add_flat_quad(m, at(r_in, a0, y1), at(r_out, a0, y1), at(r_out, a1, y1), at(r_in, a1, y1));
        add_flat_quad(m, at(r_in, a1, y0), at(r_out, a1, y0), at(r_out, a0, y0), at(r_in, a0, y0));
    }
    const float first_a = azimuth_of(0), last_a = azimuth_of(segments);
    add_flat_quad(m, at(r_in, first_a, y0), at(r_out, first_a, y0), at(r_out, first_a, y1), at(r_in, first_a, y1));
    add_flat_quad(m, at(r_out, last_a, y0), at(r_in, last_a, y0), at(r_in, last_a, y1), at(r_out, last_a, y1));
    return m;
}

mesh make_plane(float width, float depth, int subdivisions) {
    mesh m;
    m.name = "plane";
    const glm::vec3 up{0.0f, 1.0f, 0.0f};
    for (int row = 0; row <= subdivisions; ++row) {
        const float v = static_cast<float>(row) / static_cast<float>(subdivisions);
        for (int column = 0; column <= subdivisions; ++column) {
            const float u = static_cast<float>(column) / static_cast<float>(subdivisions);
            // Rows run towards -z so that (column dir) x (row dir) = (+x) x (-z) = +y.
            m.vertices.push_back({{(u - 0.5f) * width, 0.0f, (0.5f - v) * depth}, up, {u, v}});
        }
    }
    add_grid_quads(m, 0, subdivisions, subdivisions);
    return m;
}

}  // namespace emcv::demo
