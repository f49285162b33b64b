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

}  // namespace hairfit
