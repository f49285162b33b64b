// Procedural meshes shared by the fixture generator, tests and benchmarks.
#pragma once
#include "core/mesh.h"

namespace hairfit {

// A subdivided icosahedron: 20·4^levels triangles, counter-clockwise seen from outside, its
// vertices on the sphere of `radius` about `centre`.
Mesh icosphere(int levels, double radius = 1.0, const Vec3& centre = Vec3::Zero());

}  // namespace hairfit
