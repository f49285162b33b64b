// Splitting a coarse scan (a decimated one: a few hundred long triangles) into smaller flat
// triangles before the hair is cut from it. The surface stays exactly where it was; the hairline,
// the hull's distance from it and the level-set scalp then have vertices to follow it with. Without
// it, the scalp's strip zips a few long hairline edges to a piece resolved at the voxel, and its
// slivers turn inward (a bun sampled at 5 cm: 10 scalp triangles facing into the head at every
// voxel tried).
#pragma once
#include <vector>

#include "core/mesh.h"

namespace hairfit {

struct Refined {
  Mesh mesh;
  std::vector<Vec3> colors;         // per vertex: a new vertex takes the mean of its edge's ends
  int splits = 0;                   // rounds of splitting every triangle into four
  double median_edge_before = 0.0;  // scan units
  double median_edge_after = 0.0;
};

// The median edge length of a mesh (each undirected edge once).
double median_edge_length(const Mesh& mesh);

// Splits every triangle into four at its edges' midpoints (shared by the triangles on each edge)
// until the median edge is at most `max_median_edge`, at most 4 rounds; colours (per vertex, or
// empty) follow linearly.
Refined refine_coarse_scan(const Mesh& mesh, const std::vector<Vec3>& colors, double max_median_edge);

}  // namespace hairfit
