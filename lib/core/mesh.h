// A triangle mesh as an immutable value: positions in the scene's length unit (cm after loading)
// and counter-clockwise triangles (the outward side is the one the vertices turn around
// counter-clockwise when seen from it).
#pragma once
#include <cmath>
#include <string>
#include <vector>

#include "core/types.h"

namespace hairfit {

struct Mesh {
  std::vector<Vec3> positions;
  std::vector<Vec3i> triangles;
};

// Edge-based topology of a mesh: what `hairfit validate` reports and the scalp chart requires.
struct MeshTopology {
  int vertices = 0;  // vertices used by at least one triangle
  int edges = 0;
  int faces = 0;
  int euler_characteristic = 0;                 // V − E + F over used vertices
  int components = 0;                           // connected components (via shared edges)
  std::vector<std::vector<int>> boundary_loops;  // vertex indices, in the triangles' orientation
  std::vector<int> nonmanifold_vertices;        // endpoints of edges shared by 3+ triangles
  bool orientation_consistent = true;           // no interior edge traversed twice the same way
  bool closed() const { return boundary_loops.empty() && nonmanifold_vertices.empty(); }
  // A topological disk: one component, one boundary loop, manifold, χ = 1.
  bool is_disk() const {
    return components == 1 && boundary_loops.size() == 1 && nonmanifold_vertices.empty() &&
           euler_characteristic == 1;
  }
};

MeshTopology analyse_topology(const Mesh& mesh);

// Each vertex's neighbours along triangle edges, ascending, without repeats.
std::vector<std::vector<int>> vertex_neighbours(const Mesh& mesh);
// Shortest distance along the mesh's edges (Euclidean edge lengths) from the nearest source
// vertex (multi-source Dijkstra), infinite where no source is reachable; `neighbours` as
// vertex_neighbours gives them.
std::vector<double> edge_distances(const Mesh& mesh, const std::vector<std::vector<int>>& neighbours,
                                   const std::vector<int>& sources);
// One key per undirected edge a–b (vertex indices ≥ 0), for hashing edges.
inline long long edge_key(int a, int b) {
  return (static_cast<long long>(a < b ? a : b) << 32) | static_cast<long long>(a < b ? b : a);
}

double triangle_area(const Mesh& mesh, int triangle);
double surface_area(const Mesh& mesh);
// Each vertex's lumped area: a third of the area of every triangle at it, summed in triangle order.
std::vector<double> vertex_areas(const Mesh& mesh);
// Unit normal of a triangle (zero vector for a degenerate one).
Vec3 triangle_normal(const Mesh& mesh, int triangle);
// The mean of a triangle's corners, (a + b + c) / 3.
Vec3 triangle_centroid(const Mesh& mesh, int triangle);
// Axis-aligned bounds of the used positions: {min, max}.
std::pair<Vec3, Vec3> bounding_box(const Mesh& mesh);

// The point to compute a mesh about, from its bounding box [lo, hi]: the box's middle rounded to a
// multiple of Q, the power of two at least 16 times the box's size. Data about the origin (within
// 8 sizes of it) keeps the origin, so its arithmetic is untouched; data far from it is computed
// within 9 sizes of this point, where doubles resolve it as they do about the origin; and the
// same data moved by a multiple of Q gets the same coordinates about its point, bit for bit.
Vec3 frame_origin(const Vec3& lo, const Vec3& hi);

// Significant digits to write coordinates with so that points `farthest` from the origin keep
// the step `digits` give to data about the origin, relative to the data's `size`: `digits`, plus
// one for every factor of 10 by which farthest exceeds 10 × size (at most 17, a double's round
// trip).
int digits_for_far_data(int digits, double farthest, double size);

// Signed solid angle of the triangle with vertices a, b, c (relative to the viewpoint), by Van
// Oosterom and Strackee's formula: positive when the viewpoint lies behind the triangle (on the
// side its normal (b−a)×(c−a) points away from), as the inside of a closed outward-oriented mesh
// does. In [−2π, 2π] and never NaN for finite input. For a viewpoint in the triangle's plane
// inside it, or on a zero-area triangle, the numerator is zero up to rounding and the result is
// 0 or ±2π as its rounding falls.
inline double triangle_solid_angle(const Vec3& a, const Vec3& b, const Vec3& c) {
  const double la = a.norm(), lb = b.norm(), lc = c.norm();
  const double numerator = a.dot(b.cross(c));
  const double denominator = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
  return 2.0 * std::atan2(numerator, denominator);
}

// Generalised winding number of a point with respect to the mesh (Jacobson et al. 2013): 1 inside
// a closed outward-oriented mesh, 0 outside, fractional near holes. O(triangles) per query.
double winding_number(const Mesh& mesh, const Vec3& point);

}  // namespace hairfit
