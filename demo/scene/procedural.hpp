// SPDX-License-Identifier: MIT
// Built-in meshes, generated in object space with unit normals and uvs in [0, 1]. Closed meshes (sphere, torus,
// slab) wind counter-clockwise seen from outside, so their signed volume is positive. Vertices lie exactly on
// the analytic surface; tests/scene bounds area and volume against the analytic values (docs/scenes.md).
#pragma once

#include "scene.hpp"

namespace emcv::demo {

/// UV sphere centred at the origin: `segments` around the y axis (>= 3), `rings` from pole to pole (>= 2).
mesh make_sphere(float radius, int segments, int rings);

/// Torus around the y axis: tube centre at `major_radius` from the axis, tube radius `minor_radius`
/// (0 < minor < major); `segments` around the axis, `sides` around the tube (each >= 3).
mesh make_torus(float major_radius, float minor_radius, int segments, int sides);

/// Thin curved slab: a piece of a cylindrical shell around the y axis, `angle_degrees` of arc (0, 360),
/// centred on +z, mid-surface radius `radius`, `thickness` (< 2 radius) and `height` along y; closed (outer,
/// inner, two ends, top, bottom), flat-shaded edges. `segments` (>= 1) subdivide the arc.
mesh make_slab(float radius, float angle_degrees, float thickness, float height, int segments);

/// Plane in y = 0 facing +y, `width` along x, `depth` along z, centred at the origin, `subdivisions` quads
/// per side (>= 1).
mesh make_plane(float width, float depth, int subdivisions);

}  // namespace emcv::demo
