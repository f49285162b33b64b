// Procedural meshes shared by the fixture generator, tests and benchmarks.
#pragma once
#include "core/mesh.h"

namespace hairfit {

// A subdivided icosahedron: 20·4^levels triangles, counter-clockwise seen from outside, its
// vertices on the sphere of `radius` about `centre`.
Mesh icosphere(int levels, double radius = 1.0, const Vec3& centre = Vec3::Zero());

// A latitude–longitude sphere: (rings + 1) × sectors vertices (each pole repeated `sectors` times,
// so the triangles at the poles have zero area), two triangles per cell, counter-clockwise seen
// from outside.
Mesh uv_sphere(const Vec3& centre, double radius, int rings, int sectors);

// The part of the sphere of `radius` about the origin with polar angle ≤ theta0 (from +z): a pole
// and `rings` rings of `sectors` vertices, the last at theta0 (its boundary), counter-clockwise
// seen from outside. An open disk; with theta0 = π/2 a hemisphere over the plane z = 0.
Mesh spherical_cap(double theta0, int rings, int sectors, double radius = 1.0);

}  // namespace hairfit
