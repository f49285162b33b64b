// Untangling a scan that crosses itself where noise folds its small triangles over their
// neighbours: a scanner's noise of a few hundredths of a centimetre turns slivers (edges of
// 10⁻³ cm, as marching cubes or tetrahedra leave them) over onto the next ring, and a hull cut from
// such a scan crosses itself, which the volume `run` needs must not.
//
// How: the pairs of triangles that share no vertex and intersect (surface_checks.h, exact tests)
// mark their vertices; those, grown by one more ring each round, are moved by Jacobi passes toward
// their neighbours' mean (half the way, the rest of the mesh fixed) until no pair is left or the
// rounds run out. Only the folded neighbourhoods move, by about the folds' size; a scan that does
// not cross itself is left exactly as it is.
#pragma once
#include "core/mesh.h"

namespace hairfit {

struct Untangled {
  int pairs_found = 0;        // crossing pairs before (at most kMaxUntanglePairs counted)
  int pairs_left = 0;         // after the last round (0: untangled)
  int rounds = 0;             // rounds of smoothing done
  int vertices_moved = 0;     // distinct vertices the rounds moved
  double largest_move = 0.0;  // the farthest any vertex moved (mesh units)
  Vec3 first_found = Vec3::Zero(), first_left = Vec3::Zero();  // a crossing's place, before and after
};

constexpr int kMaxUntanglePairs = 100000;

// Smooths the neighbourhoods of `mesh`'s self-intersections in place (boundary vertices fixed)
// until none is left, for at most `max_rounds` rounds of `passes` passes each.
Untangled untangle_self_intersections(Mesh& mesh, int threads = 0, int max_rounds = 6, int passes = 4);

}  // namespace hairfit
