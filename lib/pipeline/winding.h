// The winding number of a closed, consistently oriented triangle mesh about a point, by counting
// signed crossings of a ray: about 50 times cheaper than summing every triangle's solid angle
// (core/mesh.h winding_number), which the input checks did for 200 points of the scalp.
#pragma once
#include "core/mesh.h"

namespace hairfit {

// For a closed mesh (every edge shared by two triangles turning the same way) and a point off its
// surface: the integer that winding_number(mesh, point) approximates (+1 inside an outward mesh,
// −1 inside an inward one, 0 outside). Where the ray along +x passes too close to an edge or a
// vertex, or the point lies too close to a triangle it crosses, to count exactly, it returns
// winding_number(mesh, point) instead.
double closed_winding_number(const Mesh& closed, const Vec3& point);

}  // namespace hairfit
