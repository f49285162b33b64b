// Welding vertices that a scan repeats along its patch seams at nearly (not exactly) the same
// position, so the hair region is one connected piece.
#pragma once
#include <vector>

#include "core/mesh.h"

namespace hairfit {

struct Welded {
  Mesh mesh;
  std::vector<int> old_to_new;   // per input vertex: its vertex in `mesh`
  std::vector<int> new_to_old;   // per output vertex: the first input vertex merged into it
  int merged_vertices = 0;       // input vertices merged into an earlier one
  int dropped_triangles = 0;     // triangles collapsed by the merge, or repeating another's vertices
};

// Merges every vertex within `tolerance` (cm, ≥ 0) of an earlier kept vertex into the lowest-indexed
// such vertex (core/weld.h's weld_points: greedy, in input order, so the result is deterministic);
// keeps the earlier position. Triangles that lose a corner or repeat another triangle's three
// vertices are dropped.
Welded weld_vertices(const Mesh& mesh, double tolerance);

}  // namespace hairfit
