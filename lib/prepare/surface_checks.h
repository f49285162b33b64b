// Geometric checks of the surfaces `hairfit prepare` makes: they are verified, not assumed.
#pragma once
#include <utility>
#include <vector>

#include "core/fast_winding.h"
#include "core/mesh.h"

namespace hairfit {

// Whether two triangles share at least one point (closed triangles; coplanar overlaps included).
// Möller's interval test, with a 2D test for the coplanar case.
bool triangles_intersect(const Vec3& a0, const Vec3& a1, const Vec3& a2, const Vec3& b0, const Vec3& b1, const Vec3& b2);

// Pairs (i < j) of triangles of `mesh` that share no vertex and yet intersect: the
// self-intersections. Stops after `max_pairs`. A uniform grid over the triangles' bounding boxes
// finds the candidates; each pair is tested once, in the cell holding the low corner of the
// overlap of their boxes, so the answer is exact and deterministic; `threads` (0 = all) tests
// cells side by side and finds the same pairs.
std::vector<std::pair<int, int>> self_intersections(const Mesh& mesh, int max_pairs = 16, int threads = 1);

// Mean curvature |H| (1/cm) at each vertex from the cotangent Laplacian over the barycentric
// area: |Σⱼ (cot αᵢⱼ + cot βᵢⱼ)(xᵢ − xⱼ)| / (4 Aᵢ). Boundary vertices get 0 (undefined there).
std::vector<double> mean_curvature(const Mesh& mesh);

// Triangles whose orientation, seen from `centre`, is not strictly counter-clockwise outward
// (signed volume of the tetrahedron (centre, a, b, c) ≤ 0): zero for a surface that is star-shaped
// about the centre with outward normals.
std::vector<int> inward_triangles(const Mesh& mesh, const Vec3& centre);

// The triangles of `sheet` (a part of the closed surface `solid` stands for, e.g. the scalp under
// the hair layer) whose front does not lie inside `solid`: the point a step in front of the
// triangle's centroid, along its normal, has winding number ≤ ½ (exactly, FastWindingNumber::above).
// The step is kFacingStep, or a tenth of the triangle's smallest altitude where that is shorter:
// the centroid lies a third of an altitude from each edge, so the point stays in front of the
// triangle itself wherever a neighbour meets it at an inside angle above 17° (tan 17° = 0.3), and
// a sliver narrower than kFacingStep in a concave corner is judged by its own side, not by the
// neighbour a longer step would cross. A triangle without area has no front and is listed.
constexpr double kFacingStep = 1e-3;  // the mesh's unit (cm)
std::vector<int> facing_out_of(const Mesh& sheet, const FastWindingNumber& solid, int threads = 1);

}  // namespace hairfit
