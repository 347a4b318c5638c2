// SPDX-License-Identifier: MIT
// Procedural meshes against their analytic area and volume, within bounds derived for the discretisation
// (each derivation beside its test), plus closedness, outward winding and unit normals.
#include <catch2/catch_test_macros.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

#include "scene/procedural.hpp"

using namespace emcv::demo;

namespace {

constexpr double pi = 3.14159265358979323846;
// fp32 vertex positions: relative rounding of a sum of ~1e4 terms, far below every discretisation bound.
constexpr double fp32_slack = 1e-5;

struct measures {
    double area = 0.0;
    double volume = 0.0;  ///< signed, divergence theorem: > 0 when triangles wind counter-clockwise from outside
    double longest_edge = 0.0;
};

glm::dvec3 at(const mesh& m, std::uint32_t i) { return glm::dvec3(m.vertices[i].position); }

measures measure(const mesh& m) {
    measures r;
    for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3) {
        const glm::dvec3 a = at(m, m.indices[t]), b = at(m, m.indices[t + 1]), c = at(m, m.indices[t + 2]);
        r.area += 0.5 * glm::length(glm::cross(b - a, c - a));
        r.volume += glm::dot(a, glm::cross(b, c)) / 6.0;
        r.longest_edge = std::max({r.longest_edge, glm::length(b - a), glm::length(c - b), glm::length(a - c)});
    }
    return r;
}

/// Closed and consistently wound: every directed edge (by position, so seams count as joined) is matched by
/// exactly one edge in the opposite direction.
bool closed_and_consistent(const mesh& m) {
    using point = std::tuple<float, float, float>;
    auto key = [&](std::uint32_t i) {
        const glm::vec3& p = m.vertices[i].position;
        return point(p.x, p.y, p.z);
    };
    std::map<std::pair<point, point>, int> directed;
    for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3)
        for (int e = 0; e < 3; ++e) {
            const auto from = key(m.indices[t + static_cast<std::size_t>(e)]);
            const auto to = key(m.indices[t + static_cast<std::size_t>((e + 1) % 3)]);
            if (from == to) return false;  // a degenerate triangle
            ++directed[{from, to}];
        }
    for (const auto& [edge, count] : directed) {
        const auto reverse = directed.find({edge.second, edge.first});
        if (count != 1 || reverse == directed.end() || reverse->second != 1) return false;
    }
    return true;
}

void check_unit_normals_and_uvs(const mesh& m) {
    for (const vertex& v : m.vertices) {
        REQUIRE(std::fabs(glm::length(v.normal) - 1.0f) < 1e-5f);
        REQUIRE(v.uv.x >= 0.0f);
        REQUIRE(v.uv.x <= 1.0f);
        REQUIRE(v.uv.y >= 0.0f);
        REQUIRE(v.uv.y <= 1.0f);
    }
    for (std::uint32_t i : m.indices) REQUIRE(i < m.vertices.size());
}

/// sin(x) / x
double sinc(double x) { return std::sin(x) / x; }

}  // namespace

TEST_CASE("sphere: closed, outward, unit normals along the radius, area and volume within the inscribed bound") {
    const double r = 1.5;
    for (auto [segments, rings] : {std::pair{48, 24}, std::pair{7, 3}, std::pair{128, 64}}) {
        INFO(segments << " x " << rings);
        const mesh m = make_sphere(static_cast<float>(r), segments, rings);
        check_unit_normals_and_uvs(m);
        CHECK(closed_and_consistent(m));
        for (const vertex& v : m.vertices) {
            REQUIRE(std::fabs(glm::length(v.position) - static_cast<float>(r)) < 1e-5f);  // on the sphere
            REQUIRE(glm::dot(v.normal, v.position) > 0.0f);                                 // pointing out
        }
        const measures got = measure(m);
        // Bound: the mesh is convex (every quad of a UV sphere is a planar isosceles trapezoid, its vertices on
        // the sphere), so it lies inside the ball of radius r and contains the ball of radius r_in, the least
        // distance from the centre to a face. A point p = sum w_i v_i of a triangle with |v_i| = r has
        // |p|^2 = r^2 - sum_{i<j} w_i w_j |v_i - v_j|^2 >= r^2 - e^2 max(sum_{i<j} w_i w_j) = r^2 - e^2 / 3,
        // e the longest edge. Volume and area are monotone under inclusion of convex bodies, hence
        // 4/3 pi r_in^3 <= V <= 4/3 pi r^3 and 4 pi r_in^2 <= A <= 4 pi r^2.
        const double r_in = std::sqrt(r * r - got.longest_edge * got.longest_edge / 3.0);
        CHECK(got.volume <= 4.0 / 3.0 * pi * r * r * r * (1.0 + fp32_slack));
        CHECK(got.volume >= 4.0 / 3.0 * pi * r_in * r_in * r_in * (1.0 - fp32_slack));
        CHECK(got.area <= 4.0 * pi * r * r * (1.0 + fp32_slack));
        CHECK(got.area >= 4.0 * pi * r_in * r_in * (1.0 - fp32_slack));
    }
}

TEST_CASE("torus: closed, outward, area and volume within the derived polyhedral bounds") {
    const double major = 1.0, minor = 0.3;
    for (auto [segments, sides] : {std::pair{64, 32}, std::pair{5, 3}, std::pair{200, 60}}) {
        INFO(segments << " x " << sides);
        const mesh m = make_torus(static_cast<float>(major), static_cast<float>(minor), segments, sides);
        check_unit_normals_and_uvs(m);
        CHECK(closed_and_consistent(m));
        for (const vertex& v : m.vertices) {
            // The normal points from the tube's centre circle to the vertex.
            const glm::vec3 centre = static_cast<float>(major) * glm::normalize(glm::vec3(v.position.x, 0.0f, v.position.z));
            REQUIRE(glm::length(glm::cross(v.normal, v.position - centre)) < 1e-5f);
            REQUIRE(glm::dot(v.normal, v.position - centre) > 0.0f);
        }
        const measures got = measure(m);
        // Derivation: vertices lie on the torus and each quad is planar (a symmetric trapezoid), so the solid
        // between two neighbouring sections (angles u, u + du) is the ruled image of the section polygon P (a
        // regular `sides`-gon of circumradius `minor` centred `major` from the axis) under
        // (rho, z, t) -> (rho ((1 - t) e_u + t e_{u+du}), z), whose Jacobian is rho sin(du). Hence
        //   V_h = segments sin(du) major area(P),  area(P) = sides / 2 minor^2 sin(dv),
        //   V_h / V = sinc(du) sinc(dv) with V = 2 pi^2 major minor^2, du = 2 pi / segments, dv = 2 pi / sides.
        // Each quad has parallel sides 2 rho_j sin(du/2), 2 rho_{j+1} sin(du/2) and height h with
        // cos(du/2) c <= h <= c, c = 2 minor sin(dv/2) the section's edge; summing (sum_j rho_j = sides major):
        //   A_h / A in [cos(du/2) s, s], s = sinc(du/2) sinc(dv/2), A = 4 pi^2 major minor.
        const double du = 2.0 * pi / segments, dv = 2.0 * pi / sides;
        const double volume = 2.0 * pi * pi * major * minor * minor;
        const double area = 4.0 * pi * pi * major * minor;
        const double volume_ratio = sinc(du) * sinc(dv);
        CHECK(std::fabs(got.volume / volume - volume_ratio) < fp32_slack);  // exact for the polyhedron
        CHECK(got.volume <= volume);
        const double s = sinc(du / 2.0) * sinc(dv / 2.0);
        CHECK(got.area <= area * s * (1.0 + fp32_slack));
        CHECK(got.area >= area * s * std::cos(du / 2.0) * (1.0 - fp32_slack));
    }
}

TEST_CASE("slab: closed, outward, volume of the chord polygon shell") {
    const double radius = 0.6, thickness = 0.03, height = 0.6, angle_degrees = 70.0;
    for (int segments : {32, 1, 5}) {
        INFO(segments << " segments");
        const mesh m = make_slab(static_cast<float>(radius), static_cast<float>(angle_degrees),
                                 static_cast<float>(thickness), static_cast<float>(height), segments);
        check_unit_normals_and_uvs(m);
        CHECK(closed_and_consistent(m));
        const measures got = measure(m);
        // The arcs are chord polygons of `segments` chords of angle da each, so the section between them has
        // area segments / 2 sin(da) (r_out^2 - r_in^2): V_h / V = sinc(da), V = theta / 2 (r_out^2 - r_in^2) h.
        const double theta = angle_degrees * pi / 180.0, da = theta / segments;
        const double r_out = radius + thickness / 2.0, r_in = radius - thickness / 2.0;
        const double volume = theta / 2.0 * (r_out * r_out - r_in * r_in) * height;
        CHECK(std::fabs(got.volume / volume - sinc(da)) < 1e-4);  // fp32: thin shell, cancelling terms
        // Area: the curved faces dominate, theta (r_out + r_in) h sinc(da / 2) of chord panels, plus the ends
        // 2 thickness h and the top and bottom 2 V_h / h.
        const double area = theta * (r_out + r_in) * height * sinc(da / 2.0) + 2.0 * thickness * height +
                            2.0 * got.volume / height;
        CHECK(std::fabs(got.area / area - 1.0) < 1e-5);
    }
}

TEST_CASE("plane: the stated size, facing +y, uvs spanning [0, 1]") {
    const mesh m = make_plane(6.0f, 4.0f, 3);
    check_unit_normals_and_uvs(m);
    const measures got = measure(m);
    CHECK(std::fabs(got.area - 24.0) < 1e-5);
    for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3) {
        const glm::vec3 a = m.vertices[m.indices[t]].position, b = m.vertices[m.indices[t + 1]].position,
                        c = m.vertices[m.indices[t + 2]].position;
        REQUIRE(glm::cross(b - a, c - a).y > 0.0f);  // counter-clockwise seen from above
    }
    for (const vertex& v : m.vertices) {
        REQUIRE(v.normal == glm::vec3(0.0f, 1.0f, 0.0f));
        REQUIRE(v.position.y == 0.0f);
        REQUIRE(std::fabs(v.position.x) <= 3.0f);
        REQUIRE(std::fabs(v.position.z) <= 2.0f);
    }
    CHECK(m.indices.size() == 3u * 2u * 9u);
}
